"""Stiffness K and consistent mass M of 3D isotropic linear elasticity (scikit-fem).

    a(u, v) = int lambda div(u) div(v) + 2 mu eps(u) : eps(v) dx      (K, N/m)
    m(u, v) = int rho u . v dx                                         (M, kg)

Displacement DOFs are interleaved: global DOF 3 * n + c is component c (x, y, z)
of scalar node n of the scalar basis (scikit-fem's vector ordering; fem.elements).

Both come from scikit-fem's scalar basis (values, gradients and quadrature
weights on the curved elements): with D[a, i, b, j] = int d_i phi_a d_j phi_b dx,
the 3x3 block of K coupling nodes a and b is

    K_ab[i, j] = lambda D[a, i, b, j] + mu D[a, j, b, i] + mu delta_ij sum_k D[a, k, b, k],

one batched matrix product per chunk of elements, summed into the blocks of a
3x3-block sparse matrix. It is the same K as scikit-fem's vector-valued
`BilinearForm` (`stiffness` below, to round-off: a test checks it), several times
faster because it touches each scalar gradient once instead of 30 vector ones
(benchmarks/assembly_routes.py). M is the scalar mass times the 3x3 identity.
"""

from __future__ import annotations

from collections import deque
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp

from shaftfem.errors import AssemblyError
from shaftfem.runtime import assembly_threads
from shaftfem.scene.model import Material

# Quadrature orders: 2 integrates P2 stiffness exactly on straight tets (4 points,
# as CalculiX's C3D10 does); 4 integrates the P2 mass exactly; likewise 6 for order 3's
# mass. Order 3's stiffness takes 5 (14 points), not the exact 4: that rule has a
# negative weight, which can make an element's stiffness indefinite. Order 4 takes 7 (24
# points) for its stiffness, not the exact 6: that rule has 15 points, too few for a
# 35-function element's 99 strain modes (on the 16 mm cylinder it left three spurious
# zero-energy modes). Order 5 takes 9 (45 points, the highest rule scikit-fem has) for
# both: its stiffness is exact on straight elements, its mass one degree short.
STIFFNESS_INTORDER = {1: 1, 2: 2, 3: 5, 4: 7, 5: 9}
MASS_INTORDER = {1: 2, 2: 4, 3: 6, 4: 8, 5: 9}
# Where an integral must stay a sum of positive terms (energies, L2 projections): rules
# with positive weights only (scikit-fem's rules 3, 4, 8 and 9 have negative ones).
POSITIVE_INTORDER = {1: 2, 2: 4, 3: 6, 4: 7, 5: 7}
# Node pairs per chunk of the element kernels (4096 P2 elements of 10 x 10 pairs; 130
# of order 5's 56 x 56): the chunk's blocks stay in arrays of a few tens of MB, and the
# chunks spread over the threads.
CHUNK_PAIRS = 4096 * 100


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
    # (n_nodes, 3): the coefficients of the coordinate field x, m; for P1 and P2 the
    # positions of the scalar DOF nodes
    nodes: np.ndarray
    point_dofs: np.ndarray      # (n_points,) scalar node of each mesh point (P1, P2)
    order: int
    # orders 3 to 5: the values at the mesh's points from the scalar DOFs, (n_points, n_nodes)
    point_values: sp.csr_matrix | None = None
    # orders 3 to 5: the coefficients of the constant field 1 (n_nodes,): 1 on the vertex
    # functions, 0 on the rest (None: 1 everywhere, as for Lagrange elements)
    constant: np.ndarray | None = None
    # orders 3 to 5: the polynomial degree of each scalar DOF's function (n_nodes,)
    degrees: np.ndarray | None = None
    # orders 3 to 5: the scalar DOF of each element's local function (n_local, n_elements)
    element_dofs: np.ndarray | None = None

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]

    def at_points(self, X: np.ndarray) -> np.ndarray:
        """Displacement vectors (n_dofs, m) at the mesh's points: (m, n_points, 3)."""
        n = self.nodes.shape[0]
        if self.point_values is not None:
            return np.stack([self.point_values @ X[:, k].reshape(n, 3) for k in range(X.shape[1])])
        return np.stack([X[:, k].reshape(n, 3)[self.point_dofs] for k in range(X.shape[1])])


def _element(order: int):
    from shaftfem.fem.elements import element

    return element(order)


# --------------------------------------------------------------------------
# Element kernels: pure functions of the basis at the quadrature points


