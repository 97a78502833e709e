"""Everything that talks to gmsh (and through it to OpenCASCADE): the session, the
shaft's solid, its tetrahedral mesh and the STEP export.

The solid (why it is built this way is in the comments):

* A groove of one hand is invariant under the screw motion (rotate by 2*pi*dz/P,
  translate by dz), so each of its cross-sections perpendicular to the axis is a
  rotated copy of one planar section: the axial-section profile mapped to angles
  by theta = 2*pi*s/P. Straight groove walls become radial lines, the floor and
  top become circular arcs, the root fillets short splines.
* A right- and a left-hand groove of the same pitch together repeat every half
  pitch, turned by 180 degrees. So one "cell" (half a pitch long) is built with
  booleans and then copied; the cells and the plain ends are glued with one
  fragment. The grooves cross once inside each cell, never on a cell face.
* Each groove piece is a loft (ThruSections) through exact sections that start
  and end exactly on the cell faces, so neighbouring cells meet on identical
  edges. The piece is cut oversized (from below the floor to above the surface)
  and intersected with the ring R-d <= r <= R+1 mm, so that every groove floor
  is the same exact cylinder and two crossing floors never meet as two slightly
  different surfaces (a trial showed full-length swept tubes failing there).

The mesh: `MeshSettings.size` away from the grooves, `groove_size` at the groove
faces, `edge_size` at the curves on the floor radius (where sharp corners make
the elastic field singular), graded in between. A shaft without grooves is
meshed as a 90-degree periodic sector (the caller copies it four times).
"""

from __future__ import annotations

import contextlib
import io
import math
import os
import tempfile
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from shaftfem.cad.profile import TOOL_OVERSHOOT, profile_outline
from shaftfem.errors import GeometryError, MeshError, ShaftfemError
from shaftfem.scene.model import Grooves, MeshSettings, Shaft, cell_type

SECTIONS_PER_CELL = 13          # exact sections per half turn (15 degree steps)
# Distance (in units of the size jump) over which the element size grows from the
# edge size to the groove size: 1 means each element is about twice its inner neighbour.
EDGE_GRADING = 1.0


def gmsh_version() -> str:
    import gmsh

    return gmsh.__version__


class Session:
    """One gmsh job: its own model; options it changes are put back for a caller's session."""

    def __init__(self, gmsh, owner: bool):
        self.gmsh, self.owner = gmsh, owner
        self._saved: dict[str, float] = {}

    def option(self, name: str, value: float) -> None:
        if name not in self._saved:
            self._saved[name] = self.gmsh.option.getNumber(name)
        self.gmsh.option.setNumber(name, value)

    def restore(self) -> None:
        for name, value in self._saved.items():
            self.gmsh.option.setNumber(name, value)


@contextmanager
def session(model: str, verbose: bool = False):
    """A gmsh model for one job. gmsh's state is global: a session we open we also
    close; inside a caller's open session we work in a model of our own and leave
    the caller's models, current model and options as they were."""
    import gmsh

    owner = not gmsh.isInitialized()
    if owner:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
    previous = None if owner else gmsh.model.getCurrent()
    s = Session(gmsh, owner)
    s.option("General.Terminal", 1 if verbose else 0)
    gmsh.model.add(model)
    try:
        yield s
    finally:
        if owner:
            gmsh.finalize()
        else:
            gmsh.model.remove()
            gmsh.model.setCurrent(previous)
            s.restore()


@contextmanager
def translated(kind: type[ShaftfemError], what: str):
    """gmsh and OpenCASCADE raise bare Exceptions carrying their log line, and meshio
    may call sys.exit: either becomes one `kind` error saying which step failed."""
    try:
        yield
    except ShaftfemError:
        raise
    except (Exception, SystemExit) as exc:
        raise kind(f"{what}: {type(exc).__name__}: {exc}") from exc


@contextmanager
def _stdout_to_devnull():
    """Silence C-level prints on stdout (OpenCASCADE's STEP writer talks there)."""
    import sys

    sys.stdout.flush()
    saved = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)


