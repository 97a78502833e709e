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
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.cad.mesh import (
    MESH_ARRAYS,
    ShaftMesh,
    check_budget,
    check_mesh_budget,
    generate_mesh,
    mesh_arrays,
    mesh_from_arrays,
)
from shaftfem.cad.solid import ShaftShape
from shaftfem.fem.estimate import (
    SAFETY,
    ErrorEstimate,
    Recovery,
    combine,
    geometry_allowances,
    matched,
    recovery_estimate,
    with_straightening,
)
from shaftfem.fem.result import ModalResult
from shaftfem.runtime import RunOptions
from shaftfem.store import cache_dir, content_key, discard, load_arrays, save_arrays
from shaftfem.workflows import stages
from shaftfem.workflows.pipeline import Stopwatch, check_order, solve_mesh, with_modes

if TYPE_CHECKING:
    from shaftfem.scene.model import Scene

ADAPT_VERSION = 1
AIM = 0.5             # aim each new mesh at half the target: fewer rounds
POWER = 7.0           # 2k + d for P2 elements in 3D (2k + 3 for order k: power(order))
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
    what: str = "mesh"   # what was adapted: the mesh, or the element orders on one mesh
    chosen: str = ""     # the route --accuracy chose, and why (workflows.route); '' if none

    def summary(self) -> str:
        steps = " -> ".join(f"{r.dofs} DOFs, bound {100 * r.max_bound:.2g} %"
                            for r in self.rounds)
        state = (f"{'reached' if self.reached else 'NOT reached'}"
                 f"{' (from cache)' if self.from_cache else ''}; {steps}")
        if self.chosen:
            head = (f"accuracy {100 * self.target:g} %: chose {self.chosen}\n"
                    f"bounds below {100 * self.target:g} %: {state}")
        else:
            head = f"adaptive {self.what} for bounds below {100 * self.target:g} %: {state}"
        return head if self.reached else f"{head}\n{self.why}"


def element_sizes(mesh: ShaftMesh) -> np.ndarray:
    """Mean edge length of each element, m."""
    v = mesh.points[mesh.cells[:, :4]]
    pairs = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))
    return np.mean([np.linalg.norm(v[:, a] - v[:, b], axis=1) for a, b in pairs], axis=0)


def power(order: int) -> float:
    """How fast an element's share of the error falls with its size where the solution is
    smooth: h^(2k + 3) for order k in 3D (POWER for P2)."""
    return POWER + 2.0 * (order - 2)


def size_field(mesh: ShaftMesh, shares: np.ndarray, target: float, largest: float
               ) -> tuple[np.ndarray, float]:
    """Sizes at the mesh's vertices for the next mesh, and its predicted element count.

    shares: (n_modes, n_elements) each element's part of each mode's error (fraction of
    the frequency); every mode's total is aimed at AIM * target."""
    h = element_sizes(mesh)
    aim = AIM * target
    e = np.maximum(shares, 1e-300)
    q = power(mesh.order)
    # equidistribution: N' tau = aim with N' = sum (e / tau)^(3 / q)
    tau = (aim / np.sum(e ** (3 / q), axis=1)) ** (q / (q - 3))
    r = np.max((e / tau[:, None]) ** (1 / q), axis=0)
    r = np.clip(r, 1.0, REFINE_MAX)
    new = np.clip(h / r, SMALLEST, largest)
    vertices = mesh.cells[:, :4]
    at = np.full(mesh.points.shape[0], np.inf)
    np.minimum.at(at, vertices.ravel(), np.repeat(new, 4))
    at[~np.isfinite(at)] = largest
    return at, float(np.sum((h / new) ** 3))


def adapt_key(scene: Scene, shape: ShaftShape, target: float, max_dofs: int) -> str:
    """A hash of everything the adapted mesh depends on."""
    mesh = stages.mesh_key(shape, scene.shaft, scene.grooves, scene.mesh, scene.seat_cuts(),
                           scene.hubs())
    payload = {"version": ADAPT_VERSION, "mesh": mesh,
               "order": scene.mesh.order,  # the mesh's key leaves the element order out
               "target": target, "max_dofs": max_dofs, "modes": scene.modes.count,
               "max_frequency": scene.modes.max_frequency,
               "material": [scene.material.youngs_modulus, scene.material.poisson_ratio,
                            scene.material.density],
               "constants": [AIM, POWER, REFINE_MAX, SMALLEST, MAX_ROUNDS],
               **({"installed": [asdict(p) for p in scene.held + scene.attachments]}
                  if scene.installed else {})}
    return content_key(payload)


