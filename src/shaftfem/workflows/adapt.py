"""A mesh adapted to a requested accuracy: refine where the modes' error is, until
every frequency's bound is below the target or the DOF budget is spent.

Each round solves the modes, takes each element's share of each mode's recovery
estimate (shaftfem.fem.estimate), scaled to the mode's bound, and asks gmsh for a new
mesh of the cached CAD solid whose element sizes equidistribute that error at
AIM times the target: for P2 in 3D an element's share falls as h^(2k + 3) = h^7
where the solution is smooth, so element K shrinks by r_K = (e_K / tau)^(1/7)
(at most REFINE_MAX per round; where it is not smooth the next round refines
again). Every round after the first is bounded with the round before as its
coarser mesh, so no convergence rate is assumed for the bound itself.

The last mesh and what its bound needs from the round before are cached, keyed by
the scene's mesh key, the target and the budget: a warm re-run solves one mesh.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.store import cache_dir, content_key, discard, load_arrays, save_arrays

if TYPE_CHECKING:
    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.cad.solid import ShaftShape
    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.scene.model import Scene
    from shaftfem.workflows.pipeline import ModalResult

ADAPT_VERSION = 1
AIM = 0.5             # aim each new mesh at half the target: fewer rounds
POWER = 7.0           # 2k + d for P2 elements in 3D
REFINE_MAX = 4.0      # an element shrinks at most this much per round, and never grows:
                      # each round's error is below the last, as the two-mesh bound needs
SMALLEST = 0.05e-3    # no element below 0.05 mm
MAX_ROUNDS = 8


@dataclass(frozen=True)
class Round:
    dofs: int
    max_bound: float     # largest bound of the round's frequencies (fraction)
    seconds: float


@dataclass(frozen=True)
class Adapted:
    """The final run, its bound, and how it was reached."""

    result: ModalResult
    estimate: ErrorEstimate
    target: float        # requested bound, fraction
    max_dofs: int
    rounds: tuple[Round, ...]
    reached: bool
    why: str             # why the adaptation stopped short ('' when reached)
    from_cache: bool

    def summary(self) -> str:
        steps = " -> ".join(f"{r.dofs} DOFs +- {100 * r.max_bound:.2g} %" for r in self.rounds)
        head = (f"adaptive mesh for +- {100 * self.target:g} %: "
                f"{'reached' if self.reached else 'NOT reached'}"
                f"{' (from cache)' if self.from_cache else ''}; {steps}")
        return head if self.reached else f"{head}\n{self.why}"


def element_sizes(mesh: ShaftMesh) -> np.ndarray:
    """Mean edge length of each element, m."""
    v = mesh.points[mesh.cells[:, :4]]
    pairs = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))
    return np.mean([np.linalg.norm(v[:, a] - v[:, b], axis=1) for a, b in pairs], axis=0)


def size_field(mesh: ShaftMesh, shares: np.ndarray, target: float, largest: float
               ) -> tuple[np.ndarray, float]:
    """Sizes at the mesh's vertices for the next mesh, and its predicted element count.

    shares: (n_modes, n_elements) each element's part of each mode's error (fraction of
    the frequency); every mode's total is aimed at AIM * target."""
    h = element_sizes(mesh)
    aim = AIM * target
    e = np.maximum(shares, 1e-300)
    # equidistribution: N' tau = aim with N' = sum (e / tau)^(3 / POWER)
    tau = (aim / np.sum(e ** (3 / POWER), axis=1)) ** (POWER / (POWER - 3))
    r = np.max((e / tau[:, None]) ** (1 / POWER), axis=0)
    r = np.clip(r, 1.0, REFINE_MAX)
    new = np.clip(h / r, SMALLEST, largest)
    vertices = mesh.cells[:, :4]
    at = np.full(mesh.points.shape[0], np.inf)
    np.minimum.at(at, vertices.ravel(), np.repeat(new, 4))
    at[~np.isfinite(at)] = largest
    return at, float(np.sum((h / new) ** 3))


def adapt_key(scene: Scene, shape: ShaftShape, target: float, max_dofs: int) -> str:
    """A hash of everything the adapted mesh depends on."""
    from shaftfem.cad.mesh import mesh_key

    payload = {"version": ADAPT_VERSION, "mesh": mesh_key(shape, scene.shaft, scene.grooves,
                                                           scene.mesh, scene.seat_cuts()),
               "target": target, "max_dofs": max_dofs, "modes": scene.modes.count,
               "max_frequency": scene.modes.max_frequency,
               "material": [scene.material.youngs_modulus, scene.material.poisson_ratio,
                            scene.material.density],
               "constants": [AIM, POWER, REFINE_MAX, SMALLEST, MAX_ROUNDS],
               **({"installed": [asdict(p) for p in scene.held + scene.attachments]}
                  if scene.installed else {})}
    return content_key(payload)


