"""The installed shaft: the free shaft's K and M reduced by its seats and parts.

With u = T q the pencil solved is

    K_r = T^T (K + K_s) T,    M_r = T^T M T + M_parts,

and the rigid motions the seats leave free (six for a free shaft, one, the turn
about the axis, in two bearings) are found from the seats alone, then checked by
the solve.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from shaftfem.errors import SolverError
from shaftfem.fem.supports import (
    FREE_MOTION,
    Carried,
    Restraint,
    band_nodes,
    carried,
    carried_mass,
    n_bodies,
    part_mass,
    restraint_stiffness,
    rigid_body_modes,
    ring_stiffness,
    seat_restraints,
    section_weights,
    slice_nodes,
    surface_weights,
    tie_rows,
)
from shaftfem.scene.model import Attachment, Scene, Support


@dataclass(frozen=True)
class Installed:
    """The shaft in its seats: the reduced pencil (K_r N/m, M_r kg), u = T q, the rigid
    motions the seats leave free (reduced coordinates), and what the export needs."""

    K: sp.csr_matrix
    M: sp.csr_matrix
    T: sp.csr_matrix
    rigid: np.ndarray
    free: tuple[str, ...]                 # names of the free rigid motions
    restraints: tuple[Restraint, ...]
    clamped: np.ndarray                   # DOFs held at zero
    tied: tuple[np.ndarray, ...]          # slice nodes of each part on a rigid joint
    parts: tuple[Attachment, ...]         # those parts, in the same order
    parts_from: int                       # their (U, Theta) from this column on
    rings: tuple[np.ndarray, ...]         # band nodes of each rigid-coupled seat
    carried: tuple[Carried, ...] = ()     # the parts on distributing joints
    M_carried: sp.csr_matrix | None = None   # their mass in the shaft's DOFs (kg)
    trains: int = 0    # the coupled machines' turns: the last columns, moving no node

    @property
    def n_rigid(self) -> int:
        return self.rigid.shape[1]

    def expand(self, X: np.ndarray) -> np.ndarray:
        """Reduced vectors (n_q, m) as displacements of every node (3 n, m)."""
        return self.T @ X

    def for_scene(self, was: Scene, scene: Scene) -> Installed:
        """This installation of `was` as `scene`'s, a scene on the same pencil (the same
        seats and parts, in the same order, making the same K and M; their names, a
        bearing's coefficients at speed and a stage's cross-coupling may differ): its
        matrices as they are, its parts and its seats' names the scene's own."""
        tied = tuple(a for a in scene.attachments if not a.carried)
        spread = [a for a in scene.attachments if a.carried]
        if len(tied) != len(self.parts) or len(spread) != len(self.carried):
            raise SolverError(f"{scene.source}: its parts are not those of the installation "
                              "it was given")
        names = {f"{a.name}: ": f"{b.name}: " for a, b in zip(was.supports, scene.supports)}

        def renamed(r: Restraint) -> Restraint:
            old = next((n for n in names if r.name.startswith(n)), None)
            return r if old is None else replace(r, name=names[old] + r.name[len(old):])

        return replace(self, parts=tied,
                       carried=tuple(replace(c, part=a) for c, a in zip(self.carried, spread)),
                       restraints=tuple(map(renamed, self.restraints)))

    def shaft_coordinates(self, U: np.ndarray) -> np.ndarray:
        """The reduced coordinates (n_q - trains, m) of the shaft's displacements U = T q
        (3 n, m) (the coupled machines' turns move no node: they are not in U)."""
        from scipy.sparse.linalg import splu

        T = self.T[:, :self.T.shape[1] - self.trains].tocsc()
        return splu((T.T @ T).tocsc()).solve(np.asarray(T.T @ U))


@dataclass
class _Seats:
    """What the scene's seats and parts do to the free shaft's nodes."""

    restraints: list[Restraint]      # distributing seats: on the band's mean motion
    rings: list[tuple[Support, np.ndarray]]   # rigid-coupled seats and their bands
    on_rings: list[Restraint]        # what those rings' springs and holds resist
    clamped: np.ndarray              # DOFs held at zero
    tied: list[tuple[np.ndarray, np.ndarray]]  # (nodes, centre) per tied part, then ring
    parts: list[Attachment]          # the parts on rigid joints (tied)
    carried: list[Carried]           # the parts on distributing joints


def install(scene: Scene, K: sp.csr_matrix, M: sp.csr_matrix, nodes: np.ndarray,
            skmesh, order: int) -> Installed:
    """The scene's seats and parts applied to the free shaft's K (N/m) and M (kg) on
    `nodes` (the scalar DOFs' positions, of a P1 or P2 basis: seats read nodal values;
    workflows.pipeline.check_order refuses higher orders); `skmesh` the scikit-fem
    mesh, for the bands' surface."""
    if n_bodies(K) != 1:
        raise SolverError("the mesh has disconnected parts; a shaft must be one piece")
    seats = _seats(scene, nodes, skmesh, order, M.diagonal()[::3])
    K_s = restraint_stiffness(seats.restraints, K.shape[0])
    M_c = carried_mass(seats.carried, M.shape[0]) if seats.carried else None
    M_full = M if M_c is None else M + M_c
    T = elimination(nodes, seats.clamped, [r for r in seats.restraints if r.held], seats.tied)
    first = T.shape[1] - 6 * len(seats.tied)
    extra_K, extra_M, keep = _parts_and_rings(scene, seats, T.shape[1], first)
    T = T[:, keep].tocsr()
    Tt = T.T.tocsr()
    K_r = Tt @ ((K + K_s) @ T) + extra_K[keep][:, keep]
    M_r = Tt @ (M_full @ T) + extra_M[keep][:, keep]
    # symmetric to round-off: made exactly so for the solvers
    K_r = ((K_r + K_r.T) * 0.5).tocsr()
    M_r = ((M_r + M_r.T) * 0.5).tocsr()
    rigid, target = _free_rigid_motions(nodes, T, Tt, seats)
    n_shaft = T.shape[1]
    K_r, M_r, T, rigid = _trains(seats, first, K_r, M_r, T, rigid)
    n_parts = len(seats.parts)
    return Installed(K=K_r, M=M_r, T=T, rigid=rigid, free=motion_names(target, nodes),
                     restraints=tuple(seats.restraints), clamped=seats.clamped,
                     tied=tuple(i for i, _ in seats.tied[:n_parts]), parts=tuple(seats.parts),
                     parts_from=first, rings=tuple(idx for _, idx in seats.rings),
                     carried=tuple(seats.carried), M_carried=M_c, trains=T.shape[1] - n_shaft)


def seat_radius(scene: Scene, nodes: np.ndarray, seat: tuple[float, float]) -> float:
    """The shaft's outer radius under a seat (m): its section's, or, on a STEP solid,
    the largest node radius within the band."""
    radius = scene.shaft.radius_at(0.5 * (seat[0] + seat[1]))
    if radius is not None:
        return radius
    z = nodes[:, 2]
    inside = (z >= seat[0] - 1e-9) & (z <= seat[1] + 1e-9)
    return float(np.hypot(nodes[inside, 0], nodes[inside, 1]).max()) if inside.any() else 0.0


def _seats(scene: Scene, nodes: np.ndarray, skmesh, order: int,
           mass_diagonal: np.ndarray) -> _Seats:
    """Each seat's band and what holds it; each part's slice (rigid joint) or section
    (distributing) and centre (`mass_diagonal`: the scalar mass matrix's diagonal, the
    sections' weights)."""
    out = _Seats([], [], [], np.zeros(0, np.int64), [], [], [])
    held_bands: list[np.ndarray] = []
    for s in scene.held:
        radius = seat_radius(scene, nodes, s.seat)
        idx = band_nodes(nodes, radius, s.seat)
        if idx.size == 0:
            raise SolverError(f"{s.name}: no mesh node on its seat band ({s.seat[0] * 1e3:g} "
                              f"to {s.seat[1] * 1e3:g} mm)")
        if s.kind == "clamped":
            held_bands.append((3 * idx[:, None] + np.arange(3)).ravel())
            continue
        means = seat_restraints(s, nodes, surface_weights(skmesh, order, radius, s.seat))
        if s.coupling == "rigid":
            out.rings.append((s, idx))
            out.on_rings += means  # a ring's motion reads a rigid motion as these means do
        else:
            out.restraints += means
    for a in scene.attachments:
        idx = band_nodes(nodes, seat_radius(scene, nodes, a.seat), a.seat)
        if idx.size == 0:
            raise SolverError(f"{a.name}: no mesh node on its seat band")
        if a.carried:
            out.carried.append(carried(a, nodes, section_weights(nodes, a.position, mass_diagonal)))
            continue
        out.parts.append(a)
        out.tied.append((slice_nodes(nodes, a.seat), np.array([0.0, 0.0, a.position])))
    out.tied += [(idx, np.array([0.0, 0.0, s.position])) for s, idx in out.rings]
    if held_bands:
        out.clamped = np.concatenate(held_bands)
    return out


def _parts_and_rings(scene: Scene, seats: _Seats, n_q: int, first: int
                     ) -> tuple[sp.csr_matrix, sp.csr_matrix, np.ndarray]:
    """The parts' masses and the rings' springs on their (U, Theta) columns (from `first`
    on), and which columns stay: a ring's DOF held exactly is dropped."""
    # (entries gathered, then one sparse matrix: a LIL matrix of the shaft's size costs a
    # list per row, 60 ms on a 40k-DOF pump, twice per run)
    rows, cols, masses = [np.zeros(0, int)], [np.zeros(0, int)], [np.zeros(0)]
    for k, a in enumerate(seats.parts):
        c = first + 6 * k
        block = np.asarray(part_mass(a), dtype=float)
        r, q = np.nonzero(block)
        rows.append(c + r)
        cols.append(c + q)
        masses.append(block[r, q])
    keep = np.ones(n_q, dtype=bool)
    springs: list[tuple[int, float]] = []
    for j, (s, _) in enumerate(seats.rings):
        c = first + 6 * (len(seats.parts) + j)
        for d, stiff in enumerate(ring_stiffness(s)):
            if math.isinf(stiff):
                keep[c + d] = False      # held exactly: the ring's DOF is dropped
            elif stiff > 0:
                springs.append((c + d, stiff))
    extra_M = sp.csr_matrix((np.concatenate(masses),
                             (np.concatenate(rows), np.concatenate(cols))), shape=(n_q, n_q))
    at = np.array([c for c, _ in springs], dtype=int)
    extra_K = sp.csr_matrix((np.array([k for _, k in springs], dtype=float), (at, at)),
                            shape=(n_q, n_q))
    extra_K.sort_indices()   # as the solvers and the sums after it expect
    extra_M.sort_indices()
    return extra_K, extra_M, keep


def _trains(seats: _Seats, first: int, K_r: sp.csr_matrix, M_r: sp.csr_matrix,
            T: sp.csr_matrix, rigid: np.ndarray
            ) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix, np.ndarray]:
    """Each coupled machine's rotor as one more coordinate, its turn phi (rad), last:
    the coupling's 1/2 k_t (theta - phi)^2 with theta its hub's turn, and 1/2 J phi'^2.
    phi moves no node of the shaft (T's column is zero); in the free turn about the
    axis it turns with its hub."""
    hubs: list[tuple[Attachment, np.ndarray]] = []
    n_q = T.shape[1]
    for k, a in enumerate(seats.parts):            # rigid joints: the part's own Theta_z
        if a.coupling_stiffness > 0:
            g = np.zeros(n_q)
            g[first + 6 * k + 5] = 1.0
            hubs.append((a, g))
    for c in seats.carried:                        # distributing: the section's mean turn
        if c.part.coupling_stiffness > 0:
            u = np.zeros(T.shape[0])
            u[c.dofs] = c.C[5]
            hubs.append((c.part, np.asarray(T.T @ u).ravel()))
    if not hubs:
        return K_r, M_r, T, rigid
    m = len(hubs)
    G = sp.hstack([sp.csr_matrix(np.vstack([g for _, g in hubs])), -sp.eye(m)]).tocsr()
    K_c = G.T @ sp.diags([a.coupling_stiffness for a, _ in hubs]) @ G   # g reads a few DOFs
    K_r = (_padded(K_r, m) + K_c).tocsr()
    M_r = (_padded(M_r, m) + sp.diags(np.concatenate(
        [np.zeros(n_q), [a.coupled_inertia for a, _ in hubs]]))).tocsr()
    T = sp.hstack([T, sp.csr_matrix((T.shape[0], m))]).tocsr()
    rigid = np.vstack([rigid, np.vstack([g for _, g in hubs]) @ rigid])
    K_r = ((K_r + K_r.T) * 0.5).tocsr()
    K_r.sort_indices()
    M_r.sort_indices()
    return K_r, M_r, T, rigid


