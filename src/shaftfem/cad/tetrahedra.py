"""The reference tetrahedron and meshes of 4-, 10- and 20-node tetrahedra: node tables,
scikit-fem meshes of them, the cubic Lagrange element that maps 20-node cells, and the
element-wise Jacobian check every mesh passes.

The cubic Lagrange tetrahedron (20 nodes: the vertices, two points on each edge at
its thirds, the centre of each face) in barycentric coordinates l_i:

    vertex i:                 l_i (3 l_i - 1)(3 l_i - 2) / 2
    edge (i, j), near i:      9/2 l_i l_j (3 l_i - 1)
    face (i, j, k):           27 l_i l_j l_k

An edge's two nodes are told apart by the edge's direction, from its local vertex
i to j. Neighbours agree on it when every element lists its vertices in ascending
global order (sorted_cells): then each edge runs from its lower global vertex to
its higher in every element that shares it.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

MIN_JACOBIAN_RATIO = 0.02  # smallest det J / largest det J allowed within one element
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


# The 10 nodes of a quadratic tetrahedron (meshio's order): the vertices, the edges' midpoints.
QUADRATIC_NODES = np.vstack([VERTICES] + [(VERTICES[i] + VERTICES[j])[None] / 2
                                          for i, j in EDGES])


def barycentric(X: np.ndarray) -> np.ndarray:
    """Barycentric coordinates (n, 4) of reference points X (n, 3)."""
    return np.column_stack([1.0 - X.sum(axis=1), X])


# d l_i / d X on the reference element (l_0 = 1 - x - y - z)
GRAD_L = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def lagrange_cubic():
    """The cubic Lagrange tetrahedron (the class), for ascending-vertex cells."""
    from skfem import ElementH1
    from skfem.refdom import RefTet

    class ElementTetP3(ElementH1):
        """The cubic Lagrange tetrahedron on ascending-vertex cells (see the module)."""

        nodal_dofs = 1
        edge_dofs = 2
        facet_dofs = 1
        maxdeg = 3
        dofnames = ["u"] * 4      # one per DOF of a vertex, an edge (2) and a face
        doflocs = CUBIC_NODES
        refdom = RefTet

        def lbasis(self, X, i):
            lam = np.array([1.0 - X[0] - X[1] - X[2], X[0], X[1], X[2]])
            phi, dl = _cubic(lam, i)
            # chain rule: d phi / d X = sum_k (d phi / d l_k) (d l_k / d X)
            dphi = np.einsum("k...,kd->d...", dl, GRAD_L)
            return phi, dphi

    return ElementTetP3


def _cubic(lam: np.ndarray, i: int) -> tuple[np.ndarray, np.ndarray]:
    """Basis function i of the cubic tetrahedron at barycentric points `lam` (4, ...), and
    its derivatives with respect to the four l's."""
    dl = np.zeros_like(lam)
    if i < 4:
        a = lam[i]
        dl[i] = (27 * a**2 - 18 * a + 2) / 2
        return a * (3 * a - 1) * (3 * a - 2) / 2, dl
    if i < 16:
        e, near_j = divmod(i - 4, 2)
        a, b = EDGES[e] if not near_j else EDGES[e][::-1]
        la, lb = lam[a], lam[b]
        dl[a] = 4.5 * lb * (6 * la - 1)
        dl[b] = 4.5 * la * (3 * la - 1)
        return 4.5 * la * lb * (3 * la - 1), dl
    a, b, c = FACES[i - 16]
    dl[a], dl[b], dl[c] = 27 * lam[b] * lam[c], 27 * lam[a] * lam[c], 27 * lam[a] * lam[b]
    return 27 * lam[a] * lam[b] * lam[c], dl


def skfem_mesh(points: np.ndarray, cells: np.ndarray):
    """scikit-fem's mesh of points (N, 3) and cells (E, 4 or 10 in meshio's order, or 20
    ascending-vertex cells in the cubic element's order: cad.cubic).

    scikit-fem takes the cells' columns as its local nodes in the same order (vertices,
    then the edge nodes, then the face nodes), which `assembly.point_dofs` relies on.
    """
    from skfem import MeshTet1, MeshTet2

    kind = {10: MeshTet2, 20: _mesh_tet3()}.get(cells.shape[1], MeshTet1)
    return kind(np.ascontiguousarray(points.T), np.ascontiguousarray(cells.T))