HISTORY = ("prev_f", "prev_eta", "prev_kinds", "prev_dofs", "round_dofs", "round_bound",
           "round_seconds", "reached", "why")


def _save(path: Path, mesh: ShaftMesh, prev: tuple, rounds: list[Round], reached: bool,
          why: str) -> None:
    from shaftfem.cad.mesh import mesh_arrays

    f, eta, kinds, dofs = prev
    save_arrays(path, dict(mesh_arrays(mesh), prev_f=f, prev_eta=eta,
                           prev_kinds=np.array(kinds), prev_dofs=np.int64(dofs),
                           round_dofs=np.array([r.dofs for r in rounds]),
                           round_bound=np.array([r.max_bound for r in rounds]),
                           round_seconds=np.array([r.seconds for r in rounds]),
                           reached=np.bool_(reached), why=np.str_(why)))


def run_adaptive(scene: Scene, target: float, max_dofs: int, use_cache: bool = True,
                 progress: Callable[[str], None] | None = None, factorizer: str = "auto",
                 threads: int | None = None) -> Adapted:
    """Solve `scene` on meshes adapted until every frequency's bound is below `target`
    (fraction) or the next mesh would exceed `max_dofs`."""
    from shaftfem.cad.mesh import MESH_ARRAYS, check_budget, mesh_from_arrays, mesh_shape, remesh
    from shaftfem.cad.solid import build_shape

    say = progress or (lambda _m: None)
    t0 = time.perf_counter()
    check_budget(scene.shaft, scene.grooves, scene.mesh, max_dofs)
    shape = build_shape(scene.shaft, scene.grooves, use_cache=use_cache)
    t_cad = time.perf_counter() - t0
    key = adapt_key(scene, shape, target, max_dofs)
    path = cache_dir() / "adapted" / f"{key}.npz"
    if use_cache and path.exists():
        z, why = load_arrays(path, MESH_ARRAYS + HISTORY)
        if z is not None:
            say("adapted mesh from cache; solving")
            mesh = mesh_from_arrays(z, 0.0)
            kept = (z["prev_f"], z["prev_eta"], [str(k) for k in z["prev_kinds"]],
                    int(z["prev_dofs"]))
            history = [Round(int(d), float(b), float(s)) for d, b, s in
                       zip(z["round_dofs"], z["round_bound"], z["round_seconds"])]
            result, rec = _solve(scene, shape, mesh, t0, t_cad, factorizer, threads, say,
                                 use_cache)
            return Adapted(result=result, estimate=_bound(result, rec, kept), target=target,
                           max_dofs=max_dofs, rounds=tuple(history), reached=bool(z["reached"]),
                           why=str(z["why"]), from_cache=True)
        discard(f"adapted mesh {key}", why, path)

    mesh = mesh_shape(shape, scene.shaft, scene.grooves, scene.mesh, use_cache=use_cache,
                      cuts=scene.seat_cuts())
    prev: tuple | None = None
    rounds: list[Round] = []
    est = None
    reached, why = False, ""
    while True:
        t = time.perf_counter()
        say(f"adaptive round {len(rounds) + 1}: {mesh.n_elements} elements; solving")
        result, rec = _solve(scene, shape, mesh, t0, t_cad, factorizer, threads, say, use_cache)
        if prev is None:
            # the modes of the first mesh fix which modes are followed from round to round
            from shaftfem.workflows.pipeline import with_modes

            scene = with_modes(scene, count=result.modes.count)
            bound = _planning_bound(rec.relative)
        else:
            est = _bound(result, rec, prev)
            bound = est.relative_error
        rounds.append(Round(result.modes.n_dofs, float(np.max(bound)),
                            time.perf_counter() - t))
        say(f"adaptive round {len(rounds)}: {result.modes.n_dofs} DOFs, largest bound "
            f"{100 * np.max(bound):.2g} %")
        # modes the coarser mesh cannot confirm (errors below its geometric noise) count
        # with their recovery bound, marked as such in the table
        if est is not None and np.max(bound) <= target:
            reached = True
            break
        if len(rounds) >= MAX_ROUNDS:
            why = (f"stopped after {MAX_ROUNDS} rounds with a largest bound of "
                   f"{100 * np.max(bound):.2g} %")
            break
        # each element's share of each mode's error, scaled up to the mode's bound
        shares = rec.elements * (bound / np.maximum(rec.relative, 1e-300))[:, None]
        sizes, n_next = size_field(mesh, shares, target, scene.mesh.size)
        predicted = int(result.modes.n_dofs * n_next / mesh.n_elements)
        if predicted > max_dofs:
            if est is None:  # a bound needs two meshes: take one within the budget
                scale = (max_dofs / predicted) ** (1 / 3)
                sizes = np.minimum(sizes / scale, scene.mesh.size)
            else:
                why = (f"the next mesh would need about {predicted} DOFs, above the budget "
                       f"of {max_dofs} DOFs (--max-dofs); the bounds shown are those "
                       f"reached at {result.modes.n_dofs} DOFs")
                break
        prev = (result.modes.frequencies, rec.relative, result.modes.kinds,
                result.modes.n_dofs)
        say(f"adaptive round {len(rounds) + 1}: remeshing (about {min(predicted, max_dofs)} "
            "DOFs)")
        mesh = remesh(shape, scene.shaft, scene.grooves, scene.mesh,
                      (mesh.points, mesh.cells[:, :4], sizes), scene.seat_cuts())
    if est is None:
        raise AssertionError("an adaptive run ends with a bounded round")
    assert prev is not None  # set by every round
    if use_cache:
        _save(path, result.mesh, prev, rounds, reached, why)
    return Adapted(result=result, estimate=est, target=target, max_dofs=max_dofs,
                   rounds=tuple(rounds), reached=reached, why=why, from_cache=False)


