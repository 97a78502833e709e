"""The modal chain, one step after another: Scene -> shape -> mesh -> K, M -> modes.

Each step is a function of the one before; this module only calls them in order
and keeps what each produced and how long it took.
"""

from __future__ import annotations

import math
import time
import weakref
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from typing import TYPE_CHECKING

from shaftfem.errors import SceneError
from shaftfem.fem.result import ModalResult, Timings
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Attachment, Scene, Support

if TYPE_CHECKING:  # the steps' modules load gmsh, scikit-fem and SciPy: only when run
    from pathlib import Path

    import numpy as np

    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.cad.solid import ShaftShape
    from shaftfem.fem.assembly import System
    from shaftfem.fem.eigen import SolverSettings
    from shaftfem.fem.installation import Installed
    from shaftfem.fem.modes import Modes


class Stopwatch:
    """The laps of one run: `with watch.lap("mesh"): ...`, then `watch.timings()`."""

    def __init__(self) -> None:
        self.start = time.perf_counter()
        self.laps: dict[str, float] = {}

    @contextmanager
    def lap(self, name: str) -> Iterator[None]:
        t = time.perf_counter()
        try:
            yield
        finally:
            self.laps[name] = self.laps.get(name, 0.0) + time.perf_counter() - t

    def timings(self) -> Timings:
        return Timings(**self.laps, total=time.perf_counter() - self.start)


def with_mesh(scene: Scene, size_mm: float | None = None, order: int | None = None,
              geometry_order: int | None = None) -> Scene:
    """The scene with another element size away from the grooves, mm (the groove sizes
    scaled alike), element order (1 to 5) and/or geometry order (2, 3)."""
    m = scene.mesh
    if size_mm is not None:
        if not 0 < size_mm <= (scene.shaft.length * 1e3 or math.inf):  # also refuses nan
            raise SceneError(f"element size {size_mm:g} mm: must be > 0 and not exceed the "
                             f"shaft length ({scene.shaft.length * 1e3:g} mm)")
        k = size_mm * 1e-3 / m.size
        m = replace(m, size=m.size * k, groove_size=m.groove_size * k, edge_size=m.edge_size * k)
    if order is not None:
        m = replace(m, order=order)
    if geometry_order is not None:
        m = replace(m, geometry_order=geometry_order)
    return replace(scene, mesh=m)


def check_order(scene: Scene) -> None:
    """Cubic elements take free shafts only: seats and parts read nodal values; cubic
    geometry takes the hierarchical elements (orders 3 to 5) only."""
    if scene.mesh.geometry_order == 3 and scene.mesh.order < 3:
        raise SceneError(f"{scene.source}: geometry order 3 with element order "
                         f"{scene.mesh.order}: cubic geometry takes element orders 3 to 5; "
                         "use --order 3, 4 or 5 ([mesh] order), or geometry order 2")
    if scene.mesh.order > 2 and scene.installed:
        raise SceneError(f"{scene.source}: element order {scene.mesh.order}: cubic elements "
                         "take free shafts only for now; use order 2 (or --free on a scene "
                         "whose only tables of that kind are [[support]])")


def with_modes(scene: Scene, count: int | None = None,
               max_frequency: float | None = None) -> Scene:
    """The scene asking for another number of modes, or every mode below max_frequency (Hz)."""
    if count is None and max_frequency is None:
        return scene
    req = scene.modes
    if count is not None:
        req = replace(req, count=count, max_frequency=None)
    if max_frequency is not None:
        req = replace(req, max_frequency=max_frequency)
    return replace(scene, modes=req)


def check_buildable(scene: Scene) -> None:
    """The scene's element orders and DOF budget, checked before anything is built (a
    STEP shaft's budget again once its import has measured it: before, its length is 0)."""
    from shaftfem.cad.mesh import check_budget

    check_order(scene)
    check_budget(scene.shaft, scene.grooves, scene.mesh, scene.max_dofs, scene.hubs())


def run_modes(scene: Scene, options: RunOptions = RunOptions()) -> ModalResult:
    """Build, mesh, assemble and solve `scene`: the modes without a bound, with every
    intermediate result. Raises GeometryError, MeshError or SolverError, each naming
    what failed."""
    watch = Stopwatch()
    scene, shape, mesh = built(scene, options, watch)
    return solve_mesh(scene, shape, mesh, options, watch)


