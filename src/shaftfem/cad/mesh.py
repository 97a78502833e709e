"""Tetrahedral meshes of the shaft's solid (cad.mesher meshes; this module checks and caches).

Second-order elements are curved onto the CAD surfaces; every element's
Jacobian determinant is checked and a mesh with an inverted or degenerate
element is refused. A shaft without grooves is meshed as a 90-degree periodic
sector and copied four times, so the mesh has the shaft's 4-fold symmetry and
bending pairs come out exactly degenerate.

Meshes are cached beside the shapes (``$SHAFTFEM_CACHE/meshes``), keyed by the
solid's BREP, the shaft and groove parameters, the settings, the meshing
constants and the gmsh version: a re-run of an unchanged scene (a new
excitation, another margin) skips meshing and gets the very same nodes.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from shaftfem.cad.solid import ShaftShape
from shaftfem.errors import BudgetError, MeshError
from shaftfem.scene.model import Grooves, MeshSettings, Shaft, cell_type
from shaftfem.store import cache_dir, content_key, discard, load_arrays, save_arrays

MIN_JACOBIAN_RATIO = 0.02  # smallest det J / largest det J allowed within one element
# Bump when the meshing or the cache entry changes, so old cached meshes are not reused
# (2: entries carry checksums; 3: the checksum covers the arrays in name order).
MESH_VERSION = 3


def skfem_mesh(points: np.ndarray, cells: np.ndarray):
    """scikit-fem's MeshTet1 / MeshTet2 of points (N, 3) and meshio-ordered cells (E, 4 or 10).

    scikit-fem takes the cells' columns as its local nodes in the same order (vertices,
    then the edge nodes), which `assembly.point_dofs` relies on.
    """
    from skfem import MeshTet1, MeshTet2

    kind = MeshTet2 if cells.shape[1] == 10 else MeshTet1
    return kind(np.ascontiguousarray(points.T), np.ascontiguousarray(cells.T))


@dataclass(frozen=True)
class ShaftMesh:
    """A tetrahedral mesh in m: points (N, 3), cells (E, 4 or 10) in VTK/meshio node order."""

    points: np.ndarray
    cells: np.ndarray
    order: int
    min_jacobian_ratio: float
    straightened: int  # P2 elements whose curved edges were straightened to stay valid
    from_cache: bool = False

    @property
    def n_elements(self) -> int:
        return self.cells.shape[0]

    @property
    def cell_type(self) -> str:
        return cell_type(self.order)

    @property
    def element_cells(self) -> np.ndarray:
        """The cells as the elements take them: for P3, vertices in ascending order
        (sorted_cells), so that neighbours agree on their edges' nodes."""
        if self.order < 3:
            return self.cells
        return sorted_cells(self.cells)

    def to_skfem(self):
        """The same mesh as a scikit-fem MeshTet1/MeshTet2, its cells as `element_cells`."""
        return skfem_mesh(self.points, self.element_cells)


# Tetrahedra gmsh makes per h^3 of volume (a regular tetrahedron fills h^3 / 8.5; gmsh's
# are less regular), and DOFs per element of a P2 / P1 mesh; fitted on the shipped scenes
# (within 40 %, enough to refuse a size that is off by orders of magnitude).
ELEMENTS_PER_H3 = 6.0
DOFS_PER_ELEMENT = {1: 0.6, 2: 5.5, 3: 17.0, 4: 40.0}
BYTES_PER_DOF = 11e3   # peak memory of a modal run per DOF (docs/performance.md)


def _graded(h0: float, h1: float, d0: float, d1: float, measure) -> float:
    """Elements in a layer whose size is h0 up to distance d0 and grows linearly to h1 at
    d1, with `measure(x)` the area (or perimeter) at distance x of the feature."""
    x = np.linspace(0.0, d1, 400)
    h = np.where(x <= d0, h0, h0 + (h1 - h0) * (x - d0) / max(d1 - d0, 1e-12))
    return float(np.trapezoid(measure(x) / h**3, x)) * ELEMENTS_PER_H3


