"""Pictures of the shaft and its mode shapes, off-screen with pyvista.

pyvista (VTK) is imported here and nowhere else. On a machine without a display
VTK renders through EGL; the set-up command installs what that needs.

A mode shape has no physical amplitude (it is mass-normalised), so every picture
draws its largest displacement as DRAWN_FRACTION of the shaft's length and
colours by |u| / max |u| of that mode (VTK's fonts have no "|", so the colour
bar says it in words); the shaft at rest is drawn in
translucent grey behind it. Each mode is seen across its own plane of motion,
so that a bending mode's deflection is in the picture, not towards the viewer.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.store import atomic_path, staged_directory

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult

GEOMETRY_SIZE = (1600, 500)
PANEL_SIZE = (800, 200)        # pixels per mode in modes.png, two modes a row
BAR_HEIGHT = 110               # pixels of the strip with the colour bar and the legend
GIF_SIZE = (800, 260)
GIF_FRAMES = 16                # frames per period in each mode's GIF
DRAWN_FRACTION = 0.06          # the largest displacement is drawn as 6 % of the length
CMAP = "viridis"
COLOUR_LABEL = "displacement / largest displacement of the mode"


def _pyvista():
    if not os.environ.get("DISPLAY"):
        # no X server: go straight to EGL instead of trying X first
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    return pv


def _surface(grid, subdivision: int):
    """Outer surface of a quadratic grid, its curved faces subdivided for drawing."""
    try:
        return grid.extract_surface(nonlinear_subdivision=subdivision,
                                    algorithm="dataset_surface")
    except TypeError:  # pyvista before 0.47 has no `algorithm`
        return grid.extract_surface(nonlinear_subdivision=subdivision)


def _grid(pv, result: ModalResult):
    from shaftfem.outputs.vtk import grid

    return pv.wrap(grid(result.mesh, scale=1e3))  # mm, as a designer reads it


def _side_view(plotter, length: float, aspect: float, plane: np.ndarray | None = None) -> None:
    """Parallel projection across the shaft (axis z, left to right), filling the panel.

    `plane`: the unit lateral direction the mode moves in; it is drawn upwards."""
    up = np.array([1.0, 0.0, 0.0]) if plane is None else np.array([plane[0], plane[1], 0.0])
    eye = np.array([-up[1], up[0], 0.0])
    centre = np.array([0.0, 0.0, length / 2])
    plotter.camera_position = [tuple(centre + 3 * length * eye), tuple(centre), tuple(up)]
    plotter.enable_parallel_projection()
    plotter.camera.parallel_scale = 0.56 * length / aspect


def _plane(u: np.ndarray) -> np.ndarray:
    """The lateral direction (x, y) of largest motion: the principal axis of (u_x, u_y)."""
    w, v = np.linalg.eigh(u[:, :2].T @ u[:, :2])
    return v[:, np.argmax(w)]


def _mode_surface(grid, u: np.ndarray, length: float):
    """The surface of `grid` (mm) carrying the mode's displacement u (at the grid's points),
    scaled for drawing, and its |u| / max |u|; and the mode's plane of motion."""
    mag = np.linalg.norm(u, axis=1)
    g = grid.copy(deep=False)
    g.point_data["u"] = u * (DRAWN_FRACTION * length / mag.max())
    g.point_data[COLOUR_LABEL] = mag / mag.max()
    return _surface(g, 1), _plane(u)


def render_geometry(result: ModalResult, path: str | Path) -> Path:
    """A PNG of the shaft's solid (its mesh surface), seen from the side."""
    pv = _pyvista()
    surf = _surface(_grid(pv, result), 2)
    p = pv.Plotter(off_screen=True, window_size=GEOMETRY_SIZE)
    p.set_background("white")
    p.add_mesh(surf, color="#b0b8c0", smooth_shading=True, specular=0.4)
    _draw_seats(pv, p, result.scene)
    shaft = result.scene.shaft
    p.add_text(f"{result.scene.name}: {shaft.length * 1e3:g} x {shaft.diameter * 1e3:g} mm",
               font_size=12, color="black")
    length = shaft.length * 1e3
    if shaft.plain:
        p.camera_position = [(0.0, -2.2 * length, length / 2), (0.0, 0.0, length / 2),
                             (1, 0, 0)]
        p.camera.elevation = 20
        p.reset_camera()
        p.camera.zoom(2.3)
    else:   # a profile: seen square from the side, its sections dimensioned
        _dimensions(pv, p, shaft)
        R = shaft.radius * 1e3   # the drawing spans x = -4 R (dimensions) to 2.3 R (labels)
        p.camera_position = [(-0.85 * R, -3 * length, length / 2),
                             (-0.85 * R, 0.0, length / 2), (1, 0, 0)]
        p.enable_parallel_projection()
        p.camera.parallel_scale = max(0.58 * length * GEOMETRY_SIZE[1] / GEOMETRY_SIZE[0],
                                      3.4 * R)
    with atomic_path(path) as tmp:
        p.screenshot(str(tmp))
    p.close()
    return Path(path)


