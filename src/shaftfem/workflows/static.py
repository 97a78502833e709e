"""The shaft's static loads solved (fem.static), and the journal bearings that carry
them: a journal without its load_n takes its reaction."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from shaftfem.errors import SceneError
from shaftfem.fem.static import StaticSolution, static_solution
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene


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
        replace(s, kind="rigid-radial", bearing=None) if s.kind == "journal" else s
        for s in scene.supports))
    placed, _, mesh = built(held, options)
    options.say("assembling K and M; solving the static loads")
    system = assemble(mesh, placed.material, threads=options.threads)
    skmesh = mesh.to_skfem()
    inst = install(placed, system.K, system.M, system.nodes, skmesh, system.order)
    return StaticResult(scene=scene, solution=static_solution(placed, system, inst, skmesh))


def with_journal_loads(scene: Scene, options: RunOptions = RunOptions()) -> Scene:
    """The scene with every journal bearing that has no load_n loaded by its reaction to
    the static loads (the load on the journal: the reaction's opposite), and its film's
    coefficients computed for it; the scene itself if none waits for one."""
    from shaftfem.scene.load import journal_coefficients

    waiting = [s for s in scene.supports if s.journal is not None and s.bearing is None]
    if not waiting:
        return scene
    assert scene.rotor is not None   # a journal needs [rotor] (scene.load)
    static = run_static(scene, options).solution
    reaction = {r.name: r.force for r in static.reactions}
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
    return replace(scene, supports=tuple(supports))
