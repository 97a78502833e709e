"""The shaft's static loads solved (fem.static), and the journal bearings that carry
them: a journal without its load_n takes its reaction, and its film's coefficients
come from it (the other parts' need no static solution: workflows.equip)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.static import StaticSolution, static_solution
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene, Support
from shaftfem.workflows.equip import (
    films_ahead,
    films_dropped,
    journal_coefficients,
    with_parts,
)


@dataclass(frozen=True)
class StaticResult:
    """The static solution of a scene, and the scene it was solved for."""

    scene: Scene
    solution: StaticSolution

    def as_dict(self) -> dict:
        """The JSON of `shaftfem static`."""
        s = self.solution
        return {"gravity_m_s2": list(self.scene.gravity),
                "load_n": [float(v) for v in s.load],
                "reactions": [{"support": r.name, "position_mm": r.position * 1e3,
                               "force_n": [float(v) for v in r.force]} for r in s.reactions],
                "deflection_line": {"z_mm": [float(v) * 1e3 for v in s.z],
                                    "x_um": [float(v) * 1e6 for v in s.x],
                                    "y_um": [float(v) * 1e6 for v in s.y]}}


def run_static(scene: Scene, options: RunOptions = RunOptions()) -> StaticResult:
    """The scene's shaft in its supports under its static loads. Journal bearings hold
    it rigidly along x and y (their films' compliance is microns, and on two bearings
    the reactions do not depend on it)."""
    from shaftfem.fem.assembly import assemble
    from shaftfem.fem.installation import install
    from shaftfem.workflows.pipeline import built

    if not scene.held:
        raise SceneError(f"{scene.source}: no [[support]] holds the shaft: a free shaft has "
                         "no static solution")
    held = replace(scene, supports=tuple(
        replace(s, kind="rigid-radial", bearing=None, journal=None, tolerance=None)
        if s.kind == "journal" else s for s in scene.supports))
    placed, _, mesh = built(with_parts(held), options)
    options.say("assembling K and M; solving the static loads")
    system = assemble(mesh, placed.material, threads=options.threads)
    skmesh = mesh.to_skfem()
    inst = install(placed, system.K, system.M, system.nodes, skmesh, system.order)
    return StaticResult(scene=scene, solution=static_solution(placed, system, inst, skmesh))


def reactions(scene: Scene, options: RunOptions = RunOptions()) -> dict[str, np.ndarray]:
    """Each support's reaction (N) to the static loads, by name: from the cache where it
    holds this scene's (keyed by all that makes them), else solved and kept there."""
    from shaftfem.store import discard, load_arrays, save_arrays
    scene = with_parts(scene)   # a ball bearing's or seal's stiffness holds the shaft too
    path = _reactions_path(scene) if options.use_cache else None
    if path is not None and path.exists():
        fields, why = load_arrays(path, ("names", "forces"))
        if fields is not None:
            return dict(zip((str(n) for n in fields["names"]), fields["forces"]))
        discard("static reactions", why, path)
    solution = run_static(scene, options).solution
    out = {r.name: r.force for r in solution.reactions}
    if path is not None:
        save_arrays(path, {"names": np.array(list(out), dtype=str),
                           "forces": np.array(list(out.values()))})
    return out


def _reactions_path(scene: Scene):
    """Where a scene's static reactions are kept: keyed by everything that makes them
    (the shaft, its mesh, material, seats, parts and loads; a journal's film aside)."""
    from dataclasses import asdict

    from shaftfem.store import cache_dir, content_key
    from shaftfem.workflows.stages import grooves_key

    # a bearing's or seal's part in the static solution is its stiffness at standstill
    # (its reference speed's): a tolerance case's seal, which has none there, or its
    # journals, held rigidly here, leave the reactions as they are
    seats = [{"name": s.name, "position": s.position, "width": s.width,
              "kind": "rigid-radial" if s.kind == "journal" else s.kind, "radial": s.radial,
              "axial": s.axial, "tilting": s.tilting, "coupling": s.coupling,
              "standstill": None if s.bearing is None or s.kind == "journal"
              else list(s.radial_xy)} for s in scene.supports]
    key = content_key({"version": 2, "shaft": asdict(scene.shaft),
                       "grooves": grooves_key(scene.grooves),
                       "material": asdict(scene.material), "mesh": asdict(scene.mesh),
                       "supports": seats,
                       "attachments": [asdict(a) for a in scene.attachments],
                       "gravity": list(scene.gravity),
                       "forces": [asdict(f) for f in scene.forces],
                       "cuts": list(scene.seat_cuts())})
    return cache_dir() / "static" / f"{key}.npz"


def equipped(scene: Scene, options: RunOptions = RunOptions()) -> Scene:
    """The scene with every part's coefficients (`with_parts`), every journal without its
    load_n loaded by its reaction to the static loads (the load on the journal: the
    reaction's opposite) and its film's coefficients computed for it."""
    scene = with_parts(scene)
    waiting = [s for s in scene.supports if s.journal is not None and s.bearing is None]
    if not waiting:
        return scene
    assert scene.rotor is not None   # a journal needs [rotor] (scene.load)
    # their films' tables are solved beside the static solution they wait for
    ahead = films_ahead([s.journal for s in waiting if s.journal is not None])
    try:
        return replace(scene, supports=_loaded(scene, reactions(scene, options)))
    finally:
        films_dropped(ahead)


def _loaded(scene: Scene, reaction: dict[str, np.ndarray]) -> tuple[Support, ...]:
    """The supports with each waiting journal loaded by its reaction, with its film's
    coefficients."""
    assert scene.rotor is not None
    supports = []
    for s in scene.supports:
        if s.journal is None or s.bearing is not None:
            supports.append(s)
            continue
        fx, fy = -reaction[s.name][:2]
        load = math.hypot(fx, fy)
        if load <= 0:
            raise SceneError(f"{scene.source}: journal bearing {s.name!r}: the static loads "
                             "leave it unloaded; give its load_n")
        bearing = replace(s.journal, load=load, direction=(fx / load, fy / load))
        try:
            coefficients = journal_coefficients(bearing, scene.rotor)
        except ValueError as e:
            raise SceneError(f"{scene.source}: journal bearing {s.name!r} carries "
                             f"{load:,.0f} N of the static loads: {e}") from None
        supports.append(replace(s, journal=bearing, bearing=coefficients))
    return tuple(supports)