def _dimensions(pv, p, shaft) -> None:
    """A stepped shaft's main dimensions, mm: each section's diameter (and bore) above it,
    its length on a dimension line below, the overall length beneath those."""
    R = shaft.radius * 1e3
    labels, points = [], []
    below = -1.6 * R
    for s, (z0, z1) in zip(shaft.profile, shaft.section_bounds()):
        z0, z1 = z0 * 1e3, z1 * 1e3
        d = (f"{s.diameter_start * 1e3:g}" if not s.conical
             else f"{s.diameter_start * 1e3:g}-{s.diameter_end * 1e3:g}")
        labels.append(f"D {d}" + (f" / bore {s.bore * 1e3:g}" if s.bore else ""))
        points.append((1.35 * R, 0.0, 0.5 * (z0 + z1)))
        p.add_mesh(pv.Line((below, 0.0, z0), (below, 0.0, z1)), color="black", line_width=2)
        for z in (z0, z1):
            p.add_mesh(pv.Line((below - 0.15 * R, 0.0, z), (-R * 1.05, 0.0, z)), color="grey")
        labels.append(f"{z1 - z0:g}")
        points.append((below - 0.35 * R, 0.0, 0.5 * (z0 + z1)))
    total = shaft.length * 1e3
    p.add_mesh(pv.Line((2.2 * below, 0.0, 0.0), (2.2 * below, 0.0, total)), color="black",
               line_width=2)
    labels.append(f"{total:g} mm")
    points.append((2.2 * below - 0.35 * R, 0.0, 0.5 * total))
    for k in shaft.keyways:
        labels.append(f"keyway {k.width * 1e3:g} x {k.depth * 1e3:g} x {k.length * 1e3:g}")
        points.append((2.0 * R, 0.0, 0.5 * (k.start + k.end) * 1e3))
    p.add_point_labels(np.array(points), labels, font_size=14, text_color="black",
                       shape=None, show_points=False, always_visible=True, justification_horizontal="center")


def _draw_seats(pv, p, scene) -> None:
    """Bearings (orange rings) and attached parts (blue disks, of the radius a solid
    disk of their mass and polar inertia would have), see-through, on their seats."""
    def R(part) -> float:   # the shaft's radius under the seat, mm
        return 1e3 * (scene.shaft.radius_at(part.position) or scene.shaft.radius)

    for s in scene.held:
        p.add_mesh(pv.Cylinder(center=(0, 0, s.position * 1e3), direction=(0, 0, 1),
                               radius=1.6 * R(s), height=s.width * 1e3, resolution=60),
                   color="#d08030", opacity=0.45)
    for a in scene.attachments:
        r = 1e3 * (2 * a.polar_inertia / a.mass) ** 0.5 if a.mass > 0 else 0.0
        p.add_mesh(pv.Cylinder(center=(0, 0, a.position * 1e3), direction=(0, 0, 1),
                               radius=max(r, 1.3 * R(a)), height=a.width * 1e3, resolution=60),
                   color="#4a78c0", opacity=0.45)


def _draw_mode(p, rest, surf, plane, length: float, aspect: float, title: str):
    """Draw one mode into the current (sub)plot; return the warped mesh drawn."""
    warped = surf.warp_by_vector("u")
    p.add_mesh(rest, color="grey", opacity=0.25)
    p.add_mesh(warped, scalars=COLOUR_LABEL, cmap=CMAP, clim=(0.0, 1.0),
               show_scalar_bar=False, smooth_shading=True)
    p.add_text(title, position="upper_left", font_size=9, color="black")
    _side_view(p, length, aspect, plane)
    return warped


