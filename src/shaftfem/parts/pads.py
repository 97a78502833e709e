"""Bearings of pads: the oil film on each arc of a bore that is not one full circle (a
two-axial-groove bore, an elliptical "lemon" bore, tilting pads), from the Reynolds
equation as in shaftfem.parts.journal, each pad on its own P1 film.

Nondimensional as the plain journal (shaftfem.parts.journal): theta from +x towards +y,
the journal turning with it, Z = z / R, lengths over the bearing's (assembled) clearance
c_b, P = p (c_b / R)^2 / (mu omega). A pad spans [start, start + arc]; its surface's
centre of curvature sits c_p - c_b towards its pivot angle theta_p, c_p = c_b / (1 - m)
with m the preload, so with the journal centred its film is thinnest (c_b) at theta_p:

    H = H_0(theta) + sum_j g_j(theta) q_j,
    H_0 = a (1 - m cos(theta - theta_p)) / (1 - m),

over the generalised coordinates q: the journal's (X, Y), with g = -cos, -sin, and a
tilting pad's tilt about its pivot, g = -sin(theta - theta_p) (the tilt's angle times
R / c_b). The film at theta_p with the journal centred, a (over c_b), is 1 but on a pad
a running bearing's heat has grown (Pad.gap, parts.pad_heat.grown). On each pad
div(H^3 grad P) = 6 dH/dtheta + 12 dH/dtau, P = 0 at the pad's edges (the grooves' oil
at ambient pressure) and its ends, Swift-Stieber cavitation where the film ruptures.
The film's generalised force on coordinate i (the virtual work of the pressure as q_i
moves the surfaces) is Q_i = int P g_i dtheta dZ, so that
Q_X, Q_Y are the force on the journal and a tilt's Q its moment about the pivot; the
stiffness K_ij = -dQ_i/dq_j and damping C_ij = -dQ_i/dq'_j are those of the discrete
film, exact (one tangent solve each on the pad's own factorisation).

References: Lund (1964), spring and damping coefficients of the tilting-pad journal
bearing; Lund and Thomsen (1978), the coefficients of fixed-geometry bearings.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from shaftfem.parts.journal import _pressure
from shaftfem.scene.model import condensed

# the film's cells around a pad, per radian of its arc, and across its half length
CELLS_PER_RADIAN = 50
Z_CELLS = 16


@dataclass(frozen=True)
class Pad:
    """One arc of a bore (rad): where it starts and how far it spans, the pivot angle
    its preload points to (a fixed pad's middle, or a tilting pad's pivot), the preload
    m = 1 - c_b / c_p in [0, 1), whether it tilts about its pivot, and its film at the
    pivot angle with the journal centred over the bearing's clearance c_b (1 but where a
    running bearing's heat has grown its parts: parts.pad_heat.grown)."""

    start: float
    arc: float
    pivot: float
    preload: float = 0.0
    tilts: bool = False
    gap: float = 1.0


@dataclass(frozen=True)
class Bore:
    """A bearing's pads and its length over diameter."""

    pads: tuple[Pad, ...]
    ratio: float

    @property
    def tilts(self) -> tuple[int, ...]:
        """The indices of the pads that tilt (each one more coordinate after X, Y)."""
        return tuple(k for k, p in enumerate(self.pads) if p.tilts)

    def coordinates(self, k: int) -> list[int]:
        """Where pad k's own coordinates (X, Y[, its tilt]) sit among the bearing's."""
        return [0, 1] + ([2 + self.tilts.index(k)] if self.pads[k].tilts else [])


def two_axial_groove(ratio: float, groove_arc: float = math.radians(20.0),
                     load_angle: float = -math.pi / 2) -> Bore:
    """Two pads split by axial grooves at right angles to the load (the load at
    `load_angle`, rad, through the middle of a pad), each pi - groove_arc long."""
    arc = math.pi - groove_arc
    return Bore(tuple(Pad(start=c - arc / 2, arc=arc, pivot=c)
                      for c in (load_angle, load_angle + math.pi)), ratio)


