"""The discretisation that `--accuracy PERCENT` chooses when the command line fixes none:
the quickest route whose bound, measured on a shaft of the same family, is below the
target within the DOF budget.

The model is what was measured on the paper's shaft (docs/accuracy.md, cold runs with
the bound, 2 cores), its DOFs scaled by the bar's volume:

* order 2 on adapted meshes (workflows.adapt), any shaft: the largest bound falls as
  1 / N, from 1.46 % at 86k DOFs (1.21 % at 125k, 0.75 % at 151k, 0.32 % at 390k),
  at about 0.66 ms a DOF over the rounds;
* fixed meshes: the default one at order 2 (bounded on a coarser mesh), and order 5
  on cubically curved elements (free shafts only), whose largest bound (0.45-0.59 %)
  is a floor set by the elements straightened at the root fillets.

Shafts of another family (steps, bores, keyways, STEP files, or none of the grooves)
have no measured model: they adapt at order 2, as they would with --order 2, and the
summary says so. The chosen run's own bound decides whether the target was reached.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from shaftfem.errors import SceneError
from shaftfem.scene.model import Scene

# the paper's shaft: a 32 mm bar 545 mm long (pi r^2 L, m^3), on which the rows were measured
REFERENCE_VOLUME = math.pi * 0.016**2 * 0.545
P2_BOUND, P2_DOFS = 0.01463, 86_055   # the default mesh's largest bound, and its DOFs
P2_RATE = 1.0                          # bound ~ N^-P2_RATE on adapted meshes
P2_SECONDS_PER_DOF = 0.66e-3          # cold, every round included (390k DOFs: 259 s)


@dataclass(frozen=True)
class FixedRoute:
    """A fixed mesh measured on the reference shaft: sizes away / grooves /
    floor edges (mm), its DOFs, largest bound (fraction) and cold seconds with the bound."""

    sizes_mm: tuple[float, float, float]
    order: int
    geometry_order: int
    dofs: int
    bound: float
    seconds: float

    def describe(self) -> str:
        a, g, e = (f"{s:g}" for s in self.sizes_mm)
        curved = " on cubic elements" if self.geometry_order == 3 else ""
        return f"order {self.order}{curved}, {a}/{g}/{e} mm"


# benchmarks/order_bounds.py (bound) and time_to_accuracy.py --cli (cold seconds); the
# first is the default mesh, bounded on a coarser one (docs/accuracy.md)
FIXED = (
    FixedRoute((8.0, 4.0, 4.0), 2, 2, P2_DOFS, P2_BOUND, 15.0),
    FixedRoute((16.0, 12.0, 12.0), 5, 3, 254_163, 0.0059, 42.0),
    FixedRoute((12.0, 12.0, 12.0), 5, 3, 286_038, 0.0045, 51.0),
)


@dataclass(frozen=True)
class Route:
    """What `--accuracy` runs: `scene` (a fixed mesh when `adaptive` is False, its target
    kept for the verdict), the predicted DOFs and largest bound (fraction; nan where no
    model predicts it), and why this route (one or two sentences, for the user)."""

    scene: Scene
    adaptive: bool
    dofs: int
    bound: float
    why: str


def modelled(scene: Scene) -> bool:
    """Whether the scene is of the measured family: a free round bar with helical grooves."""
    return scene.grooves is not None and scene.shaft.plain and not scene.installed


def scale(scene: Scene) -> float:
    """The scene's DOFs per the reference shaft's at the same sizes: their volumes' ratio."""
    return math.pi * scene.shaft.radius**2 * scene.shaft.length / REFERENCE_VOLUME


def p2_dofs(scene: Scene, target: float) -> int:
    """DOFs the adapted order-2 meshes need for a largest bound of `target` (fraction)."""
    return round(P2_DOFS * scale(scene) * (P2_BOUND / target) ** (1 / P2_RATE))


def choose_route(scene: Scene, target: float, max_dofs: int) -> Route:
    """The route for a largest bound of `target` (fraction) within `max_dofs`; a
    SceneError (before any computation) when the model puts the target beyond the budget."""
    from shaftfem.workflows.pipeline import with_mesh

    if not modelled(scene):
        return Route(scene, True, 0, math.nan,
                     f"order 2, the mesh adapted: no cost model has been measured for "
                     f"this shaft ({_family(scene)}), only for free grooved round bars")
    n2, k = p2_dofs(scene, target), scale(scene)
    floor = min(r.bound for r in FIXED if r.order > 2)   # the best order 5 bounds
    fits = [r for r in FIXED if r.bound <= target and r.dofs * k <= max_dofs]
    if fits and (n2 > max_dofs or min(r.seconds for r in fits) < n2 * P2_SECONDS_PER_DOF):
        r = min(fits, key=lambda r: r.seconds)
        s = with_mesh(scene, order=r.order, geometry_order=r.geometry_order)
        a, g, e = (x * 1e-3 for x in r.sizes_mm)
        s = replace(s, mesh=replace(s.mesh, size=a, groove_size=g, edge_size=e))
        adapted = ("" if r.order == 2 else
                   f"; adapted meshes at order 2 would need about {_dofs(n2)} DOFs"
                   + (f" and {n2 * P2_SECONDS_PER_DOF:.0f} s" if n2 <= max_dofs
                      else ", above the budget"))
        return Route(s, False, round(r.dofs * k), r.bound,
                     f"{r.describe()}: about {_dofs(r.dofs * k)} DOFs and {r.seconds:.0f} s, "
                     f"bounds up to {100 * r.bound:.3g} % on the paper's shaft{adapted}")
    if n2 <= max_dofs:
        return Route(scene, True, n2, target,
                     f"order 2, the mesh adapted: about {_dofs(n2)} DOFs and "
                     f"{n2 * P2_SECONDS_PER_DOF:.0f} s on the paper's shaft (order 5 on cubic "
                     f"elements bounds no better than {100 * floor:.3g} %)")
    # the smallest bound some route reaches within the budget: adapted meshes at the
    # budget's DOFs, or a fixed mesh that fits it
    lowest = min([P2_BOUND * (P2_DOFS * k / max_dofs) ** P2_RATE]
                 + [r.bound for r in FIXED if r.dofs * k <= max_dofs])
    raise SceneError(
        f"--accuracy {100 * target:g}: a bound of {100 * target:g} % lies beyond the budget of "
        f"{max_dofs:,} DOFs on this shaft. Measured on the paper's shaft, order 2 on adapted "
        f"meshes would need about {_dofs(n2)} DOFs (its bound falls as 1/N from "
        f"{100 * P2_BOUND:.3g} % at {P2_DOFS:,} DOFs), and order 5 on cubic elements "
        f"bounds {100 * floor:.3g} % at best. Ask for {_up(100 * lowest):g} % or more, "
        f"or raise the budget (--max-dofs; order 2 takes about 17 GB a million DOFs)")


def _up(x: float) -> float:
    """x > 0 rounded up to two significant figures (a target said to be reachable is)."""
    step = 10.0 ** (math.floor(math.log10(x)) - 1)
    return round(math.ceil(x / step - 1e-9) * step, 12)


def _dofs(n: float) -> str:
    """A predicted DOF count to three figures, with thousands separated: 254,000."""
    return f"{float(f'{n:.3g}'):,.0f}"


def _family(scene: Scene) -> str:
    """What puts the scene outside the measured family, in a few words."""
    if scene.installed:
        return "it is held or carries parts"
    if scene.shaft.step is not None:
        return "a STEP solid"
    if not scene.shaft.plain:
        return "steps, a bore, keyways or chamfers"
    return "no grooves"
