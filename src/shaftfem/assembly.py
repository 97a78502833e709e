"""Stiffness K and consistent mass M of 3D isotropic linear elasticity (scikit-fem).

    a(u, v) = int lambda div(u) div(v) + 2 mu eps(u) : eps(v) dx      (K, N/m)
    m(u, v) = int rho u . v dx                                         (M, kg)

Displacement DOFs are interleaved: global DOF 3 * n + c is component c (x, y, z)
of scalar node n of scikit-fem's P1/P2 basis.

K is assembled from scikit-fem's *scalar* basis: with D_ab[i, j] = int d_a phi_i
d_b phi_j, the 30x30 (P2) element block is

    K[(i,a), (j,b)] = lambda D_ab[i,j] + mu D_ba[i,j] + mu delta_ab sum_c D_cc[i,j],

which is several times faster than scikit-fem's generic vector-valued form
(`benchmarks/assembly_routes.py` measures both). M is the scalar mass matrix
times the 3x3 identity.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .scene import Material

# Quadrature orders: 2 integrates P2 stiffness exactly on straight tets (4 points,
# as CalculiX's C3D10 does); 4 integrates the P2 mass exactly.
STIFFNESS_INTORDER = {1: 1, 2: 2}
MASS_INTORDER = {1: 2, 2: 4}
_CHUNK = 20000  # elements per block of the element-matrix computation (memory bound)


@dataclass
class System:
    """K (N/m) and M (kg) in CSR form, with the nodes their DOFs belong to."""

    K: sp.csr_matrix
    M: sp.csr_matrix
    mass_scalar: sp.csr_matrix  # scalar consistent mass, kg (for energy splits)
    nodes: np.ndarray           # (n_nodes, 3) positions of the scalar DOFs, m
    order: int
    seconds: float

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]


def _element(order: int):
    from skfem import ElementTetP1, ElementTetP2

    return ElementTetP2() if order == 2 else ElementTetP1()


def assemble(skmesh, order: int, material: Material, mass_intorder: int | None = None) -> System:
    """K and M of `skmesh` (scikit-fem MeshTet1/MeshTet2) with P`order` elements."""
    from skfem import Basis, BilinearForm

    t0 = time.perf_counter()
    elem = _element(order)
    kb = Basis(skmesh, elem, intorder=STIFFNESS_INTORDER[order])
    lam, mu = material.lame
    K = stiffness(kb, lam, mu)

    @BilinearForm
    def mass(u, v, _):
        return u * v

    mb = kb if mass_intorder == STIFFNESS_INTORDER[order] else Basis(
        skmesh, elem, intorder=mass_intorder or MASS_INTORDER[order]
    )
    Ms = (material.density * mass.assemble(mb)).tocsr()
    M = sp.kron(Ms, sp.identity(3, format="csr"), format="csr")
    return System(K=K, M=M, mass_scalar=Ms, nodes=np.ascontiguousarray(kb.doflocs.T),
                  order=order, seconds=time.perf_counter() - t0)


def stiffness(basis, lam: float, mu: float) -> sp.csr_matrix:
    """Elastic stiffness from a scalar basis, element blocks of (3 n_loc)^2 entries."""
    nloc = len(basis.basis)
    nel = basis.nelems
    n = basis.N
    dofs = basis.element_dofs.T  # (nel, nloc)
    eye = np.eye(3)
    data = np.empty((nel, 3 * nloc, 3 * nloc))
    for lo in range(0, nel, _CHUNK):
        hi = min(nel, lo + _CHUNK)
        # grads[i, a, e, q]: derivative a of local basis function i at quadrature point q
        grads = np.stack([basis.basis[i][0].grad[:, lo:hi] for i in range(nloc)])
        wq = basis.dx[lo:hi]
        D = np.einsum("iaeq,jbeq,eq->eabij", grads, grads, wq, optimize=True)
        trace = np.einsum("eccij->eij", D)
        # Ke[e, i, a, j, b]
        Ke = (lam * D.transpose(0, 3, 1, 4, 2)
              + mu * D.transpose(0, 3, 2, 4, 1)
              + mu * trace[:, :, None, :, None] * eye[None, None, :, None, :])
        data[lo:hi] = Ke.reshape(hi - lo, 3 * nloc, 3 * nloc)
    gdof = (3 * dofs[:, :, None] + np.arange(3)).reshape(nel, 3 * nloc).astype(np.int32)
    rows = np.repeat(gdof, 3 * nloc, axis=1).ravel()
    cols = np.tile(gdof, (1, 3 * nloc)).ravel()
    K = sp.coo_matrix((data.ravel(), (rows, cols)), shape=(3 * n, 3 * n)).tocsr()
    K.sum_duplicates()
    return K