def elliptical(ratio: float, preload: float, groove_arc: float = math.radians(20.0),
               load_angle: float = -math.pi / 2) -> Bore:
    """A lemon bore: the two pads of two_axial_groove with their centres of curvature
    moved apart along the load line (preload m)."""
    b = two_axial_groove(ratio, groove_arc, load_angle)
    return Bore(tuple(Pad(p.start, p.arc, p.pivot, preload) for p in b.pads), ratio)


def tilting(ratio: float, pads: int, arc: float, preload: float, offset: float = 0.5,
            first_pivot: float = -math.pi / 2) -> Bore:
    """Tilting pads: `pads` of `arc` (rad) evenly round the bore, the first pivot at
    `first_pivot` (the load's angle: load on pad; half a pitch from it: between pads),
    each pivot `offset` of its arc from its leading edge (in the turning's sense)."""
    pitch = 2 * math.pi / pads
    return Bore(tuple(Pad(start=first_pivot + k * pitch - offset * arc, arc=arc,
                          pivot=first_pivot + k * pitch, preload=preload, tilts=True)
                      for k in range(pads)), ratio)


@dataclass(frozen=True)
class PadFilm:
    """One pad's half film (Z from 0 to L / D) on a P1 mesh: the operators that do not
    depend on where the journal or the pad is."""

    basis: Any
    free: np.ndarray        # nodes off the pad's edges and its end
    theta: np.ndarray       # the quadrature points' theta (elements, points)
    flow: Any               # flow_matrix's operator: k at the points -> the matrix's data
    pattern: tuple[np.ndarray, np.ndarray]   # that matrix's CSR indices and indptr

    def flow_matrix(self, k: np.ndarray):
        """int k grad u . grad v over the film (k at the quadrature points, (elements,
        points)): the matrix skfem assembles, its data linear in k, so one sparse product
        (a film is assembled thousands of times on the same pad)."""
        import scipy.sparse as sp

        n = self.basis.N
        data = self.flow @ np.broadcast_to(k, self.theta.shape).ravel()
        return sp.csr_matrix((data, *self.pattern), shape=(n, n))


@lru_cache(maxsize=64)
def cells_round(arc: float, per_radian: int | None = None) -> int:
    """A pad film's cells along its arc (rad): CELLS_PER_RADIAN (or `per_radian`) a
    radian, at least 8."""
    return max(8, round((CELLS_PER_RADIAN if per_radian is None else per_radian) * arc))


@lru_cache(maxsize=256)
def pad_film(start: float, arc: float, ratio: float, cells: int, z_cells: int) -> PadFilm:
    """The pad's film mesh (cached by its arc, L / D and cells: a film's pressure is
    solved thousands of times on the same few pads)."""
    from skfem import Basis, ElementTriP1, MeshTri

    mesh = MeshTri.init_tensor(np.linspace(start, start + arc, cells + 1),
                               np.linspace(0.0, ratio, z_cells + 1))
    basis = Basis(mesh, ElementTriP1(), intorder=4)
    x = mesh.p
    edge = (np.isclose(x[0], start) | np.isclose(x[0], start + arc) | np.isclose(x[1], ratio))
    flow, pattern = _flow_operator(basis)
    return PadFilm(basis=basis, free=np.flatnonzero(~edge),
                   theta=np.asarray(basis.global_coordinates())[0], flow=flow,
                   pattern=pattern)


class Banded:
    """The Cholesky factor of a pad's film matrix (symmetric positive definite, its nodes
    numbered along the pad's width first: a band of about Z_CELLS), by LAPACK's banded
    Cholesky: a film is solved thousands of times, and this is several times quicker
    than a general sparse LU of the same matrix."""

    def __init__(self, A) -> None:
        from scipy.linalg import cholesky_banded

        C = A.tocoo()
        up = C.row <= C.col
        u = int((C.col[up] - C.row[up]).max(initial=0))
        ab = np.zeros((u + 1, A.shape[0]))
        ab[u + C.row[up] - C.col[up], C.col[up]] = C.data[up]
        self.factor = cholesky_banded(ab, overwrite_ab=True, check_finite=False)

    def solve(self, b: np.ndarray) -> np.ndarray:
        from scipy.linalg import cho_solve_banded

        return cho_solve_banded((self.factor, False), b, check_finite=False)