# --------------------------------------------------------------------------
# The solid


def _section_wire(occ, outline, z: float, theta: float, pitch: float) -> int:
    """One transverse section of a groove tool at height z, centred at angle theta."""
    k = 2 * math.pi / pitch

    def xy(s: float, r: float) -> tuple[float, float, float]:
        ang = theta + k * s
        return r * math.cos(ang), r * math.sin(ang), z

    points: dict[tuple[float, float], int] = {}

    def pt(s: float, r: float) -> int:
        key = (round(s, 12), round(r, 12))
        if key not in points:
            points[key] = occ.addPoint(*xy(s, r))
        return points[key]

    centre = None
    curves = []
    for kind, pts in outline:
        if kind == "radial":
            curves.append(occ.addLine(pt(*pts[0]), pt(*pts[1])))
        elif kind == "arc":
            if centre is None:
                centre = occ.addPoint(0.0, 0.0, z)
            curves.append(occ.addCircleArc(pt(*pts[0]), centre, pt(*pts[-1])))
        else:
            tags = [pt(*pts[0])] + [occ.addPoint(*xy(*p)) for p in pts[1:-1]] + [pt(*pts[-1])]
            curves.append(occ.addSpline(tags))
    return occ.addWire(curves)


def _groove_piece(occ, g: Grooves, radius: float, outline, hand: int,
                  z0: float, length: float, theta0: float) -> int:
    """A groove tool over [z0, z0 + length] whose centre starts at angle theta0."""
    n = max(3, math.ceil((SECTIONS_PER_CELL - 1) * length / (g.pitch / 2)) + 1)
    wires = []
    for z in np.linspace(z0, z0 + length, n):
        theta = theta0 + hand * 2 * math.pi * (z - z0) / g.pitch
        wires.append(_section_wire(occ, outline, float(z), theta, g.pitch))
    out = occ.addThruSections(wires, makeSolid=True, makeRuled=False)
    vols = [t for d, t in out if d == 3]
    if len(vols) != 1:
        raise GeometryError(f"groove loft gave {len(vols)} solids instead of 1")
    return vols[0]


def _cell(occ, g: Grooves, radius: float, outline, z0: float, length: float,
          turn: float) -> int:
    """A grooved stretch [z0, z0 + length]: cylinder minus each hand's groove piece.

    `turn` is the angle of the right-hand groove's centre at z0 minus pi/2.
    """
    floor = radius - g.depth
    body = occ.addCylinder(0, 0, z0, 0, 0, length, radius)
    for hand in g.hands:
        theta0 = hand * (math.pi / 2 + turn)
        tool = _groove_piece(occ, g, radius, outline, hand, z0, length, theta0)
        outer = occ.addCylinder(0, 0, z0 - 1e-3, 0, 0, length + 2e-3, radius + 2 * TOOL_OVERSHOOT)
        inner = occ.addCylinder(0, 0, z0 - 2e-3, 0, 0, length + 4e-3, floor)
        ring, _ = occ.cut([(3, outer)], [(3, inner)])
        piece, _ = occ.intersect([(3, tool)], ring)
        if not piece:
            raise GeometryError("a groove piece does not meet the ring R-d..R+1 mm")
        cut, _ = occ.cut([(3, body)], piece)
        if len(cut) != 1:
            raise GeometryError(f"cutting a groove piece left {len(cut)} solids instead of 1")
        body = cut[0][1]
    return body


