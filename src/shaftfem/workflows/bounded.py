"""Every modal command's entry point: the modes with an error bound for each frequency.

A scene with a target error is solved on meshes adapted to it (workflows.adapt) at
order 2, or with element orders adapted on its mesh up to its order 3 to 5
(workflows.order_adapt). Otherwise its fixed mesh is solved and, when asked, bounded by its recovery
estimate confirmed on the same scene solved on a mesh COARSER times coarser
(fem.estimate says how the two combine).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene

if TYPE_CHECKING:
    from collections.abc import Callable

    import numpy as np

    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.fem.result import ModalResult
    from shaftfem.workflows.adapt import Adapted
    from shaftfem.workflows.route import Route

COARSER = 1.5        # size ratio of the coarser mesh behind a fixed mesh's estimate


@dataclass(frozen=True)
class Bounded:
    """A modal run with its bounds: the result, each frequency's bound (None when not
    asked for), and how the mesh was adapted (None on the scene's fixed mesh)."""

    result: ModalResult
    estimate: ErrorEstimate | None
    adapted: Adapted | None = None


def run_bounded(scene: Scene, estimate: bool = True,
                options: RunOptions = RunOptions(), choose: bool = False,
                solved: Callable[[ModalResult], object] | None = None) -> Bounded:
    """The modes with their error bounds (`Bounded.estimate.relative_error`, fractions
    of each frequency): adapted to the scene's target_error when it has one (the mesh at
    order 2, the element orders up to the scene's order 3 to 5), else on its fixed mesh
    (bounded when `estimate`). `choose`: an order-2 scene's target may be met on another
    discretisation, the one workflows.route chooses. Journal bearings without their load
    carry their reactions to the static loads (workflows.static). `solved(result)` is
    called as soon as the modes are known, before their bound is (design starts its
    pictures there)."""
    from shaftfem.workflows.static import equipped

    scene = equipped(scene, options)
    told = False   # whether `solved` heard of the modes
    if (choose and scene.target_error is not None and scene.mesh.order == 2
            and scene.mesh.geometry_order == 2):
        from shaftfem.workflows.route import choose_route

        bounded = run_route(choose_route(scene, scene.target_error, scene.max_dofs), options)
    elif scene.target_error is not None:
        if scene.mesh.order >= 3:
            from shaftfem.workflows.order_adapt import run_order_adaptive as run
        else:
            from shaftfem.workflows.adapt import run_adaptive as run

        a = run(scene, scene.target_error, scene.max_dofs, options)
        bounded = Bounded(a.result, a.estimate, a)
    else:
        from shaftfem.workflows.pipeline import Stopwatch, built, solve_mesh

        watch = Stopwatch()
        placed, shape, mesh = built(scene, options, watch)
        # a mesh just made: the bound's coarser one is made and solved beside this solve
        ahead = (CoarseAhead.start(placed, options)
                 if estimate and not mesh.from_cache else None)
        try:
            result = solve_mesh(placed, shape, mesh, options, watch)
            if solved is not None:
                solved(result)
                told = True
            bounded = Bounded(result, timed_estimate(result, options, ahead)
                              if estimate else None)
        finally:
            if ahead is not None:
                ahead.close()
    if solved is not None and not told:
        solved(bounded.result)
    _warn_if_implausible(bounded.result)
    return bounded


def run_route(route: Route, options: RunOptions = RunOptions()) -> Bounded:
    """A route chosen for an accuracy: adapted at order 2, or its fixed mesh bounded,
    the target reached when every bound is below it."""
    import time

    import numpy as np

    from shaftfem.workflows.adapt import Adapted, Round, run_adaptive
    from shaftfem.workflows.pipeline import run_modes

    scene = route.scene
    target = scene.target_error
    assert target is not None  # a route is chosen for a target
    options.say(f"accuracy {100 * target:g} %: {route.why}")
    if route.adaptive:
        a = run_adaptive(scene, target, scene.max_dofs, options)
        return Bounded(a.result, a.estimate, replace(a, chosen=route.why))
    t = time.perf_counter()
    result = run_modes(replace(scene, target_error=None), options)
    est = timed_estimate(result, options)
    largest = float(np.max(est.relative_error))
    reached = largest <= target
    why = "" if reached else (
        f"the largest bound is {100 * largest:.2g} %, above {100 * target:g} %: this route "
        f"bounds no better on this shaft; --order 2 --accuracy {100 * target:g} adapts the "
        "mesh instead, at more DOFs")
    rounds = (Round(result.modes.n_dofs, largest, time.perf_counter() - t),)
    return Bounded(result, est, Adapted(result, est, target, scene.max_dofs, rounds, reached,
                                        why, from_cache=False, chosen=route.why))


def _warn_if_implausible(result: ModalResult) -> None:
    """A first frequency no machine shaft has, said once per run (on stderr from the
    command line): most often lengths given in metres."""
    import warnings

    from shaftfem.scene.checks import PlausibilityWarning, implausible_frequency

    if result.modes.count:
        for message in implausible_frequency(result.scene.source,
                                             float(result.modes.frequencies[0])):
            warnings.warn(message, PlausibilityWarning, stacklevel=3)


def timed_estimate(result: ModalResult, options: RunOptions = RunOptions(),
                   ahead: CoarseAhead | None = None) -> ErrorEstimate:
    """estimate_errors, with the wall time it took (`ErrorEstimate.seconds`)."""
    import time

    t = time.perf_counter()
    est = estimate_errors(result, options, ahead=ahead)
    return replace(est, seconds=time.perf_counter() - t)


# the bounds kept in the cache: raise when what makes a bound changes
BOUND_VERSION = 1
BOUND_FIELDS = ("relative_error", "recovery", "two_mesh", "reliable", "coarse_dofs", "method",
                "geometry", "notes", "straightening")


def estimate_errors(result: ModalResult, options: RunOptions = RunOptions(),
                    ratio: float = COARSER, ahead: CoarseAhead | None = None) -> ErrorEstimate:
    """The bound of a fixed mesh's frequencies (`bound_of`), kept in the cache by the
    content of everything that makes it (the scene's shaft, material, seats and parts,
    the mode request, the mesh's settings and its very nodes and cells), unless the
    options say not to: a warm run of the same scene reads it back."""
    import numpy as np

    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.store import cache_dir, discard, load_arrays, save_arrays
    from shaftfem.workflows.pipeline import _solve_path

    if not options.use_cache:
        return bound_of(result, options, ratio, ahead)
    # the key of a solve of this scene on this mesh, in a space of its own
    stem = _solve_path(result.scene, result.mesh,
                       f"bound {BOUND_VERSION} {ratio:g} {result.modes.count}").stem
    path = cache_dir() / "bounds" / f"{stem}.npz"
    if path.exists():
        fields, why = load_arrays(path, BOUND_FIELDS)
        if fields is not None and fields["relative_error"].shape == (result.modes.count,):
            options.say("error estimate: this mesh's bound, from the cache")
            return ErrorEstimate(
                relative_error=fields["relative_error"], recovery=fields["recovery"],
                two_mesh=fields["two_mesh"], reliable=fields["reliable"].astype(bool),
                coarse_dofs=int(fields["coarse_dofs"]), method=str(fields["method"]),
                geometry=float(fields["geometry"]),
                notes=tuple(str(n) for n in fields["notes"]),
                straightening=(None if fields["straightening"].size == 0
                               else fields["straightening"]))
        discard("error bound", why or "another mode count", path)
    est = bound_of(result, options, ratio, ahead)
    try:
        save_arrays(path, {
            "relative_error": est.relative_error, "recovery": est.recovery,
            "two_mesh": est.two_mesh, "reliable": est.reliable,
            "coarse_dofs": np.int64(est.coarse_dofs), "method": np.str_(est.method),
            "geometry": np.float64(est.geometry), "notes": np.array(est.notes, dtype=str),
            "straightening": (np.zeros(0) if est.straightening is None
                              else est.straightening)})
    except OSError:   # a cache that cannot be written costs time, not the result
        pass
    return est


def bound_of(result: ModalResult, options: RunOptions = RunOptions(),
             ratio: float = COARSER, ahead: CoarseAhead | None = None) -> ErrorEstimate:
    """The bound of a fixed mesh's frequencies: its recovery estimate, confirmed by the
    same scene solved on a mesh `ratio` times coarser (cached like any solve, unless
    the options say not to; solved in another process while this one solved the fine
    mesh where `ahead` did)."""
    from shaftfem.fem.estimate import (
        RECOVERY_SHORTFALL,
        combine,
        geometry_allowances,
        matched,
        recovery_estimate,
        with_straightening,
    )
    if result.system.degrees is not None and result.system.order > result.mesh.geometry_order:
        return hierarchy_errors(result, options)
    scene, m = result.scene, result.modes
    size_mm = scene.mesh.size * 1e3 * ratio
    options.say(f"error estimate: recovery on this mesh, and a coarser mesh ({size_mm:.3g} mm)")
    fine = recovery_estimate(result.mesh, scene.material, m)
    side = ahead.result(scene, m.count, ratio) if ahead is not None else None
    if side is None:
        side = coarse_side(scene, m.count, ratio, options)
    geometry, straightened = geometry_allowances(result.mesh, result.shape, scene.shaft,
                                                 scene.material, m, fine.volume)
    return with_straightening(
        combine(m.frequencies, fine.relative,
                matched(m.kinds, side.kinds, side.frequencies),
                matched(m.kinds, side.kinds, side.recovery), side.n_dofs,
                method=f"recovery, confirmed on a {ratio:g}x coarser mesh", geometry=geometry,
                # no BREP: a plain bar, meshed as one sector copied round the axis
                shortfall=1.0 if result.shape.brep is None else RECOVERY_SHORTFALL,
                shifts=(straightened.shift, matched(m.kinds, side.kinds, side.shift))),
        m.frequencies, straightened.relative)


@dataclass(frozen=True)
class CoarseSide:
    """What the bound takes of the coarser mesh's solve: its modes' frequencies (Hz),
    kinds, recovery estimates and straightening shifts, and its DOF count."""

    frequencies: np.ndarray
    kinds: list[str]
    recovery: np.ndarray
    shift: np.ndarray
    n_dofs: int


def coarse_side(scene: Scene, count: int, ratio: float = COARSER,
                options: RunOptions = RunOptions()) -> CoarseSide:
    """The scene solved on a mesh `ratio` times coarser, as many modes as the fine run
    (counted: a frequency limit could select others on a coarse mesh)."""
    from shaftfem.fem.estimate import recovery_estimate, straightening
    from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes

    coarse_scene = with_modes(with_mesh(scene, scene.mesh.size * 1e3 * ratio), count=count)
    coarse = run_modes(coarse_scene, replace(options, progress=None))
    return CoarseSide(
        frequencies=coarse.modes.frequencies, kinds=list(coarse.modes.kinds),
        recovery=recovery_estimate(coarse.mesh, scene.material, coarse.modes).relative,
        shift=straightening(coarse.mesh, scene.material, coarse.modes).shift,
        n_dofs=coarse.modes.n_dofs)


class CoarseAhead:
    """The bound's coarser mesh made and solved in another process while this one solves
    the fine mesh, so that the two share the machine's cores (started where the fine mesh
    was just made: on a warm run the bound comes from the cache). That process is a new
    Python (`python -m shaftfem.workflows.bounded IN OUT`, the scene handed over as a
    pickle), never a copy of the caller's: a user's script is not run again in it, as
    multiprocessing's spawn would. Its answer is taken only for the very scene, mode
    count and ratio the bound asks; else, or if that process failed, the bound solves
    the coarse mesh itself."""

    def __init__(self, scene: Scene, count: int, ratio: float, process, folder) -> None:
        self.asked = (scene, count, ratio)
        self._process, self._folder = process, folder

    @classmethod
    def start(cls, scene: Scene, options: RunOptions, ratio: float = COARSER
              ) -> CoarseAhead | None:
        import pickle
        import subprocess
        import sys
        import tempfile
        from pathlib import Path

        from shaftfem.cad.solid import needs_cad

        if (scene.mesh.order > 2 or scene.modes.max_frequency is not None
                or not needs_cad(scene.shaft, scene.grooves)):
            return None
        folder = tempfile.TemporaryDirectory(prefix="shaftfem-bound-")
        asked = Path(folder.name) / "asked.pickle"
        quiet = replace(options, progress=None)
        asked.write_bytes(pickle.dumps((scene, scene.modes.count, ratio, quiet)))
        process = subprocess.Popen(
            [sys.executable, "-m", "shaftfem.workflows.bounded", str(asked),
             str(Path(folder.name) / "side.pickle")], stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return cls(scene, scene.modes.count, ratio, process, folder)

    def result(self, scene: Scene, count: int, ratio: float) -> CoarseSide | None:
        import pickle
        from pathlib import Path

        if (scene, count, ratio) != self.asked or self._process.wait() != 0:
            return None   # the bound solves it here, where its error is said
        try:
            side = pickle.loads((Path(self._folder.name) / "side.pickle").read_bytes())
        except Exception:   # likewise
            return None
        return side if isinstance(side, CoarseSide) else None

    def close(self) -> None:
        """Stop the other process if it still runs (an error or Ctrl-C here)."""
        if self._process.poll() is None:
            self._process.terminate()
            self._process.wait()
        self._folder.cleanup()


def _coarse_main(asked: str, out: str) -> None:
    """The other process of CoarseAhead: the coarse side of the scene in `asked`, kept in
    `out` (both pickles)."""
    import pickle
    from pathlib import Path

    from shaftfem.runtime import configure_threads

    configure_threads()
    scene, count, ratio, options = pickle.loads(Path(asked).read_bytes())
    side = coarse_side(scene, count, ratio, options)
    Path(out).write_bytes(pickle.dumps(side))


def hierarchy_errors(result: ModalResult, options: RunOptions = RunOptions()) -> ErrorEstimate:
    """The bound of a hierarchical (order p >= 3) run's frequencies from the lower orders
    inside the same space (fem.hierarchy), whose frequencies are never below order p's:
    orders p - 1 and p - 2 measure the rate of convergence (fem.estimate.hierarchy_estimate).
    No order below the geometry's moves the body rigidly (x is not in its space), so order
    3 on quadratic geometry and order 4 on cubic have only one order below them, whose
    recovery estimate gives the ratio of the errors (combine). (Order 3 on cubic geometry
    has none: estimate_errors confirms it on a coarser mesh.)"""
    import numpy as np

    from shaftfem.fem.estimate import (
        combine,
        geometry_allowances,
        hierarchy_estimate,
        matched,
        mesh_volume,
        recovery_estimate,
        with_straightening,
    )
    from shaftfem.fem.hierarchy import lower_order, raised

    scene, m, system = result.scene, result.modes, result.system
    p = system.order
    below = min(2, p - result.mesh.geometry_order)
    options.say(f"error estimate: order{'s' if below > 1 else ''} "
                f"{', '.join(str(p - k) for k in range(below, 0, -1))} inside order {p}'s space")
    geometry, straightened = geometry_allowances(result.mesh, result.shape, scene.shaft,
                                                 scene.material, m, mesh_volume(result.mesh))
    lower, keep = lower_order(system)
    first = _solve_lower(lower, result, options)
    f1 = matched(m.kinds, first.kinds, first.frequencies)
    if below == 2:
        second = _solve_lower(lower_order(lower)[0], result, options)
        f = (matched(m.kinds, second.kinds, second.frequencies), f1, m.frequencies)
        dofs = (second.n_dofs, first.n_dofs, m.n_dofs)
        # the recovery estimate (seconds at order 5) is only the fallback of a mode
        # whose rate the three orders do not measure
        est = hierarchy_estimate(f, dofs, np.full(m.count, np.nan), geometry)
        if not np.isfinite(est.two_mesh).all():
            est = hierarchy_estimate(f, dofs, recovery_estimate(result.mesh, scene.material,
                                                                m).relative, geometry)
        return with_straightening(est, m.frequencies, straightened.relative)
    fine = recovery_estimate(result.mesh, scene.material, m)
    low = replace(first, shapes=raised(first.shapes, keep, system.nodes.shape[0]))
    ceta = recovery_estimate(result.mesh, scene.material, low).relative
    return with_straightening(
        combine(m.frequencies, fine.relative, f1, matched(m.kinds, first.kinds, ceta),
                first.n_dofs, method=f"recovery, confirmed by order {p - 1} in the same space",
                geometry=geometry), m.frequencies, straightened.relative)


def _solve_lower(system, result: ModalResult, options: RunOptions):
    """The modes of a lower order's system, as many as the run's (with the cache,
    refined from this order's last solve on the mesh, like any solve), their count
    proven under the run's own: the lower order's space lies inside the run's."""
    from shaftfem.fem.eigen import SolverSettings
    from shaftfem.workflows.pipeline import solve_system

    scene = result.scene
    request = replace(scene.modes, count=result.modes.count, max_frequency=None)
    lower = replace(scene, modes=request, mesh=replace(scene.mesh, order=system.order))
    return solve_system(lower, result.mesh, system, options, SolverSettings(options.factoriser),
                        space=f"inside order {result.system.order}",
                        ceiling=(result.modes.inertia_shift, result.modes.inertia_count))


def with_accuracy(scene: Scene, percent: float | None = None, max_dofs: int | None = None,
                  fixed: bool = False) -> Scene:
    """The scene asking for another bound (`percent`, %) and DOF budget; `fixed`: on
    its fixed mesh (the target is dropped unless one is given here)."""
    target = scene.target_error
    if fixed:
        target = None
    if percent is not None:
        target = percent / 100
    return replace(scene, target_error=target,
                   max_dofs=scene.max_dofs if max_dofs is None else max_dofs)


if __name__ == "__main__":
    import sys

    # the module's own copy (not this __main__'s), so that what it pickles names it
    from shaftfem.workflows import bounded

    bounded._coarse_main(sys.argv[1], sys.argv[2])