def _flow_operator(basis) -> tuple[Any, tuple[np.ndarray, np.ndarray]]:
    """The sparse operator taking k at the quadrature points to the CSR data of int k
    grad u . grad v (row i, column j, element e: sum over points q of k_eq
    grad phi_i . grad phi_j dx_eq), and that CSR matrix's indices and indptr."""
    import scipy.sparse as sp

    dofs = basis.element_dofs                      # (local, elements)
    grads = [b[0].grad for b in basis.basis]       # each (2, elements, points)
    dx = basis.dx                                  # (elements, points)
    ne, nq = dx.shape
    n_local = len(grads)
    rows, cols, vals = [], [], []
    for i in range(n_local):
        for j in range(n_local):
            rows.append(dofs[i])
            cols.append(dofs[j])
            vals.append(np.einsum("deq,deq->eq", grads[i], grads[j]) * dx)
    r, c = np.concatenate(rows), np.concatenate(cols)   # (n_local^2 * ne,)
    keys, slot = np.unique(r.astype(np.int64) * basis.N + c, return_inverse=True)
    point = (np.arange(ne)[:, None] * nq + np.arange(nq)[None, :])   # (ne, nq)
    op = sp.csr_matrix((np.concatenate(vals).ravel(),
                        (np.repeat(slot, nq), np.tile(point, (n_local**2, 1)).ravel())),
                       shape=(keys.size, ne * nq))
    indptr = np.searchsorted(keys // basis.N, np.arange(basis.N + 1)).astype(np.int32)
    return op, ((keys % basis.N).astype(np.int32), indptr)


def _modes(pad: Pad, theta: np.ndarray, tilt: bool) -> list[tuple[np.ndarray, np.ndarray]]:
    """g and dg/dtheta of the coordinates that move this pad's film: X, Y and, if it
    tilts, its tilt."""
    out = [(-np.cos(theta), np.sin(theta)), (-np.sin(theta), -np.cos(theta))]
    if tilt:
        out.append((-np.sin(theta - pad.pivot), -np.cos(theta - pad.pivot)))
    return out


@dataclass(frozen=True)
class _Weights:
    """A pad film's integrals that do not move with the journal: each coordinate's int g
    v (its force and squeeze) and int dg/dtheta v (its Couette term), (n, nodes), and
    the preload's int dH0/dtheta v (nodes)."""

    gv: np.ndarray
    dgv: np.ndarray
    preload: np.ndarray
    g: tuple[np.ndarray, ...]   # each coordinate's g at the quadrature points
    h0: np.ndarray              # the film at q = 0 (the preload's) there


@lru_cache(maxsize=256)
def _weights(pad: Pad, ratio: float, cells: int, z_cells: int, tilt: bool) -> _Weights:
    from skfem import LinearForm

    @LinearForm
    def weighted(v, w):
        return w.k * v

    f = pad_film(pad.start, pad.arc, ratio, cells, z_cells)
    modes = _modes(pad, f.theta, tilt)
    m = pad.preload
    return _Weights(
        gv=np.array([weighted.assemble(f.basis, k=g) for g, _ in modes]),
        dgv=np.array([weighted.assemble(f.basis, k=dg) for _, dg in modes]),
        preload=weighted.assemble(f.basis, k=pad.gap * m * np.sin(f.theta - pad.pivot)
                                  / (1 - m)),
        g=tuple(g for g, _ in modes),
        h0=_film(pad, f.theta, np.zeros(len(modes)))[0])


def _film(pad: Pad, theta: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pad's film thickness H and dH/dtheta at angles theta, its coordinates q =
    (X, Y[, tilt])."""
    m, a = pad.preload, pad.gap / (1 - pad.preload)
    H = a * (1 - m * np.cos(theta - pad.pivot))
    dH = a * m * np.sin(theta - pad.pivot)
    for (g, dg), qj in zip(_modes(pad, theta, len(q) > 2), q):
        H = H + g * qj
        dH = dH + dg * qj
    return H, dH


@dataclass(frozen=True)
class PadState:
    """One pad's film at q: its generalised forces Q (n,), stiffness K and damping C
    (n, n) on its own coordinates (X, Y[, tilt]), the pressure on its nodes, and the
    share of its film that carries pressure."""

    force: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    pressure: np.ndarray
    wet: float


def pad_state(pad: Pad, ratio: float, q: np.ndarray, guess: np.ndarray | None = None,
              cells_per_radian: int | None = None, z_cells: int | None = None,
              viscosity: np.ndarray | None = None) -> PadState:
    """The pad's film with its coordinates q = (X, Y[, tilt]) (module docstring); the
    whole length's forces (twice the half film's). `guess`: where a nearby state's film
    ruptured, to start the cavitation's active set from; `viscosity`: the film's on the
    pad's nodes over the one P is scaled with (a heated film: parts.pad_heat; None:
    isoviscous), div(H^3 / mu grad P) = 6 dH/dtheta + 12 dH/dtau."""
    cells = cells_round(pad.arc, cells_per_radian)
    z_cells = Z_CELLS if z_cells is None else z_cells
    f = pad_film(pad.start, pad.arc, ratio, cells, z_cells)
    fixed = _weights(pad, ratio, cells, z_cells, len(q) > 2)
    H = fixed.h0 + sum(g * qj for g, qj in zip(fixed.g, q))   # _film's, its trig kept
    if float(H.min()) <= 0:
        raise ValueError(f"the journal touches the pad at {math.degrees(pad.pivot):.0f} deg "
                         f"(film {float(H.min()):.3g} of the clearance)")

    fluidity = 1.0 if viscosity is None else 1.0 / f.basis.interpolate(viscosity)
    A = f.flow_matrix(H ** 3 * fluidity)
    # int dH v: dH is the preload's term and the coordinates' dg q_j
    b = -6.0 * (fixed.preload + q @ fixed.dgv)
    P, live, lu = _pressure(A, b, f.free, "reynolds", guess, factor=Banded)
    n = len(fixed.g)
    rhs = np.zeros((P.size, 2 * n))
    for j, g in enumerate(fixed.g):
        # int 3 H^2 g grad P . grad v: the flow's matrix with k = 3 H^2 g, times P
        rhs[:, j] = -6.0 * fixed.dgv[j] - f.flow_matrix(3.0 * H ** 2 * g * fluidity) @ P
        rhs[:, n + j] = -12.0 * fixed.gv[j]
    dP = np.zeros_like(rhs)
    dP[live] = lu.solve(rhs[live])
    G = 2.0 * fixed.gv                # (n, nodes): Q_i = G_i . P over the whole length
    dQ = G @ dP
    return PadState(force=G @ P, stiffness=-dQ[:, :n], damping=-dQ[:, n:], pressure=P,
                    wet=float(live.size / max(f.free.size, 1)))


@dataclass(frozen=True)
class BoreState:
    """The bearing's film at q = (X, Y, tilts...): its generalised forces Q, stiffness K
    and damping C on all of q, and each pad's state."""

    q: np.ndarray
    force: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    pads: tuple[PadState, ...]


