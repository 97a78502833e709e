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
    mesh = mesh_shape(shape.brep, scene.shaft, scene.grooves, scene.mesh)
    seconds["mesh"] = time.perf_counter() - t
    say(f"mesh: {mesh.n_elements} elements; assembling K and M")

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
                       seconds=seconds)
