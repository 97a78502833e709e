"""Pictures of the shaft and its mode shapes, off-screen with pyvista.

pyvista (VTK) is imported here and nowhere else. On a machine without a display
VTK renders through EGL; the set-up command installs what that needs.

A mode shape has no physical amplitude (it is mass-normalised), so every picture
draws it at a fixed size: a bending or axial mode's largest displacement as
DRAWN_FRACTION of the shaft's length, a torsion mode's as TWIST_FRACTION of its
radius (drawn at the length's scale, a twist would wrap the shaft round itself). The
colour is |u| / max |u| of that mode (VTK's fonts have no "|", so the colour bar says
it in words); the shaft at rest is drawn in translucent grey behind it, a hair
thinner so that where the two coincide (at the bearings, in torsion) the moving
surface is the one seen. Bearings are orange rings and parts blue disks. Each mode is
seen across its own plane of motion, so that a bending mode's deflection is in the
picture, not towards the viewer.

The shaft's surface is extracted once for every picture, with every mode's drawn
displacement on it; a GIF's frames are drawn in one window, and a frame whose phase
repeats (sin is symmetric) is drawn once.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, replace
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from shaftfem.store import atomic_path, staged_directory

if TYPE_CHECKING:
    from collections.abc import Sequence

    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.fem.result import ModalResult
    from shaftfem.scene.model import Scene

GEOMETRY_SIZE = (1600, 500)
PANEL_SIZE = (800, 200)        # pixels per mode in modes.png, two modes a row
BAR_HEIGHT = 110               # pixels of the strip with the colour bar and the legend
GIF_SIZE = (800, 260)
GIF_FRAMES = 16                # frames per period in each mode's GIF
GIF_COLOURS = 128              # a GIF frame's palette
DRAWN_FRACTION = 0.06          # bending, axial: largest displacement, of the length
TWIST_FRACTION = 0.4           # torsion: largest displacement, of the radius
REST_SHRINK = 0.985            # the grey shaft at rest, scaled about the axis
CMAP = "viridis"
COLOUR_LABEL = "displacement / largest displacement of the mode"
BEARING_COLOUR, PART_COLOUR = "#d08030", "#4a78c0"


def load_pyvista():
    if not os.environ.get("DISPLAY"):
        # no X server: go straight to EGL instead of trying X first
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    return pv


def plotter(pv, size: tuple[int, int], samples: int = 4, off_screen: bool = True, **kwargs):
    """A plotter (off-screen by default) on white with `samples` x multi-sampling
    (pyvista's default of 8 costs half again the time in software rendering, for edges no
    one sees)."""
    theme = pv.themes.DocumentTheme()
    theme.multi_samples = samples
    p = pv.Plotter(off_screen=off_screen, window_size=size, theme=theme, **kwargs)
    p.set_background("white")
    return p


def _surface(grid, subdivision: int):
    """Outer surface of a quadratic grid, its curved faces subdivided for drawing."""
    try:
        return grid.extract_surface(nonlinear_subdivision=subdivision,
                                    algorithm="dataset_surface")
    except TypeError:  # pyvista before 0.47 has no `algorithm`
        return grid.extract_surface(nonlinear_subdivision=subdivision)


@dataclass(frozen=True)
class Drawing:
    """The shaft's outer surface (mm) with each mode's drawn displacement ("u1", ...)
    and colour ("c1", ...) on it, the surface at rest, and each mode's plane of motion;
    `grid`, the mesh they come from (`at` draws it with another subdivision)."""

    grid: Any
    surface: Any
    rest: Any
    planes: list[np.ndarray]
    titles: list[str]
    length: float   # mm

    def at(self, subdivision: int) -> Drawing:
        """The same modes on the surface with its curved faces subdivided so often."""
        surface, rest = _surfaces(self.grid, subdivision, self.length)
        return replace(self, surface=surface, rest=rest)

    @cached_property
    def coarse(self) -> Drawing:
        """The same modes on the curved faces unsubdivided: what a moving or on-screen
        view needs (the GIFs, report.html's 3D view), extracted once for both."""
        return self.at(subdivision=0)

    def moved(self, k: int, phase: float = 1.0) -> np.ndarray:
        """Mode k's surface points at `phase` (-1 to 1) of its drawn amplitude."""
        return np.asarray(self.surface.points) + phase * np.asarray(
            self.surface.point_data[f"u{k + 1}"])


def drawing(pv, result: ModalResult, subdivision: int = 1) -> Drawing:
    """Every mode of a run on one extracted surface (see drawing_of)."""
    m = result.modes
    return drawing_of(pv, result.scene, result.mesh, m.frequencies, m.kinds,
                      result.shapes_at_points(), subdivision)


def drawing_of(pv, scene: Scene, mesh: ShaftMesh, frequencies: np.ndarray,
               kinds: Sequence[str], shapes: np.ndarray, subdivision: int = 1) -> Drawing:
    """Every mode (`shapes` (n_modes, n_points, 3) at the mesh's points, with its frequency
    in Hz and kind) on one extracted surface: its displacement scaled for drawing
    (DRAWN_FRACTION of the length, TWIST_FRACTION of the radius for torsion)."""
    from shaftfem.outputs.vtk import grid as vtk_grid

    shaft = scene.shaft
    length, radius = shaft.length * 1e3, shaft.radius * 1e3
    grid = pv.wrap(vtk_grid(mesh, scale=1e3))  # mm, as a designer reads it
    planes = []
    for k, u in enumerate(shapes):
        mag = np.linalg.norm(u, axis=1)
        reach = TWIST_FRACTION * radius if kinds[k] == "torsion" else DRAWN_FRACTION * length
        grid.point_data[f"u{k + 1}"] = u * (reach / mag.max())
        grid.point_data[f"c{k + 1}"] = mag / mag.max()
        planes.append(_plane(u))
    surface, rest = _surfaces(grid, subdivision, length)
    titles = [f"mode {k + 1}: {f:.1f} Hz, {kind}" for k, (f, kind)
              in enumerate(zip(frequencies, kinds))]
    return Drawing(grid=grid, surface=surface, rest=rest, planes=planes, titles=titles,
                   length=length)


def mode_view(d: Drawing, k: int, scene: Scene, size: tuple[int, int] = (900, 400),
              off_screen: bool = True):
    """A plotter with mode k of drawing `d` in it, framed above its colour bar: the picture
    a notebook shows (`show()`) or saves (`screenshot(path)`)."""
    pv = load_pyvista()
    p = plotter(pv, size, off_screen=off_screen, shape=(2, 1), border=False,
                row_weights=[size[1] - BAR_HEIGHT, BAR_HEIGHT])
    _draw_mode(pv, p, d, k, scene, size[0] / (size[1] - BAR_HEIGHT))
    p.subplot(1, 0)
    _colour_bar(pv, p)
    return p


def _surfaces(grid, subdivision: int, length: float):
    """The drawn surface of `grid` with its normals, and the shaft at rest: the same a
    hair thinner and shorter (where the two coincide the moving one is seen)."""
    # the normals of the surface at rest shade it moved as well (the drawn motion is a
    # few per cent): drawn without a normals filter, its points can move frame by frame
    surface = _surface(grid, subdivision).compute_normals(
        cell_normals=False, split_vertices=False, consistent_normals=False,
        auto_orient_normals=False)
    rest = surface.copy(deep=True)
    rest.points[:, :2] *= REST_SHRINK
    rest.points[:, 2] = 0.5 * length + (rest.points[:, 2] - 0.5 * length) * (
        1 - 0.2 * (1 - REST_SHRINK))
    return surface, rest


def _plane(u: np.ndarray) -> np.ndarray:
    """The lateral direction (x, y) of largest motion: the principal axis of (u_x, u_y),
    its sign fixed (so that the same mode is seen from the same side every time)."""
    w, v = np.linalg.eigh(u[:, :2].T @ u[:, :2])
    d = v[:, np.argmax(w)]
    return d if d[np.argmax(np.abs(d))] > 0 else -d


@dataclass(frozen=True)
class Framing:
    """A parallel-projection camera across the shaft: where it stands and looks (mm),
    which way is up, and the half-height it shows (mm)."""

    position: np.ndarray
    focus: np.ndarray
    up: np.ndarray
    parallel_scale: float


def framing(points: np.ndarray, aspect: float, plane: np.ndarray | None = None,
            margin: float = 1.08) -> Framing:
    """The view across the shaft (axis z, left to right) that `points` (mm) fill, in a
    window of `aspect` (width / height); `plane`: the lateral direction drawn upwards."""
    up = np.array([1.0, 0.0, 0.0]) if plane is None else np.array([plane[0], plane[1], 0.0])
    eye = np.array([-up[1], up[0], 0.0])
    height, along = points @ up, points[:, 2]
    centre = (0.5 * (along.min() + along.max()) * np.array([0.0, 0.0, 1.0])
              + 0.5 * (height.min() + height.max()) * up)
    half = max(0.5 * (height.max() - height.min()), 0.5 * (along.max() - along.min()) / aspect)
    span = along.max() - along.min()
    return Framing(position=centre + 3 * span * eye, focus=centre, up=up,
                   parallel_scale=margin * half)


def aim(plotter, f: Framing) -> None:
    """Set `plotter`'s camera to the framing `f`."""
    plotter.camera_position = [tuple(f.position), tuple(f.focus), tuple(f.up)]
    plotter.enable_parallel_projection()
    plotter.camera.parallel_scale = f.parallel_scale


def frame_view(plotter, points: np.ndarray, aspect: float, plane: np.ndarray | None = None,
               margin: float = 1.08) -> None:
    """Set `plotter`'s camera to `framing(points, aspect, plane, margin)`."""
    aim(plotter, framing(points, aspect, plane, margin))


def _disk_radius(part, shaft_radius: float) -> float:
    """An attached part's drawn radius, mm: that of a solid disk of its mass and polar
    inertia, and at least 1.3 times the shaft's under it (`shaft_radius`, mm)."""
    r = 1e3 * (2 * part.polar_inertia / part.mass) ** 0.5 if part.mass > 0 else 0.0
    return max(r, 1.3 * shaft_radius)


def draw_seats(pv, p, scene) -> np.ndarray:
    """Bearings (orange rings) and attached parts (blue disks, of the radius a solid
    disk of their mass and polar inertia would have), see-through, on their seats.
    Returns the corners of what was drawn (mm), for framing."""
    def R(part) -> float:   # the shaft's radius under the seat, mm
        return 1e3 * (scene.shaft.radius_at(part.position) or scene.shaft.radius)

    corners = []
    for part, colour in ([(s, BEARING_COLOUR) for s in scene.held]
                         + [(a, PART_COLOUR) for a in scene.attachments]):
        r = _disk_radius(part, R(part)) if colour == PART_COLOUR else 1.6 * R(part)
        z, h = part.position * 1e3, part.width * 1e3
        p.add_mesh(pv.Cylinder(center=(0, 0, z), direction=(0, 0, 1), radius=r, height=h,
                               resolution=60), color=colour, opacity=0.45)
        corners += [(s * r, t * r, z + e * h / 2) for s in (-1, 1) for t in (-1, 1)
                    for e in (-1, 1)]
    return np.array(corners).reshape(-1, 3)


def render_geometry(result: ModalResult, path: str | Path, d: Drawing | None = None) -> Path:
    """A PNG of the shaft's solid (its mesh surface) seen square from the side, with its
    bearings and parts, and its main dimensions in mm."""
    pv = load_pyvista()
    surf = (d or drawing(pv, result)).surface
    p = plotter(pv, GEOMETRY_SIZE)
    p.add_mesh(surf, color="#b0b8c0", smooth_shading=True, specular=0.3)
    seats = draw_seats(pv, p, result.scene)
    shaft = result.scene.shaft
    p.add_text(f"{result.scene.name}: {shaft.length * 1e3:g} mm long, largest diameter "
               f"{shaft.diameter * 1e3:g} mm", font_size=12, color="black")
    labels = _dimensions(pv, p, result.scene)
    pts = np.vstack([np.asarray(surf.points), seats, labels])
    frame_view(p, pts, GEOMETRY_SIZE[0] / GEOMETRY_SIZE[1], margin=1.12)
    with atomic_path(path) as tmp:
        p.screenshot(str(tmp))
    p.close()
    return Path(path)


def _dimensions(pv, p, scene) -> np.ndarray:
    """The shaft's main dimensions, mm: each section's diameter (and bore) above it, its
    length on a dimension line below, the overall length beneath those; the grooves'
    and keyways' sizes. Returns where the labels stand (mm), for framing."""
    shaft = scene.shaft
    R = shaft.radius * 1e3
    labels, points = [], []
    below = -1.9 * R
    sections = list(zip(shaft.profile, shaft.section_bounds())) if shaft.profile else []
    for s, (z0, z1) in sections:
        z0, z1 = z0 * 1e3, z1 * 1e3
        d = (f"{s.diameter_start * 1e3:g}" if not s.conical
             else f"{s.diameter_start * 1e3:g}-{s.diameter_end * 1e3:g}")
        labels.append(f"D {d}" + (f" / bore {s.bore * 1e3:g}" if s.bore else ""))
        points.append((1.45 * R, 0.0, 0.5 * (z0 + z1)))
        if len(sections) > 1:
            p.add_mesh(pv.Line((below, 0.0, z0), (below, 0.0, z1)), color="black",
                       line_width=2)
            labels.append(f"{z1 - z0:g}")
            points.append((below - 0.45 * R, 0.0, 0.5 * (z0 + z1)))
    total = shaft.length * 1e3
    overall = 2.2 * below if len(sections) > 1 else below
    for z in sorted({round(z * 1e3, 9) for b in shaft.section_bounds() for z in b}
                    | {0.0, total}):
        p.add_mesh(pv.Line((overall - 0.15 * R, 0.0, z), (-R * 1.05, 0.0, z)), color="grey")
    p.add_mesh(pv.Line((overall, 0.0, 0.0), (overall, 0.0, total)), color="black",
               line_width=2)
    labels.append(f"{total:g} mm")
    points.append((overall - 0.45 * R, 0.0, 0.5 * total))
    for k in shaft.keyways:
        labels.append(f"keyway {k.width * 1e3:g} x {k.depth * 1e3:g} x {k.length * 1e3:g}")
        points.append((-1.45 * R, 0.0, 0.5 * (k.start + k.end) * 1e3))
    g = scene.grooves
    if g is not None:
        labels.append(f"{len(g.hands)} grooves, pitch {g.pitch * 1e3:g}, {g.width * 1e3:g} "
                      f"wide, {g.depth * 1e3:g} deep")
        points.append((2.3 * R, 0.0, (g.start + 0.5 * g.length) * 1e3))
    for part in scene.held:   # under the overall length, by its bearing
        labels.append(part.name)
        points.append((overall - 1.2 * R, 0.0, part.position * 1e3))
    for a in scene.attachments:   # over its disk
        labels.append(a.name)
        points.append((_disk_radius(a, R) + 0.5 * R, 0.0, a.position * 1e3))
    pts = np.array(points)
    p.add_point_labels(pts, labels, font_size=14, text_color="black", shape=None,
                       show_points=False, always_visible=True,
                       justification_horizontal="center")
    return pts


def _draw_mode(pv, p, d: Drawing, k: int, scene, aspect: float):
    """Mode k into the current (sub)plot, framed; returns the moving mesh drawn."""
    moving = d.surface.copy(deep=True)   # its points move; the drawing's stay
    moving.points = d.moved(k)
    p.add_mesh(d.rest, color="grey", opacity=0.25)
    actor = p.add_mesh(moving, scalars=f"c{k + 1}", cmap=CMAP, clim=(0.0, 1.0),
                       show_scalar_bar=False)
    actor.prop.interpolation = "gouraud"   # with the surface's own normals
    seats = draw_seats(pv, p, scene)
    p.add_text(d.titles[k], position="upper_left", font_size=9, color="black")
    lo = d.moved(k, -1.0)
    frame_view(p, np.vstack([moving.points, lo, seats]), aspect, d.planes[k])
    return moving


def _colour_bar(pv, p) -> None:
    """The colour bar of |u| / max |u| in the current (sub)plot, its words above it."""
    bar = pv.Line((0, 0, 0), (1, 0, 0), resolution=8)
    bar.point_data[COLOUR_LABEL] = np.linspace(0.0, 1.0, bar.n_points)
    p.add_mesh(bar, scalars=COLOUR_LABEL, cmap=CMAP, clim=(0.0, 1.0), opacity=0.0,
               show_scalar_bar=False)
    sb = p.add_scalar_bar(title=COLOUR_LABEL, vertical=False, position_x=0.3, position_y=0.28,
                          width=0.4, height=0.42, color="black", label_font_size=12,
                          n_labels=6, fmt="%.1f")
    sb.SetTitle("")  # said above the bar instead: VTK sets a bar's title onto its numbers
    p.add_text(COLOUR_LABEL, position="upper_edge", font_size=9, color="black")


def render_modes(result: ModalResult, path: str | Path, d: Drawing | None = None) -> Path:
    """One PNG with a panel per mode (two a row), deformed, coloured by |u| / max |u|,
    with one colour bar and the drawing scale stated below them."""
    pv = load_pyvista()
    d = d or drawing(pv, result)
    n, cols = result.modes.count, 2
    rows = math.ceil(n / cols)
    w, h = PANEL_SIZE
    size = (cols * w, rows * h + BAR_HEIGHT)
    p = plotter(pv, size, shape=(rows + 1, cols), border=True, border_color="lightgrey",
                 groups=[(rows, slice(None))], row_weights=[h] * rows + [BAR_HEIGHT])
    for k in range(n):
        p.subplot(k // cols, k % cols)
        _draw_mode(pv, p, d, k, result.scene, w / h)
    p.subplot(rows, 0)
    _colour_bar(pv, p)
    scene = result.scene
    glyphs = (["orange: bearings"] if scene.held else []) + (
        ["blue: parts"] if scene.attachments else [])
    p.add_text(f"drawn to scale: largest displacement {100 * DRAWN_FRACTION:g} % of the "
               f"{d.length:g} mm shaft (torsion: {100 * TWIST_FRACTION:g} % of its radius); "
               + "; ".join(["grey: the shaft at rest"] + glyphs),
               position="lower_edge", font_size=9, color="black")
    with atomic_path(path) as tmp:
        p.screenshot(str(tmp))
    p.close()
    return Path(path)


def render_mode_gifs(result: ModalResult, out: str | Path, frames: int = GIF_FRAMES,
                     d: Drawing | None = None, say=None) -> list[Path]:
    """mode_NN.gif per mode: one period of the motion, `frames` frames, drawn in one
    window; `say(message)` after each."""
    from PIL import Image

    pv = load_pyvista()
    d = d or drawing(pv, result)
    out = Path(out)
    written = []
    p = plotter(pv, GIF_SIZE, samples=1)   # quantised to GIF_COLOURS: edges alias anyway
    for k in range(result.modes.count):
        moving = _draw_mode(pv, p, d, k, result.scene, GIF_SIZE[0] / GIF_SIZE[1])
        drawn: dict[float, Image.Image] = {}
        images = []
        for i in range(frames):
            phase = round(math.sin(2 * math.pi * i / frames), 12)
            if phase not in drawn:
                moving.points = d.moved(k, phase)
                p.render()
                img = Image.fromarray(p.screenshot(return_img=True))
                drawn[phase] = img.quantize(GIF_COLOURS, method=Image.Quantize.FASTOCTREE)
            images.append(drawn[phase])
        p.clear()   # texts too
        path = out / f"mode_{k + 1:02d}.gif"
        with atomic_path(path) as tmp:
            images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:],
                           duration=round(2000 / frames), loop=0)
        written.append(path)
        if say is not None:
            say(f"picture {path.name}")
    p.close()
    return written


MANIFEST = "render.manifest.json"


def render_all(result: ModalResult, out: str | Path, say=None) -> list[Path]:
    """geometry.png, modes.png and mode_NN.gif per mode, published together in `out`
    under render.manifest.json."""
    with staged_directory(out, MANIFEST) as stage:
        written = render_into(result, stage, say)
    return [Path(out) / p.name for p in written]


def render_into(result: ModalResult, folder: Path, say=None,
                d: Drawing | None = None) -> list[Path]:
    """The pictures of render_all, written straight into `folder`; `say(message)` after
    each picture; `d`: the run's drawing, where the caller has made it already."""
    def done(path: Path) -> Path:
        if say is not None:
            say(f"picture {path.name}")
        return path

    d = d or drawing(load_pyvista(), result)
    # the GIFs are 800 px wide and move: the curved faces unsubdivided do (a quarter of
    # the triangles, a fifth less time per frame)
    return [done(render_geometry(result, folder / "geometry.png", d)),
            done(render_modes(result, folder / "modes.png", d)),
            *render_mode_gifs(result, folder, d=d.coarse, say=say)]