def _padded(A: sp.csr_matrix, m: int) -> sp.csr_matrix:
    """A with m empty rows and columns after its own (block_diag with zeros, without
    rebuilding A's structure)."""
    A = A.tocsr()
    n = A.shape[0]
    indptr = np.concatenate([A.indptr, np.full(m, A.indptr[-1])])
    return sp.csr_matrix((A.data, A.indices, indptr), shape=(n + m, n + m))


def _free_rigid_motions(nodes: np.ndarray, T: sp.csr_matrix, Tt: sp.csr_matrix,
                        seats: _Seats) -> tuple[np.ndarray, np.ndarray]:
    """The rigid motions the seats leave free, in reduced coordinates and as nodal
    displacements; checked to survive the elimination."""
    R6 = rigid_body_modes(nodes)
    R6 /= np.linalg.norm(R6, axis=0)
    combos = free_motions(R6, seats.clamped, seats.restraints + seats.on_rings)
    target = R6 @ combos
    rigid = np.asarray(spsolve((Tt @ T).tocsc(), Tt @ target)).reshape(T.shape[1], -1)
    if combos.shape[1]:
        miss = np.linalg.norm(T @ rigid - target) / np.linalg.norm(target)
        if miss > 1e-9:
            raise SolverError(f"the seats' free rigid motions do not survive the "
                              f"elimination (misfit {miss:.2g})")
    return rigid, target


