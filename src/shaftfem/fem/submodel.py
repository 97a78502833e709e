"""A hot spot's local model driven by the whole shaft's solution (submodelling).

A slice of the solid round the spot (cad.local), meshed far finer there than the whole
shaft can afford, carries the same duty: its two cut faces move as the whole shaft's
P2 displacement field says (read at each of their nodes, `read_displacements`), and
gravity acts in it as in the whole; nothing else loads it (a slice is taken clear of
every load band and seat). Each of the duty's cases is one right-hand side of one
factorisation: K_ff u_f = f_f - K_fb u_b, with u_b prescribed on the cut faces.

The cut faces lie a few of the whole shaft's elements from the spot: its displacements
there are far more accurate than its stresses at the notch (they converge as h^3 against
h^2, and the notch's disturbance decays within about its own size, Saint-Venant).
"""

from __future__ import annotations

import numpy as np

from shaftfem.errors import SolverError

# candidate tetrahedra per point (the nearest centroids), and how far outside a curved
# tetrahedron a point may lie (its least barycentric coordinate) and still be read from
# it: a cut face's node on the true surface lies a hair outside a coarse mesh's
# element, curved onto the surface only to second order
CANDIDATES = 12
MORE_CANDIDATES = 400    # for the points the nearest CANDIDATES do not hold
REACH = 0.25
NEWTON_STEPS = 6
# VTK's 10-node tetrahedron: the vertices, then the edges' midpoints in this order
EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))


