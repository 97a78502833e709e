"""Bearing seats that hold the shaft and parts fixed on it, as stiffness and ties.

A seat is the band of shaft surface r = R, z0 <= z <= z1 (the mesh has faces at z0
and z1, so the band is a set of boundary faces and every node on it is known).
A bearing acts on the band's mean motion, as a distributing coupling does:

    q_x = sum_i c_i u_x,i,  q_y, q_z alike;  tilts theta_x, theta_y from u_y, u_x,

each c the weighted least-squares fit of that component's three rigid motions
(translation, tilt, turn about the axis) to the band's displacements, with weights
w_i, the band's area lumped to its nodes (the diagonal of the P2 surface mass,
scaled to sum to 1). On a symmetric band c = w for the means and +-w d / sum w d^2
for the tilts (d_i = z_i - sum_j w_j z_j); on any band each mean reads exactly its
own rigid motion and no other, so no spring resists a motion it should leave free.
So the section under the seat keeps its own
deformation and the shaft tilts in the bearing, as in a ball bearing, unless a
tilting stiffness is given.

* "springs": k_r on q_x and q_y, k_a on q_z, k_t on the tilts: K_s = sum k c c^T,
  one small dense block per seat.
* "rigid" holds q_x, q_y, q_z exactly; "rigid-radial" q_x and q_y. Each held q
  eliminates one DOF of its band (the one with the largest weight).
* "clamped" holds every node of the band in every direction (a press fit in a
  rigid housing).
* A part on a "rigid" joint (a shrink fit, its hub much stiffer than the shaft)
  ties the shaft's slice under its hub, inside and on the surface, to its centre c
  on the axis, u_i = U + Theta x (x_i - c), and adds its mass and inertias there:
  the rigid segment of a beam model.
* A part on a "distributing" joint (a slip or keyed fit) moves as the mass-weighted
  means of the shaft's cross-section at its hub's centre, (U, Theta) = C u (a beam's
  w and psi there, where a beam model puts its disk): the translations and the turn
  as a bearing's, the tilts from the axial displacements (the section's rotation).
  It adds C^T M_part C to the mass and no stiffness.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from shaftfem.errors import MeshError, SolverError
from shaftfem.scene.model import Attachment, Support

# A node lies on a seat band within this distance (m): the mesh follows the seats.
ON_SURFACE = 1e-7
# Eigenvalues of the seats' restraint of the rigid motions below this fraction of the
# largest count as free.
FREE_MOTION = 1e-10


def rigid_body_modes(nodes: np.ndarray, centre: np.ndarray | None = None,
                     constant: np.ndarray | None = None) -> np.ndarray:
    """The six rigid motions of a body whose DOF 3 n + c moves node n along axis c:
    three translations and three rotations about `centre` (default its centroid),
    (3 n_nodes, 6). For a hierarchical basis `nodes` are the coefficients of the
    coordinate field and `constant` those of the field 1 (None: 1 everywhere)."""
    one = np.ones(nodes.shape[0]) if constant is None else constant
    if centre is None:
        centre = nodes[one > 0].mean(axis=0)
    x = nodes - one[:, None] * centre
    R = np.zeros((nodes.shape[0], 3, 6))
    for c in range(3):
        R[:, c, c] = one
        e = np.zeros(3)
        e[c] = 1.0
        R[:, :, 3 + c] = np.cross(e, x)
    return R.reshape(-1, 6)


def n_bodies(K: sp.spmatrix) -> int:
    """How many disconnected pieces a (node-interleaved) stiffness couples."""
    graph = K[::3, ::3] if K.shape[0] % 3 == 0 else K
    n, _ = connected_components(graph, directed=False)
    return n


def band_nodes(nodes: np.ndarray, radius: float, seat: tuple[float, float]) -> np.ndarray:
    """Indices of the nodes on the shaft surface between the seat's two edges."""
    r = np.hypot(nodes[:, 0], nodes[:, 1])
    z = nodes[:, 2]
    on = (np.abs(r - radius) < ON_SURFACE) & (z > seat[0] - ON_SURFACE) & (
        z < seat[1] + ON_SURFACE)
    return np.flatnonzero(on)