@functools.cache
def _mesh_tet3():
    """scikit-fem's tetrahedral mesh with a cubic Lagrange map (20 nodes per cell)."""
    from skfem import MeshTet1

    @dataclass(repr=False)
    class MeshTet3(MeshTet1):
        elem: type = lagrange_cubic()
        affine: bool = False
        sort_t: bool = False

    return MeshTet3


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
    pts = list(QUADRATIC_NODES)
    pts += [(v[i] + v[j] + v[k]) / 3 for i, j, k in FACES]
    pts.append(v.mean(axis=0))
    if cells.shape[1] == 20:  # and the cubic map's edge nodes
        pts += list(CUBIC_NODES[4:16])
    # det J from J itself: scikit-fem's detDF raises on an exact zero, which a trial
    # share of an element's curving (straighten_folded) can give
    J = mapping.DF(np.array(pts).T)
    det = (J[0, 0] * (J[1, 1] * J[2, 2] - J[1, 2] * J[2, 1])
           - J[0, 1] * (J[1, 0] * J[2, 2] - J[1, 2] * J[2, 0])
           + J[0, 2] * (J[1, 0] * J[2, 1] - J[1, 1] * J[2, 0]))
    # each element against its straight-sided self (ascending-vertex cells mix orientations)
    det = np.sign(triple_products(points, cells))[:, None] * det
    return det.min(axis=1) / np.abs(det).max(axis=1)


def triple_products(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """(E,): six times each straight-sided tetrahedron's signed volume, m^3, from its
    first four nodes (positive where vertex 3 lies on the side of face 0-1-2 its
    right-handed normal points to)."""
    v = points[cells[:, :4]]
    return np.einsum("ed,ed->e", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]),
                     v[:, 3] - v[:, 0])


def straight_positions(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """(E, n - 4, 3): where a straight-sided element puts the edge and face nodes of
    `cells` (E, 10 in meshio's order, or 20 in the cubic element's)."""
    local = QUADRATIC_NODES if cells.shape[1] == 10 else CUBIC_NODES
    return np.einsum("nk,ekd->end", barycentric(local)[4:], points[cells[:, :4]])


# shares of its curving a folded element tries to keep, largest first, and the det J
# ratio that a share must give it (a barely valid element fits the field poorly)
KEPT_CURVING = (0.75, 0.5, 0.25)
KEPT_RATIO = 0.1


def straighten_folded(points: np.ndarray, cells: np.ndarray,
                      rounds: int = 10) -> tuple[np.ndarray, int]:
    """Take back the curving of every element (10- or 20-node) whose det J ratio is at
    most MIN_JACOBIAN_RATIO: each keeps the largest share of it (KEPT_CURVING) that gives
    it a ratio above KEPT_RATIO on its own, else none (straight-sided). Its shared nodes
    move too, so neighbours may need a next round; the last rounds straighten fully. The
    new points and how many elements were touched.

    A share kept is geometry kept: on a STEP bar with a cross hole, 28 elements made
    straight-sided moved its frequencies by up to 0.11 %, as much as the discretisation
    error (fem.estimate.straightening measures it, and the bound carries it)."""
    points = points.copy()
    done = np.zeros(len(cells), dtype=bool)
    width = cells.shape[1]
    for r in range(rounds):
        bad = element_jacobian_ratios(points, cells) <= MIN_JACOBIAN_RATIO
        if not bad.any():
            break
        nodes = cells[bad, 4:]
        straight = straight_positions(points, cells[bad])
        bend = points[nodes] - straight
        n = int(bad.sum())
        share = np.zeros(n)
        if r < rounds // 2:  # partial first; a fold left after that goes straight
            own = points[cells[bad]]       # each element on its own nodes
            alone = np.arange(width * n).reshape(n, width)
            for t in KEPT_CURVING:
                own[:, 4:] = straight + t * bend
                ok = (share == 0) & (element_jacobian_ratios(own.reshape(-1, 3), alone)
                                     > KEPT_RATIO)
                share[ok] = t
        points[nodes] = straight + share[:, None, None] * bend
        done |= bad
    return points, int(done.sum())


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