def elasticity_blocks(grad: np.ndarray, dx: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """Element stiffness blocks (E, n, n, 3, 3), N/m, of lam div u div v + 2 mu eps(u):eps(v).

    grad (E, Q, n, 3): gradients of the n scalar basis functions at Q points;
    dx (E, Q): quadrature weights times |J|."""
    E, Q, n, _ = grad.shape
    G = grad.reshape(E, Q, 3 * n)
    D = np.matmul((G * dx[:, :, None]).transpose(0, 2, 1), G).reshape(E, n, 3, n, 3)
    K = lam * D.transpose(0, 1, 3, 2, 4) + mu * D.transpose(0, 1, 3, 4, 2)
    div_free = mu * np.einsum("eakbk->eab", D)
    for c in range(3):
        K[:, :, :, c, c] += div_free
    return K


def mass_blocks(phi: np.ndarray, dx: np.ndarray) -> np.ndarray:
    """Scalar element mass matrices (E, n, n), m^3: int phi_a phi_b dx.

    phi (Q, n): the reference functions at the Q points (isoparametric elements:
    the same on every element); dx (E, Q): quadrature weights times |J|."""
    n = phi.shape[1]
    return (dx @ (phi[:, :, None] * phi[:, None, :]).reshape(len(phi), n * n)).reshape(-1, n, n)


# --------------------------------------------------------------------------
# Sparse structure: one 3x3 block per pair of nodes that share an element


@dataclass(frozen=True)
class Pattern:
    """Where each element's (a, b) node pair lands among the matrix's stored blocks."""

    indptr: np.ndarray
    indices: np.ndarray
    # (E * n * n,) index of the block of element e's pair (a, b); n_blocks for a pair
    # left out (a function outside the space)
    slot: np.ndarray
    n_nodes: int

    @classmethod
    def of(cls, element_dofs: np.ndarray, n_nodes: int,
           kept: np.ndarray | None = None) -> Pattern:
        """element_dofs (n, E): the scalar node of each element's local function;
        `kept` (n, E): which local functions belong to the space (None: all)."""
        n = element_dofs.shape[0]
        e = element_dofs.T.astype(np.int64)
        key = (np.repeat(e, n, axis=1) * n_nodes + np.tile(e, (1, n))).ravel()
        inside = None
        if kept is not None:
            k = kept.T
            inside = (np.repeat(k, n, axis=1) & np.tile(k, (1, n))).ravel()
            key = key[inside]
        pairs, slot = np.unique(key, return_inverse=True)
        if inside is not None:
            full = np.full(inside.size, len(pairs), dtype=np.int64)
            full[inside] = slot.ravel()
            slot = full
        indptr = np.searchsorted(pairs // n_nodes, np.arange(n_nodes + 1))
        return cls(indptr=indptr.astype(np.int32), indices=(pairs % n_nodes).astype(np.int32),
                   slot=slot.ravel(), n_nodes=n_nodes)

    @property
    def n_blocks(self) -> int:
        return len(self.indices)

    def sum_blocks(self, values: np.ndarray, elements: slice
                   ) -> tuple[np.ndarray | slice, np.ndarray]:
        """Sum (E, n, n, k) element values of `elements` by stored block: which blocks
        (n_blocks stands for the pairs left out) and their sums there, (m, k). Compact
        where the chunk touches few of the blocks (high orders), so that it costs its own
        size, not the matrix's; else all n_blocks + 1 (the sort would cost more)."""
        E, n = values.shape[0], values.shape[1]
        v = values.reshape(E * n * n, -1)
        row = self.slot[elements.start * n * n: elements.stop * n * n]
        touched: np.ndarray | slice = slice(0, self.n_blocks + 1)
        m = self.n_blocks + 1
        if self.n_blocks > 4 * len(row):
            touched, row = np.unique(row, return_inverse=True)
            m = len(touched)
        # a 0/1 matrix with one entry per column: its product scatters and adds in C
        scatter = sp.csc_matrix((np.ones(len(row)), row.ravel(), np.arange(len(row) + 1)),
                                shape=(m, len(row)))
        return touched, scatter @ v

    def upper(self, size: int) -> sp.csr_matrix:
        """The upper triangle (diagonal included) of the sparsity of `matrix(_, size)`,
        values ones, built from the blocks' pattern: scalar row size I + a holds the
        diagonal block's columns size I + a .. size I + size - 1, then the columns of
        the row's blocks right of the diagonal (the pattern holds every diagonal block)."""
        n, k = self.n_nodes, size
        rows = np.repeat(np.arange(n, dtype=np.int32), np.diff(self.indptr))
        if np.count_nonzero(self.indices == rows) != n:
            raise ValueError("upper: a block row without its diagonal block")
        right = self.indices > rows
        m = np.bincount(rows[right], minlength=n)            # blocks right of the diagonal
        del rows
        # each block row's right columns, once: k m_I entries, ascending
        cols = (k * self.indices[right][:, None] + np.arange(k, dtype=np.int32)).ravel()
        lengths = (np.arange(k, 0, -1)[None, :] + k * m[:, None]).ravel()
        indptr = np.zeros(n * k + 1, dtype=np.int64)
        np.cumsum(lengths, out=indptr[1:])
        indices = np.empty(int(indptr[-1]), dtype=np.int32)
        starts = indptr[:-1].reshape(n, k)
        for a in range(k):
            for t in range(k - a):       # the diagonal block's part of row (I, a)
                indices[starts[:, a] + t] = k * np.arange(n, dtype=np.int32) + a + t
        # the right part of row (I, a) starts after its k - a diagonal entries; the
        # right columns of block row I lie contiguously in `cols`, in the same order
        owner = np.repeat(np.arange(n), k * m)         # the block row of each entry of cols
        before = k * np.concatenate([[0], np.cumsum(m)[:-1]])
        for a in range(k):
            # entry j of cols, of block row I, goes to at[I] + j
            at = starts[:, a] + (k - a) - before
            indices[at[owner] + np.arange(cols.size)] = cols
        return sp.csr_matrix((np.ones(indptr[-1]), indices, indptr.astype(np.int32)
                              if indptr[-1] < 2**31 else indptr), shape=(n * k, n * k))

    def matrix(self, blocks: np.ndarray, size: int) -> sp.csr_matrix:
        """The CSR matrix of (n_blocks, size * size) summed blocks."""
        shape = (size * self.n_nodes,) * 2
        if size == 1:
            return sp.csr_matrix((blocks[:, 0], self.indices, self.indptr), shape=shape)
        return sp.bsr_matrix((blocks.reshape(-1, size, size), self.indices, self.indptr),
                             shape=shape).tocsr()


def _reference_values(basis, intorder: int) -> tuple[np.ndarray, np.ndarray]:
    """The basis' reference functions (Q, n) at the points of a rule of `intorder` on
    the reference tetrahedron, and the rule's weights times |J| on each element (E, Q)."""
    from skfem.quadrature import get_quadrature

    X, W = get_quadrature(basis.elem.refdom, intorder)
    phi = np.stack([basis.elem.lbasis(X, a)[0] for a in range(basis.Nbfun)], axis=-1)
    return phi, np.abs(basis.mapping.detDF(X)) * W


def _gradients(basis) -> np.ndarray:
    """Gradients (E, Q, n, 3) of a scalar scikit-fem basis' n functions, 1/m."""
    return np.stack([basis.basis[a][0].grad for a in range(basis.Nbfun)],
                    axis=-1).transpose(1, 2, 3, 0)


def _sum_over_chunks(kernel, n_elements: int, n_local: int, width: int, pattern: Pattern,
                     threads: int) -> np.ndarray:
    """The (n_blocks, width) sum of kernel(chunk), (E, n_local, n_local, width), over
    chunks of elements: the chunks' block sums made on `threads` threads (NumPy's products
    release the GIL), added in the chunks' order, so that K and M come out the same to the
    last bit on every run. The kernels only read arrays made before: scikit-fem fills a
    mesh's mapping lazily and not thread-safely (a cold P1 stiffness once came out 18 %
    wrong), so no scikit-fem call runs in the threads."""
    size = max(1, CHUNK_PAIRS // n_local**2)
    chunks = [slice(i, min(i + size, n_elements)) for i in range(0, n_elements, size)]
    total = np.zeros((pattern.n_blocks + 1, width))  # the last row: the pairs left out

    def sums(c: slice) -> tuple[np.ndarray | slice, np.ndarray]:
        return pattern.sum_blocks(kernel(c), c)

    def add(touched: np.ndarray | slice, block_sums: np.ndarray) -> None:
        total[touched] += block_sums

    if threads <= 1 or len(chunks) == 1:
        for c in chunks:
            add(*sums(c))
        return total[:pattern.n_blocks]
    # a few chunks ahead at most, so that the sums waiting to be added stay small
    with ThreadPoolExecutor(threads) as pool:
        waiting: deque[Future] = deque()
        for c in chunks:
            waiting.append(pool.submit(sums, c))
            if len(waiting) > 2 * threads:
                add(*waiting.popleft().result())
        while waiting:
            add(*waiting.popleft().result())
    return total[:pattern.n_blocks]


@dataclass(frozen=True)
class Discretisation:
    """A mesh's scalar basis and the sparsity of its K and M, before any value: what
    the solver's analysis (ordering) needs, so that it can start while K and M are
    assembled."""

    basis: Any         # scikit-fem's scalar basis at the stiffness quadrature
    pattern: Pattern
    order: int

    @property
    def n_dofs(self) -> int:
        return 3 * self.pattern.n_nodes

    def upper_structure(self) -> sp.csr_matrix:
        """The upper triangle (diagonal included) of K's sparsity as `assemble` stores K
        (3x3 blocks), values ones: what the solver's analysis reads."""
        return self.pattern.upper(3)


def discretise(mesh) -> Discretisation:
    """The scalar P1/P2 basis on a mesh.ShaftMesh and the block sparsity of K and M."""
    basis = scalar_basis(mesh)
    return Discretisation(basis=basis,
                          pattern=Pattern.of(basis.element_dofs, basis.N), order=mesh.order)


def scalar_basis(mesh):
    """scikit-fem's scalar basis of the mesh's order on a mesh.ShaftMesh, at the
    stiffness quadrature."""
    from skfem import Basis

    return Basis(mesh.to_skfem(), _element(mesh.order), intorder=STIFFNESS_INTORDER[mesh.order])


def stiffness_and_mass(basis, pattern: Pattern, material: Material, mass_intorder: int,
                       threads: int) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """K (N/m, 3x3 blocks) and the scalar consistent mass (kg) on a scalar basis, its
    element kernels summed over chunks on `threads` threads (the pattern's pairs left
    out, of functions outside the space, dropped)."""
    lam, mu = material.lame
    grad = _gradients(basis)
    phi, m_dx = _reference_values(basis, mass_intorder)
    n_el, nb = grad.shape[0], grad.shape[2]
    K = pattern.matrix(_sum_over_chunks(
        lambda c: elasticity_blocks(grad[c], basis.dx[c], lam, mu).reshape(
            c.stop - c.start, nb, nb, 9), n_el, nb, 9, pattern, threads), 3)
    Ms = material.density * pattern.matrix(_sum_over_chunks(
        lambda c: mass_blocks(phi, m_dx[c])[..., None], n_el, nb, 1, pattern, threads), 1)
    return K, Ms


def assemble(mesh, material: Material, mass_intorder: int | None = None,
             threads: int | None = None, discretisation: Discretisation | None = None
             ) -> System:
    """K and M of a mesh.ShaftMesh with P1/P2 elements (its order), on `threads`
    threads (default: one per core); `discretisation`: the mesh's, if made already."""
    d = discretisation or discretise(mesh)
    order, k_basis = d.order, d.basis
    K, Ms = stiffness_and_mass(k_basis, d.pattern, material,
                               mass_intorder or MASS_INTORDER[order], assembly_threads(threads))
    if order >= 3:  # hierarchical: values at the mesh's points come from the basis
        return hierarchical_system(mesh, k_basis, K, Ms)
    M = vector_mass(Ms)
    nodes = np.ascontiguousarray(k_basis.doflocs.T)
    _check_translations(K, nodes)
    return System(K=K, M=M, mass_scalar=Ms, nodes=nodes,
                  point_dofs=point_dofs(mesh.cells, k_basis.element_dofs, nodes, mesh.points),
                  order=order)


def hierarchical_degrees_of(basis) -> np.ndarray:
    """The polynomial degree of each of a hierarchical `basis`' scalar functions (N,)."""
    from shaftfem.fem.elements import hierarchical_degrees

    degrees = np.zeros(basis.N, dtype=np.int64)
    degrees[basis.element_dofs] = hierarchical_degrees(basis.elem.maxdeg)[:, None]
    return degrees


def hierarchical_system(mesh, basis, K: sp.csr_matrix, Ms: sp.csr_matrix,
                        keep: np.ndarray | None = None, order: int | None = None) -> System:
    """The System of K and the scalar mass Ms on a hierarchical `basis` of a
    mesh.ShaftMesh, or, with `keep` (ascending indices of its scalar functions), of the
    space they span (K and Ms already of those functions; `order` its highest degree).
    Checked: a rigid translation costs no strain."""
    from shaftfem.fem.elements import hierarchical_coordinates

    constant, nodes = hierarchical_coordinates(basis)
    degrees = hierarchical_degrees_of(basis)
    values = point_values(mesh.element_cells, basis, mesh.points.shape[0])
    element_dofs = basis.element_dofs
    if keep is not None:
        constant, nodes, degrees = constant[keep], nodes[keep], degrees[keep]
        values, element_dofs = values[:, keep].tocsr(), None
    _check_translations(K, nodes, constant)
    return System(K=K, M=vector_mass(Ms),
                  mass_scalar=Ms, nodes=nodes, point_dofs=np.zeros(0, np.int64),
                  order=order or mesh.order, point_values=values, constant=constant,
                  degrees=degrees, element_dofs=element_dofs)


def point_dofs(cells: np.ndarray, element_dofs: np.ndarray, nodes: np.ndarray,
               points: np.ndarray) -> np.ndarray:
    """The scalar DOF of every mesh point: column j of `cells` is local DOF j of the
    scalar basis (mesh.skfem_mesh). Checked against the positions."""
    out = np.full(points.shape[0], -1, dtype=np.int64)
    out[cells.T] = element_dofs
    if np.any(out < 0) or np.max(np.abs(nodes[out] - points)) > 1e-12 * np.abs(points).max():
        raise AssemblyError("the mesh's points and the basis' DOF nodes do not correspond")
    return out


def point_values(cells: np.ndarray, basis, n_points: int) -> sp.csr_matrix:
    """(n_points, n_nodes): the scalar field at every point of the mesh (the nodes of its
    10-node cells, or of its 20-node ones, in `cells`' local order) from the basis' DOFs."""
    from shaftfem.cad.tetrahedra import CUBIC_NODES, QUADRATIC_NODES

    ref = CUBIC_NODES if cells.shape[1] == 20 else QUADRATIC_NODES
    E = np.stack([basis.elem.lbasis(ref.T, i)[0] for i in range(basis.Nbfun)], axis=-1)
    # each point from the first element that has it
    points, first = np.unique(cells.ravel(), return_index=True)
    element, local = np.divmod(first, cells.shape[1])
    rows = np.repeat(points, basis.Nbfun)
    cols = basis.element_dofs[:, element].T.ravel()
    vals = E[local].ravel()
    P = sp.csr_matrix((vals, (rows, cols)), shape=(n_points, basis.N))
    P.eliminate_zeros()
    return P


def _check_translations(K: sp.csr_matrix, nodes: np.ndarray,
                        constant: np.ndarray | None = None) -> None:
    """A rigid translation must cost no strain energy: K t = 0 to round-off. `constant`:
    the coefficients of the constant field (None: 1 on every DOF)."""
    one = np.ones(nodes.shape[0]) if constant is None else constant
    scale = max(K.data.max(), -K.data.min()) * np.linalg.norm(one)
    T = np.zeros((K.shape[0], 3))
    for c in range(3):
        T[c::3, c] = one
    ratios = np.linalg.norm(K @ T, axis=0) / scale   # one pass over K for all three
    for c, ratio in enumerate(ratios):
        if ratio > 1e-9:
            raise AssemblyError(
                f"the assembled stiffness resists a rigid translation along {'xyz'[c]} "
                f"(|K t| / |K| = {ratio:.2g}): K is wrong")


def vector_mass(Ms: sp.csr_matrix) -> sp.csr_matrix:
    """M = Ms (x) I3, kg: the scalar mass on each of the three interleaved components
    (the CSR arrays written directly: row 3 i + c holds row i's entries at 3 j + c)."""
    Ms = Ms.tocsr()
    Ms.sort_indices()
    n, counts = Ms.shape[0], np.diff(Ms.indptr)
    indptr = np.zeros(3 * n + 1, dtype=np.int64)
    indptr[1:] = np.cumsum(np.repeat(counts, 3))
    row_of = np.repeat(np.arange(n), counts)          # the scalar row of each entry
    start = np.repeat(Ms.indptr[:-1], counts)         # and where its row starts
    # entry k of row i goes to rows 3 i + c, at offset (k - start) after the row's start
    within = np.arange(Ms.nnz) - start
    indices = np.empty(3 * Ms.nnz, dtype=np.int64)
    data = np.empty(3 * Ms.nnz)
    for c in range(3):
        at = indptr[3 * row_of + c] + within
        indices[at] = 3 * Ms.indices + c
        data[at] = Ms.data
    index_type = np.int32 if 3 * n < 2**31 and 3 * Ms.nnz < 2**31 else np.int64
    return sp.csr_matrix((data, indices.astype(index_type), indptr.astype(index_type)),
                         shape=(3 * n, 3 * n))


# --------------------------------------------------------------------------
# scikit-fem's own forms: the reference the block route is checked against


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