def _gathered(bore: Bore, q: np.ndarray, states: list[PadState]) -> BoreState:
    """The pads' states gathered on the bearing's coordinates q."""
    n = q.size
    Q, K, C = np.zeros(n), np.zeros((n, n)), np.zeros((n, n))
    for k, s in enumerate(states):
        idx = bore.coordinates(k)
        Q[idx] += s.force
        K[np.ix_(idx, idx)] += s.stiffness
        C[np.ix_(idx, idx)] += s.damping
    return BoreState(q=q, force=Q, stiffness=K, damping=C, pads=tuple(states))


def _film_at(pad: Pad, q: np.ndarray, samples: int = 721) -> tuple[np.ndarray, np.ndarray]:
    """`samples` angles over the pad's arc, and its film thickness H there."""
    theta = np.linspace(pad.start, pad.start + pad.arc, samples)
    return theta, _film(pad, theta, q)[0]


# a film thinner than this share of the clearance anywhere is a touch (the search's
# limits)
TOUCH = 1e-3


def settle(pad: Pad, ratio: float, X: float, Y: float, tilt: float,
           guess: np.ndarray | None, tol: float, viscosity: np.ndarray | None = None
           ) -> tuple[float, PadState]:
    """The tilt about its pivot at which the pad's film has no moment about it (the
    journal at X, Y): Newton's steps on the exact dQ/dtilt, kept inside a bracket
    [Q > 0, Q < 0] (a larger tilt closes the trailing edge, which moves the pressure's
    centre back past the pivot), halving it where a step leaves it."""
    theta, H = _film_at(pad, np.array([X, Y]))
    s = np.sin(theta - pad.pivot)
    room = H - TOUCH
    hi = float(np.min(room[s > 0] / s[s > 0]))
    lo = float(np.max(room[s < 0] / s[s < 0]))
    tilt = float(np.clip(tilt, lo + 1e-9 * (hi - lo), hi - 1e-9 * (hi - lo)))
    for _ in range(100):
        state = pad_state(pad, ratio, np.array([X, Y, tilt]), guess, viscosity=viscosity)
        Q, K = float(state.force[2]), float(state.stiffness[2, 2])
        scale = max(float(np.abs(state.force[:2]).max()), 1e-300)
        if abs(Q) <= tol * scale:
            return tilt, state
        if Q > 0:
            lo = tilt
        else:
            hi = tilt
        step = tilt + Q / K if K != 0 else np.nan
        tilt = step if lo < step < hi else 0.5 * (lo + hi)
        guess = state.pressure <= 0
    raise ValueError(f"the pad at {math.degrees(pad.pivot):.0f} deg found no tilt without a "
                     "moment about its pivot")


