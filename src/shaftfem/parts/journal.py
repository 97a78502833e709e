"""A plain cylindrical journal bearing from its oil film: Reynolds' equation solved by
finite elements (scikit-fem) on the unwrapped film; the journal's eccentricity,
attitude angle, minimum film and Sommerfeld number under its load, and the eight
stiffness and damping coefficients.

Nondimensional, with theta around the bearing from +x towards +y, Z = z / R,
H = h / c, P = p (c / R)^2 / (mu omega), tau = omega t, and the journal's centre at
(e_x, e_y) = c (X, Y), turning at omega about +z:

    div(H^3 grad P) = 6 dH/dtheta + 12 dH/dtau,     H = 1 - X cos(theta) - Y sin(theta),

with P = 0 at the bearing's ends Z = +-L / (2 R) and periodic in theta (the ends'
symmetry halves the film). Cavitation:

* "reynolds" (Swift-Stieber): P >= 0, and the film ruptures where P and its gradient
  vanish: the complementarity problem min 1/2 P.A P - b.P over P >= 0, solved by a
  primal-dual active set (the P1 film on right triangles is an M-matrix, so it ends in
  a few steps);
* "gumbel" (the half-Sommerfeld film of Ocvirk's short bearing): the linear solution's
  negative pressures are dropped.

The film's force on the journal is F = -(mu omega R^4 / c^2) int P (cos, sin) dtheta dZ.
Its derivatives along X, Y (stiffness) and dX/dtau, dY/dtau (damping) are those of the
discrete film, exact: one tangent solve each on the film's own factorisation (where
the film ends P and its gradient vanish, so the edge's motion adds nothing at first
order). In the load's units K = (W / c) Kbar / |Fbar| and C = (W / (c omega)) Cbar / |Fbar|.

References: Reynolds (1886); Ocvirk (1952), the short bearing; Raimondi and Boyd
(1958), the finite bearing's tables; Lund (1987), the coefficients by perturbation.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from shaftfem.scene.model import (
    JOURNAL_RATIOS,
    BearingCoefficients,
    JournalBearing,
    Rotor,
    TiltingFilm,
    condensed,
)

CAVITATION = ("reynolds", "gumbel")
# The lengths over diameter the film is solved for (outside them a bearing is not plain).
RATIOS = JOURNAL_RATIOS
# The film's mesh: cells around the bearing (graded towards the thinnest film) and
# across its half length. The tests measure what they leave (docs/journal-bearing.md).
THETA_CELLS = 240
Z_CELLS = 16
# theta = s - GRADING sin(s): cells at the thinnest film this many times finer
GRADING = 0.75
# The active-set steps allowed to settle the film's edge, from the edge of a film of
# half as many cells around (COARSEST cells: from the half-Sommerfeld film)
STEPS = 60
COARSEST = 60
FEED = True
# The eccentricity ratios the table is solved at (its ends: the lightest and the
# heaviest load it holds).
ECCENTRICITIES = tuple(np.concatenate([
    [1e-3, 0.01, 0.03], np.linspace(0.05, 0.8, 16), 1 - np.geomspace(0.18, 0.02, 10)]).round(6))


@dataclass(frozen=True)
class FilmState:
    """The film with the journal at (X, Y) = (eps, 0): its force on the journal (Fbar,
    2), the stiffness Kbar = -dFbar/d(X, Y) and the damping Cbar = -dFbar/d(X', Y')
    (2x2), all nondimensional (module docstring); `wet`, the film's share that carries
    pressure; and what heats the oil (film_heat): the friction integral, the flow into
    the film at its feed and the flow out of its ends."""

    eccentricity: float
    force: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    wet: float
    friction: float = 0.0
    inflow: float = 0.0
    side_flow: float = 0.0


@dataclass(frozen=True)
class Film:
    """The unwrapped half film of a bearing of L / D = `ratio` on a P1 mesh: the
    operators that do not depend on where the journal is."""

    ratio: float
    basis: Any
    free: np.ndarray          # the unknowns: nodes off the end Z = L / (2 R)
    cos: np.ndarray           # int cos(theta) v, int sin(theta) v (per node)
    sin: np.ndarray
    periodic: Any             # (nodes, unknowns): theta = pi is theta = -pi
    at: np.ndarray            # (unknowns, 2): each unknown's (theta, Z)


@lru_cache(maxsize=8)
def film(ratio: float, theta_cells: int = THETA_CELLS, z_cells: int = Z_CELLS) -> Film:
    """The film's mesh and its constant operators (cached by its L / D and cells)."""
    import scipy.sparse as sp
    from skfem import Basis, ElementTriP1, LinearForm, MeshTri

    s = np.linspace(-math.pi, math.pi, theta_cells + 1)
    theta = s - GRADING * np.sin(s)
    mesh = MeshTri.init_tensor(theta, np.linspace(0.0, ratio, z_cells + 1))
    basis = Basis(mesh, ElementTriP1(), intorder=4)
    x = mesh.p
    n = x.shape[1]
    # theta = +pi is the node at theta = -pi with the same Z
    seam = np.isclose(x[0], math.pi)
    target = np.arange(n)
    left = np.flatnonzero(np.isclose(x[0], -math.pi))
    for i in np.flatnonzero(seam):
        target[i] = left[np.argmin(np.abs(x[1, left] - x[1, i]))]
    kept = np.flatnonzero(~seam)
    index = -np.ones(n, dtype=int)
    index[kept] = np.arange(kept.size)
    T = sp.csr_matrix((np.ones(n), (np.arange(n), index[target])), shape=(n, kept.size))
    end = np.isclose(x[1, kept], ratio) | (FEED & np.isclose(x[0, kept], -math.pi))
    cos = T.T @ LinearForm(lambda v, w: np.cos(w.x[0]) * v).assemble(basis)
    sin = T.T @ LinearForm(lambda v, w: np.sin(w.x[0]) * v).assemble(basis)
    return Film(ratio=ratio, basis=basis, free=np.flatnonzero(~end), cos=cos, sin=sin,
                periodic=T, at=x[:, kept].T)