def slice_nodes(nodes: np.ndarray, seat: tuple[float, float]) -> np.ndarray:
    """Indices of the nodes of the shaft's slice between the seat's two edges, inside and
    on the surface: what a rigid hub holds rigid."""
    z = nodes[:, 2]
    return np.flatnonzero((z > seat[0] - ON_SURFACE) & (z < seat[1] + ON_SURFACE))


# A section between the mesh's nodes is read on a slab around it holding at least this
# many nodes on each side (a few layers of elements).
SLAB_NODES = 100


def section_weights(nodes: np.ndarray, z0: float, mass_diagonal: np.ndarray) -> np.ndarray:
    """The shaft's cross-section at z0, weighted by the mass lumped to its nodes (the
    mass matrix's diagonal), as fractions summing to 1 (zero off the section). Where the
    mesh has a node plane at z0 (a part's or a seat's centre), its nodes; elsewhere the
    nodes of a slab around z0, weighted by mass times a hat in z, from which `carried`
    fits the section's motion linear in z (so any position on the shaft is read)."""
    d = nodes[:, 2] - z0
    idx = np.flatnonzero(np.abs(d) < ON_SURFACE)
    w = np.zeros(nodes.shape[0])
    if idx.size >= 3 and np.linalg.matrix_rank(nodes[idx, :2] - nodes[idx[0], :2]) == 2:
        w[idx] = mass_diagonal[idx]
        return w / w.sum()
    below, above = np.sort(-d[d < 0]), np.sort(d[d > 0])
    if below.size + above.size < 4:
        raise SolverError(f"no mesh node near the cross-section at {z0 * 1e3:g} mm")
    h = max(side[min(SLAB_NODES, side.size) - 1] for side in (below, above) if side.size)
    h *= 1 + 1e-9
    on = np.abs(d) < h
    w[on] = mass_diagonal[on] * (1 - np.abs(d[on]) / h)
    return w / w.sum()


def surface_weights(skmesh, order: int, radius: float, seat: tuple[float, float]
                    ) -> np.ndarray:
    """The band's area lumped to the scalar nodes, as fractions summing to 1 (zero off
    the band): the diagonal of the P2 (P1) surface mass, scaled. Kept on the mesh: the
    installation, the bearings' residual modes and their modal motions each ask."""
    known = skmesh.__dict__.setdefault("_band_weights", {})
    key = (order, radius, seat)
    if key not in known:
        known[key] = _surface_weights(skmesh, order, radius, seat)
    return known[key]


def _surface_weights(skmesh, order: int, radius: float, seat: tuple[float, float]
                     ) -> np.ndarray:
    from skfem import BilinearForm, ElementTetP1, ElementTetP2, FacetBasis

    facets = skmesh.boundary_facets()
    xyz = skmesh.p[:, skmesh.facets[:, facets]]          # (3, 3 vertices, n facets)
    r = np.hypot(xyz[0], xyz[1])
    inside = np.all((np.abs(r - radius) < ON_SURFACE) & (xyz[2] > seat[0] - ON_SURFACE)
                    & (xyz[2] < seat[1] + ON_SURFACE), axis=0)
    if not inside.any():
        raise SolverError(f"no boundary face on the seat band {seat[0] * 1e3:g} to "
                          f"{seat[1] * 1e3:g} mm")
    element = ElementTetP2() if order == 2 else ElementTetP1()  # seats take P1 and P2 only
    try:
        fb = FacetBasis(skmesh, element, facets=facets[inside], intorder=4)
    except Exception as e:
        # scikit-fem inverts each curved element's map at the faces' quadrature points;
        # an element curved too far to invert is the mesh's fault, not the seat's
        if "Newton iteration" not in str(e):
            raise
        raise MeshError(f"an element on the seat band {seat[0] * 1e3:g} to "
                        f"{seat[1] * 1e3:g} mm is curved too far for its map to be "
                        "inverted") from None
    diag = BilinearForm(lambda u, v, _: u * v).assemble(fb).diagonal()
    return diag / diag.sum()


@dataclass(frozen=True)
class Restraint:
    """One mean motion of a seat band, q = c . u over DOFs `dofs` (m, or rad for a
    tilt), and what resists it: `stiffness` (N/m, N m/rad), math.inf when held."""

    name: str
    dofs: np.ndarray
    coeffs: np.ndarray
    stiffness: float

    @property
    def held(self) -> bool:
        return math.isinf(self.stiffness)