def render_modes(result: ModalResult, path: str | Path) -> Path:
    """One PNG with a panel per mode (two a row), deformed, coloured by |u| / max |u|,
    with one colour bar and the drawing scale stated below them."""
    pv = _pyvista()
    m = result.modes
    n, cols = m.count, 2
    rows = math.ceil(n / cols)
    w, h = PANEL_SIZE
    size = (cols * w, rows * h + BAR_HEIGHT)
    p = pv.Plotter(off_screen=True, window_size=size, shape=(rows + 1, cols), border=True,
                   border_color="lightgrey", groups=[(rows, slice(None))],
                   row_weights=[h] * rows + [BAR_HEIGHT])
    p.set_background("white")
    length = result.scene.shaft.length * 1e3
    grid = _grid(pv, result)
    rest = _surface(grid, 1)
    for k, u in enumerate(result.shapes_at_points()):
        surf, plane = _mode_surface(grid, u, length)
        p.subplot(k // cols, k % cols)
        _draw_mode(p, rest, surf, plane, length, w / h,
                   f"mode {k + 1}: {m.frequencies[k]:.1f} Hz, {m.kinds[k]}")
    p.subplot(rows, 0)
    bar = pv.Line((0, 0, 0), (1, 0, 0), resolution=8)
    bar.point_data[COLOUR_LABEL] = np.linspace(0.0, 1.0, bar.n_points)
    p.add_mesh(bar, scalars=COLOUR_LABEL, cmap=CMAP, clim=(0.0, 1.0), opacity=0.0,
               show_scalar_bar=False)
    sb = p.add_scalar_bar(title=COLOUR_LABEL, vertical=False, position_x=0.3, position_y=0.28,
                          width=0.4, height=0.42, color="black", label_font_size=12,
                          n_labels=6, fmt="%.1f")
    sb.SetTitle("")  # said above the bar instead: VTK sets a bar's title onto its numbers
    p.add_text(COLOUR_LABEL, position="upper_edge", font_size=9, color="black")
    p.add_text(f"deformation drawn to scale: largest displacement = {100 * DRAWN_FRACTION:g} % "
               f"of the {length:g} mm shaft; grey: the shaft at rest", position="lower_edge",
               font_size=9, color="black")
    with atomic_path(path) as tmp:
        p.screenshot(str(tmp))
    p.close()
    return Path(path)


def render_mode_gifs(result: ModalResult, out: str | Path, frames: int = GIF_FRAMES
                     ) -> list[Path]:
    """mode_NN.gif per mode: one period of the motion, `frames` frames."""
    pv = _pyvista()
    out = Path(out)
    m = result.modes
    length = result.scene.shaft.length * 1e3
    grid = _grid(pv, result)
    rest = _surface(grid, 1)
    written = []
    for k, u_points in enumerate(result.shapes_at_points()):
        surf, plane = _mode_surface(grid, u_points, length)
        base, u = np.array(surf.points), np.array(surf.point_data["u"])
        p = pv.Plotter(off_screen=True, window_size=GIF_SIZE)
        p.set_background("white")
        shown = _draw_mode(p, rest, surf, plane, length, GIF_SIZE[0] / GIF_SIZE[1],
                           f"mode {k + 1}: {m.frequencies[k]:.1f} Hz, {m.kinds[k]}")
        path = out / f"mode_{k + 1:02d}.gif"
        with atomic_path(path) as tmp:
            p.open_gif(str(tmp), fps=frames // 2)
            for i in range(frames):
                shown.points = base + math.sin(2 * math.pi * i / frames) * u
                p.write_frame()
            p.close()  # the GIF is written out when its plotter closes
        written.append(path)
    return written


MANIFEST = "render.manifest.json"


def render_all(result: ModalResult, out: str | Path) -> list[Path]:
    """geometry.png, modes.png and mode_NN.gif per mode, published together in `out`
    under render.manifest.json."""
    with staged_directory(out, MANIFEST) as stage:
        written = render_into(result, stage)
    return [Path(out) / p.name for p in written]


def render_into(result: ModalResult, folder: Path) -> list[Path]:
    """The pictures of render_all, written straight into `folder`."""
    return [render_geometry(result, folder / "geometry.png"),
            render_modes(result, folder / "modes.png"), *render_mode_gifs(result, folder)]