def _assemble(f: Film, X: float, Y: float, short: bool = False):
    """A(H), the Couette load b, the tangents dA/dX, dA/dY and the loads' derivatives
    (along X, Y, X', Y'), on the periodic unknowns; `short` drops the circumferential
    pressure flow (Ocvirk's short bearing)."""
    from skfem import BilinearForm, LinearForm

    # the film's thickness and its derivatives at the quadrature points, once (a form's
    # kernel runs once per pair of basis functions)
    theta = np.asarray(f.basis.global_coordinates())[0]
    cos, sin = np.cos(theta), np.sin(theta)
    H = 1.0 - X * cos - Y * sin
    around = 0.0 if short else 1.0

    @BilinearForm
    def flow(u, v, w):      # the weight w.k times the film's flux
        return w.k * (around * u.grad[0] * v.grad[0] + u.grad[1] * v.grad[1])

    @LinearForm
    def couette(v, w):      # -6 dH/dtheta, dH/dtheta = X sin - Y cos
        return w.k * v

    T = f.periodic

    def red(M):
        return (T.T @ M @ T).tocsr()

    b = T.T @ couette.assemble(f.basis, k=-6.0 * (X * sin - Y * cos))
    loads = np.column_stack([-6.0 * f.sin, 6.0 * f.cos, 12.0 * f.cos, 12.0 * f.sin])
    dH3 = -3.0 * H ** 2            # d(H^3)/dH times dH/dX = -cos (dH/dY = -sin)
    return (red(flow.assemble(f.basis, k=H ** 3)), b, red(flow.assemble(f.basis, k=dH3 * cos)),
            red(flow.assemble(f.basis, k=dH3 * sin)), loads)


def _pressure(A, b: np.ndarray, free: np.ndarray, cavitation: str,
              guess: np.ndarray | None = None, factor: Any = None
              ) -> tuple[np.ndarray, np.ndarray, Any]:
    """The film pressure P (on every unknown, 0 at the ends), the unknowns where it is
    free (the rest held at 0) and the factors of A there (to solve its derivatives
    with): Swift-Stieber by a primal-dual active set (from the ruptured film `guess`, or
    the half-Sommerfeld one; each step moves the film's edge by about a cell), or the
    half-Sommerfeld film. `factor`: what factors A's CSC block (SuperLU by default)."""
    from scipy.sparse.linalg import splu

    factorise = factor or splu
    n = A.shape[0]
    tol_r = 1e-9 * float(np.abs(b).max())
    active = np.zeros(n, dtype=bool)
    if guess is None or cavitation == "gumbel":
        lu = factorise(A[free][:, free].tocsc())
        P = np.zeros(n)
        P[free] = lu.solve(b[free])
        if cavitation == "gumbel":
            return P, free, lu
        active[free] = P[free] < 0
    else:
        active[free] = guess[free]
    tol_p = None
    for _ in range(STEPS):
        live = free[~active[free]]
        lu = factorise(A[live][:, live].tocsc())
        P = np.zeros(n)
        P[live] = lu.solve(b[live])
        # ties (a node whose pressure or multiplier is zero to round-off) stay as they are
        tol_p = 1e-9 * float(np.abs(P).max()) if tol_p is None else tol_p
        residual = A @ P - b
        now = np.zeros(n, dtype=bool)
        now[free] = np.where(active[free], residual[free] > -tol_r, P[free] < -tol_p)
        if np.array_equal(now, active):
            return P, live, lu
        active = now
    raise RuntimeError(f"the film's cavitation boundary did not settle in {STEPS} steps")


