"""The solid's tetrahedral mesh, made by gmsh and read back through meshio.

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
from pathlib import Path

import numpy as np

from shaftfem.cad.session import session, translated
from shaftfem.errors import MeshError
from shaftfem.scene.model import Grooves, MeshSettings, Section, Shaft, cell_type

# Under an attached part's hub, and one shaft radius beyond each end, elements are
# HUB_SIZE times the size away from the grooves, graded back over one diameter: the
# part's inertia acts on the shaft there: a gear's tilting mode (the cylinder of
# tests/test_parts.py, the joint then on the slice under the hub) came 0.60 % from a
# beam's at the default 8 mm, 0.41 % with 4 mm there, at 1.4 times the DOFs.
HUB_SIZE = 0.5

# A bored section's elements are at most this many times its wall thickness: a 1.5 mm
# wall under 12 mm elements left gmsh no valid surface mesh (its faces intersected).
WALL_ELEMENTS = 2.0
# ... and at most this many times its bore's radius: larger ones, curved onto the bore,
# fold. A 16 mm bore under the 14 mm elements of a 16 mm mesh had its elements straightened
# there, and the frequencies moved by up to 0.5 %.
BORE_ELEMENTS = 1.0

# Elements per full turn of a curved face of a STEP solid (gmsh's size from curvature):
# a 1 mm fillet gets elements of about 0.5 mm, a 32 mm shaft's surface about 8 mm ones.
STEP_CURVATURE = 12

# Distance (in units of the size jump) over which the element size grows from the
# groove size on the groove and feature faces to the size away from them.
FACE_GRADING = 2.5

# Distance (in units of the size jump) over which the element size grows from the
# edge size to the groove size: 1 means each element is about twice its inner neighbour.
EDGE_GRADING = 1.0


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


def _groove_entities(gmsh, shaft: Shaft, grooves: Grooves
                     ) -> tuple[list[int], dict[int, np.ndarray]]:
    """Boundary faces of the grooves, and the helical curves along their floor edges
    with their sampled points."""
    L = shaft.length
    R = shaft.profile[shaft.section_at(grooves.start + grooves.length / 2) or 0].diameter_start / 2
    floor = R - grooves.depth
    tol = 1e-6

    lo, hi = grooves.cut

    def in_zone(z: np.ndarray) -> bool:
        return bool(np.all((z > lo - tol) & (z < hi + tol)))

    faces = []
    for _, s in gmsh.model.getEntities(2):
        up, _ = gmsh.model.getAdjacencies(2, s)
        if len(up) != 1:
            continue  # a face between two cells
        xyz = _sample(gmsh, 2, s)
        r = np.hypot(xyz[:, 0], xyz[:, 1])
        if np.all(np.abs(r - R) < tol) or np.all(np.abs(xyz[:, 2]) < tol) or np.all(
            np.abs(xyz[:, 2] - L) < tol
        ) or not in_zone(xyz[:, 2]):
            continue
        faces.append(s)
    edges = {}
    for _, c in gmsh.model.getEntities(1):
        xyz = _sample(gmsh, 1, c, 5)
        r = np.hypot(xyz[:, 0], xyz[:, 1])
        # every curve on the floor radius: the helical floor edges, and the arcs where
        # the grooves' flat ends meet the floor (sharp re-entrant edges) or their runouts
        # leave it (a shallow kink)
        if np.all(np.abs(r - floor) < tol) and in_zone(xyz[:, 2]):
            edges[c] = xyz
    return faces, edges


def _near(gmsh, entities: str, tags: list[int], sampling: int, small: float, large: float,
          grading: float, local: bool = False) -> int:
    """A size field: `small` within small / 2 of the entities (`entities`: gmsh's
    "SurfacesList" or "CurvesList"), growing linearly to `large` over `grading` times
    the difference; beyond that `large` everywhere, or, `local`, no size at all (another
    field's)."""
    f = gmsh.model.mesh.field
    d = f.add("Distance")
    f.setNumbers(d, entities, tags)
    f.setNumber(d, "Sampling", sampling)
    t = f.add("Threshold")
    f.setNumber(t, "InField", d)
    f.setNumber(t, "SizeMin", small)
    f.setNumber(t, "SizeMax", large)
    f.setNumber(t, "DistMin", 0.5 * small)
    f.setNumber(t, "DistMax", 0.5 * small + grading * (large - small))
    if local:
        f.setNumber(t, "StopAtDistMax", 1)
    return t


def _edge_field(gmsh, curves: dict[int, np.ndarray], s: MeshSettings,
                local: bool = False) -> int:
    """edge_size along `curves` (tag: sampled points), graded to groove_size; the
    distance to them sampled about twice per element along the longest (its 5 sampled
    points make it a fifth short at most)."""
    longest = max(float(np.sum(np.linalg.norm(np.diff(xyz, axis=0), axis=1)))
                  for xyz in curves.values()) * 6 / 5
    return _near(gmsh, "CurvesList", list(curves), max(20, math.ceil(2 * longest / s.edge_size)),
                 s.edge_size, s.groove_size, EDGE_GRADING, local)


def _groove_fields(gmsh, shaft: Shaft, grooves: Grooves, s: MeshSettings) -> list[int]:
    """Size fields: groove_size at the groove faces, edge_size at the floor curves."""
    faces, edges = _groove_entities(gmsh, shaft, grooves)
    fields = []
    if faces:
        fields.append(_near(gmsh, "SurfacesList", faces, 60, s.groove_size, s.size,
                            FACE_GRADING))
    if edges and s.edge_size < s.groove_size:
        fields.append(_edge_field(gmsh, edges, s))
    return fields


def _hub_fields(gmsh, shaft: Shaft, hubs: tuple[tuple[float, float], ...],
                s: MeshSettings) -> list[int]:
    """Size fields: HUB_SIZE * size under each hub and one radius beyond it."""
    f = gmsh.model.mesh.field
    fields = []
    pad = shaft.radius
    for z0, z1 in hubs:
        b = f.add("Box")
        for key, value in dict(VIn=HUB_SIZE * s.size, VOut=s.size, XMin=-2 * pad,
                               XMax=2 * pad, YMin=-2 * pad, YMax=2 * pad, ZMin=z0 - pad,
                               ZMax=z1 + pad, Thickness=2 * pad).items():
            f.setNumber(b, key, value)
        fields.append(b)
    return fields


def section_size(shaft: Shaft, sec: Section, size: float) -> float:
    """A profile section's element size, m: `size` times its diameter over the largest
    (in proportion, so that a mesh asked 1.5 times coarser is that everywhere, as the
    bound's second mesh must be); in a bored section at most WALL_ELEMENTS times its wall
    (a thin wall needs elements of its thickness to be meshed at all) and BORE_ELEMENTS
    times the bore's radius."""
    thinnest = min(sec.diameter_start, sec.diameter_end)
    local = size * thinnest / (2 * shaft.radius)
    if sec.bore:
        local = min(local, WALL_ELEMENTS * (thinnest - sec.bore) / 2,
                    BORE_ELEMENTS * sec.bore / 2)
    return min(local, size)


def _profile_fields(gmsh, shaft: Shaft, s: MeshSettings) -> list[int]:
    """Size fields of a stepped shaft: each section's elements at its section_size,
    `groove_size` on the faces of its features
    (fillets, chamfers, keyways), graded back to the size over 2.5 times the difference,
    and `edge_size` along its sharp concave edges (a keyway's floor edges, a step without
    a fillet), where the stress is singular, as at the grooves' floor edges."""
    from shaftfem.cad.outline import feature_faces, singular_edges

    f = gmsh.model.mesh.field
    fields = []
    for sec, (z0, z1) in zip(shaft.profile, shaft.section_bounds()):
        local = section_size(shaft, sec, s.size)
        if local < s.size:
            b = f.add("Box")
            big = 2 * shaft.radius
            for key, value in dict(VIn=local, VOut=s.size, XMin=-big, XMax=big, YMin=-big,
                                   YMax=big, ZMin=z0, ZMax=z1, Thickness=local).items():
                f.setNumber(b, key, value)
            fields.append(b)
    samples = {t: _sample(gmsh, 2, t) for _, t in gmsh.model.getEntities(2)}
    faces = feature_faces(shaft, samples)
    if faces and s.groove_size < s.size:
        fields.append(_near(gmsh, "SurfacesList", faces, 40, s.groove_size, s.size,
                            FACE_GRADING))
    curves = {t: _sample(gmsh, 1, t, 5) for _, t in gmsh.model.getEntities(1)}
    edges = singular_edges(shaft, curves)
    if edges and s.edge_size < s.groove_size:
        fields.append(_edge_field(gmsh, {t: curves[t] for t in edges}, s, local=True))
    return fields


def _background(gmsh, fields: list[int]) -> None:
    """The smallest of the size fields as the mesh's size."""
    if fields:
        f = gmsh.model.mesh.field
        m = f.add("Min")
        f.setNumbers(m, "FieldsList", fields)
        f.setAsBackgroundMesh(m)


def _cut_at(gmsh, cuts: tuple[float, ...], radius: float) -> None:
    """Split the solid by the planes z = cuts, so that the mesh has faces there and a
    seat band (shaftfem.fem.supports) is exactly a set of boundary faces.

    Each volume is cut by its own planes alone: seats sit on the plain stretches, and
    a fragment of the whole grooved solid would intersect every helical face anew."""
    if not cuts:
        return
    occ = gmsh.model.occ
    for _, v in gmsh.model.getEntities(3):
        z0, z1 = occ.getBoundingBox(3, v)[2::3]
        inside = [z for z in cuts if z0 + 1e-9 < z < z1 - 1e-9]
        if inside:
            disks = [(2, occ.addDisk(0, 0, z, 2 * radius, 2 * radius)) for z in inside]
            occ.fragment([(3, v)], disks)
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

def mesh_options(s, shaft: Shaft, largest: float, smallest: float, hxt: bool) -> None:
    """The session's meshing options: sizes from the background field alone, between
    half the smallest it asks and `largest` (m); a STEP solid's small features found by
    their curvature; `hxt`: the volume by HXT on one thread (reproducible) instead of
    the Delaunay refinement."""
    s.option("Mesh.MeshSizeMax", largest)
    s.option("Mesh.MeshSizeMin", smallest * 0.5)
    s.option("Mesh.MeshSizeFromPoints", 0)
    # the user's own solid: its small features are found by their curvature
    s.option("Mesh.MeshSizeFromCurvature", STEP_CURVATURE if shaft.step else 0)
    s.option("Mesh.MeshSizeExtendFromBoundary", 0)
    s.option("Mesh.Optimize", 1)
    if hxt:
        s.option("Mesh.Algorithm3D", 10)
        s.option("Mesh.MaxNumThreads3D", 1)


def scene_fields(gmsh, shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
                 hubs: tuple[tuple[float, float], ...]) -> tuple[list[int], float]:
    """The size fields of the settings on the current model (the hubs', the grooves',
    the profile's features'), and the smallest size they ask, m."""
    smallest = min(settings.edge_size, settings.size)
    fields = _hub_fields(gmsh, shaft, hubs, settings)
    if hubs:
        smallest = min(smallest, HUB_SIZE * settings.size)
    if grooves is not None:
        fields += _groove_fields(gmsh, shaft, grooves, settings)
    if shaft.profile and not shaft.plain:
        fields += _profile_fields(gmsh, shaft, settings)
    return fields, smallest


def _background_sizes(gmsh, sizes: tuple[np.ndarray, np.ndarray, np.ndarray]
                      ) -> tuple[float, int, int]:
    """Element sizes from a former mesh: `sizes` = (points (N, 3), tets (E, 4), size at
    each point, m), a list-based view read through a PostView field. Returns the smallest
    size, the view (to be removed after meshing) and the field."""
    points, tets, h = sizes
    xyz = points[tets]
    data = np.hstack([xyz[:, :, 0], xyz[:, :, 1], xyz[:, :, 2], h[tets]])
    view = gmsh.view.add("element size")
    gmsh.view.addListData(view, "SS", len(tets), data.ravel().tolist())
    f = gmsh.model.mesh.field
    field = f.add("PostView")
    f.setNumber(field, "ViewTag", view)
    return float(h.min()), view, field


def mesh_solid(brep: Path | None, shaft: Shaft, grooves: Grooves | None,
               settings: MeshSettings,
               sizes: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
               cuts: tuple[float, ...] = (), hubs: tuple[tuple[float, float], ...] = (),
               refine: bool = False, hxt: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Tetrahedra of the solid in `brep` (None: a plain shaft's 90-degree sector):
    points (N, 3) in m and cells (E, 4 or 10) in meshio's node order, or (E, 20) in the
    cubic element's (cad.cubic) for `settings.geometry_order` 3. `sizes`: an
    element-size field (points, tets, size at each point, m) in place of the settings'
    groove, edge and hub sizes, or with `refine` the smaller of it and those at each
    point (a former mesh refined, never coarsened); `cuts`: z (m) of planes the mesh must
    follow; `hubs`: (z0, z1) (m) of the parts' seats, meshed finer; `hxt`: the volume
    by gmsh's HXT on one thread (reproducible) instead of its Delaunay refinement."""

    with session("mesh") as s, translated(MeshError, "gmsh could not mesh the solid"):
        gmsh = s.gmsh
        if brep is None:
            _quarter_cylinder(gmsh, shaft, cuts)
        else:
            gmsh.model.occ.importShapes(str(brep))
            gmsh.model.occ.synchronize()
            _cut_at(gmsh, cuts, shaft.radius)
        smallest, view = min(settings.edge_size, settings.size), None
        fields: list[int] = []
        if sizes is None or refine:
            fields, smallest = scene_fields(gmsh, shaft, grooves, settings, hubs)
        if sizes is not None:
            given, view, field = _background_sizes(gmsh, sizes)
            smallest = given if not refine else min(smallest, given)
            fields.append(field)
        _background(gmsh, fields)
        mesh_options(s, shaft, settings.size, smallest, hxt)
        gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], 1, "shaft")
        try:
            gmsh.model.mesh.generate(3)
            if settings.geometry_order == 3:
                # no high-order optimiser: cad.cubic carries the boundary's curving
                # inside and straightens what still folds (see there for why)
                gmsh.model.mesh.setOrder(3)
                _even_on_cad(gmsh)
                return _cubic_cells(gmsh)
            if settings.order >= 2:  # curved: the geometry is quadratic for P2 and up
                gmsh.model.mesh.setOrder(2)
        finally:
            if view is not None:
                gmsh.view.remove(view)
        return read_tetrahedra(gmsh, settings.order, "the mesh")


def read_tetrahedra(gmsh, order: int, what: str) -> tuple[np.ndarray, np.ndarray]:
    """The current model's tetrahedra of the element order's cell type, through an .msh
    file and meshio (meshio puts the 10-node tets in VTK order): points (N, 3) and cells;
    `what` names the mesh in the error when it has none."""
    import meshio

    fd, tmp = tempfile.mkstemp(suffix=".msh")
    os.close(fd)
    try:
        gmsh.write(tmp)
        with contextlib.redirect_stdout(io.StringIO()):  # meshio prints a blank line
            m = meshio.read(tmp)
    finally:
        os.unlink(tmp)
    cells = m.cells_dict.get(cell_type(order))
    if cells is None or len(cells) == 0:
        raise MeshError(f"{what} has no tetrahedra")
    return m.points, cells


def _cubic_cells(gmsh) -> tuple[np.ndarray, np.ndarray]:
    """gmsh's 20-node tetrahedra: points (N, 3) and cells (E, 20) in the cubic element's
    order, vertices ascending (cad.cubic)."""
    from shaftfem.cad.cubic import ascending

    etype = gmsh.model.mesh.getElementType("tetrahedron", 3)
    local = np.array(gmsh.model.mesh.getElementProperties(etype)[4]).reshape(-1, 3)
    _, nodes = gmsh.model.mesh.getElementsByType(etype)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    if len(nodes) == 0:
        raise MeshError("the mesh has no tetrahedra")
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(tags.size)
    cells = index[np.asarray(nodes, dtype=np.int64)].reshape(-1, 20)
    return coords.reshape(-1, 3), ascending(cells, local)


def _unwrapped(uv: np.ndarray, period: np.ndarray) -> np.ndarray:
    """Parameters (n, k, d) of each element's nodes, moved by whole periods next to its
    first node's (a periodic surface's or curve's seam)."""
    out = uv.copy()
    for d in range(uv.shape[2]):
        if period[d] > 0:
            out[:, :, d] -= period[d] * np.round((uv[:, :, d] - uv[:, :1, d]) / period[d])
    return out


def _even_on_cad(gmsh) -> None:
    """Every boundary node of a curved mesh at its element's parametric position: the
    nodes inside each boundary line and triangle go where the element's vertices'
    parameters, interpolated linearly, put them on the curve or surface.

    gmsh projects the straight element's points onto the surface instead: on a curved
    face that puts an edge's nodes nearer its ends than its thirds (0.325 on a 45-degree
    arc), an uneven map on which orders 3 and 4 fit the field worse. The 32 mm
    cylinder at 12 mm: torsion at order 4 9.3e-5 from c_t / 2L, 9.5e-6 with the nodes
    placed here (quadratic geometry's midpoints are even by symmetry)."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = {int(t): coords[3 * i:3 * i + 3] for i, t in enumerate(tags)}
    for dim, name in ((1, "line"), (2, "triangle")):
        etype = gmsh.model.mesh.getElementType(name, 3)
        local = np.array(gmsh.model.mesh.getElementProperties(etype)[4]).reshape(-1, dim)
        if dim == 1:
            lam = np.column_stack([(1 - local[:, 0]) / 2, (1 + local[:, 0]) / 2])
        else:
            lam = np.column_stack([1 - local.sum(axis=1), local])
        for _, tag in gmsh.model.getEntities(dim):
            _, nodes = gmsh.model.mesh.getElementsByType(etype, tag)
            if len(nodes) == 0:
                continue
            own = set(int(t) for t in gmsh.model.mesh.getNodes(dim, tag, includeBoundary=False)[0])
            cells = np.asarray(nodes, dtype=np.int64).reshape(-1, len(lam))
            verts = cells[:, :dim + 1]
            flat = np.concatenate([xyz[int(t)] for t in verts.ravel()])
            uv = np.asarray(gmsh.model.getParametrization(dim, tag, flat)).reshape(
                verts.shape[0], dim + 1, dim)
            period = _periods(gmsh, dim, tag)
            uv = _unwrapped(uv, period)
            for k in range(dim + 1, len(lam)):
                moving = np.array([int(t) in own for t in cells[:, k]])
                if not moving.any():
                    continue
                target = np.einsum("j,njd->nd", lam[k], uv[moving])
                new = np.asarray(gmsh.model.getValue(dim, tag, target.ravel())).reshape(-1, 3)
                for t, x, q in zip(cells[moving, k], new, target):
                    gmsh.model.mesh.setNode(int(t), x.tolist(), q.tolist())
                    xyz[int(t)] = x


def _periods(gmsh, dim: int, tag: int) -> np.ndarray:
    """Each parameter's period on a curve or surface (0: not periodic): its range, when
    the two ends of the range map to the same points."""
    lo, hi = gmsh.model.getParametrizationBounds(dim, tag)
    out = np.zeros(dim)
    for d in range(dim):
        rest = np.linspace(lo[1 - d], hi[1 - d], 5)[1:-1] if dim == 2 else [None]
        ends = []
        for end in (lo[d], hi[d]):
            uv = [[end, r] if d == 0 else [r, end] for r in rest] if dim == 2 else [[end]]
            ends.append(np.asarray(gmsh.model.getValue(dim, tag, np.ravel(uv))).reshape(-1, 3))
        size = np.ptp(np.vstack(ends), axis=0).max() + 1e-300
        if np.abs(ends[0] - ends[1]).max() < 1e-9 * max(size, 1e-3):
            out[d] = hi[d] - lo[d]
    return out