def estimate_dofs(shaft: Shaft, grooves: Grooves | None, settings: MeshSettings) -> int:
    """About how many DOFs `settings` give on this shaft, without meshing: the shaft at
    the element size, plus a graded layer over the groove faces and a tube around the
    floor edges (the size fields of cad.mesher)."""
    from shaftfem.cad.mesher import EDGE_GRADING

    s, order = settings.size, settings.order
    volume = np.pi * shaft.radius**2 * shaft.length
    elements = ELEMENTS_PER_H3 * volume / s**3
    if grooves is not None:
        g, gs, es = grooves, settings.groove_size, settings.edge_size
        r_mid = shaft.radius - g.depth / 2
        helix = g.length * np.hypot(1.0, 2 * np.pi * r_mid / g.pitch)
        faces = len(g.hands) * helix * (g.width + 2 * g.depth)
        if gs < s:
            elements += _graded(gs, s, 0.5 * gs, 0.5 * gs + 2.5 * (s - gs),
                                lambda x: np.full_like(x, faces))
        if es < gs:
            edges = 2 * len(g.hands) * helix
            elements += _graded(es, gs, 0.5 * es, 0.5 * es + EDGE_GRADING * (gs - es),
                                lambda x: edges * np.pi * np.maximum(x, 0.5 * es))
    return int(elements * DOFS_PER_ELEMENT[order])


def check_budget(shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
                 max_dofs: int) -> int:
    """Refuse, before meshing, a mesh that would need more than `max_dofs` DOFs."""
    n = estimate_dofs(shaft, grooves, settings)
    if n > max_dofs:
        raise BudgetError(
            f"element size {settings.size * 1e3:g} mm (grooves {settings.groove_size * 1e3:.3g} "
            f"mm, floor edges {settings.edge_size * 1e3:.3g} mm) would need about {n:.2g} DOFs "
            f"and {n * BYTES_PER_DOF / 1e9:.2g} GB, above the budget of {max_dofs} DOFs; "
            "use a larger size, or raise the budget ([mesh] max_dofs or --max-dofs)")
    return n


def mesh_key(shape: ShaftShape, shaft: Shaft, grooves: Grooves | None,
             settings: MeshSettings, cuts: tuple[float, ...] = (),
             hubs: tuple[tuple[float, float], ...] = ()) -> str:
    """A hash of everything the mesh depends on."""
    from shaftfem.cad.mesher import EDGE_GRADING, HUB_SIZE
    from shaftfem.cad.session import gmsh_version

    payload = {
        "version": MESH_VERSION, "gmsh": gmsh_version(),
        "constants": [MIN_JACOBIAN_RATIO, EDGE_GRADING],
        "shaft": asdict(shaft), "grooves": asdict(grooves) if grooves else None,
        "settings": asdict(settings), **({"cuts": list(cuts)} if cuts else {}),
        **({"hubs": [list(h) for h in hubs], "hub_size": HUB_SIZE} if hubs else {}),
    }
    return content_key(payload, files=() if shape.brep is None else (shape.brep,))


def mesh_shape(shape: ShaftShape, shaft: Shaft, grooves: Grooves | None,
               settings: MeshSettings, use_cache: bool = True,
               cuts: tuple[float, ...] = (), hubs: tuple[tuple[float, float], ...] = ()
               ) -> ShaftMesh:
    """Mesh the solid (or fetch the same mesh from the cache; without `use_cache` the
    cache is neither read nor written); `cuts`: z (m) where the mesh must have faces
    (the edges of seat bands); `hubs`: the parts' seats (z0, z1), meshed finer."""
    key = mesh_key(shape, shaft, grooves, settings, cuts, hubs)
    path = cache_dir() / "meshes" / f"{key}.npz"
    if use_cache and path.exists():
        fields, why = load_arrays(path, MESH_ARRAYS)
        if fields is not None:
            return mesh_from_arrays(fields)
        discard(f"mesh {key}", why, path)
    mesh = _generate(shape, shaft, grooves, settings, cuts=cuts, hubs=hubs)
    if use_cache:
        save_arrays(path, mesh_arrays(mesh))
    return mesh


MESH_ARRAYS = ("points", "cells", "order", "ratio", "straightened")


def mesh_arrays(mesh: ShaftMesh) -> dict[str, Any]:
    """A mesh as the named arrays of a cache entry."""
    return dict(points=mesh.points, cells=mesh.cells, order=np.int64(mesh.order),
                ratio=np.float64(mesh.min_jacobian_ratio),
                straightened=np.int64(mesh.straightened))