def built(scene: Scene, options: RunOptions = RunOptions(), watch: Stopwatch | None = None
          ) -> tuple[Scene, ShaftShape, ShaftMesh]:
    """The scene's solid and mesh (each from the cache when it holds them), checked
    against the budgets; the scene as placed (a STEP shaft's)."""
    from shaftfem.cad.mesh import check_memory, check_mesh_budget
    from shaftfem.workflows import stages

    watch = watch or Stopwatch()
    check_buildable(scene)
    options.say("building the shaft's solid (CAD)")
    with watch.lap("cad"):
        scene, shape = stages.solid(scene, use_cache=options.use_cache)
    if scene.shaft.step is not None:
        check_buildable(scene)
    options.say(f"CAD done ({'from cache' if shape.from_cache else 'built'}), meshing")
    with watch.lap("mesh"):
        mesh = stages.mesh(shape, scene.shaft, scene.grooves, scene.mesh,
                           use_cache=options.use_cache, cuts=scene.seat_cuts(),
                           hubs=scene.hubs())
    options.say(f"mesh: {mesh.n_elements} elements{' (from cache)' if mesh.from_cache else ''}; "
                "assembling K and M")
    check_memory(check_mesh_budget(mesh, scene.mesh, scene.max_dofs))
    return scene, shape, mesh


def solve_mesh(scene: Scene, shape: ShaftShape, mesh: ShaftMesh,
               options: RunOptions = RunOptions(), watch: Stopwatch | None = None
               ) -> ModalResult:
    """Assemble and solve one mesh of the scene's solid (`watch`: the run's laps so far).

    With the cache: start from the shift where the last solve of this scene (any mesh)
    proved its modes complete, and keep this solve's (see fem.eigen.solve_modes)."""
    from shaftfem.fem.assembly import assemble, discretise
    from shaftfem.fem.eigen import SolverSettings
    from shaftfem.fem.factor import analyse_in_background, uses_pardiso
    from shaftfem.workflows.equip import with_parts

    scene = with_parts(scene)   # the installed shaft holds its bearings' stiffness
    watch = watch or Stopwatch()
    solved = _solved_here(scene, mesh, options)
    if solved is not None:
        options.say(f"{solved.modes.n_dofs} DOFs; the lowest {scene.modes.count} of the "
                    f"{solved.modes.count} modes solved on this mesh in this run")
        modes = solved.modes.lowest(scene.modes.count)
        # the same K and M, but the parts (their names, a stage's cross-coupling) are
        # this scene's: the rotor model reads them from the installation
        installed = (None if solved.installed is None
                     else solved.installed.for_scene(solved.scene, scene))
        return replace(solved, scene=scene, shape=shape, modes=modes, installed=installed,
                       timings=watch.timings(), warnings=scene_warnings(scene, modes))
    with watch.lap("assembly"):
        d = discretise(mesh)
        # The solver's ordering needs only the sparsity: it runs while K and M are filled
        # (a free shaft's: seats change the sparsity).
        pardiso = uses_pardiso(options.factoriser, d.n_dofs, 9 * d.pattern.n_blocks)
        analysis = (analyse_in_background(d.upper_structure())
                    if not scene.installed and pardiso else None)
        system = assemble(mesh, scene.material, threads=options.threads, discretisation=d)
        installed = None
        if scene.installed:
            from shaftfem.fem.installation import install

            installed = install(scene, system.K, system.M, system.nodes, d.basis.mesh, d.order)
    # nothing after assembly reads the basis at the quadrature points: let it go before
    # the factorisations (order 5 at 254k DOFs: 0.1 GB at once, the run's peak sampled
    # at 6.06 GB with it kept, 5.74 GB without)
    del d
    n_dofs = system.n_dofs if installed is None else installed.K.shape[0]
    options.say(f"{n_dofs} DOFs; factorising and solving")
    with watch.lap("solve"):
        modes = solve_system(scene, mesh, system, options,
                             SolverSettings(options.factoriser, analysis=analysis), installed)
    result = ModalResult(scene=scene, shape=shape, mesh=mesh, system=system, modes=modes,
                         timings=watch.timings(), warnings=scene_warnings(scene, modes),
                         installed=installed)
    _keep_here(result, options)
    return result


# The solves of this process that are still in use, by their pencil and mesh
# (_solve_path): a solve of fewer modes of the same pencil on the same mesh takes the
# lowest of one of more (the design's standstill modes, those of the whirl's basis,
# which the rotor model keeps), not assembling K and M again. Held weakly: a solve
# nothing else holds (a sweep's last variant) is let go as before.
_SOLVED: weakref.WeakValueDictionary[str, ModalResult] = weakref.WeakValueDictionary()


def _here_key(scene: Scene, mesh: ShaftMesh, options: RunOptions) -> str | None:
    if not options.use_cache or scene.modes.max_frequency is not None:
        return None
    return f"{options.factoriser}|{_solve_path(scene, mesh, '')}"


