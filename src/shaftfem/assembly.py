"""Stiffness K and consistent mass M of 3D isotropic linear elasticity (scikit-fem).

    a(u, v) = int lambda div(u) div(v) + 2 mu eps(u) : eps(v) dx      (K, N/m)
    m(u, v) = int rho u . v dx                                         (M, kg)

Displacement DOFs are interleaved: global DOF 3 * n + c is component c (x, y, z)
of scalar node n of scikit-fem's P1/P2 basis (scikit-fem's vector ordering).

K is scikit-fem's vector-valued form. A trial before the project found it several
times slower than assembling 30x30 element blocks from the scalar basis; with
scikit-fem 12 it is faster (1.6 s against 2.0 s for the paper's shaft at 8 mm,
`benchmarks/assembly_routes.py`), so the library's form is used. M is the scalar
mass matrix times the 3x3 identity.
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
    K = stiffness(skmesh, order, lam, mu)

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


def stiffness(skmesh, order: int, lam: float, mu: float) -> sp.csr_matrix:
    """Elastic stiffness (N/m) with scikit-fem's vector-valued P1/P2 basis."""
    from skfem import Basis, BilinearForm, ElementVector
    from skfem.helpers import ddot, sym_grad, trace

    @BilinearForm
    def elasticity(u, v, _):
        eps_u, eps_v = sym_grad(u), sym_grad(v)
        return lam * trace(eps_u) * trace(eps_v) + 2 * mu * ddot(eps_u, eps_v)

    basis = Basis(skmesh, ElementVector(_element(order)), intorder=STIFFNESS_INTORDER[order])
    return elasticity.assemble(basis).tocsr()