def equilibrium(bore: Bore, load: np.ndarray, tol: float = 1e-10, steps: int = 60,
                start: BoreState | None = None, viscosity: tuple | None = None) -> BoreState:
    """The journal's place (and the pads' tilts) where the film carries the load:
    Q_X, Q_Y = -load (the nondimensional load on the journal, W c_b^2 / (mu omega R^4)
    along its direction) and every tilt's moment zero (from `start`, a nearby load's
    state, if given). At each place the journal takes,
    each tilting pad settles first (settle); the journal then moves by Newton's steps
    on the film's stiffness with the pads settled (each pad's tilt condensed out),
    shortened while they do not lower the residual or would close the film. `viscosity`:
    each pad's film viscosity on its nodes (pad_state), None isoviscous."""
    visc = viscosity if viscosity is not None else (None,) * len(bore.pads)
    load = np.asarray(load, dtype=float)
    scale = max(float(np.linalg.norm(load)), 1e-300)
    n = 2 + len(bore.tilts)

    def at(xy: np.ndarray, q: np.ndarray, guesses: tuple) -> BoreState:
        q = q.copy()
        q[:2] = xy
        states = []
        for k, pad in enumerate(bore.pads):
            if pad.tilts:
                t = bore.coordinates(k)[2]
                q[t], s = settle(pad, bore.ratio, xy[0], xy[1], q[t], guesses[k], tol,
                                 visc[k])
            else:
                s = pad_state(pad, bore.ratio, xy, guesses[k], viscosity=visc[k])
            states.append(s)
        return _gathered(bore, q, states)

    if start is None:
        xy = 0.05 * load / scale
        state = at(xy, np.zeros(n), (None,) * len(bore.pads))
    else:   # from a nearby load's state
        xy = start.q[:2].copy()
        state = at(xy, start.q, tuple(p.pressure <= 0 for p in start.pads))
    for _ in range(steps):
        r = state.force[:2] + load
        if float(np.linalg.norm(r)) <= tol * scale:
            return state
        step = np.linalg.solve(condensed(state.stiffness), r)
        t = 1.0
        while True:
            try:
                trial = at(xy + t * step, state.q, tuple(p.pressure <= 0 for p in state.pads))
            except ValueError:
                trial = None
            if trial is not None and (np.linalg.norm(trial.force[:2] + load)
                                      < np.linalg.norm(r)):
                break
            if t < 1e-4:
                raise ValueError("the film does not carry the load: the journal touches "
                                 "a pad")
            t /= 2
        xy, state = xy + t * step, trial
    raise ValueError(f"the film's equilibrium did not settle in {steps} steps")


