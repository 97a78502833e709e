"""Tetrahedral meshes of the shaft's solid (gmsh), handed to scikit-fem.

Sizes: `MeshSettings.size` away from the grooves, `groove_size` at the groove
faces, `edge_size` at the groove's inner floor edges (where a sharp corner makes
the elastic field singular), graded in between. Second-order elements are
curved onto the CAD surfaces; every element's Jacobian determinant is checked
and a mesh with an inverted or degenerate element is refused.

Meshes are cached beside the shapes (``$SHAFTFEM_CACHE/meshes``), keyed by the
solid's BREP, the shaft and groove parameters, the settings, this module's
meshing constants and the gmsh version: a re-run of an unchanged scene (a new
excitation, another margin) skips meshing and gets the very same nodes.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import math
import os
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from .errors import MeshError
from .scene import Grooves, MeshSettings, Shaft

MIN_JACOBIAN_RATIO = 0.02  # smallest det J / largest det J allowed within one element
# Distance (in units of the size jump) over which the element size grows from the
# edge size to the groove size: 1 means each element is about twice its inner neighbour.
EDGE_GRADING = 1.0
# Bump when the meshing changes, so old cached meshes are not reused.
MESH_VERSION = 1


@dataclass
class ShaftMesh:
    """A tetrahedral mesh in m: points (N, 3), cells (E, 4 or 10) in VTK/meshio node order."""

    points: np.ndarray
    cells: np.ndarray
    order: int
    min_jacobian_ratio: float
    straightened: int  # P2 elements whose curved edges were straightened to stay valid
    seconds: float
    from_cache: bool = False

    @property
    def n_elements(self) -> int:
        return self.cells.shape[0]

    @property
    def cell_type(self) -> str:
        return "tetra10" if self.order == 2 else "tetra"

    def to_skfem(self):
        """The same mesh as a scikit-fem MeshTet1/MeshTet2 (node order handled by skfem.io)."""
        import meshio
        from skfem.io.meshio import from_meshio

        return from_meshio(meshio.Mesh(self.points, [(self.cell_type, self.cells)]))


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


def mesh_key(brep: Path, shaft: Shaft, grooves: Grooves | None, settings: MeshSettings) -> str:
    """A hash of everything the mesh depends on."""
    import gmsh

    h = hashlib.sha256()
    if grooves is not None:  # ungrooved shafts are meshed from the parameters alone
        h.update(Path(brep).read_bytes())
    payload = {
        "version": MESH_VERSION, "gmsh": gmsh.__version__,
        "constants": [MIN_JACOBIAN_RATIO, EDGE_GRADING],
        "shaft": asdict(shaft), "grooves": asdict(grooves) if grooves else None,
        "settings": asdict(settings),
    }
    h.update(json.dumps(payload, sort_keys=True, default=lambda v: round(v, 12)).encode())
    return h.hexdigest()[:20]


def mesh_shape(brep: Path, shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
               use_cache: bool = True) -> ShaftMesh:
    """Mesh the solid in `brep` (or fetch the same mesh from the cache)."""
    from .geometry import cache_dir

    t0 = time.perf_counter()
    path = cache_dir() / "meshes" / f"{mesh_key(brep, shaft, grooves, settings)}.npz"
    if use_cache and path.exists():
        with np.load(path) as z:
            return ShaftMesh(points=z["points"], cells=z["cells"], order=int(z["order"]),
                             min_jacobian_ratio=float(z["ratio"]),
                             straightened=int(z["straightened"]),
                             seconds=time.perf_counter() - t0, from_cache=True)
    mesh = _generate(brep, shaft, grooves, settings)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(suffix=".npz", dir=path.parent)
    with os.fdopen(fd, "wb") as f:
        np.savez(f, points=mesh.points, cells=mesh.cells, order=mesh.order,
                 ratio=mesh.min_jacobian_ratio, straightened=mesh.straightened)
    os.replace(tmp, path)
    return mesh


def _generate(brep: Path, shaft: Shaft, grooves: Grooves | None,
              settings: MeshSettings) -> ShaftMesh:
    import meshio

    from .geometry import gmsh_session

    t0 = time.perf_counter()
    with gmsh_session() as gmsh:
        gmsh.model.add("mesh")
        sector = grooves is None
        if sector:
            # An ungrooved shaft is meshed as a 90-degree sector with periodic radial
            # faces and copied four times: the mesh then has the shaft's 4-fold
            # symmetry, so bending pairs come out exactly degenerate.
            _quarter_cylinder(gmsh, shaft)
        else:
            gmsh.model.occ.importShapes(str(brep))
            gmsh.model.occ.synchronize()
        opt = gmsh.option.setNumber
        opt("Mesh.MeshSizeMax", settings.size)
        opt("Mesh.MeshSizeMin", min(settings.edge_size, settings.size) * 0.5)
        opt("Mesh.MeshSizeFromPoints", 0)
        opt("Mesh.MeshSizeFromCurvature", 0)
        opt("Mesh.MeshSizeExtendFromBoundary", 0)
        opt("Mesh.Optimize", 1)
        if grooves is not None:
            _size_fields(gmsh, shaft, grooves, settings)
        gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], 1, "shaft")
        try:
            gmsh.model.mesh.generate(3)
            if settings.order == 2:
                gmsh.model.mesh.setOrder(2)
        except Exception as exc:  # gmsh raises a bare Exception with its log line
            raise MeshError(f"gmsh could not mesh the solid: {exc}") from None
        fd, tmp = tempfile.mkstemp(suffix=".msh")
        os.close(fd)
        try:
            gmsh.write(tmp)
            with contextlib.redirect_stdout(io.StringIO()):  # meshio prints a blank line
                m = meshio.read(tmp)
        finally:
            os.unlink(tmp)
    cell_type = "tetra10" if settings.order == 2 else "tetra"
    cells = m.cells_dict.get(cell_type)
    if cells is None or len(cells) == 0:
        raise MeshError("the mesh has no tetrahedra")
    points = m.points
    if sector:
        points, cells = _four_copies(points, cells)
    points, cells = _compact(points, cells)
    straightened = 0
    if settings.order == 2:
        points, straightened = straighten_bad_elements(points, cells)
    ratio = check_jacobians(points, cells)
    return ShaftMesh(points=points, cells=cells, order=settings.order, min_jacobian_ratio=ratio,
                     straightened=straightened, seconds=time.perf_counter() - t0)


def _quarter_cylinder(gmsh, shaft: Shaft) -> None:
    occ = gmsh.model.occ
    occ.addCylinder(0, 0, 0, 0, 0, shaft.length, shaft.radius, angle=math.pi / 2)
    occ.synchronize()
    planes = {}
    for _, f in gmsh.model.getEntities(2):
        c = gmsh.model.occ.getCenterOfMass(2, f)
        if abs(c[1]) < 1e-12 and c[0] > 0:
            planes["y0"] = f
        elif abs(c[0]) < 1e-12 and c[1] > 0:
            planes["x0"] = f
    # exact quarter turn about z: (x, y) -> (-y, x)
    turn = [0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    gmsh.model.mesh.setPeriodic(2, [planes["x0"]], [planes["y0"]], turn)


def _four_copies(points: np.ndarray, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rotate a quarter mesh by 0, 90, 180, 270 degrees and merge the shared nodes."""
    pts, cls = [], []
    p = points.copy()
    for k in range(4):
        pts.append(p)
        cls.append(cells + k * len(points))
        p = np.column_stack([-p[:, 1], p[:, 0], p[:, 2]])  # exact quarter turn
    allp = np.vstack(pts)
    # Copies of a node agree to round-off of the periodic mapping; merge on a 1e-9 m grid.
    _, first, inverse = np.unique(np.round(allp, 9), axis=0, return_index=True,
                                  return_inverse=True)
    return allp[first], inverse.reshape(-1)[np.vstack(cls)]