def state(ratio: float, eccentricity: float, cavitation: str = "reynolds",
          theta_cells: int = THETA_CELLS, z_cells: int = Z_CELLS, short: bool = False
          ) -> FilmState:
    """The film of a bearing of L / D = ratio with its journal at (eps, 0); `short`:
    without the circumferential pressure flow, Ocvirk's short-bearing film (a check)."""
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation {cavitation!r}: one of {CAVITATION}")
    f = film(float(ratio), theta_cells, z_cells)
    A, b, Ax, Ay, loads = _assemble(f, eccentricity, 0.0, short)
    P, live, lu = _pressure(A, b, f.free, cavitation,
                        _ruptured(float(ratio), eccentricity, cavitation, theta_cells, z_cells,
                                  short))
    carried = P.copy() if cavitation == "reynolds" else np.maximum(P, 0.0)
    wet = np.flatnonzero(carried > 0) if cavitation == "gumbel" else live

    def force(p: np.ndarray) -> np.ndarray:   # the whole film: twice the half
        return -2.0 * np.array([f.cos @ p, f.sin @ p])

    rhs = np.column_stack([loads[:, 0] - Ax @ P, loads[:, 1] - Ay @ P, loads[:, 2], loads[:, 3]])
    dP = np.zeros((A.shape[0], 4))
    dP[live] = lu.solve(rhs[live])
    if cavitation == "gumbel":
        mask = np.zeros(A.shape[0])
        mask[wet] = 1.0
        dP = dP * mask[:, None]
    dF = np.column_stack([force(dP[:, k]) for k in range(4)])
    friction, inflow, side_flow = film_heat(f, eccentricity, carried, A @ P - b)
    return FilmState(eccentricity=float(eccentricity), force=force(carried),
                     stiffness=-dF[:, :2], damping=-dF[:, 2:],
                     wet=float(wet.size / max(f.free.size, 1)), friction=friction,
                     inflow=inflow, side_flow=side_flow)


def film_heat(f: Film, eps: float, P: np.ndarray, residual: np.ndarray
              ) -> tuple[float, float, float]:
    """What heats the oil and what carries the heat away, nondimensional, for the whole
    length (the half film doubled), the journal at (eps, 0):

    * the friction integral I = int [1/H + (H / 2) dP/dtheta] dtheta dZ: the shear on
      the journal (Couette, also where the film has ruptured into streamers, as Petroff
      and Raimondi and Boyd take it, and Poiseuille), its friction force mu omega R^3 I
      / c and power loss mu omega^2 R^4 I / c;
    * the flow into the film at its feed (theta = -pi, the widest gap), q_in = int [H /
      2 - (H^3 / 12) dP/dtheta] dZ, the pressure's part read from the discrete film's
      flux there (`residual` = A P - b at the feed's nodes);
    * the side flow out of both ends, q_s = q_in - q_out, q_out the Couette flow where
      the film ruptures on each line along the journal (its pressure and gradient zero
      there): by mass conservation, as accurate as the film's cells round the bearing.

    A flow Q = omega R^2 c q. Raimondi and Boyd's variables: (R / c) f = I / |Fbar|,
    Q / (R c N L) = pi q_in / (L / D), likewise Q_s."""
    from skfem import Functional

    x = f.at
    ratio = f.ratio
    end = np.isclose(x[:, 1], ratio)
    feed = np.isclose(x[:, 0], -math.pi) & ~end
    inflow = ratio * (1 + eps) - (2.0 / 12.0) * float(-residual[feed].sum())
    leaving = []
    lines = np.unique(x[~end, 1])
    for z in lines:
        row = np.flatnonzero(np.isclose(x[:, 1], z))
        row = row[np.argsort(x[row, 0])]
        wet = np.flatnonzero(P[row] > 0)
        # the first dry node after the pressurised film (the last node, if none ruptures)
        k = row[min(int(wet.max()) + 1, row.size - 1)] if wet.size else row[0]
        leaving.append(0.5 * (1 - eps * math.cos(float(x[k, 0]))))
    q = np.append(leaving, leaving[-1])
    outflow = 2.0 * float(np.sum(0.5 * (q[1:] + q[:-1]) * np.diff(np.append(lines, ratio))))
    Pn = f.periodic @ P
    shear = Functional(lambda w: 1.0 / (1 - eps * np.cos(w.x[0]))
                       + 0.5 * (1 - eps * np.cos(w.x[0])) * w["p"].grad[0])
    friction = 2.0 * float(shear.assemble(f.basis, p=f.basis.interpolate(Pn)))
    return friction, float(inflow), float(inflow - outflow)


