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

Both are assembled over chunks of elements in threads, one per core, and the
chunks' matrices summed: NumPy releases the GIL in scikit-fem's element kernels,
so on 2 cores K of the paper's shaft takes 0.8-0.9 s instead of 1.5-2.4 s (the
same matrix to 3e-16).
"""

from __future__ import annotations

import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .errors import AssemblyError
from .runtime import assembly_threads
from .scene import Material

# Quadrature orders: 2 integrates P2 stiffness exactly on straight tets (4 points,
# as CalculiX's C3D10 does); 4 integrates the P2 mass exactly.
STIFFNESS_INTORDER = {1: 1, 2: 2}
MASS_INTORDER = {1: 2, 2: 4}


@dataclass(frozen=True)
class System:
    """K (N/m) and M (kg) in CSR form, with the nodes their DOFs belong to.

    Displacement DOF 3 n + c is component c of scalar node n; `point_dofs[i]` is
    the scalar node of the mesh's point i, so u at the points is
    X.reshape(-1, 3)[point_dofs].
    """

    K: sp.csr_matrix
    M: sp.csr_matrix
    mass_scalar: sp.csr_matrix  # scalar consistent mass, kg (for energy splits)
    nodes: np.ndarray           # (n_nodes, 3) positions of the scalar DOFs, m
    point_dofs: np.ndarray      # (n_points,) scalar node of each mesh point
    order: int
    seconds: float

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]

    def at_points(self, X: np.ndarray) -> np.ndarray:
        """Displacement vectors (n_dofs, m) at the mesh's points: (m, n_points, 3)."""
        n = self.nodes.shape[0]
        return np.stack([X[:, k].reshape(n, 3)[self.point_dofs] for k in range(X.shape[1])])


def _element(order: int):
    from skfem import ElementTetP1, ElementTetP2

    return ElementTetP2() if order == 2 else ElementTetP1()


def _chunks(skmesh, n: int, first: int = 64) -> list[np.ndarray]:
    """A small first chunk, then the rest of the elements in n chunks."""
    ix = np.arange(skmesh.nelements)
    return [ix[:first]] + [c for c in np.array_split(ix[first:], n) if len(c)]


def _sum(parts) -> sp.csr_matrix:
    total = parts[0]
    for p in parts[1:]:
        total = total + p
    return total.tocsr()


def assemble(mesh, material: Material, mass_intorder: int | None = None,
             threads: int | None = None) -> System:
    """K and M of a mesh.ShaftMesh with P1/P2 elements (its order), on `threads`
    threads (default: one per core)."""
    from skfem import Basis

    t0 = time.perf_counter()
    skmesh, order = mesh.to_skfem(), mesh.order
    lam, mu = material.lame
    intorder = mass_intorder or MASS_INTORDER[order]
    n = assembly_threads(threads)
    k_chunks, m_chunks = _chunks(skmesh, 2 * n), _chunks(skmesh, n)
    # scikit-fem fills a mesh's cached data (the affine map, the Jacobians) lazily
    # and not thread-safely: a P1 matrix assembled cold in two threads came out
    # wrong. The first, small chunk is assembled here first, which builds them.
    k_parts = [stiffness(skmesh, order, lam, mu, k_chunks[0])]
    m_parts = [scalar_mass(skmesh, order, intorder, m_chunks[0])]
    with ThreadPoolExecutor(n) as pool:
        k_jobs = [pool.submit(stiffness, skmesh, order, lam, mu, c) for c in k_chunks[1:]]
        m_jobs = [pool.submit(scalar_mass, skmesh, order, intorder, c) for c in m_chunks[1:]]
        K = _sum(k_parts + [f.result() for f in k_jobs])
        Ms = (material.density * _sum(m_parts + [f.result() for f in m_jobs])).tocsr()
    M = sp.kron(Ms, sp.identity(3, format="csr"), format="csr")
    basis = Basis(skmesh, _element(order), intorder=1)
    nodes = np.ascontiguousarray(basis.doflocs.T)
    _check_translations(K, nodes)
    return System(K=K, M=M, mass_scalar=Ms, nodes=nodes,
                  point_dofs=point_dofs(mesh.cells, basis.element_dofs, nodes, mesh.points),
                  order=order, seconds=time.perf_counter() - t0)


def point_dofs(cells: np.ndarray, element_dofs: np.ndarray, nodes: np.ndarray,
               points: np.ndarray) -> np.ndarray:
    """The scalar DOF of every mesh point: column j of `cells` is local DOF j of the
    scalar basis (mesh.skfem_mesh). Checked against the positions."""
    out = np.full(points.shape[0], -1, dtype=np.int64)
    out[cells.T] = element_dofs
    if np.any(out < 0) or np.max(np.abs(nodes[out] - points)) > 1e-12 * np.abs(points).max():
        raise AssemblyError("the mesh's points and the basis' DOF nodes do not correspond")
    return out


def _check_translations(K: sp.csr_matrix, nodes: np.ndarray) -> None:
    """A rigid translation must cost no strain energy: K t = 0 to round-off."""
    scale = np.abs(K.data).max() * np.sqrt(nodes.shape[0])
    for c in range(3):
        t = np.zeros(K.shape[0])
        t[c::3] = 1.0
        ratio = np.linalg.norm(K @ t) / scale
        if ratio > 1e-9:
            raise AssemblyError(
                f"the assembled stiffness resists a rigid translation along {'xyz'[c]} "
                f"(|K t| / |K| = {ratio:.2g}): K is wrong")


def stiffness(skmesh, order: int, lam: float, mu: float,
              elements: np.ndarray | None = None) -> sp.csr_matrix:
    """Elastic stiffness (N/m) with scikit-fem's vector-valued P1/P2 basis, of all
    elements or only of `elements` (indices)."""
    from skfem import Basis, BilinearForm, ElementVector
    from skfem.helpers import ddot, sym_grad, trace

    @BilinearForm
    def elasticity(u, v, _):
        eps_u, eps_v = sym_grad(u), sym_grad(v)
        return lam * trace(eps_u) * trace(eps_v) + 2 * mu * ddot(eps_u, eps_v)

    basis = Basis(skmesh, ElementVector(_element(order)), intorder=STIFFNESS_INTORDER[order],
                  elements=elements)
    return elasticity.assemble(basis).tocsr()


def scalar_mass(skmesh, order: int, intorder: int,
                elements: np.ndarray | None = None) -> sp.csr_matrix:
    """int phi_i phi_j dx (m^3) with the scalar P1/P2 basis; times density it is the mass."""
    from skfem import Basis, BilinearForm

    @BilinearForm
    def mass(u, v, _):
        return u * v

    return mass.assemble(Basis(skmesh, _element(order), intorder=intorder,
                               elements=elements)).tocsr()