def _compact(points: np.ndarray, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Drop nodes no element uses (gmsh keeps CAD points as mesh nodes)."""
    used = np.unique(cells)
    remap = np.full(points.shape[0], -1, dtype=np.int64)
    remap[used] = np.arange(used.size)
    return np.ascontiguousarray(points[used]), remap[cells]


# Edges of a 10-node tetrahedron in VTK/meshio order: node 4 + k sits on EDGES[k].
EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))


def straighten_bad_elements(points: np.ndarray, cells: np.ndarray,
                            rounds: int = 5) -> tuple[np.ndarray, int]:
    """Move the edge nodes of badly curved P2 elements back to their edges' midpoints.

    Curving second-order tets onto the helical groove faces can invert thin
    elements. gmsh's high-order optimiser repairs them but is slow and has aborted
    the whole process (an uncaught C++ exception) on this geometry, so such
    elements are made straight-sided instead: always valid, at a local geometric
    error of the order of the element's curvature. Returns the new points and
    how many elements were straightened.
    """
    points = points.copy()
    done = np.zeros(len(cells), dtype=bool)
    for _ in range(rounds):
        bad = (element_jacobian_ratios(points, cells) <= MIN_JACOBIAN_RATIO) & ~done
        if not bad.any():
            break
        c = cells[bad]
        for k, (a, b) in enumerate(EDGES):
            points[c[:, 4 + k]] = 0.5 * (points[c[:, a]] + points[c[:, b]])
        done |= bad
    return points, int(done.sum())


def check_jacobians(points: np.ndarray, cells: np.ndarray) -> float:
    """Refuse a mesh with an inverted or degenerate element; return the worst ratio."""
    ratio = jacobian_ratio(points, cells)
    if ratio <= MIN_JACOBIAN_RATIO:
        raise MeshError(
            f"the mesh has an inverted or degenerate element (min/max det J within an "
            f"element = {ratio:.3g}, required > {MIN_JACOBIAN_RATIO}); try a different "
            "element size"
        )
    return ratio


def jacobian_ratio(points: np.ndarray, cells: np.ndarray) -> float:
    """Smallest over elements of min(det J) / max |det J|, sampled at nodes and inside."""
    return float(np.min(element_jacobian_ratios(points, cells)))


def element_jacobian_ratios(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Per element min(det J) / max |det J|, sampled at nodes and inside.

    Negative means an inverted element; the determinant is evaluated with
    scikit-fem's isoparametric mapping, the one the assembly integrates with.
    """
    import meshio
    from skfem.io.meshio import from_meshio

    ctype = "tetra10" if cells.shape[1] == 10 else "tetra"
    mesh = from_meshio(meshio.Mesh(points, [(ctype, cells)]))
    mapping = mesh._mapping()
    # vertices, edge midpoints, face centroids and the centroid of the reference tet
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    pts = list(v)
    pts += [(v[i] + v[j]) / 2 for i in range(4) for j in range(i + 1, 4)]
    pts += [(v[i] + v[j] + v[k]) / 3 for i, j, k in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3))]
    pts.append(v.mean(axis=0))
    det = mapping.detDF(np.array(pts).T)
    sign = np.sign(np.median(det))
    det = sign * det
    return det.min(axis=1) / np.abs(det).max(axis=1)