def _build(gmsh, shaft: Shaft, grooves: Grooves | None) -> None:
    """Create the shaft in the current gmsh model (not yet synchronised)."""
    occ = gmsh.model.occ
    R, L = shaft.radius, shaft.length
    if grooves is None:
        occ.addCylinder(0, 0, 0, 0, 0, L, R)
        return
    g = grooves
    outline = profile_outline(g, R)
    half = g.pitch / 2
    n_full = int(math.floor(g.length / half + 1e-9))
    rest = g.length - n_full * half
    pieces = []
    if g.start > 1e-9:
        pieces.append((3, occ.addCylinder(0, 0, 0, 0, 0, g.start, R)))
    if n_full:
        cell = _cell(occ, g, R, outline, g.start, half, 0.0)
        pieces.append((3, cell))
        for k in range(1, n_full):
            copy = occ.copy([(3, cell)])
            if k % 2:
                occ.rotate(copy, 0, 0, 0, 0, 0, 1, math.pi)
            occ.translate(copy, 0, 0, k * half)
            pieces += copy
    if rest > 1e-9:
        pieces.append((3, _cell(occ, g, R, outline, g.start + n_full * half, rest,
                                n_full * math.pi)))
    end = g.start + g.length
    if L - end > 1e-9:
        pieces.append((3, occ.addCylinder(0, 0, end, 0, 0, L - end, R)))
    if len(pieces) > 1:
        occ.fragment(pieces[:1], pieces[1:])


def _check_connected(gmsh) -> None:
    """All volumes must form one body: every volume shares a face with another."""
    vols = [t for _, t in gmsh.model.getEntities(3)]
    if len(vols) < 2:
        return
    faces: dict[int, list[int]] = {}
    for v in vols:
        _, bnd = gmsh.model.getAdjacencies(3, v)
        for f in bnd:
            faces.setdefault(int(f), []).append(v)
    parent = {v: v for v in vols}

    def find(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for owners in faces.values():
        for a in owners[1:]:
            parent[find(a)] = find(owners[0])
    roots = {find(v) for v in vols}
    if len(roots) != 1:
        raise GeometryError(f"the solid fell apart into {len(roots)} bodies after the booleans")

def build_solid(shaft: Shaft, grooves: Grooves | None, brep: Path) -> tuple[float, int]:
    """Build the shaft, check it is one body, write it to `brep`; return its volume
    (m^3) and how many CAD volumes it has."""
    with session("shaft") as s, translated(GeometryError, "OpenCASCADE could not build the "
                                           "shaft's solid (check the groove dimensions)"):
        gmsh = s.gmsh
        _build(gmsh, shaft, grooves)
        gmsh.model.occ.synchronize()
        vols = gmsh.model.getEntities(3)
        volume = sum(gmsh.model.occ.getMass(3, t) for _, t in vols)
        _check_connected(gmsh)
        gmsh.write(str(brep))
    return volume, len(vols)


def write_solid(brep: Path | None, shaft: Shaft, paths: list[Path]) -> None:
    """The solid as STEP or BREP files (by suffix; for CAD and the workshop): from its
    BREP, or, for a shaft without grooves, a plain cylinder built on the spot."""
    with session("export") as s, _stdout_to_devnull(), \
            translated(GeometryError, "the solid could not be written as STEP/BREP"):
        gmsh = s.gmsh
        if brep is None:
            gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, shaft.length, shaft.radius)
        else:
            gmsh.model.occ.importShapes(str(brep))
        gmsh.model.occ.synchronize()
        for path in paths:
            gmsh.write(str(path))


# --------------------------------------------------------------------------
# The mesh


def _sample(gmsh, dim: int, tag: int, n: int = 3) -> np.ndarray:
    lo, hi = gmsh.model.getParametrizationBounds(dim, tag)
    if dim == 1:
        params = np.linspace(lo[0], hi[0], n + 2)[1:-1]
    else:
        u = np.linspace(lo[0], hi[0], n + 2)[1:-1]
        v = np.linspace(lo[1], hi[1], n + 2)[1:-1]
        params = np.array([[a, b] for a in u for b in v]).ravel()
    return np.asarray(gmsh.model.getValue(dim, tag, params)).reshape(-1, 3)