@dataclass(frozen=True)
class Coarser:
    """What a round's bound needs from the round before: its frequencies, recovery
    estimates (fraction), mode kinds and DOFs."""

    frequencies: np.ndarray
    recovery: np.ndarray
    kinds: list[str]
    dofs: int


HISTORY = ("prev_f", "prev_eta", "prev_kinds", "prev_dofs", "round_dofs", "round_bound",
           "round_seconds", "reached", "why")


def _save(path: Path, mesh: ShaftMesh, prev: Coarser, rounds: list[Round], reached: bool,
          why: str) -> None:
    save_arrays(path, dict(mesh_arrays(mesh), prev_f=prev.frequencies, prev_eta=prev.recovery,
                           prev_kinds=np.array(prev.kinds), prev_dofs=np.int64(prev.dofs),
                           round_dofs=np.array([r.dofs for r in rounds]),
                           round_bound=np.array([r.max_bound for r in rounds]),
                           round_seconds=np.array([r.seconds for r in rounds]),
                           reached=np.bool_(reached), why=np.str_(why)))


def run_adaptive(scene: Scene, target: float, max_dofs: int,
                 options: RunOptions = RunOptions()) -> Adapted:
    """Solve `scene` on meshes adapted until every frequency's bound is below `target`
    (fraction) or the next mesh would exceed `max_dofs`."""
    watch = Stopwatch()
    check_order(scene)
    check_budget(scene.shaft, scene.grooves, scene.mesh, max_dofs, scene.hubs())
    with watch.lap("cad"):
        scene, shape = stages.solid(scene, use_cache=options.use_cache)
    if scene.shaft.step is not None:  # its budget now that the import measured it
        check_budget(scene.shaft, scene.grooves, scene.mesh, max_dofs, scene.hubs())
    path = cache_dir() / "adapted" / f"{adapt_key(scene, shape, target, max_dofs)}.npz"
    if options.use_cache and path.exists():
        cached = _cached(path, scene, shape, target, max_dofs, options, watch)
        if cached is not None:
            return cached
    with watch.lap("mesh"):
        mesh = stages.mesh(shape, scene.shaft, scene.grooves, scene.mesh,
                           use_cache=options.use_cache, cuts=scene.seat_cuts(),
                           hubs=scene.hubs())
    check_mesh_budget(mesh, scene.mesh, max_dofs)   # the first mesh's own count
    return _adapt(scene, shape, mesh, target, max_dofs, options, watch, path)


def _cached(path: Path, scene: Scene, shape: ShaftShape, target: float, max_dofs: int,
            options: RunOptions, watch: Stopwatch) -> Adapted | None:
    """The cached adapted mesh solved once, bounded with the round before it kept beside
    it; None (and the entry discarded) where the entry is damaged."""
    z, why = load_arrays(path, MESH_ARRAYS + HISTORY)
    if z is None:
        discard(f"adapted mesh {path.stem}", why, path)
        return None
    options.say("adapted mesh from cache; solving")
    kept = Coarser(z["prev_f"], z["prev_eta"], [str(k) for k in z["prev_kinds"]],
                   int(z["prev_dofs"]))
    history = [Round(int(d), float(b), float(s)) for d, b, s in
               zip(z["round_dofs"], z["round_bound"], z["round_seconds"])]
    result, rec = _solve(scene, shape, mesh_from_arrays(z), options, watch)
    return Adapted(result=result, estimate=_bound(result, rec, kept), target=target,
                   max_dofs=max_dofs, rounds=tuple(history), reached=bool(z["reached"]),
                   why=str(z["why"]), from_cache=True)