def _ruptured(ratio: float, eccentricity: float, cavitation: str, theta_cells: int,
              z_cells: int, short: bool) -> np.ndarray | None:
    """Where the film of half as many cells around is ruptured, on this film's unknowns
    (None for the coarsest film, or the half-Sommerfeld one)."""
    if cavitation != "reynolds" or theta_cells <= COARSEST or theta_cells % 2:
        return None
    half = theta_cells // 2
    coarse = film(ratio, half, z_cells)
    A, b, *_ = _assemble(coarse, eccentricity, 0.0, short)
    P, _, _ = _pressure(A, b, coarse.free, cavitation,
                     _ruptured(ratio, eccentricity, cavitation, half, z_cells, short))
    fine = film(ratio, theta_cells, z_cells)
    xc, xf = coarse.at, fine.at
    guess = np.zeros(xf.shape[0], dtype=bool)
    for z in np.unique(xf[:, 1]):
        row, crow = np.flatnonzero(xf[:, 1] == z), np.flatnonzero(np.isclose(xc[:, 1], z))
        order, fine_order = np.argsort(xc[crow, 0]), np.argsort(xf[row, 0])
        p = np.interp(xf[row[fine_order], 0], xc[crow[order], 0], P[crow[order]],
                      period=2 * math.pi)
        guess[row[fine_order]] = p <= 0
    return guess


def rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


@dataclass(frozen=True)
class FilmTable:
    """A bearing's film over the eccentricity ratios ECCENTRICITIES, in the frame where
    the load on the journal points along -y: the Sommerfeld number, the attitude angle
    (rad, from the load line to the line of centres, with the journal's turn), |Fbar|,
    and Kbar, Cbar (n, 2, 2)."""

    ratio: float
    cavitation: str
    eccentricity: np.ndarray
    sommerfeld: np.ndarray
    attitude: np.ndarray
    force: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    bore: Any = None            # scene.model.JournalBore; None: the plain bore
    thinnest: np.ndarray | None = None    # the thinnest film over c (None: 1 - eps)
    # what heats the oil, per row (FilmState; None: not solved for this bore)
    friction: np.ndarray | None = None
    inflow: np.ndarray | None = None
    side_flow: np.ndarray | None = None
    # a bore of tilting pads: each pad's Kbar, Cbar on (X, Y, its tilt, its pivot's
    # radial motion) (n, P, 4, 4; parts.pads.film_table), what the synchronously reduced
    # ones are condensed from (assembled)
    pad_stiffness: np.ndarray | None = None
    pad_damping: np.ndarray | None = None

    @property
    def films(self) -> np.ndarray:
        """The thinnest film over the clearance at each row."""
        return 1 - self.eccentricity if self.thinnest is None else self.thinnest


# tables made elsewhere (read from a cache by the caller), by (L / D, cavitation, bore)
_KNOWN: dict[tuple[float, str, Any], FilmTable] = {}
# what a film table depends on besides its L / D and cavitation: a cache's key
SETTINGS = {"version": 2, "eccentricities": list(ECCENTRICITIES), "theta_cells": THETA_CELLS,
            "z_cells": Z_CELLS, "grading": GRADING, "feed": FEED, "coarsest": COARSEST}
TABLE_FIELDS = ("eccentricity", "sommerfeld", "attitude", "force", "stiffness", "damping")
# a plain film's table also keeps what heats its oil
HEAT_FIELDS = ("friction", "inflow", "side_flow")
# a bore of tilting pads also keeps its film on the tilts
PAD_FIELDS = ("pad_stiffness", "pad_damping")


