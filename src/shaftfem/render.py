"""Pictures of the shaft and its mode shapes, off-screen with pyvista.

pyvista (VTK) is imported here and nowhere else. On a machine without a display
VTK renders through EGL; the set-up command installs what that needs.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .store import atomic_path

if TYPE_CHECKING:
    from .pipeline import ModalResult

GEOMETRY_SIZE = (1600, 500)
MODES_SIZE = (1600, 1000)
MODES_SHOWN = 8


def _pyvista():
    if not os.environ.get("DISPLAY"):
        # no X server: go straight to EGL instead of trying X first
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    return pv


def _grid(pv, mesh):
    from vtkmodules.util.vtkConstants import VTK_QUADRATIC_TETRA, VTK_TETRA

    ctype = VTK_QUADRATIC_TETRA if mesh.order == 2 else VTK_TETRA
    n = mesh.cells.shape[1]
    cells = np.hstack([np.full((mesh.n_elements, 1), n), mesh.cells]).ravel()
    return pv.UnstructuredGrid(cells, np.full(mesh.n_elements, ctype, dtype=np.uint8),
                               mesh.points * 1e3)  # mm, as a designer reads it


def _surface(grid, subdivision: int):
    """Outer surface of a quadratic grid, its curved faces subdivided for drawing."""
    try:
        return grid.extract_surface(nonlinear_subdivision=subdivision,
                                    algorithm="dataset_surface")
    except TypeError:  # pyvista before 0.47 has no `algorithm`
        return grid.extract_surface(nonlinear_subdivision=subdivision)


def _side_view(plotter, length_mm: float, zoom: float = 1.6) -> None:
    # the shaft lies along z; look at it from the side, z running left to right
    plotter.camera_position = [(0.0, -2.2 * length_mm, length_mm / 2),
                               (0.0, 0.0, length_mm / 2), (1.0, 0.0, 0.0)]
    plotter.camera.elevation = 20
    plotter.reset_camera(bounds=None)
    plotter.camera.zoom(zoom)


def render_geometry(result: ModalResult, path: str | Path) -> Path:
    """A PNG of the shaft's solid (its mesh surface), seen from the side."""
    pv = _pyvista()
    grid = _grid(pv, result.mesh)
    surf = _surface(grid, 2)
    p = pv.Plotter(off_screen=True, window_size=GEOMETRY_SIZE)
    p.set_background("white")
    p.add_mesh(surf, color="#b0b8c0", smooth_shading=True, specular=0.4)
    p.add_text(f"{result.scene.name}: {result.scene.shaft.length * 1e3:g} x "
               f"{result.scene.shaft.diameter * 1e3:g} mm", font_size=12, color="black")
    _side_view(p, result.scene.shaft.length * 1e3, zoom=2.3)
    with atomic_path(path) as tmp:
        p.screenshot(str(tmp))
    p.close()
    return Path(path)


def render_modes(result: ModalResult, path: str | Path, n: int = MODES_SHOWN) -> Path:
    """A grid PNG of the first n mode shapes, deformed and coloured by |u| (like Fig. 2)."""
    pv = _pyvista()
    grid = _grid(pv, result.mesh)
    shapes = result.shapes_at_points()
    n = min(n, len(shapes))
    L = result.scene.shaft.length * 1e3
    cols = 2
    rows = (n + cols - 1) // cols
    p = pv.Plotter(off_screen=True, window_size=MODES_SIZE, shape=(rows, cols), border=False)
    p.set_background("white")
    for k in range(n):
        u = shapes[k]
        mag = np.linalg.norm(u, axis=1)
        scale = 0.06 * L / (mag.max() * 1e3)  # largest displacement drawn as 6 % of L
        g = grid.copy()
        g.point_data["u"] = u * 1e3
        g.point_data["|u| (scaled)"] = mag / mag.max()
        warped = _surface(g.warp_by_vector("u", factor=scale), 1)
        p.subplot(k // cols, k % cols)
        p.add_mesh(warped, scalars="|u| (scaled)", cmap="jet", show_scalar_bar=False,
                   smooth_shading=True)
        f = result.modes.frequencies[k]
        p.add_text(f"mode {k + 1}: {f:.1f} Hz ({result.modes.kinds[k]})", font_size=10,
                   color="black")
        _side_view(p, L)
    with atomic_path(path) as tmp:
        p.screenshot(str(tmp))
    p.close()
    return Path(path)