def _planning_bound(recovery: np.ndarray) -> np.ndarray:
    """Before a second mesh exists: the recovery estimate with the safety factor (it may
    fall short; it only plans the next mesh)."""
    from shaftfem.fem.estimate import SAFETY

    return SAFETY * recovery


def _solve(scene: Scene, shape: ShaftShape, mesh: ShaftMesh, t0: float, t_cad: float,
           factorizer: str, threads: int | None, say: Callable[[str], None],
           use_cache: bool = True):
    """One mesh solved (pipeline.solve_mesh) and its recovery estimate."""
    from shaftfem.fem.estimate import recovery_estimate
    from shaftfem.workflows.pipeline import solve_mesh

    result = solve_mesh(scene, shape, mesh, t0, t_cad, mesh.seconds, say, factorizer, threads,
                        use_cache=use_cache)
    return result, recovery_estimate(mesh, scene.material, result.modes)


def _bound(result: ModalResult, rec, prev: tuple) -> ErrorEstimate:
    from shaftfem.fem.estimate import combine, matched, volume_difference

    f, eta, kinds, dofs = prev
    m = result.modes
    return combine(m.frequencies, rec.relative, matched(m.kinds, kinds, f),
                   matched(m.kinds, kinds, eta), dofs,
                   method=f"recovery, confirmed on the adaptive round before ({dofs} DOFs)",
                   geometry=volume_difference(rec.volume, result.shape, result.scene.shaft))


def run_bounded(scene: Scene, estimate: bool = True, use_cache: bool = True,
                progress: Callable[[str], None] | None = None, factorizer: str = "auto",
                threads: int | None = None) -> tuple[ModalResult, ErrorEstimate | None,
                                                      Adapted | None]:
    """The modes with their error bounds: on a mesh adapted to the scene's target_error
    when it has one, else on its fixed mesh (bounded when `estimate`)."""
    if scene.target_error is not None:
        a = run_adaptive(scene, scene.target_error, scene.max_dofs, use_cache=use_cache,
                         progress=progress, factorizer=factorizer, threads=threads)
        return a.result, a.estimate, a
    from shaftfem.workflows.pipeline import run_modes

    result = run_modes(scene, use_cache=use_cache, progress=progress, factorizer=factorizer,
                       threads=threads)
    est = None
    if estimate:
        from shaftfem.fem.estimate import estimate_errors

        est = estimate_errors(result, progress=progress, factorizer=factorizer, threads=threads,
                              use_cache=use_cache)
    return result, est, None


def with_accuracy(scene: Scene, percent: float | None = None, max_dofs: int | None = None,
                  fixed: bool = False) -> Scene:
    """The scene asking for another bound (percent) and DOF budget; `fixed`: on its
    fixed mesh (the target is dropped unless one is given here)."""
    target = scene.target_error
    if fixed:
        target = None
    if percent is not None:
        target = percent / 100
    return replace(scene, target_error=target,
                   max_dofs=scene.max_dofs if max_dofs is None else max_dofs)
