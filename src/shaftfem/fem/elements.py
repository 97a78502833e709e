"""The scalar elements, by order: scikit-fem's P1 and P2 tetrahedra, a cubic Lagrange
one, and a hierarchical family of any order p >= 2.

The cubic Lagrange tetrahedron (cad.tetrahedra) checks the hierarchical one.

The hierarchical tetrahedron of order p spans the cubic's polynomials at p = 3; its functions are
products of barycentric bubbles and Legendre polynomials P_n, so order p's functions are
order p - 1's and a few more (nested spaces: the frequencies fall as p rises):

    vertex i:                       l_i
    edge (a, b), k = 2..p:          l_a l_b P_(k-2)(l_b - l_a)
    face (a, b, c), i + j <= p - 3: l_a l_b l_c P_i(l_b - l_a) P_j(2 l_c - 1)
    interior, i + j + k <= p - 4:   l_0 l_1 l_2 l_3 P_i(l_1 - l_0) P_j(2 l_2 - 1) P_k(2 l_3 - 1)

On ascending-vertex cells (a < b < c in global numbering too) an edge's or a face's
functions depend only on its own barycentrics, in the same order from either side, so
neighbours agree without sign flips.
"""

from __future__ import annotations

import numpy as np

from shaftfem.cad.tetrahedra import (  # the reference tetrahedron, the cubic Lagrange map
    EDGES,
    FACES,
    GRAD_L,
    VERTICES,
)