def pad_heat_terms(pad: Pad, ratio: float, q: np.ndarray, P: np.ndarray
                   ) -> tuple[float, float, float]:
    """What heats a pad's oil and what carries it away, nondimensional, whole length
    (parts.journal.film_heat's on a plain film): the friction integral int [1/H + (H / 2)
    dP/dtheta] over the pad, the flow into its leading edge int [H / 2 - (H^3 / 12)
    dP/dtheta] dZ, and its side flow, that less what leaves the film downstream: on each
    line along the journal the Couette flow H / 2 where the film ruptures (its pressure
    and gradient zero there), or across the trailing edge where it does not."""
    from skfem import Functional

    f = pad_film(pad.start, pad.arc, ratio, cells_round(pad.arc), Z_CELLS)

    @Functional
    def shear(w):
        H = _film(pad, w.x[0], q)[0]
        return 1.0 / H + 0.5 * H * w["p"].grad[0]

    friction = 2.0 * float(shear.assemble(f.basis, p=f.basis.interpolate(P)))
    # the flux across each edge from the elements beside it (P's gradient is constant
    # on each P1 cell): the cells' mean over Z of H / 2 - (H^3 / 12) dP/dtheta at the edge
    mesh = f.basis.mesh
    x = mesh.p
    cells = mesh.t
    grad = np.asarray(f.basis.interpolate(P).grad[0]).mean(axis=1)   # per element
    flows = []
    for edge in (pad.start, pad.start + pad.arc):
        on = np.isclose(x[0][cells], edge).sum(axis=0) == 2   # cells with a side there
        z = np.sort(x[1][cells[:, on]][np.isclose(x[0][cells[:, on]], edge)].reshape(-1, 2),
                    axis=1)
        H = _film(pad, np.full(z.shape[0], edge), q)[0]
        flux = 0.5 * H - H**3 / 12 * grad[on]
        flows.append(2.0 * float(np.sum(flux * (z[:, 1] - z[:, 0]))))
    # where each line's film ruptures before the trailing edge, what leaves it is the
    # Couette flow where it ruptures first (the cells' flux at the trailing edge counts
    # the gap's, not the streamers')
    lines = np.unique(x[1].round(12))
    leaving = []
    for zl in lines[:-1]:                       # the end line is the pad's edge, P = 0
        row = np.flatnonzero(np.isclose(x[1], zl))
        row = row[np.argsort(x[0][row])]
        dry = np.flatnonzero(P[row[1:-1]] <= 0)
        if not dry.size:
            leaving.append(np.nan)              # a full film to the trailing edge
        else:
            # the film ruptures first there (at once: at the leading edge), and no more oil
            # than passes there goes on: a film formed again downstream (Swift-Stieber's
            # pressure near a converging trailing edge) carries no more
            k = row[1 + dry[0]] if dry[0] > 0 else row[0]
            leaving.append(0.5 * float(_film(pad, x[0][k:k + 1], q)[0][0]))
    if not np.isnan(leaving).all():
        # lines that do not rupture: their share of the trailing edge's flux
        edge_q = flows[1] / (2 * lines[-1])
        q_out = np.append(np.where(np.isnan(leaving), edge_q, leaving), edge_q)
        flows[1] = 2.0 * float(np.sum(0.5 * (q_out[1:] + q_out[:-1]) * np.diff(lines)))
    return friction, flows[0], flows[0] - flows[1]


def _on_pivot(pad: Pad, s: PadState) -> tuple[np.ndarray, np.ndarray]:
    """A tilting pad's film (K, C) on (X, Y, its tilt, r): r its pivot's motion outward
    along n = (cos, sin) of its pivot angle, which opens its film as the journal's motion
    by -r n does (the pad's own coordinates are (X - r n_x, Y - r n_y, tilt))."""
    n = np.array([math.cos(pad.pivot), math.sin(pad.pivot)])
    T = np.array([[1.0, 0.0, 0.0, -n[0]], [0.0, 1.0, 0.0, -n[1]], [0.0, 0.0, 1.0, 0.0]])
    return T.T @ s.stiffness @ T, T.T @ s.damping @ T