def remember(t: FilmTable) -> None:
    """Take `t` as the film table of its L / D, cavitation and bore (one read from a
    cache)."""
    _KNOWN[(t.ratio, t.cavitation, t.bore)] = t


@lru_cache(maxsize=16)
def table(ratio: float, cavitation: str = "reynolds", bore: Any = None) -> FilmTable:
    """The film of a bearing of L / D = ratio at every eccentricity of ECCENTRICITIES;
    a bore of pads' (`bore`), once remembered (parts.pads.film_table solves it)."""
    if (ratio, cavitation, bore) in _KNOWN:
        return _KNOWN[(ratio, cavitation, bore)]
    if bore is not None:   # solved by parts.pads.film_table, kept by remember()
        raise ValueError(f"the film table of a {bore.kind} bore (L/D {ratio:g}) is not "
                         "solved yet (shaftfem.parts.pads.film_table)")
    rows = [state(ratio, e, cavitation) for e in ECCENTRICITIES]
    S, phi, F, K, C = [], [], [], [], []
    for r in rows:
        load_angle = math.atan2(r.force[1], r.force[0]) + math.pi   # W = -F
        Q = rotation(-math.pi / 2 - load_angle)     # the load turned onto -y
        S.append(2 * ratio / (math.pi * float(np.hypot(*r.force))))
        phi.append(math.remainder(0.0 - load_angle, 2 * math.pi))
        F.append(float(np.hypot(*r.force)))
        K.append(Q @ r.stiffness @ Q.T)
        C.append(Q @ r.damping @ Q.T)
    return FilmTable(ratio, cavitation, np.array(ECCENTRICITIES), np.array(S), np.array(phi),
                     np.array(F), np.array(K), np.array(C),
                     friction=np.array([r.friction for r in rows]),
                     inflow=np.array([r.inflow for r in rows]),
                     side_flow=np.array([r.side_flow for r in rows]))


@dataclass(frozen=True)
class Operating:
    """A journal bearing at one speed: eccentricity ratio, attitude angle (rad), minimum
    film (m), Sommerfeld number, K (N/m) and C (N s/m) on (x, y), and whether the
    speed is beyond the table's heaviest load (the film then thinner than its last row;
    the values are that row's)."""

    speed: float
    eccentricity: float
    attitude: float
    min_film: float
    sommerfeld: float
    K: np.ndarray
    C: np.ndarray
    beyond: bool = False
    # a bore of tilting pads: K (N/m), C (N s/m) on (x, y, R phi_1, ...) (FilmTable)
    pad_K: np.ndarray | None = None
    pad_C: np.ndarray | None = None


def assembled(blocks: np.ndarray, pivots: bool) -> np.ndarray:
    """A tilting-pad bearing's matrix on (x, y, each pad's tilt[, each pivot's radial
    motion]) from its pads' blocks (P, 4, 4) on (x, y, tilt, r) (FilmTable): rigid pivots
    leave the radial motions out."""
    P = blocks.shape[0]
    A = np.zeros((2 + P * (2 if pivots else 1),) * 2, dtype=blocks.dtype)
    for k, block in enumerate(blocks):
        idx = [0, 1, 2 + k] + ([2 + P + k] if pivots else [])
        A[np.ix_(idx, idx)] += block[:len(idx), :len(idx)]
    return A


def pad_matrices(b: JournalBearing, Kp: np.ndarray, Cp: np.ndarray, unit: float,
                 omega: float) -> tuple[np.ndarray, np.ndarray]:
    """A bore of tilting pads' K (N/m) and C (N s/m) on (x, y, R phi_1, ...[, each
    pivot's radial motion]) from its pads' nondimensional blocks (P, 4, 4; FilmTable),
    the film's force scale over c (`unit`, N/m) and the spin (rad/s), turned onto the
    load's direction, each flexible pivot's spring on its pad's radial motion."""
    Q = rotation(math.atan2(b.direction[1], b.direction[0]) + math.pi / 2)
    k_pivot = b.pivot_stiffness
    pivots = k_pivot is not None
    # the tilts and radial motions are scalars: only the journal's block turns
    T = np.eye(2 + Kp.shape[0] * (2 if pivots else 1))
    T[:2, :2] = Q
    K = unit * (T @ assembled(Kp, pivots) @ T.T)
    C = unit / omega * (T @ assembled(Cp, pivots) @ T.T)
    if k_pivot is not None:   # each pivot's spring holds its pad's radial motion
        P = Kp.shape[0]
        K[2 + P:, 2 + P:] += k_pivot * np.eye(P)
    return K, C