def seat_restraints(support: Support, nodes: np.ndarray, weights: np.ndarray
                    ) -> list[Restraint]:
    """The band's mean translations and tilts with the bearing's stiffness on each
    (zero-stiffness ones left out); `weights` from `surface_weights`."""
    on = np.flatnonzero(weights > 1e-12 * weights.max())  # nodes off the band get ~1e-33
    w = weights[on]
    seen = _seen(nodes[on], w @ nodes[on, 2])   # about the band's centre
    kx, ky, axial, tilting, _, _ = ring_stiffness(support)
    means = [("x", 0, 0, kx), ("y", 1, 0, ky), ("z", 2, 0, axial),
             ("tilt about x", 1, 1, tilting), ("tilt about y", 0, 1, tilting)]
    return [Restraint(f"{support.name}: {what}", 3 * on + c, weighted_mean(w, seen[c], own), k)
            for what, c, own, k in means if k > 0]


def _seen(nodes: np.ndarray, z0: float) -> dict[int, tuple[np.ndarray, ...]]:
    """What each rigid motion about (0, 0, z0) moves along x, y, z (component 0, 1, 2) at
    `nodes`: (translation, tilt, turn about the axis). A mean fitted to these reads its
    own motion and none of the other two."""
    x, y, z = nodes.T
    d = z - z0
    return {0: (np.ones_like(d), d, -y), 1: (np.ones_like(d), -d, x), 2: (np.ones_like(d), y, -x)}


def weighted_mean(w: np.ndarray, motions: tuple[np.ndarray, ...], own: int) -> np.ndarray:
    """Coefficients c of the band's mean of one rigid motion, q = c . u: the weighted
    least-squares fit of `motions` (their values at the band's nodes) to u, row `own`.
    So c . motions[j] = 1 for j = own and 0 for the others, exactly, on any mesh: a
    bearing's radial spring does not resist the turn about the axis, nor its tilting
    spring the turn, however unsymmetric the band's nodes (as a distributing coupling,
    RBE3). On a symmetric band these are the plain weighted means w and w d / J."""
    B = np.column_stack(motions)           # (m, 3)
    G = B.T @ (w[:, None] * B)             # Gram matrix of the motions under w
    return w * (B @ np.linalg.solve(G, np.eye(len(motions))[own]))


def restraint_stiffness(restraints: list[Restraint], n_dofs: int) -> sp.csr_matrix:
    """K_s = sum k c c^T over the restraints with a finite stiffness (N/m)."""
    return dense_blocks([(r.dofs, r.stiffness * np.outer(r.coeffs, r.coeffs))
                         for r in restraints if not r.held], n_dofs)


def dense_blocks(blocks: list[tuple[np.ndarray, np.ndarray]], n_dofs: int) -> sp.csr_matrix:
    """The (n_dofs, n_dofs) sum of dense blocks B over their DOFs: [(dofs, B), ...]."""
    rows, cols, vals = [np.zeros(0, np.int64)], [np.zeros(0, np.int64)], [np.zeros(0)]
    for dofs, B in blocks:
        rows.append(np.repeat(dofs, dofs.size))
        cols.append(np.tile(dofs, dofs.size))
        vals.append(B.ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n_dofs, n_dofs))


@dataclass(frozen=True)
class Carried:
    """A part on a distributing joint: its (U, Theta) at its centre is the mean rigid
    motion of the cross-section there, q = C u over the section's DOFs, and it adds no
    stiffness."""

    part: Attachment
    dofs: np.ndarray      # (3 m,) the section's DOFs, node by node
    C: np.ndarray         # (6, 3 m)


