"""The modal chain, one step after another: Scene -> shape -> mesh -> K, M -> modes.

Each step is a function of the one before; this module only calls them in order
and keeps what each produced and how long it took.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Callable

from .scene import Scene


@dataclass
class ModalResult:
    scene: Scene
    shape: object       # geometry.ShaftShape
    mesh: object        # mesh.ShaftMesh
    system: object      # assembly.System
    modes: object       # modal.Modes
    seconds: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)


def with_mesh(scene: Scene, size_mm: float | None = None, order: int | None = None) -> Scene:
    """The scene with another element size (all sizes scaled alike) and/or order."""
    m = scene.mesh
    if size_mm is not None:
        k = size_mm * 1e-3 / m.size
        m = replace(m, size=m.size * k, groove_size=m.groove_size * k, edge_size=m.edge_size * k)
    if order is not None:
        m = replace(m, order=order)
    return replace(scene, mesh=m)


def run_modes(scene: Scene, n_modes: int = 10, use_cache: bool = True,
              progress: Callable[[str], None] | None = None,
              mass_intorder: int | None = None, factorizer: str = "auto") -> ModalResult:
    """Build, mesh, assemble and solve `scene`; return every intermediate result."""
    from .assembly import assemble
    from .geometry import build_shape
    from .mesh import mesh_shape
    from .modal import modal_analysis

    say = progress or (lambda _msg: None)
    seconds = {}
    t0 = time.perf_counter()

    say("building the shaft's solid (CAD)")
    shape = build_shape(scene.shaft, scene.grooves, use_cache=use_cache)
    seconds["cad"] = time.perf_counter() - t0
    say(f"CAD done ({'from cache' if shape.from_cache else 'built'}), meshing")

    t = time.perf_counter()
    mesh = mesh_shape(shape.brep, scene.shaft, scene.grooves, scene.mesh, use_cache=use_cache)
    seconds["mesh"] = time.perf_counter() - t
    say(f"mesh: {mesh.n_elements} elements{' (from cache)' if mesh.from_cache else ''}; "
        "assembling K and M")

    t = time.perf_counter()
    system = assemble(mesh.to_skfem(), scene.mesh.order, scene.material,
                      mass_intorder=mass_intorder)
    seconds["assembly"] = time.perf_counter() - t
    say(f"{system.n_dofs} DOFs; factorising and solving")

    modes = modal_analysis(system.K, system.M, system.nodes, system.mass_scalar, n_modes,
                           factorizer=factorizer)
    seconds.update(modes.seconds)
    seconds["total"] = time.perf_counter() - t0
    return ModalResult(scene=scene, shape=shape, mesh=mesh, system=system, modes=modes,
                       seconds=seconds, warnings=scene_warnings(scene))


def scene_warnings(scene: Scene) -> list[str]:
    """Cases the method handles poorly: said, never silently computed."""
    out = []
    m, R = scene.mesh, scene.shaft.radius
    if m.size > R:
        out.append(f"element size {m.size * 1e3:g} mm exceeds the shaft radius "
                   f"({R * 1e3:g} mm): fewer than two elements across the section, the "
                   "frequencies can be far from converged (see the error estimate)")
    nu = scene.material.poisson_ratio
    if m.order == 1 and nu > 0.45:
        out.append(f"P1 (linear) elements lock for a nearly incompressible material "
                   f"(nu = {nu:g}): bending frequencies come out too high; use order 2")
    if scene.grooves is not None and m.groove_size > scene.grooves.width:
        out.append(f"groove element size {m.groove_size * 1e3:g} mm exceeds the groove width "
                   f"({scene.grooves.width * 1e3:g} mm): the grooves are barely resolved")
    return out