def operating(b: JournalBearing, omega: float) -> Operating:
    """The bearing at the spin omega (rad/s > 0): the film's table at its Sommerfeld
    number, scaled by the load and turned onto the load's direction."""
    t = table(round(b.ratio, 9), b.cavitation, b.bore)
    S = b.sommerfeld(max(omega, 1e-12))
    beyond = t.sommerfeld[-1] > S
    eps = _eccentricity(t, S)
    Kt, Ct = t.pad_stiffness, t.pad_damping
    pads = Kt is not None and Ct is not None
    n = Kt.shape[1] * 16 if Kt is not None else 0   # the pads' 4 x 4 blocks
    if t.sommerfeld[0] < S:   # lighter than the first row: the film's linear limit
        phi, Fbar = t.attitude[0], t.force[0] * eps / t.eccentricity[0]
        Kbar, Cbar = t.stiffness[0], t.damping[0]
        film = 1 - eps if t.thinnest is None else float(t.films[0])
        if Kt is not None and Ct is not None:
            Kp, Cp = Kt[0], Ct[0]
    else:
        at = _curve(t, "film")(eps)
        phi, Fbar = float(at[0]), float(at[1])
        Kbar, Cbar = at[2:6].reshape(2, 2), at[6:10].reshape(2, 2)
        film = float(at[10])
        if pads:
            Kp, Cp = at[11:11 + n].reshape(-1, 4, 4), at[11 + n:].reshape(-1, 4, 4)
    Q = rotation(math.atan2(b.direction[1], b.direction[0]) + math.pi / 2)
    unit = b.load / (b.clearance * Fbar)
    w = max(omega, 1e-12)
    K, C = unit * (Q @ Kbar @ Q.T), unit / w * (Q @ Cbar @ Q.T)
    pad_K = pad_C = None
    if pads:
        pad_K, pad_C = pad_matrices(b, Kp, Cp, unit, w)
        # reduced from the film read here, so that the two agree exactly at this speed
        Z = condensed(pad_K + 1j * w * pad_C)
        K, C = Z.real, Z.imag / w
    return Operating(speed=omega, eccentricity=float(eps), attitude=float(phi),
                     min_film=b.clearance * film, sommerfeld=S, K=K, C=C,
                     beyond=bool(beyond), pad_K=pad_K, pad_C=pad_C)


# each table's interpolants, made once: a heated film's speed table reads its table
# some ten thousand times (parts.heat), and making them was most of its cost
_CURVES: dict[int, tuple[FilmTable, dict[str, Any]]] = {}


def _curve(t: FilmTable, name: str) -> Any:
    """Table t's monotone cubic interpolant `name`: "eccentricity" of -log S, "heat"
    (friction, inflow, side flow), "film" (attitude, |Fbar|, Kbar, Cbar, the thinnest
    film and the pads' blocks) of the eccentricity."""
    from scipy.interpolate import PchipInterpolator

    kept = _CURVES.get(id(t))
    if kept is None or kept[0] is not t:   # (a table remembered anew under its key)
        kept = _CURVES[id(t)] = (t, {})
    curves = kept[1]
    if name not in curves:
        if name == "eccentricity":
            curves[name] = PchipInterpolator(-np.log(t.sommerfeld), t.eccentricity)
        elif name == "heat":
            assert t.friction is not None and t.inflow is not None and t.side_flow is not None
            curves[name] = PchipInterpolator(t.eccentricity, np.column_stack(
                [t.friction, t.inflow, t.side_flow]))
        else:
            columns = [t.attitude, t.force, t.stiffness.reshape(-1, 4),
                       t.damping.reshape(-1, 4), t.films]
            if t.pad_stiffness is not None and t.pad_damping is not None:
                n = t.pad_stiffness.shape[1] * 16
                columns += [t.pad_stiffness.reshape(-1, n), t.pad_damping.reshape(-1, n)]
            curves[name] = PchipInterpolator(t.eccentricity, np.column_stack(columns))
    return curves[name]