def mesh_from_arrays(fields: dict) -> ShaftMesh:
    """The mesh of a cache entry's arrays."""
    return ShaftMesh(points=fields["points"], cells=fields["cells"], order=int(fields["order"]),
                     min_jacobian_ratio=float(fields["ratio"]),
                     straightened=int(fields["straightened"]),
                     from_cache=True)


def remesh(shape: ShaftShape, shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
           sizes: tuple[np.ndarray, np.ndarray, np.ndarray],
           cuts: tuple[float, ...] = ()) -> ShaftMesh:
    """A new mesh of the solid following an element-size field (points (N, 3), tets
    (E, 4), size at each point, m), not cached (shaftfem.workflows.adapt caches its last mesh)."""
    return _generate(shape, shaft, grooves, settings, sizes, cuts)


def _generate(shape: ShaftShape, shaft: Shaft, grooves: Grooves | None,
              settings: MeshSettings, sizes=None, cuts: tuple[float, ...] = (),
              hubs: tuple[tuple[float, float], ...] = ()) -> ShaftMesh:
    from shaftfem.cad.mesher import mesh_solid

    points, cells = mesh_solid(shape.brep, shaft, grooves, settings, sizes, cuts, hubs)
    if shape.brep is None:
        points, cells = _four_copies(points, cells)
    points, cells = _compact(points, cells)
    straightened = 0
    if settings.order >= 2:
        points, straightened = straighten_bad_elements(points, cells)
    ratio = check_jacobians(points, cells)
    return ShaftMesh(points=points, cells=cells, order=settings.order, min_jacobian_ratio=ratio,
                     straightened=straightened)


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
# scikit-fem's reference tetrahedron: its vertices and its faces in local order
VERTICES = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
FACES = ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3))
# The 20 nodes of a cubic tetrahedron, reference coordinates: the vertices, two points on
# each edge at its thirds (the one near the edge's first vertex first), each face's centre.
CUBIC_NODES = np.vstack(
    [VERTICES]
    + [np.array([(2 * VERTICES[i] + VERTICES[j]) / 3, (VERTICES[i] + 2 * VERTICES[j]) / 3])
       for i, j in EDGES]
    + [VERTICES[list(f)].mean(axis=0)[None] for f in FACES])


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

    Negative means an element inverted against its straight-sided self; the
    determinant is evaluated with
    scikit-fem's isoparametric mapping, the one the assembly integrates with.
    """
    mapping = skfem_mesh(points, cells)._mapping()
    # vertices, edge midpoints, face centroids and the centroid of the reference tet
    v = VERTICES
    pts = list(v)
    pts += [(v[i] + v[j]) / 2 for i in range(4) for j in range(i + 1, 4)]
    pts += [(v[i] + v[j] + v[k]) / 3 for i, j, k in FACES]
    pts.append(v.mean(axis=0))
    det = mapping.detDF(np.array(pts).T)
    # each element against its straight-sided self (ascending-vertex cells mix orientations)
    v = points[cells[:, :4]]
    straight = np.einsum("ed,ed->e", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]),
                         v[:, 3] - v[:, 0])
    det = np.sign(straight)[:, None] * det
    return det.min(axis=1) / np.abs(det).max(axis=1)


def sorted_cells(cells: np.ndarray) -> np.ndarray:
    """Cells (E, 4) or (E, 10, meshio order) with their vertices in ascending order and
    the edge nodes permuted to match: the cubic element's (fem.elements) edge nodes then agree
    between neighbours. (An odd permutation flips the element's orientation; the
    quadrature takes |det J|.)"""
    perm = np.argsort(cells[:, :4], axis=1)
    out = np.take_along_axis(cells[:, :4], perm, axis=1)
    if cells.shape[1] == 4:
        return out
    edge_of = np.zeros((4, 4), dtype=np.int64)      # local vertices -> local edge
    for k, (a, b) in enumerate(EDGES):
        edge_of[a, b] = edge_of[b, a] = k
    rows = np.arange(cells.shape[0])
    mids = [cells[rows, 4 + edge_of[perm[:, a], perm[:, b]]] for a, b in EDGES]
    return np.hstack([out, np.column_stack(mids)])