def _adapt(scene: Scene, shape: ShaftShape, mesh: ShaftMesh, target: float, max_dofs: int,
           options: RunOptions, watch: Stopwatch, path: Path) -> Adapted:
    """The rounds: solve, bound against the round before, stop or remesh."""
    prev: Coarser | None = None
    rounds: list[Round] = []
    est = None
    while True:
        t = time.perf_counter()
        options.say(f"adaptive round {len(rounds) + 1}: {mesh.n_elements} elements; solving")
        result, rec = _solve(scene, shape, mesh, options, watch)
        if prev is None:
            # the modes of the first mesh fix which modes are followed from round to round
            scene = with_modes(scene, count=result.modes.count)
            bound = planning_bound(rec.relative)
        else:
            est = _bound(result, rec, prev)
            bound = est.relative_error
        rounds.append(Round(result.modes.n_dofs, float(np.max(bound)), time.perf_counter() - t))
        options.say(f"adaptive round {len(rounds)}: {result.modes.n_dofs} DOFs, largest bound "
                    f"{100 * np.max(bound):.2g} %")
        # modes the coarser mesh cannot confirm (errors below its geometric noise) count
        # with their recovery bound, marked as such in the table
        reached = est is not None and np.max(bound) <= target
        why = "" if reached else _why_stop(rounds, bound)
        if reached or why:
            break
        sizes, predicted, why = _next_sizes(scene, result, rec, bound, target, max_dofs,
                                            bounded=est is not None)
        if why:
            break
        prev = Coarser(result.modes.frequencies, rec.relative, result.modes.kinds,
                       result.modes.n_dofs)
        options.say(f"adaptive round {len(rounds) + 1}: remeshing (about "
                    f"{min(predicted, max_dofs)} DOFs)")
        with watch.lap("mesh"):
            mesh = generate_mesh(shape, scene.shaft, scene.grooves, scene.mesh,
                                 (mesh.points, mesh.cells[:, :4], sizes), scene.seat_cuts())
    if est is None or prev is None:
        raise AssertionError("an adaptive run ends with a bounded round")
    if options.use_cache:
        _save(path, result.mesh, prev, rounds, reached, why)
    return Adapted(result=result, estimate=est, target=target, max_dofs=max_dofs,
                   rounds=tuple(rounds), reached=reached, why=why, from_cache=False)


def _why_stop(rounds: list[Round], bound: np.ndarray) -> str:
    if len(rounds) >= MAX_ROUNDS:
        return (f"stopped after {MAX_ROUNDS} rounds with a largest bound of "
                f"{100 * np.max(bound):.2g} %")
    return ""


def _next_sizes(scene: Scene, result: ModalResult, rec: Recovery, bound: np.ndarray,
                target: float, max_dofs: int, bounded: bool) -> tuple[np.ndarray, int, str]:
    """The next mesh's sizes at this mesh's vertices and its predicted DOFs; or why
    there is no next mesh (the budget, once a bound exists)."""
    mesh = result.mesh
    # each element's share of each mode's error, scaled up to the mode's bound
    shares = rec.elements * (bound / np.maximum(rec.relative, 1e-300))[:, None]
    sizes, n_next = size_field(mesh, shares, target, scene.mesh.size)
    predicted = int(result.modes.n_dofs * n_next / mesh.n_elements)
    if predicted > max_dofs:
        if bounded:
            return sizes, predicted, (
                f"the next mesh would need about {predicted} DOFs, above the budget "
                f"of {max_dofs} DOFs (--max-dofs); the bounds shown are those "
                f"reached at {result.modes.n_dofs} DOFs")
        # a bound needs two meshes: take one within the budget
        scale = (max_dofs / predicted) ** (1 / 3)
        sizes = np.minimum(sizes / scale, scene.mesh.size)
    return sizes, predicted, ""


def planning_bound(recovery: np.ndarray) -> np.ndarray:
    """Before a second mesh exists: the recovery estimate with the safety factor (it may
    fall short; it only plans the next mesh)."""
    return SAFETY * recovery


def _solve(scene: Scene, shape: ShaftShape, mesh: ShaftMesh, options: RunOptions,
           watch: Stopwatch) -> tuple[ModalResult, Recovery]:
    """One mesh solved (pipeline.solve_mesh) and its recovery estimate."""
    result = solve_mesh(scene, shape, mesh, options, watch)
    return result, recovery_estimate(mesh, scene.material, result.modes)


def _bound(result: ModalResult, rec: Recovery, prev: Coarser) -> ErrorEstimate:
    m = result.modes
    geometry, straightened = geometry_allowances(result.mesh, result.shape, result.scene.shaft,
                                                 result.scene.material, m, rec.volume)
    return with_straightening(
        combine(m.frequencies, rec.relative, matched(m.kinds, prev.kinds, prev.frequencies),
                matched(m.kinds, prev.kinds, prev.recovery), prev.dofs,
                method=f"recovery, confirmed on the adaptive round before ({prev.dofs} DOFs)",
                geometry=geometry), m.frequencies, straightened.relative)