def elimination(nodes: np.ndarray, clamped: np.ndarray, held: list[Restraint],
                tied: list[tuple[np.ndarray, np.ndarray]]) -> sp.csr_matrix:
    """T (3 n, n_q) with u = T q: clamped DOFs are dropped; each held restraint's
    pivot DOF follows from the others of its band (c . u = 0); tied nodes follow
    their part's (U, Theta) at its centre, the last 6 columns per part.

    The held restraints of one seat act on disjoint DOFs (x, y, z means), so each
    pivot is eliminated on its own."""
    n = 3 * nodes.shape[0]
    keep = np.ones(n, dtype=bool)
    keep[clamped] = False
    for idx, _ in tied:
        keep[(3 * idx[:, None] + np.arange(3)).ravel()] = False
    pivots = []
    for r in held:
        p = int(np.argmax(np.abs(r.coeffs)))
        pivots.append(p)
        keep[r.dofs[p]] = False
    col = np.cumsum(keep) - 1
    kept = np.flatnonzero(keep)
    rows, cols, vals = [kept], [col[kept]], [np.ones(kept.size)]
    for r, p in zip(held, pivots):
        others = np.arange(r.dofs.size) != p
        rows.append(np.full(others.sum(), r.dofs[p]))
        cols.append(col[r.dofs[others]])
        vals.append(-r.coeffs[others] / r.coeffs[p])
    first = kept.size
    for k, (idx, centre) in enumerate(tied):
        B = tie_rows(nodes, idx, centre)
        rows.append(np.broadcast_to(3 * idx[:, None, None] + np.arange(3)[None, :, None],
                                    B.shape).ravel())
        cols.append(np.broadcast_to(first + 6 * k + np.arange(6), B.shape).ravel())
        vals.append(B.ravel())
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(n, first + 6 * len(tied)))
    T.eliminate_zeros()
    return T