def _eccentricity(t: FilmTable, S: float) -> float:
    """The eccentricity ratio at Sommerfeld's S on the table (lighter than its first
    row: the film's linear limit, eps proportional to 1 / S; heavier than its last: the
    last row's)."""
    if t.sommerfeld[0] < S:
        return float(t.eccentricity[0] * t.sommerfeld[0] / S)
    return float(_curve(t, "eccentricity")(-math.log(max(S, t.sommerfeld[-1]))))


def heat_terms(b: JournalBearing, omega: float) -> tuple[float, float, float]:
    """The film's friction power (W), flow into it at its feed and side flow out of its
    ends (m^3/s) at the spin omega (rad/s), at its viscosity (film_heat's integrals
    read from the table at its Sommerfeld number)."""
    t = table(round(b.ratio, 9), b.cavitation, b.bore)
    if t.friction is None or t.inflow is None or t.side_flow is None:
        raise ValueError("the film's heating is not in its table")
    assert b.viscosity is not None
    # lighter than the first row: that row's (Petroff's) film
    eps = max(_eccentricity(t, b.sommerfeld(max(omega, 1e-12))), float(t.eccentricity[0]))
    I, q_in, q_s = (float(v) for v in _curve(t, "heat")(eps))
    R, c = b.diameter / 2, b.clearance
    return (b.viscosity * omega**2 * R**4 * I / c, omega * R**2 * c * q_in,
            omega * R**2 * c * q_s)


# The speed table a journal bearing's coefficients are given to the rotor on: this
# many speeds, spaced evenly in log(speed) from where the film lifts the journal to
# its last table row (eccentricity 0.98) up to the top speed (between them linear: a
# step of 1 to 4 % in speed, far below the film's own error).
SPEED_POINTS = 161


@dataclass(frozen=True)
class SpeedTable:
    """A journal bearing's coefficients against speed: speeds (rad/s, ascending), K
    (n, 2, 2) N/m and C (n, 2, 2) N s/m; `lift`, the speed (rad/s) below which the film
    is thinner than the table's last row (there the values are held at that row's)."""

    speeds: np.ndarray
    K: np.ndarray
    C: np.ndarray
    lift: float
    # a bore of tilting pads: on the journal and its tilts (n, 2 + P, 2 + P; Operating)
    pad_K: np.ndarray | None = None
    pad_C: np.ndarray | None = None


def table_end(b: JournalBearing) -> float:
    """The speed (rad/s) below which the film is thinner than its table's last row
    (eccentricity 0.98): the values there are that row's."""
    t = table(round(b.ratio, 9), b.cavitation, b.bore)
    return 2 * math.pi * t.sommerfeld[-1] / b.sommerfeld(2 * math.pi)


def lift_off(b: JournalBearing) -> float:
    """The lift-off speed (rad/s): from it the least film h_min = c (1 - eps) is at least
    the bearing's `min_film` (the surfaces' roughness it must clear), so the journal
    runs on a full film. Below it the journal rubs its shell and the film's
    coefficients are placeholders; Sommerfeld's number grows with the speed, so it is
    the speed where the film table's S meets that eccentricity."""
    from scipy.interpolate import PchipInterpolator

    t = table(round(b.ratio, 9), b.cavitation, b.bore)
    eps = 1 - b.min_film / b.clearance
    if t.thinnest is not None:   # a bore of pads: where its thinnest film is min_film
        h = b.min_film / b.clearance
        if h >= t.films[0]:
            S = t.sommerfeld[0]
        elif h <= t.films[-1]:
            S = t.sommerfeld[-1]
        else:
            S = float(np.exp(PchipInterpolator(-t.films, np.log(t.sommerfeld))(-h)))
    elif eps <= t.eccentricity[0]:   # a film that thick is met only in the linear limit
        S = t.sommerfeld[0] * t.eccentricity[0] / max(eps, 1e-12)
    elif eps >= t.eccentricity[-1]:
        S = t.sommerfeld[-1]
    else:
        S = float(np.exp(PchipInterpolator(t.eccentricity, np.log(t.sommerfeld))(eps)))
    return max(2 * math.pi * S / b.sommerfeld(2 * math.pi), table_end(b))