def _solved_here(scene: Scene, mesh: ShaftMesh, options: RunOptions) -> ModalResult | None:
    """A solve of this process on this pencil and mesh of more modes than the scene asks,
    where its lowest are a solve of their own (no pair split at the count)."""
    from shaftfem.fem.modes import DEGENERATE_SPLIT

    key = _here_key(scene, mesh, options)
    kept = _SOLVED.get(key) if key is not None else None
    n = scene.modes.count
    if kept is None or kept.modes.count <= n:
        return None
    # a pair split by the count would be another basis of that pair than a solve's own
    f = kept.modes.frequencies
    if f[n] - f[n - 1] <= 100 * DEGENERATE_SPLIT * f[n]:
        return None
    return kept


def _keep_here(result: ModalResult, options: RunOptions) -> None:
    key = _here_key(result.scene, result.mesh, options)
    if key is not None:
        _SOLVED[key] = result


def solve_system(scene: Scene, mesh: ShaftMesh, system: System, options: RunOptions,
                 settings: SolverSettings, installed: Installed | None = None,
                 space: str = "", ceiling: tuple[float, int] | None = None) -> Modes:
    """The scene's modes of `system` on `mesh` (`scene.mesh.order` its order; `space`
    names its basis where another of that order on the mesh differs from it, as a lower
    order inside a hierarchical space does from a Lagrange one).

    With the cache: factorised first at the shift where the last solve of this scene on
    this mesh proved its modes complete, and its shapes refined there instead of a new
    search (none kept: the last proven shift of the scene on any mesh); this solve's
    kept in turn (unless the options say not to). `ceiling`: see fem.eigen.search."""
    from shaftfem.fem.modes import modal_analysis

    path = (_solve_path(scene, mesh, space) if options.use_cache
            and scene.modes.max_frequency is None else None)
    # an installed shaft is solved, and its solve kept, in its reduced coordinates
    n = system.n_dofs if installed is None else installed.K.shape[0]
    last = last_solve(path, n, scene.modes.count) if path else None
    hint = last[0] if last else (shift_hint(scene) if options.use_cache else None)
    modes = modal_analysis(system, scene.modes, settings, installed=installed,
                           shift_hint=hint, start=last[1] if last else None, ceiling=ceiling)
    if options.use_cache and modes.inertia_shift != hint:
        keep_shift(scene, modes.inertia_shift)
    if path and options.keep_solves and (last is None or modes.inertia_shift != hint):
        keep_solve(path, modes.inertia_shift, solver_start(modes, installed))
    return modes


def solver_start(modes: Modes, installed: Installed | None = None) -> np.ndarray:
    """Every pair the solve proved below its inertia shift, in the coordinates its pencil
    is solved in (an installed shaft's reduced ones: the shaft's part from its
    displacements, then the coupled machines' turns): the next solve's start."""
    import numpy as np

    q = modes.shapes
    if installed is not None:
        q = installed.shaft_coordinates(q)
        q = q if modes.trains is None else np.vstack([q, modes.trains])
    return q if modes.beyond is None else np.hstack([q, modes.beyond])


def _pencil(scene: Scene) -> dict:
    """Everything that makes the scene's K and M but the mesh (of the supports, what
    _seated keeps)."""
    from dataclasses import asdict

    from shaftfem.workflows.stages import grooves_key

    return {"shaft": asdict(scene.shaft),
            "grooves": grooves_key(scene.grooves),
            "material": asdict(scene.material), "order": scene.mesh.order,
            "supports": [_seated(s) for s in scene.supports],
            "attachments": [_carried(a) for a in scene.attachments],
            "hanging_free": scene.hanging_free}


def _shift_path(scene: Scene):
    """Where the proven shift of the scene's pencil is kept, for as many modes as it
    asks: keyed by its pencil (_pencil) and mode request, not its mesh, so that a finer
    or adapted mesh of the same shaft starts from it too."""
    from dataclasses import asdict

    from shaftfem.store import cache_dir, content_key

    key = content_key({"version": 3, **_pencil(scene), "modes": asdict(scene.modes)})
    return cache_dir() / "shifts" / f"{key}.npz"


def _seated(s: Support) -> dict:
    """What of a support makes K and M: its seat, kind, coupling, holds and stiffness at
    standstill; not its coefficients at speed, its damping or the part they come from
    (a tolerance case, a table and its constant, solve on one pencil)."""
    return {"position": s.position, "width": s.width, "kind": s.kind, "coupling": s.coupling,
            "radial_xy": list(s.radial_xy), "axial": s.axial, "tilting": s.tilting}


def _carried(a: Attachment) -> dict:
    """What of a part makes K and M: its seat, mass, inertias, joint and coupled
    machine; not its name, its stage or its cross-coupling at speed (a Level I that
    varies the stage's power solves on one pencil)."""
    return {"position": a.position, "width": a.width, "mass": a.mass,
            "polar_inertia": a.polar_inertia, "diametral_inertia": a.diametral_inertia,
            "joint": a.joint, "coupling_stiffness": a.coupling_stiffness,
            "coupled_inertia": a.coupled_inertia}