def carried(part: Attachment, nodes: np.ndarray, weights: np.ndarray) -> Carried:
    """The part's joint to the shaft's cross-section at its centre: its (U, Theta) are
    the section's mass-weighted means, the beam's w and psi there: the translations and
    the turn as a bearing's means (seat_restraints), the tilts from the axial
    displacements (the section's rotation); each reads exactly its own rigid motion.
    `weights` from `section_weights`. A section, not the slice under the hub: the
    means couple every node they read with every other (C^T M_p C is dense), and a
    slice holds 10-20 times as many nodes."""
    on = np.flatnonzero(weights)            # the section's nodes
    w = weights[on]
    seen = _seen(nodes[on], part.position)   # (U, Theta) at the part's centre
    turn = 2
    if np.ptp(nodes[on, 2]) < ON_SURFACE:
        # in its own plane a section does not see the tilts: x and y read the
        # translation and the turn only (on a slab the tilt's column fits x and y
        # linear in z, so the translation read is the section's at the centre)
        seen = {0: seen[0][::2], 1: seen[1][::2], 2: seen[2]}
        turn = 1
    C = np.zeros((6, 3 * on.size))
    for row, c, own, share in ((0, 0, 0, 1.0), (1, 1, 0, 1.0), (2, 2, 0, 1.0), (3, 2, 1, 1.0),
                               (4, 2, 2, 1.0), (5, 0, turn, 0.5), (5, 1, turn, 0.5)):
        C[row, c::3] += share * weighted_mean(w, seen[c], own)
    return Carried(part, (3 * on[:, None] + np.arange(3)).ravel(), C)


def section_means(nodes: np.ndarray, mass_diagonal: np.ndarray, z: float) -> Carried:
    """The mean motion of the cross-section at z (m), q = C u, as a part on a
    distributing joint there would move (no mass): where a beam model reads its node,
    and where a force on the section acts (as C^T F)."""
    probe = Attachment(name="section", position=z, width=0.0, mass=0.0, polar_inertia=0.0,
                       diametral_inertia=0.0, joint="distributing")
    return carried(probe, nodes, section_weights(nodes, z, mass_diagonal))


def carried_mass(parts: list[Carried], n_dofs: int) -> sp.csr_matrix:
    """sum C^T M_p C over the parts on distributing joints: their kinetic energy in the
    shaft's DOFs (kg)."""
    return dense_blocks([(c.dofs, c.C.T @ part_mass(c.part) @ c.C) for c in parts], n_dofs)


def part_mass(part: Attachment) -> np.ndarray:
    """The 6x6 rigid-body mass at the part's centre: m I for (U), diag(I_d, I_d, I_p)
    for (Theta), kg and kg m^2."""
    return np.diag([part.mass] * 3 + [part.diametral_inertia] * 2 + [part.polar_inertia])


def tie_rows(nodes: np.ndarray, idx: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """(m, 3, 6): u_i = U + Theta x (x_i - c) = U - [d_i]x Theta for the nodes idx."""
    d = nodes[idx] - centre
    B = np.zeros((idx.size, 3, 6))
    B[:, :, :3] = np.eye(3)
    B[:, 0, 4], B[:, 0, 5] = d[:, 2], -d[:, 1]
    B[:, 1, 3], B[:, 1, 5] = -d[:, 2], d[:, 0]
    B[:, 2, 3], B[:, 2, 4] = d[:, 1], -d[:, 0]
    return B


def ring_stiffness(s: Support) -> tuple[float, ...]:
    """What a seat resists along its (U_x, U_y, U_z, Theta_x, Theta_y, Theta_z), a
    rigid ring's or a distributing seat's means: N/m, N m/rad, math.inf where held, 0
    where free (a bearing: its kxx and kyy at standstill; what it adds turning, the
    rotor model adds: fem.rotor)."""
    rigid = {"rigid": (math.inf, math.inf), "rigid-radial": (math.inf, 0.0)}
    if s.kind == "journal" and s.bearing is None:
        raise SolverError(f"journal bearing {s.name!r} has no load yet: its film needs the "
                          "static loads solved first (workflows.static.equipped)")
    if s.awaits_part:
        raise SolverError(f"support {s.name!r}: its part was not asked for its coefficients "
                          "(workflows.equip.with_parts)")
    if s.kind in rigid:
        radial, axial = rigid[s.kind]
        return (radial, radial, axial, 0.0, 0.0, 0.0)
    tilting = s.tilting if s.kind in ("springs", "bearing", "journal", "ball", "roller") else 0.0
    kx, ky = s.radial_xy
    return (kx, ky, s.axial, tilting, tilting, 0.0)