def sommerfeld_load(ratio: float, sommerfeld: float) -> float:
    """The nondimensional load |Fbar| = W c^2 / (mu omega R^4) of a bearing of L / D =
    ratio at Sommerfeld's S = mu N L D / W (R / c)^2 (N in rev/s): 2 ratio / (pi S)."""
    return 2 * ratio / (math.pi * sommerfeld)


def thinnest(bore: Bore, state: BoreState) -> float:
    """The thinnest film over the pads, over the clearance c_b."""
    return min(float(_film_at(p, state.q[bore.coordinates(k)])[1].min())
               for k, p in enumerate(bore.pads))


def bore_of(spec, ratio: float) -> Bore:
    """A scene's bore (scene.model.JournalBore) set about a load along -y."""
    down = -math.pi / 2
    if spec.kind == "two_axial_groove":
        return two_axial_groove(ratio, spec.groove, down)
    if spec.kind == "elliptical":
        return elliptical(ratio, spec.preload, spec.groove, down)
    if spec.kind == "tilting_pad":
        first = down + (math.pi / spec.pads if spec.between else 0.0)
        return tilting(ratio, spec.pads, spec.arc, spec.preload, spec.offset, first)
    raise ValueError(f"bore {spec.kind!r}: not a bore of pads")


# the Sommerfeld numbers (on c_b) a bore's table is solved at, lightest load first; it
# ends where the film would be thinner than THINNEST of the clearance
SOMMERFELD = tuple(np.geomspace(10.0, 0.005, 28).round(6))
THINNEST = 0.02
# what a bore's film table depends on besides its L / D and bore: a cache's key
SETTINGS = {"version": 5, "pads": True, "cells_per_radian": CELLS_PER_RADIAN,
            "z_cells": Z_CELLS, "sommerfeld": list(SOMMERFELD), "thinnest": THINNEST}


def film_table(spec, ratio: float):
    """A bore's film over SOMMERFELD, in the frame where the load on the journal points
    along -y (parts.journal.FilmTable): each row's eccentricity and attitude, |Fbar|,
    and the synchronously reduced Kbar, Cbar (a tilting pad's tilt condensed out at a
    whirl at the speed of the spin, its pad massless), and the thinnest film; a bore of
    tilting pads also each pad's Kbar, Cbar on (X, Y, its tilt, its pivot's radial
    motion) (n, pads, 4, 4; a tilt's coordinate is its angle times R / c_b, as the
    journal's are over c_b; _on_pivot), for the rotor model to keep the tilts (and a
    flexible pivot's motion) as its own coordinates (parts.journal.assembled)."""
    from shaftfem.parts.journal import FilmTable

    bore = bore_of(spec, ratio)
    rows = []
    state = None
    for S in SOMMERFELD:
        F = sommerfeld_load(ratio, S)
        try:
            state = equilibrium(bore, np.array([0.0, -F]), start=state)
        except ValueError:
            break
        h = thinnest(bore, state)
        if h < THINNEST:
            break
        Z = condensed(state.stiffness + 1j * state.damping)
        X, Y = state.q[:2]
        heat = np.sum([pad_heat_terms(p, ratio, state.q[bore.coordinates(k)], s.pressure)
                       for k, (p, s) in enumerate(zip(bore.pads, state.pads))], axis=0)
        blocks = [_on_pivot(p, s) for p, s in zip(bore.pads, state.pads) if p.tilts]
        rows.append((math.hypot(X, Y), S, math.atan2(X, -Y), F, Z.real, Z.imag, h,
                     np.array([b[0] for b in blocks]), np.array([b[1] for b in blocks]),
                     *heat))
    if len(rows) < 4:
        raise ValueError(f"the {spec.kind} bore's film carries too little load to tabulate")
    col: list[np.ndarray] = [np.array(c) for c in zip(*rows)]
    return FilmTable(ratio=ratio, cavitation="reynolds", eccentricity=col[0],
                     sommerfeld=col[1], attitude=col[2], force=col[3], stiffness=col[4],
                     damping=col[5], bore=spec, thinnest=col[6],
                     pad_stiffness=col[7] if bore.tilts else None,
                     pad_damping=col[8] if bore.tilts else None,
                     friction=col[9], inflow=col[10], side_flow=col[11])