def free_motions(R: np.ndarray, clamped: np.ndarray, restraints: list[Restraint]
                 ) -> np.ndarray:
    """(6, r) orthonormal: the combinations of the rigid motions R (3 n, 6, columns of
    unit norm) that no seat resists."""
    A = np.zeros((6, 6))
    parts = [R[clamped]] + [r.coeffs @ R[r.dofs] for r in restraints]
    for C in parts:
        C = np.atleast_2d(C)
        if C.size:
            G = C.T @ C
            A += G / max(np.abs(G).max(), 1e-300)
    lam, V = np.linalg.eigh(A)
    return V[:, lam <= FREE_MOTION * max(lam.max(), 1.0)]


def motion_names(free: np.ndarray, nodes: np.ndarray) -> tuple[str, ...]:
    """Names of the free rigid motions `free` (3 n, r): translations, the turn about
    the axis, tilting about x or y (about some point of the axis); a count when these
    do not describe them."""
    r = free.shape[1]
    if r in (0, 6):
        return () if r == 0 else ("all six rigid motions",)
    motions = rigid_body_modes(nodes, np.array([0.0, 0.0, nodes[:, 2].mean()]))
    unit = dict(zip(("tx", "ty", "tz", "rx", "ry", "rz"), motions.T))
    Q = np.linalg.qr(free)[0]

    def shared(*names: str) -> int:
        """Dimension of span(free) and span(names) in common."""
        B = np.linalg.qr(np.column_stack([unit[n] for n in names]))[0]
        # the seats hold the mean of a mesh that is not exactly symmetric: near enough
        return int(np.sum(np.linalg.svd(Q.T @ B, compute_uv=False) > 1 - 1e-6))

    named = [label for label, n in (("translation along x", "tx"), ("translation along y", "ty"),
                                    ("translation along z", "tz"),
                                    ("rotation about the axis (z)", "rz")) if shared(n)]
    for label, rot, move in (("tilting about x", "rx", "ty"), ("tilting about y", "ry", "tx")):
        if shared(rot, move) > shared(move):
            named.append(label)
    return tuple(named) if len(named) == r else (f"{r} rigid motions",)