def _groove_entities(gmsh, shaft: Shaft, grooves: Grooves) -> tuple[list[int], list[int], float]:
    """Boundary faces of the grooves, and the helical curves along their floor edges."""
    R, L = shaft.radius, shaft.length
    floor = R - grooves.depth
    tol = 1e-6
    faces = []
    for _, s in gmsh.model.getEntities(2):
        up, _ = gmsh.model.getAdjacencies(2, s)
        if len(up) != 1:
            continue  # a face between two cells
        xyz = _sample(gmsh, 2, s)
        r = np.hypot(xyz[:, 0], xyz[:, 1])
        if np.all(np.abs(r - R) < tol) or np.all(np.abs(xyz[:, 2]) < tol) or np.all(
            np.abs(xyz[:, 2] - L) < tol
        ):
            continue
        faces.append(s)
    edges, longest = [], 0.0
    for _, c in gmsh.model.getEntities(1):
        xyz = _sample(gmsh, 1, c, 5)
        r = np.hypot(xyz[:, 0], xyz[:, 1])
        # every curve on the floor radius: the helical floor edges, and the arcs where
        # the grooves' flat ends meet the floor (sharp re-entrant edges)
        if np.all(np.abs(r - floor) < tol):
            edges.append(c)
            longest = max(longest, float(np.sum(np.linalg.norm(np.diff(xyz, axis=0), axis=1))))
    return faces, edges, longest * 6 / 5


def _size_fields(gmsh, shaft: Shaft, grooves: Grooves, s: MeshSettings) -> None:
    f = gmsh.model.mesh.field
    faces, edges, longest = _groove_entities(gmsh, shaft, grooves)
    fields = []
    if faces:
        d = f.add("Distance")
        f.setNumbers(d, "SurfacesList", faces)
        f.setNumber(d, "Sampling", 60)
        t = f.add("Threshold")
        f.setNumber(t, "InField", d)
        f.setNumber(t, "SizeMin", s.groove_size)
        f.setNumber(t, "SizeMax", s.size)
        f.setNumber(t, "DistMin", 0.5 * s.groove_size)
        f.setNumber(t, "DistMax", 0.5 * s.groove_size + 2.5 * (s.size - s.groove_size))
        fields.append(t)
    if edges and s.edge_size < s.groove_size:
        d = f.add("Distance")
        f.setNumbers(d, "CurvesList", edges)
        f.setNumber(d, "Sampling", max(20, math.ceil(2 * longest / s.edge_size)))
        t = f.add("Threshold")
        f.setNumber(t, "InField", d)
        f.setNumber(t, "SizeMin", s.edge_size)
        f.setNumber(t, "SizeMax", s.groove_size)
        f.setNumber(t, "DistMin", 0.5 * s.edge_size)
        f.setNumber(t, "DistMax", 0.5 * s.edge_size + EDGE_GRADING * (s.groove_size - s.edge_size))
        fields.append(t)
    if fields:
        m = f.add("Min")
        f.setNumbers(m, "FieldsList", fields)
        f.setAsBackgroundMesh(m)


def _cut_at(gmsh, cuts: tuple[float, ...], radius: float) -> None:
    """Split the solid by the planes z = cuts, so that the mesh has faces there and a
    seat band (shaftfem.fem.supports) is exactly a set of boundary faces."""
    if not cuts:
        return
    occ = gmsh.model.occ
    disks = [(2, occ.addDisk(0, 0, z, 2 * radius, 2 * radius)) for z in cuts]
    occ.fragment(occ.getEntities(3), disks)
    occ.synchronize()
    # the disks' parts outside the shaft bound no volume
    stray = [(2, t) for _, t in gmsh.model.getEntities(2)
             if len(gmsh.model.getAdjacencies(2, t)[0]) == 0]
    occ.remove(stray, recursive=True)
    occ.synchronize()