def _shape(lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """P2 shape functions (..., 10) at barycentric coordinates lam (..., 4), and their
    derivatives along lam_1..lam_3 (lam_0 = 1 - the others) (..., 10, 3)."""
    n = [lam[..., i] * (2 * lam[..., i] - 1) for i in range(4)]
    n += [4 * lam[..., i] * lam[..., j] for i, j in EDGES]
    dl = np.zeros(lam.shape + (3,))      # d lam_i / d xi_k
    dl[..., 0, :] = -1.0
    for k in range(3):
        dl[..., k + 1, k] = 1.0
    dn = [(4 * lam[..., i, None] - 1) * dl[..., i, :] for i in range(4)]
    dn += [4 * (lam[..., i, None] * dl[..., j, :] + lam[..., j, None] * dl[..., i, :])
           for i, j in EDGES]
    return np.stack(n, axis=-1), np.stack(dn, axis=-2)


def read_displacements(points: np.ndarray, cells: np.ndarray, u: np.ndarray,
                       at: np.ndarray) -> np.ndarray:
    """A P2 field u (cases, N, 3) at the points of a curved 10-node mesh (points (N, 3)
    m, cells (E, 10) in VTK's order), read at `at` (k, 3): in the element holding each
    point, found by inverting its curved map (Newton from the straight element's
    barycentric coordinates). Returns (cases, k, 3). A point farther outside every
    element than REACH is refused (SolverError): the slice and the whole do not match."""
    from scipy.spatial import cKDTree

    tree = cKDTree(points[cells[:, :4]].mean(axis=1))
    own, lam, worst = _located(points, cells, tree, at, min(CANDIDATES, len(cells)))
    # among small elements (a runout's seam, a fine feature) the nearest centres may all
    # be others': those points are looked for again among many more
    again = np.flatnonzero(worst > REACH)
    chunks = -(-again.size // 256) if len(cells) > CANDIDATES else 0
    for part in np.array_split(again, chunks) if chunks else []:
        e, l_, w = _located(points, cells, tree, at[part], min(MORE_CANDIDATES, len(cells)))
        better = w < worst[part]
        own[part[better]], lam[part[better]], worst[part[better]] = (
            e[better], l_[better], w[better])
    if (worst > REACH).any():
        far = at[np.argmax(worst)] * 1e3
        raise SolverError(f"a local model's cut face has a point ({far[0]:.2f}, "
                          f"{far[1]:.2f}, {far[2]:.2f}) mm outside the whole shaft's mesh")
    n, _ = _shape(lam)                                          # (m, 10)
    return np.einsum("ma,cmad->cmd", n, u[:, cells[own]])


def _located(points: np.ndarray, cells: np.ndarray, tree, at: np.ndarray, k: int
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For each point of `at`, among the k elements whose centres lie nearest: the one
    holding it (or nearest to), its barycentric coordinates there, and how far outside
    that element it lies (-min lam; <= 0 inside)."""
    _, near = tree.query(at, k)
    near = near.reshape(len(at), k)
    nodes = points[cells[near]]                                # (m, k, 10, 3)
    # the straight element's coordinates first
    c = nodes[..., :4, :]
    J = np.transpose(c[..., 1:, :] - c[..., :1, :], (0, 1, 3, 2))
    xi = np.linalg.solve(J, (at[:, None, :] - c[..., 0, :])[..., None])[..., 0]
    for _ in range(NEWTON_STEPS):
        lam = np.concatenate([1 - xi.sum(-1, keepdims=True), xi], axis=-1)
        n, dn = _shape(lam)
        x = np.einsum("mka,mkad->mkd", n, nodes)
        Jc = np.einsum("mkae,mkad->mkde", dn, nodes)           # dx_d / dxi_e
        step = np.linalg.solve(Jc, (at[:, None, :] - x)[..., None])[..., 0]
        xi = xi + step
    lam = np.concatenate([1 - xi.sum(-1, keepdims=True), xi], axis=-1)
    n, _ = _shape(lam)
    miss = np.linalg.norm(np.einsum("mka,mkad->mkd", n, nodes) - at[:, None, :], axis=-1)
    size = np.linalg.norm(c[..., 1, :] - c[..., 0, :], axis=-1)
    # an element whose map Newton did not invert (far outside it) is no candidate
    inside = np.where(miss <= 1e-9 * size, lam.min(-1), -np.inf)
    rows = np.arange(len(at))
    best = np.argmax(inside, axis=1)
    return near[rows, best], lam[rows, best], -lam[rows, best].min(-1)


def carried(nodes: np.ndarray, forces: np.ndarray, z: float) -> np.ndarray:
    """What the whole shaft beyond z (m) exerts on the part before it, per case: force and
    moment about (0, 0, z) (cases, 6), N and N m, from its nodal forces K u (cases, n,
    3) at its scalar nodes (n, 3). K u is the applied loads and the supports' reactions
    at each node, exactly, so the sum over the nodes beyond z is the section's resultant
    on any mesh: it does not depend on the mesh's stiffness (nothing is loaded between a
    node and the plane but gravity on an element's share)."""
    beyond = nodes[:, 2] > z
    arm = nodes[beyond] - np.array([0.0, 0.0, z])
    f = forces[:, beyond]
    return np.concatenate([f.sum(axis=1), np.cross(arm, f).sum(axis=1)], axis=1)


def rigid_motions(points: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """The six rigid motions of points (k, 3) about `centre`: (3 k, 6), translations
    along x, y, z, then rotations about them (m per m, m per rad)."""
    G = np.zeros((3 * len(points), 6))
    r = points - centre
    for i in range(3):
        G[i::3, i] = 1.0
        e = np.eye(3)[i]
        G[:, 3 + i] = np.cross(e, r).ravel()
    return G


def reduced_dofs(T, nodes: np.ndarray) -> np.ndarray:
    """The reduced coordinates (u = T q) that are the DOFs of `nodes` (bool, n) as they
    are: a cut face's nodes lie clear of every seat and part, where T is the identity.
    Refused (SolverError) where one is not."""
    dofs = np.flatnonzero(np.repeat(nodes, 3))
    rows = T.tocsr()[dofs]
    counts = np.diff(rows.indptr)
    if (counts != 1).any() or not np.allclose(rows.data, 1.0):
        raise SolverError("a local model's cut face passes through a part's or a seat's band")
    return rows.indices.copy()


def driven_solve(K, F: np.ndarray, held: np.ndarray, u_held: np.ndarray,
                 floating: np.ndarray | None = None, u_floating: np.ndarray | None = None,
                 G: np.ndarray | None = None, load: np.ndarray | None = None) -> np.ndarray:
    """The solution (n, cases) of K x = F (K N/m, F N: columns the cases) with the DOFs
    `held` (indices) at u_held (k, cases); and, if given, the DOFs `floating` at
    u_floating plus a rigid motion G c of their own (G: (k, 6), the six rigid motions
    of the face, rigid_motions), whose six generalised forces G^T (K x - F) are `load`
    (cases, 6: the force and moment the rest of the shaft exerts there, `carried`): the
    whole's deformation of that face is kept and its resultant imposed, not the whole's
    stiffness."""
    import scipy.sparse as sp

    from shaftfem.fem.factor import factorise

    n, cases = F.shape
    X = np.zeros((n, cases))
    X[held] = u_held
    free = np.ones(n, dtype=bool)
    free[held] = False
    if floating is not None:
        free[floating] = False
    free_idx = np.flatnonzero(free)
    Kc = K.tocsr()
    Kf = Kc[free_idx]
    rhs = F[free_idx] - Kf[:, held] @ X[held]
    if floating is None:
        A = Kf[:, free_idx]
    else:
        assert u_floating is not None and G is not None and load is not None
        X[floating] = u_floating
        Km = Kc[floating]
        KfG = sp.csr_matrix(Kf[:, floating] @ G)
        A = sp.bmat([[Kf[:, free_idx], KfG], [KfG.T, G.T @ (Km[:, floating] @ G)]],
                    format="csr")
        rhs = np.vstack([rhs - Kf[:, floating] @ X[floating],
                         load.T + G.T @ (F[floating] - Km[:, held] @ X[held]
                                         - Km[:, floating] @ X[floating])])
    solve, _ = factorise(A)
    x = solve(np.ascontiguousarray(rhs)).reshape(-1, cases)
    X[free_idx] = x[:free_idx.size]
    if floating is not None:
        X[floating] += G @ x[free_idx.size:]
    residual = Kf @ X - F[free_idx]
    scale = max(float(np.abs(F).max()), float(np.abs(Kf[:, held] @ X[held]).max()), 1e-300)
    if float(np.abs(residual).max()) > 1e-6 * scale:
        raise SolverError(f"a local model's solve left a residual of "
                          f"{float(np.abs(residual).max()) / scale:.2g} of its loads")
    return X