def speed_table(b: JournalBearing, top: float, points: int = SPEED_POINTS,
                film: Callable[[JournalBearing, float], JournalBearing] | None = None
                ) -> SpeedTable:
    """The bearing's coefficients from its lift-off speed to `top` (rad/s), its film at
    each speed as `film(b, omega)` gives it (parts.heat.at_speed: heated; None: as it
    is); a ValueError if the film does not lift the journal below `top`."""
    lift = table_end(b)
    if lift >= top:
        raise ValueError(f"the film lifts the journal (eccentricity {ECCENTRICITIES[-1]:g}) "
                         f"only at {lift * 60 / (2 * math.pi):,.0f} r/min, above the top "
                         f"speed {top * 60 / (2 * math.pi):,.0f} r/min")
    speeds = np.geomspace(lift, top, points)
    ops = [operating(b if film is None else film(b, w), w) for w in speeds]
    pads = ops[0].pad_K is not None
    return SpeedTable(speeds=speeds, K=np.array([o.K for o in ops]),
                      C=np.array([o.C for o in ops]), lift=float(lift),
                      pad_K=np.array([o.pad_K for o in ops]) if pads else None,
                      pad_C=np.array([o.pad_C for o in ops]) if pads else None)


def with_oil(b: JournalBearing) -> JournalBearing:
    """The bearing with its oil's viscosity (Pa s): as declared, or its ISO VG grade's at
    the film's temperature (shaftfem.parts.oil)."""
    from dataclasses import replace

    from shaftfem.parts import oil

    temperature = b.oil_temperature if b.oil_supply_temperature is None else \
        b.oil_supply_temperature
    if b.oil_iso_vg is None or temperature is None:
        return b
    return replace(b, viscosity=oil.dynamic(b.oil_iso_vg, temperature))


def coefficients(b: JournalBearing, rotor: Rotor,
                 film: Callable[[JournalBearing, float], JournalBearing] | None = None,
                 amend: Callable[[JournalBearing, SpeedTable], SpeedTable] | None = None
                 ) -> BearingCoefficients:
    """A loaded journal bearing's coefficients against speed, up to the Campbell
    diagram's end; its standstill ones at the lowest operating speed (or where its film
    lifts the journal, if later); `amend`: a finer film's correction of the speed table
    (parts.pad_heat.heated_table). A ValueError if the film does not lift it by then."""
    try:
        speeds = speed_table(with_oil(b), rotor.max_speed, film=film)
        if amend is not None:
            speeds = amend(with_oil(b), speeds)
    except ValueError as e:
        raise ValueError(f"{e}; the load is too large for this film (a larger clearance "
                         "ratio, viscosity, length or speed carries more)") from None
    K, C = speeds.K, speeds.C
    pads = _pad_film(b, speeds)
    if pads is not None and pads.masses and speeds.pad_K is not None \
            and speeds.pad_C is not None:
        # pads with inertia: the 2x2 at each speed is the film condensed with it
        reduced = [condensed(A + 1j * w * B - w * w * pads.mass) for w, A, B in
                   zip(speeds.speeds, speeds.pad_K, speeds.pad_C)]
        K = np.array([Z.real for Z in reduced])
        C = np.array([Z.imag / w for Z, w in zip(reduced, speeds.speeds)])

    def column(A, i: int, j: int) -> tuple[float, ...]:
        return tuple(float(v) for v in A[:, i, j])

    low = min(lo for lo, _ in rotor.spans)
    return BearingCoefficients(
        speeds=tuple(float(w) for w in speeds.speeds), kxx=column(K, 0, 0),
        kxy=column(K, 0, 1), kyx=column(K, 1, 0), kyy=column(K, 1, 1), cxx=column(C, 0, 0),
        cxy=column(C, 0, 1), cyx=column(C, 1, 0), cyy=column(C, 1, 1),
        reference=max(low, speeds.lift), pads=pads)


def _pad_film(b: JournalBearing, speeds: SpeedTable) -> TiltingFilm | None:
    """A bore of tilting pads' film on its tilts (and its pivots' radial motions) for the
    rotor model, with each pad's inertia about its pivot over R^2 on its tilt (the tilt's
    coordinate is R phi) and its mass on its radial motion."""
    if speeds.pad_K is None or speeds.pad_C is None:
        return None
    n = speeds.pad_K.shape[1]
    P = n - 2 if b.pivot_stiffness is None else (n - 2) // 2
    R = b.diameter / 2
    masses = (b.pad_inertia / R**2,) * P + ((b.pad_mass,) * P if b.pivot_stiffness else ())
    return TiltingFilm(size=n, stiffness=tuple(float(v) for v in speeds.pad_K.ravel()),
                       damping=tuple(float(v) for v in speeds.pad_C.ravel()),
                       masses=masses if any(masses) else ())