def _quarter_cylinder(gmsh, shaft: Shaft, cuts: tuple[float, ...] = ()) -> None:
    occ = gmsh.model.occ
    occ.addCylinder(0, 0, 0, 0, 0, shaft.length, shaft.radius, angle=math.pi / 2)
    occ.synchronize()
    _cut_at(gmsh, cuts, shaft.radius)
    planes: dict[str, dict[float, int]] = {"x0": {}, "y0": {}}
    for _, f in gmsh.model.getEntities(2):
        c = gmsh.model.occ.getCenterOfMass(2, f)
        if abs(c[1]) < 1e-12 and c[0] > 0:
            planes["y0"][round(c[2], 9)] = f
        elif abs(c[0]) < 1e-12 and c[1] > 0:
            planes["x0"][round(c[2], 9)] = f
    if sorted(planes["x0"]) != sorted(planes["y0"]):
        raise MeshError("the quarter cylinder's two cut planes do not match")
    # exact quarter turn about z: (x, y) -> (-y, x)
    turn = [0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    for z, f in planes["x0"].items():
        gmsh.model.mesh.setPeriodic(2, [f], [planes["y0"][z]], turn)

def _background_sizes(gmsh, sizes: tuple[np.ndarray, np.ndarray, np.ndarray]
                      ) -> tuple[float, int]:
    """Element sizes from a former mesh: `sizes` = (points (N, 3), tets (E, 4), size at
    each point, m), a list-based view read through a PostView field. Returns the smallest
    size and the view (to be removed after meshing)."""
    points, tets, h = sizes
    xyz = points[tets]
    data = np.hstack([xyz[:, :, 0], xyz[:, :, 1], xyz[:, :, 2], h[tets]])
    view = gmsh.view.add("element size")
    gmsh.view.addListData(view, "SS", len(tets), data.ravel().tolist())
    f = gmsh.model.mesh.field
    field = f.add("PostView")
    f.setNumber(field, "ViewTag", view)
    f.setAsBackgroundMesh(field)
    return float(h.min()), view


def mesh_solid(brep: Path | None, shaft: Shaft, grooves: Grooves | None,
               settings: MeshSettings,
               sizes: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
               cuts: tuple[float, ...] = ()) -> tuple[np.ndarray, np.ndarray]:
    """Tetrahedra of the solid in `brep` (None: a plain shaft's 90-degree sector):
    points (N, 3) in m and cells (E, 4 or 10) in meshio's node order. `sizes`: an
    element-size field (points, tets, size at each point, m) in place of the
    settings' groove and edge sizes; `cuts`: z (m) of planes the mesh must follow."""
    import meshio

    with session("mesh") as s, translated(MeshError, "gmsh could not mesh the solid"):
        gmsh = s.gmsh
        if brep is None:
            _quarter_cylinder(gmsh, shaft, cuts)
        else:
            gmsh.model.occ.importShapes(str(brep))
            gmsh.model.occ.synchronize()
            _cut_at(gmsh, cuts, shaft.radius)
        smallest, view = min(settings.edge_size, settings.size), None
        if sizes is not None:
            smallest, view = _background_sizes(gmsh, sizes)
        elif grooves is not None:
            _size_fields(gmsh, shaft, grooves, settings)
        s.option("Mesh.MeshSizeMax", settings.size)
        s.option("Mesh.MeshSizeMin", smallest * 0.5)
        s.option("Mesh.MeshSizeFromPoints", 0)
        s.option("Mesh.MeshSizeFromCurvature", 0)
        s.option("Mesh.MeshSizeExtendFromBoundary", 0)
        s.option("Mesh.Optimize", 1)
        gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], 1, "shaft")
        try:
            gmsh.model.mesh.generate(3)
            if settings.order == 2:
                gmsh.model.mesh.setOrder(2)
        finally:
            if view is not None:
                gmsh.view.remove(view)
        # through an .msh file and meshio: meshio puts the 10-node tets in VTK order
        fd, tmp = tempfile.mkstemp(suffix=".msh")
        os.close(fd)
        try:
            gmsh.write(tmp)
            with contextlib.redirect_stdout(io.StringIO()):  # meshio prints a blank line
                m = meshio.read(tmp)
        finally:
            os.unlink(tmp)
    cells = m.cells_dict.get(cell_type(settings.order))
    if cells is None or len(cells) == 0:
        raise MeshError("the mesh has no tetrahedra")
    return m.points, cells
