"""The scalar elements, by order: scikit-fem's P1 and P2 tetrahedra, and a cubic one.

The cubic Lagrange tetrahedron (20 nodes: the vertices, two points on each edge at
its thirds, the centre of each face) in barycentric coordinates l_i:

    vertex i:                 l_i (3 l_i - 1)(3 l_i - 2) / 2
    edge (i, j), near i:      9/2 l_i l_j (3 l_i - 1)
    face (i, j, k):           27 l_i l_j l_k

An edge's two nodes are told apart by the edge's direction, from its local vertex
i to j. Neighbours agree on it when every element lists its vertices in ascending
global order (cad.mesh.sorted_cells): then each edge runs from its lower global vertex to
its higher in every element that shares it.
"""

from __future__ import annotations

import numpy as np

from shaftfem.cad.mesh import EDGES  # scikit-fem's (and meshio's) local edge order

# scikit-fem's reference tetrahedron: its faces in local order, its vertices
FACES = ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3))
VERTICES = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
# d l_i / d X on the reference element (l_0 = 1 - x - y - z)
GRAD_L = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def _cubic_element():
    from skfem import ElementH1
    from skfem.refdom import RefTet

    class ElementTetP3(ElementH1):
        """The cubic Lagrange tetrahedron on ascending-vertex cells (see the module)."""

        nodal_dofs = 1
        edge_dofs = 2
        facet_dofs = 1
        maxdeg = 3
        dofnames = ["u", "u", "u"]
        doflocs = np.vstack(
            [VERTICES]
            + [np.array([(2 * VERTICES[i] + VERTICES[j]) / 3, (VERTICES[i] + 2 * VERTICES[j]) / 3])
               for i, j in EDGES]
            + [VERTICES[list(f)].mean(axis=0)[None] for f in FACES])
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


def element(order: int):
    """scikit-fem's scalar element of that order (1, 2 or 3) on tetrahedra."""
    from skfem import ElementTetP1, ElementTetP2

    if order == 3:
        return _cubic_element()()
    return ElementTetP2() if order == 2 else ElementTetP1()