def shift_hint(scene: Scene) -> float | None:
    """The shift (rad^2/s^2) above the wanted modes that the last solve of this scene
    counted at, if one was kept: where the next solve factorises first."""
    from shaftfem.store import discard, load_arrays

    path = _shift_path(scene)
    if not path.exists():
        return None
    fields, why = load_arrays(path, ("shift",))
    if fields is None or not float(fields["shift"]) > 0:
        discard("shift hint", why or "not a positive shift", path)
        return None
    return float(fields["shift"])


def keep_shift(scene: Scene, shift: float) -> None:
    """Keep a solve's proven shift for the next solve of the scene."""
    import numpy as np

    from shaftfem.store import save_arrays

    if shift > 0:
        save_arrays(_shift_path(scene), {"shift": np.float64(shift)})


def _solve_path(scene: Scene, mesh: ShaftMesh, space: str) -> Path:
    """Where the last solve of this scene's pencil on this very mesh is kept (its pencil,
    the mesh settings, the mesh's own nodes and cells, and the basis), whatever its
    count: a solve of fewer modes refines those of more kept before (the whirl's basis,
    then the design's modes); a solve up to a frequency limit keeps none."""
    import hashlib
    from dataclasses import asdict

    from shaftfem.store import cache_dir, content_key

    digest = hashlib.sha256(mesh.points.tobytes() + mesh.cells.tobytes()).hexdigest()
    key = content_key({"version": 3, "pencil": _pencil(scene), "mesh": asdict(scene.mesh),
                       "nodes": digest, "space": space})
    return cache_dir() / "solves" / f"{key}.npz"


def last_solve(path: Path, n_dofs: int, count: int) -> tuple[float, np.ndarray] | None:
    """(shift, shapes) of the last solve kept at `path` (_solve_path), if any: the shift
    (rad^2/s^2) where it proved its modes complete and every pair below it (n_dofs, at
    least count), from which the next solve refines the modes instead of searching for
    them (fem.eigen.refine_below proves them anew)."""
    from shaftfem.store import discard, load_arrays

    if not path.exists():
        return None
    fields, why = load_arrays(path, ("shift", "shapes"))
    if fields is None or not float(fields["shift"]) > 0 or fields["shapes"].shape[0] != n_dofs:
        discard("last solve", why or "another system's shift or shapes", path)
        return None
    if fields["shapes"].shape[1] < count:   # a solve of fewer modes: this one replaces it
        return None
    return float(fields["shift"]), fields["shapes"]


def keep_solve(path: Path, shift: float, shapes: np.ndarray) -> None:
    """Keep a solve's proven shift and mode shapes at `path` (_solve_path) for the next
    solve on the same mesh."""
    import numpy as np

    from shaftfem.store import save_arrays

    if shift > 0:
        save_arrays(path, {"shift": np.float64(shift), "shapes": shapes})


def scene_warnings(scene: Scene, modes: Modes | None = None) -> tuple[str, ...]:
    """Cases the method handles poorly: said, never silently computed."""
    out = []
    m, R = scene.mesh, scene.shaft.radius
    if m.size > R:
        out.append(f"element size {m.size * 1e3:g} mm exceeds the shaft radius "
                   f"({R * 1e3:g} mm): fewer than two elements across the section, the "
                   "frequencies can be far from converged (see the error estimate)")
    for a in scene.attachments:
        if a.width < R:
            out.append(f"{a.name}: a {a.width * 1e3:g} mm hub on a {2 * R * 1e3:g} mm shaft "
                       "(shorter than its radius): how the part bears on so short a band "
                       "decides its modes more than the part does; give the hub's real length")
    nu = scene.material.poisson_ratio
    if m.order == 1 and nu > 0.45:
        out.append(f"P1 (linear) elements lock for a nearly incompressible material "
                   f"(nu = {nu:g}): bending frequencies come out too high; use order 2")
    # quadratic faces wider than a groove miss its curvature (16/8/8 mm: 0.5 % of the
    # volume); cubic ones follow it (16/12/12 at order 5: 0.066 %, docs/accuracy.md)
    if (scene.grooves is not None and m.groove_size > scene.grooves.width
            and m.geometry_order == 2):
        out.append(f"groove element size {m.groove_size * 1e3:g} mm exceeds the groove width "
                   f"({scene.grooves.width * 1e3:g} mm): the grooves are barely resolved")
    fmax = scene.modes.max_frequency
    if modes is not None and fmax is not None and modes.frequencies[0] >= fmax:
        out.append(f"no elastic mode below {fmax:g} Hz; the lowest "
                   f"({modes.frequencies[0]:.2f} Hz) is shown")
    return tuple(out)