def _legendre(n: int, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """P_n(s) and P_n'(s)."""
    from numpy.polynomial import legendre

    c = np.zeros(n + 1)
    c[n] = 1.0
    return legendre.legval(s, c), legendre.legval(s, legendre.legder(c))


def _pairs(n: int) -> list[tuple[int, int]]:
    """(i, j) with i + j <= n, by total degree: order p's face functions come first."""
    return [(i, d - i) for d in range(n + 1) for i in range(d, -1, -1)]


def _triples(n: int) -> list[tuple[int, int, int]]:
    return [(i, j, d - i - j) for d in range(n + 1) for i in range(d, -1, -1)
            for j in range(d - i, -1, -1)]


def hierarchical_counts(p: int) -> tuple[int, int, int]:
    """Functions per edge, per face and inside an element of order p."""
    return p - 1, (p - 1) * (p - 2) // 2, (p - 1) * (p - 2) * (p - 3) // 6


def _hierarchical(lam: np.ndarray, i: int, p: int) -> tuple[np.ndarray, np.ndarray]:
    """Hierarchical basis function i of order p at barycentric points `lam` (4, ...), and
    its derivatives with respect to the four l's (see the module)."""
    ne, nf, _ = hierarchical_counts(p)
    dl = np.zeros_like(lam)
    if i < 4:
        dl[i] = 1.0
        return lam[i].copy(), dl
    i -= 4
    if i < 6 * ne:
        e, n = divmod(i, ne)
        a, b = EDGES[e]
        la, lb = lam[a], lam[b]
        P, dP = _legendre(n, lb - la)
        dl[a] = lb * P - la * lb * dP
        dl[b] = la * P + la * lb * dP
        return la * lb * P, dl
    i -= 6 * ne
    if i < 4 * nf:
        f, n = divmod(i, nf)
        a, b, c = FACES[f]
        la, lb, lc = lam[a], lam[b], lam[c]
        ii, jj = _pairs(p - 3)[n]
        Pi, dPi = _legendre(ii, lb - la)
        Pj, dPj = _legendre(jj, 2 * lc - 1)
        bub = la * lb * lc
        dl[a] = lb * lc * Pi * Pj - bub * dPi * Pj
        dl[b] = la * lc * Pi * Pj + bub * dPi * Pj
        dl[c] = la * lb * Pi * Pj + 2 * bub * Pi * dPj
        return bub * Pi * Pj, dl
    i -= 4 * nf
    ii, jj, kk = _triples(p - 4)[i]
    Pi, dPi = _legendre(ii, lam[1] - lam[0])
    Pj, dPj = _legendre(jj, 2 * lam[2] - 1)
    Pk, dPk = _legendre(kk, 2 * lam[3] - 1)
    bub, Q = lam[0] * lam[1] * lam[2] * lam[3], Pi * Pj * Pk
    dl[0] = lam[1] * lam[2] * lam[3] * Q - bub * dPi * Pj * Pk
    dl[1] = lam[0] * lam[2] * lam[3] * Q + bub * dPi * Pj * Pk
    dl[2] = lam[0] * lam[1] * lam[3] * Q + 2 * bub * Pi * dPj * Pk
    dl[3] = lam[0] * lam[1] * lam[2] * Q + 2 * bub * Pi * Pj * dPk
    return bub * Q, dl


def hierarchical(p: int):
    """The hierarchical tetrahedron of order p >= 2, for ascending-vertex cells."""
    from skfem import ElementH1
    from skfem.refdom import RefTet

    ne, nf, ni = hierarchical_counts(p)

    class ElementTetHierarchical(ElementH1):
        """Hierarchical H1 tetrahedron of one order (see the module)."""

        nodal_dofs = 1
        edge_dofs = ne
        facet_dofs = nf
        interior_dofs = ni
        maxdeg = p
        dofnames = ["u"] * (1 + ne + nf + ni)
        # where each function "lives" (its vertex, or its edge's, face's or cell's centre);
        # no function is a value there except the vertices'
        doflocs = np.vstack(
            [VERTICES]
            + [np.repeat(((VERTICES[a] + VERTICES[b]) / 2)[None], ne, axis=0) for a, b in EDGES]
            + [np.repeat(VERTICES[list(f)].mean(axis=0)[None], nf, axis=0) for f in FACES]
            + [np.repeat(VERTICES.mean(axis=0)[None], ni, axis=0)])
        refdom = RefTet

        def lbasis(self, X, i):
            lam = np.array([1.0 - X[0] - X[1] - X[2], X[0], X[1], X[2]])
            phi, dl = _hierarchical(lam, i, p)
            return phi, np.einsum("k...,kd->d...", dl, GRAD_L)

    return ElementTetHierarchical()


def hierarchical_degrees(p: int) -> np.ndarray:
    """The polynomial degree of each local function of the order-p hierarchical
    tetrahedron: the functions of degree <= q span order q's space (q = 1 .. p)."""
    ne, nf, ni = hierarchical_counts(p)
    edge = list(range(2, p + 1))
    face = [3 + i + j for i, j in _pairs(p - 3)]
    interior = [4 + sum(t) for t in _triples(p - 4)] if ni else []
    return np.array([1] * 4 + edge * 6 + face * 4 + interior, dtype=np.int64)


def hierarchical_coordinates(basis) -> tuple[np.ndarray, np.ndarray]:
    """The coefficients, in a hierarchical `basis`, of the constant field 1 (n,) and of the
    coordinates x (n, 3): the fields rigid motions are made of. The geometry is a
    Lagrange map of degree g <= p (its nodes on the mesh), so x lies in the space: its
    coefficients on the functions of degree <= g interpolate the nodes, element by
    element (neighbours agree, as both sides interpolate the same shared nodes)."""
    from skfem import Basis

    mesh = basis.mesh
    geometry = Basis(mesh, mesh.elem(), intorder=1)
    nodes = geometry.doflocs[:, geometry.element_dofs]            # (3, n_geo, E)
    local = np.flatnonzero(hierarchical_degrees(basis.elem.maxdeg) <= mesh.elem.maxdeg)
    ref = mesh.elem.doflocs.T                                    # (3, n_geo)
    V = np.column_stack([basis.elem.lbasis(ref, int(i))[0] for i in local])  # (n_geo, n_geo)
    coeff = np.einsum("ij,cje->cie", np.linalg.inv(V), nodes)   # (3, n_geo, E)
    n = basis.N
    one, x = np.zeros(n), np.zeros((n, 3))
    dofs = basis.element_dofs[local]                              # (n_geo, E)
    one[basis.element_dofs[:4].ravel()] = 1.0
    x[dofs.ravel()] = coeff.reshape(3, -1).T
    return one, x


def element(order: int):
    """The scalar element of that order on tetrahedra: scikit-fem's P1 and P2, and the
    hierarchical one from 3 on (its spaces nested: order 4 contains order 3)."""
    from skfem import ElementTetP1, ElementTetP2

    if order >= 3:
        return hierarchical(order)
    return ElementTetP2() if order == 2 else ElementTetP1()
