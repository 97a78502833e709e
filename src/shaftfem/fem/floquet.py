"""A shaft that is not of revolution in bearings that differ along x and y: seen from
the turning shaft, its own matrices are constant and each bearing's deviatoric part
turns at twice the spin, so on the reduced model (fem.rotor, rotating frame)

    M q'' + D(t) q' + K(t) q = 0,   D(t) = D + D_c cos 2 Omega t + D_s sin 2 Omega t

(and so K) has coefficients of period T = pi / Omega. Floquet theory: every solution
is a sum of forms q(t) = exp(lam t) p(t), p of period T, lam a Floquet exponent,
defined up to i 2 Omega k; a form grows where Re lam > 0.

Two routes, independent of each other:

- Hill's method: p = sum_k p_k exp(i 2 k Omega t), k = -H..H, turns the equations
  into one eigenproblem (the first-order form's harmonic blocks; Bentvelsen and
  Lazarus 2018). Each exponent appears once per harmonic shifted by i 2 Omega k; the
  copy kept is the one whose form's harmonics are centred on k = 0. H is raised until
  the exponents kept stop moving.
- The monodromy matrix: the first-order system integrated over one period (fourth-
  order Magnus steps, each exact for the mean system), its eigenvalues the Floquet
  multipliers mu = exp(lam T): |mu| > 1 grows, Re lam = ln |mu| / T.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SolverError, UnsettledError
from shaftfem.fem.rotor import Roots, roots, unbalance_response

if TYPE_CHECKING:
    from shaftfem.fem.rotor import RotorModel

# Hill's harmonics: from this many, raised by HILL_STEP while a form kept has an
# estimated error above HILL_TOL (a fraction of its exponent), up to HILL_MAX. The
# estimate is r^2 / (2 Omega |lam|), r the form's truncation residual: an exponent's
# error goes as the square of the residual (the truncation misses the left and the
# right form alike) over the harmonics' spacing; measured on a keyed shaft and a keyed
# pump in anisotropic bearings from 750 to 8,000 r/min, the true error was at most 0.2
# of the estimate (and HILL_TOL of 1e-7 left errors of 5e-10 at most).
HILL_START = 2
HILL_STEP = 2
HILL_TOL = 1e-7
HILL_MAX = 12
# ... and up to this many at the speeds a rotor runs at (widen): a slow shaft's forms
# spread over about (the bearings' split of a mode's frequency) / (2 Omega) harmonics,
# and its operating speed must be solved whatever it takes (the paper's cam shaft at
# 80 r/min in bearings twice as stiff along x as along y: 24); past HILL_MAX the step
# grows with H (the cost goes as H^3)
HILL_WIDE = 40
# ... watching this share of the exponents, the lowest, those damped at most this
# ratio (-Re lam / |lam|).
WATCHED = 2 / 3
OVERDAMPED = 0.5
# The monodromy's steps: from this many a period, doubled until the multipliers that
# decide stability (RESOLVED) move by less than MONODROMY_TOL of their exponents (each
# step's exponential is exact for the mean system, so the step follows the bearings'
# turning, not the fastest mode: 8,000 steps a period held 1e-8 at 80 r/min where the
# fastest mode turns 8 rad a step), at most MONODROMY_MAX.
MONODROMY_STEPS = 256
MONODROMY_TOL = 1e-7
MONODROMY_MAX = 2**17
# the forms whose multipliers the two routes compare: those above this (a decay of less
# than e^-13.8 a period), and how far apart they may lie (a fraction of |lam|; measured
# 6e-7 at most on a keyed pump on journals from 1,000 to 9,000 r/min)
RESOLVED = 1e-6
ROUTES_TOL = 1e-5
# harmonic balance: harmonics raised while the 1x response moves by more than this
BALANCE_TOL = 1e-7
# how far the window [-1/2, 1/2) of a kept form's harmonic centroid is moved
CENTRE_SLACK = 1e-3
# the harmonics either side of a form's dominant one whose shares it reports (drawn
# thin on the Campbell diagram)
SIDES = 3


@dataclass
class _Memo:
    """What one model's solves leave for its next: the harmonics each converged solve
    took, by speed (a slower spin needs at least as many as a faster one: the forms
    spread as 2 Omega shrinks against the bearings' split, so the next solve starts
    from the slowest speed above it), and the roots of the last speeds solved (a
    Campbell run asks the same speed again: its curves, its rows, its bands)."""

    took: dict[float, int]
    roots: dict[float, Roots]
    # every converged solve's harmonics by speed, widened ones too (harmonics_taken)
    harmonics: dict[float, int]


# by id(model), each entry dropped when its model is collected: an id is reused once
# its object is gone, and a memo kept past it would hand a new model (Level I's rotor
# at another Q) the old one's roots
_MEMOS: dict[int, _Memo] = {}


def _memo(model: RotorModel) -> _Memo:
    """The model's own memo, made on first use."""
    key = id(model)
    memo = _MEMOS.get(key)
    if memo is None:
        memo = _MEMOS[key] = _Memo({}, {}, {})
        weakref.finalize(model, _MEMOS.pop, key, None)
    return memo


@dataclass(frozen=True)
class FirstOrder:
    """x' = (A + A_c cos 2 Omega t + A_s sin 2 Omega t) x, x = (q, q'), at one spin."""

    omega: float
    A: np.ndarray
    Ac: np.ndarray
    As: np.ndarray

    def at(self, t: float) -> np.ndarray:
        c, s = math.cos(2 * self.omega * t), math.sin(2 * self.omega * t)
        return self.A + c * self.Ac + s * self.As


def first_order(model: RotorModel, omega: float) -> FirstOrder:
    """The rotor's first-order form at the spin omega (rad/s), the mass solved out."""
    D, K = model.matrices(omega)
    Dc, Ds, Kc, Ks = model.periodic_parts(omega)
    n = model.size
    M = model.mass(omega)
    Minv = np.linalg.inv(M)
    Z, eye = np.zeros((n, n)), np.eye(n)

    def block(Kx: np.ndarray, Dx: np.ndarray, top: np.ndarray) -> np.ndarray:
        return np.block([[Z, top], [-Minv @ Kx, -Minv @ Dx]])

    return FirstOrder(omega, block(K, D, eye), block(Kc, Dc, Z), block(Ks, Ds, Z))


@dataclass(frozen=True)
class Hill:
    """Hill's exponents at one spin: each Floquet exponent once (2 N, s^-1), its form's
    harmonic coefficients of q at k = 0 (N, 2 N), the centroid of its harmonics, the
    harmonics used (H), and each exponent's truncation residual: what its form would
    need of the harmonics beyond H, |A_+ x_H| + |A_- x_-H| over |x| (s^-1)."""

    lam: np.ndarray
    y: np.ndarray
    centroid: np.ndarray
    harmonics: int
    residual: np.ndarray
    forms: np.ndarray | None = None   # each form's harmonics of q, k = -H..H (2H+1, N, 2N)
    top: float = math.inf   # the largest |lam| settled (s^-1): those above are not

    @property
    def settled(self) -> np.ndarray:
        """Which exponents are settled (|lam| up to top; every one where top is inf)."""
        return np.abs(self.lam) <= self.top * (1 + 1e-9)


def hill(model: RotorModel, omega: float, harmonics: int) -> Hill:
    """The Floquet exponents at the spin omega (rad/s) by Hill's method with harmonics
    -H..H: x = exp(lam t) sum_k x_k exp(i 2 k Omega t) gives
    (lam + i 2 k Omega) x_k = A x_k + A_+ x_{k-1} + A_- x_{k+1}, A_+- = (A_c -+ i A_s) / 2.
    Solved in the real harmonics (1, cos 2 k Omega t, sin 2 k Omega t), where the matrix
    is real (half the cost), the forms then read back in the complex ones."""
    f = first_order(model, omega)
    m = f.A.shape[0]
    H = harmonics
    size = 2 * H + 1
    Ap, Am = 0.5 * (f.Ac - 1j * f.As), 0.5 * (f.Ac + 1j * f.As)
    # x_k (k = -H..H) = sum_j t[k, j] z_j, z = (a_0, a_1, b_1, .. a_H, b_H):
    # x_0 = a_0, x_+-k = (a_k -+ i b_k) / 2
    t = np.zeros((size, size), dtype=complex)
    t[H, 0] = 1.0
    for k in range(1, H + 1):
        t[H + k, 2 * k - 1], t[H + k, 2 * k] = 0.5, -0.5j
        t[H - k, 2 * k - 1], t[H - k, 2 * k] = 0.5, 0.5j
    tinv = np.linalg.inv(t)

    def block(i: int, j: int) -> np.ndarray | None:   # the complex matrix's (i, j) block
        if i == j:
            return f.A - 2j * (i - H) * omega * np.eye(m)
        return Ap if j == i - 1 else Am if j == i + 1 else None

    big = np.zeros((size * m, size * m))
    for p in range(size):
        for i in (int(x) for x in np.flatnonzero(tinv[p])):
            for j in range(max(i - 1, 0), min(i + 2, size)):
                b = block(i, j)
                assert b is not None
                for q in np.flatnonzero(t[j]):
                    big[p * m:(p + 1) * m, q * m:(q + 1) * m] += (tinv[p, i] * b * t[j, q]).real
    lam, Z = np.linalg.eig(big)
    V = np.einsum("kj,jmn->kmn", t, Z.reshape(size, m, -1))
    weight = np.sum(np.abs(V) ** 2, axis=1)                  # (size, all)
    norm = np.sqrt(weight.sum(axis=0))
    weight = weight / weight.sum(axis=0)
    ks = np.arange(-H, H + 1)
    centroid = ks @ weight
    residual = (np.linalg.norm(Ap @ V[-1], axis=0) + np.linalg.norm(Am @ V[0], axis=0)) / norm
    keep = one_copy(lam, centroid, residual / max(float(np.abs(lam).max()), 1.0), omega, m)
    n = m // 2
    return Hill(lam=lam[keep], y=V[H, :n, keep].T, centroid=centroid[keep], harmonics=H,
                residual=residual[keep], forms=V[:, :n][:, :, keep])


def one_copy(lam: np.ndarray, centroid: np.ndarray, residual: np.ndarray, omega: float,
             m: int) -> np.ndarray:
    """Which of Hill's eigenvalues to keep, m of them: of each exponent's copies
    (lam + i 2 Omega k, their harmonics' centroids shifted by k) the one whose centroid
    lies in [-1/2, 1/2) (a form of two equal harmonics, as a round shaft's in bearings
    that differ along x and y is seen from the turning shaft, has its copies at -1/2
    and 1/2: the window is moved by CENTRE_SLACK so that round-off keeps one). The
    best settled first (least truncation residual): the copies of a form that spreads
    beyond the harmonics taken are not exact copies of each other, and must not crowd
    out the settled ones."""
    scale = max(float(np.abs(lam).max()), omega, 1.0)

    def is_copy(j: int, i: int) -> bool:
        d = lam[j] - lam[i]
        turns = d.imag / (2 * omega)
        shift = centroid[j] - centroid[i]
        return bool(abs(d.real) <= 1e-6 * scale
                    and abs(turns - round(turns)) <= 1e-6 * scale / omega
                    and round(turns) != 0 and abs(shift - round(shift)) < 0.25
                    and round(shift) != 0)

    inside = (centroid >= -0.5 - CENTRE_SLACK) & (centroid < 0.5 - CENTRE_SLACK)
    kept: list[int] = []
    for pool in (np.flatnonzero(inside), np.flatnonzero(~inside)):
        for j in pool[np.lexsort((np.abs(centroid[pool]), residual[pool]))]:
            if len(kept) == m:
                break
            if not any(is_copy(int(j), i) for i in kept):
                kept.append(int(j))
    return np.array(kept)


def apart(a: np.ndarray, b: np.ndarray, omega: float) -> np.ndarray:
    """|a_i - b_j| for exponents (s^-1), their imaginary parts modulo 2 omega (the same
    Floquet form whichever copy each is): (len a, len b)."""
    d = a[:, None] - b[None, :]
    im = np.abs(np.mod(d.imag + omega, 2 * omega) - omega)
    return np.hypot(d.real, im)


def matched_change(a: np.ndarray, b: np.ndarray, omega: float) -> float:
    """The largest distance between two sets of exponents paired one to one (apart)."""
    from scipy.optimize import linear_sum_assignment

    if a.size == 0 or b.size == 0:
        return 0.0
    cost = apart(a, b, omega)
    i, j = linear_sum_assignment(cost)
    return float(cost[i, j].max())


def not_overdamped(lam: np.ndarray) -> np.ndarray:
    """Which exponents are damped at most OVERDAMPED (-Re lam / |lam|): the forms damped
    beyond decay within a fraction of a turn, and no stability question rests on them
    (an oil film's damping on the bearings' residual modes); Hill's method does not
    settle them."""
    return -lam.real <= OVERDAMPED * np.abs(lam)


def widen(model: RotorModel, speeds: tuple[float, ...], forms: int) -> RotorModel:
    """The model with Hill's method let take up to HILL_WIDE harmonics at these speeds
    (rad/s), settling there its lowest `forms` Floquet forms: the speeds it runs at,
    solved whatever they take, and only the forms reported there (the diagram's other
    speeds stop at HILL_MAX and settle the lower WATCHED of the forms, and the diagram
    starts where they settle)."""
    return replace(model, wide=tuple(float(w) for w in speeds), wide_forms=forms)


def _wide(model: RotorModel, omega: float) -> bool:
    return float(omega) in model.wide


def _next(H: int) -> int:
    return H + HILL_STEP if H < HILL_MAX else H + max(HILL_STEP, H // 4)


def watched_top(model: RotorModel, omega: float, lam: np.ndarray, wide: bool) -> float:
    """The largest |lam| (s^-1) of the forms Hill's method settles at the spin omega: the
    lower WATCHED of them, or (wide) the lowest model.wide_forms that oscillate and are
    not overdamped."""
    if wide:
        live = np.sort(np.abs(lam[not_overdamped(lam) & (np.abs(lam.imag) > 1e-9 * omega)]))
        if live.size:
            return float(live[min(model.wide_forms, live.size) - 1])
    return float(np.sort(np.abs(lam))[int(WATCHED * (lam.size - 1))])


def converged_hill(model: RotorModel, omega: float) -> Hill:
    """Hill's exponents with H raised until the lower WATCHED of them (what the basis
    check vouches for; the basis' top converges last), but for the forms damped beyond
    OVERDAMPED, have an estimated error of at most HILL_TOL of themselves (their forms
    hold next to nothing in the outermost harmonics). It starts from the harmonics the
    slowest faster speed took and stops early where the estimate's fall from one H to
    the next could not reach HILL_TOL by HILL_MAX. At a widened speed that this does
    not settle, H goes on up to HILL_WIDE for the forms reported there (a slow spin's
    higher forms, those of the bearings' stiffness split by far more than 2 Omega,
    would take hundreds). An UnsettledError (a SolverError) if they do not settle."""
    took = _memo(model).took
    above = [w for w in took if w >= omega]
    below = [w for w in took if w < omega]
    H = (took[min(above)] if above else took[max(below)] if below else HILL_START)
    try:
        h = _settled(model, omega, min(H, HILL_MAX), False)
    except UnsettledError as e:
        if not model.wide_forms:
            raise
        h = _settled(model, omega, min(H, HILL_MAX, e.harmonics), True)
    if len(took) >= 4096:
        took.clear()
    if h.harmonics <= HILL_MAX:   # (a widened speed's are no start for the diagram's)
        took[omega] = h.harmonics
    taken = _memo(model).harmonics
    if len(taken) >= 4096:
        taken.clear()
    taken[float(omega)] = h.harmonics
    return h


def harmonics_taken(model: RotorModel, omega: float) -> int | None:
    """The harmonics Hill's method took at the spin omega (rad/s) for this model, if it
    was solved there: past HILL_MAX a slow spin's forms spread wide, and each solve
    there costs as the cube of them."""
    return _memo(model).harmonics.get(float(omega))


def _settled(model: RotorModel, omega: float, H: int, wide: bool) -> Hill:
    cap = HILL_WIDE if wide and _wide(model, omega) else HILL_MAX
    before, last = math.inf, H
    while True:
        h = hill(model, omega, H)
        low = watched_top(model, omega, h.lam, wide)
        watched = (np.abs(h.lam) <= low * (1 + 1e-9)) & not_overdamped(h.lam)
        estimate = h.residual**2 / (2 * omega * np.maximum(np.abs(h.lam), omega))
        worst = float(estimate[watched].max())
        if worst <= HILL_TOL:
            return replace(h, top=low) if wide else h
        # the estimate falls about geometrically with H where the forms settle (not
        # widened: a slow spin's forms spread over some harmonics, then fall faster than
        # geometrically, as Bessel functions of the split over 2 Omega)
        fall = (worst / before) ** (HILL_STEP / (H - last)) if before < math.inf else 1.0
        reach = worst * fall ** ((cap - H) / HILL_STEP) if fall < 1 else math.inf
        if cap <= H or (not wide and before < math.inf and reach > 1e3 * HILL_TOL):
            raise UnsettledError(f"Hill's method at {omega * 30 / math.pi:,.0f} r/min: the "
                                 f"Floquet forms still reach the outermost of {H} harmonics "
                                 f"(estimated error {worst:.2g} of an exponent)", omega, H)
        before, last = worst, H
        H = min(_next(H), cap)


def monodromy(model: RotorModel, omega: float, steps: int) -> np.ndarray:
    """The monodromy matrix (2 N, 2 N): the first-order state after one period
    T = pi / omega from each unit state, by `steps` fourth-order Magnus steps (two Gauss
    points; each step's exponential exact for a constant system)."""
    import scipy.linalg

    f = first_order(model, omega)
    T = math.pi / omega
    h = T / steps
    c1, c2 = 0.5 - math.sqrt(3) / 6, 0.5 + math.sqrt(3) / 6
    Phi = np.eye(f.A.shape[0])
    for j in range(steps):
        A1, A2 = f.at((j + c1) * h), f.at((j + c2) * h)
        Om = 0.5 * h * (A1 + A2) + (math.sqrt(3) / 12) * h * h * (A2 @ A1 - A1 @ A2)
        Phi = scipy.linalg.expm(Om) @ Phi
    return Phi


def resolved_exponents(mu: np.ndarray, omega: float) -> np.ndarray:
    """The exponents ln(mu) / T of the multipliers that decide stability (|mu| at least
    RESOLVED of the largest or of 1)."""
    T = math.pi / omega
    top = max(float(np.abs(mu).max()), 1.0)
    return np.log(mu[np.abs(mu) >= RESOLVED * top].astype(complex)) / T


def multipliers(model: RotorModel, omega: float, steps: int | None = None) -> np.ndarray:
    """The Floquet multipliers mu = exp(lam T) from the monodromy matrix: with `steps`
    steps, or from MONODROMY_STEPS doubled until the exponents of those that decide
    stability move by at most MONODROMY_TOL of themselves (a SolverError if
    MONODROMY_MAX steps do not settle them)."""
    if steps is not None:
        return np.linalg.eigvals(monodromy(model, omega, steps))
    T = math.pi / omega
    steps = MONODROMY_STEPS
    before = np.log(np.linalg.eigvals(monodromy(model, omega, steps)).astype(complex)) / T
    while steps < MONODROMY_MAX:
        steps *= 2
        mu = np.linalg.eigvals(monodromy(model, omega, steps))
        now = resolved_exponents(mu, omega)
        moved = apart(now, before, omega).min(axis=1) if now.size else np.zeros(0)
        if np.all(moved <= MONODROMY_TOL * np.maximum(np.abs(now), omega)):
            return mu
        before = np.log(mu.astype(complex)) / T
    raise SolverError(f"the monodromy matrix at {omega * 30 / math.pi:,.0f} r/min does not "
                      f"settle with {MONODROMY_MAX:,} steps a period")


def routes_apart(model: RotorModel, omega: float) -> float:
    """How far Hill's exponents lie from the monodromy's (both at the spin omega): the
    largest distance of a pair, each exponent's growth rate ln |mu| / T and its
    frequency modulo 2 omega, over the largest |lam| (a fraction)."""
    lam = converged_hill(model, omega).lam
    T = math.pi / omega
    mono = np.log(multipliers(model, omega).astype(complex)) / T
    scale = max(float(np.abs(lam).max()), omega, 1.0)
    return matched_change(lam, mono, omega) / scale


def growth_apart(model: RotorModel, omega: float) -> float:
    """How far the monodromy's exponents lie from Hill's at the spin omega, over the forms
    that decay by less than RESOLVED a period (a multiplier below it is lost in the
    monodromy's round-off against the largest, and decides no stability question): the
    largest |lam_Hill - lam_monodromy| (frequency modulo 2 omega) over |lam| (a
    fraction). Where Hill's method settled only the lowest forms (a widened speed), a
    growing exponent of the monodromy that none of them has counts as 1."""
    h = converged_hill(model, omega)
    T = math.pi / omega
    settled = h.lam[h.settled]
    lam = settled[settled.real * T >= math.log(RESOLVED)]
    mono = np.log(multipliers(model, omega).astype(complex)) / T
    worst = 0.0
    if lam.size:
        worst = float((apart(lam, mono, omega).min(axis=1)
                       / np.maximum(np.abs(lam), omega)).max())
    grows = mono[mono.real > 1e-9 * max(float(np.abs(mono).max()), omega)]
    if grows.size and h.top < math.inf:
        near = (apart(grows, settled, omega).min(axis=1) if settled.size
                else np.full(grows.size, math.inf))
        if np.any(near > ROUTES_TOL * np.maximum(np.abs(grows), omega)):
            worst = 1.0
    return worst


def solved_from(model: RotorModel, speeds: np.ndarray, lowest: float) -> float:
    """The lowest speed (rad/s) from which Hill's method settles at every one of
    `speeds` (ascending) above it, and below the lowest of them down to `lowest` by
    halving: below it the Floquet forms spread over more harmonics than HILL_MAX (a
    slow spin in strongly anisotropic bearings)."""
    def settles(w: float) -> bool:
        if not model.periodic(w):
            return True
        try:
            floquet_roots(model, w)   # kept: the diagram asks these speeds again
        except UnsettledError:
            return False
        # with harmonics to spare: the speeds the tracker puts between two of the grid's
        # have been seen to need four more than either (the keyed pump: 8 at 250 r/min
        # and 6 at 500 r/min, 12 at 254 to 266 r/min), the dearest solves of the diagram
        return _memo(model).took.get(w, HILL_START) <= HILL_MAX - 3 * HILL_STEP

    positive = [float(w) for w in speeds if w > 0]
    floor = positive[-1]
    for w in positive[::-1]:
        if not settles(w):
            return floor
        floor = w
    # halved while the halved speed leaves harmonics to spare (a slower one needs more;
    # an attempt that climbs to HILL_MAX in vain costs more than the rest of the diagram)
    while floor / 2 >= lowest and settles(floor / 2):
        floor /= 2
    return floor


def harmonic_balance(model: RotorModel, omega: float, load: np.ndarray, base: float,
                     watched: range, what: str) -> np.ndarray:
    """The steady response of the rotor at the spin omega (rad/s) to load exp(i base t)
    (N,), its coefficients periodic in 2 Omega: q = sum_k q_k exp(i w_k t),
    w_k = base + 2 k Omega, and for each harmonic k
    (K - w_k^2 M + i w_k D) q_k + (K_+ + i w_{k-1} D_+) q_{k-1}
    + (K_- + i w_{k+1} D_-) q_{k+1} = load delta_k0. The harmonics (N, 2 H + 1), H raised
    one at a time from HILL_START until the harmonics k in `watched` move by at most
    BALANCE_TOL; a rotor whose coefficients are constant there (K_+- = D_+- = 0) in its
    one harmonic, k = 0."""
    D, K = model.matrices(omega)
    Mm = model.mass(omega)
    Dc, Ds, Kc, Ks = (model.periodic_parts(omega) if model.periodic(omega)
                      else (np.zeros_like(K),) * 4)
    Kp, Km, Dp, Dm = (0.5 * (Kc - 1j * Ks), 0.5 * (Kc + 1j * Ks), 0.5 * (Dc - 1j * Ds),
                      0.5 * (Dc + 1j * Ds))
    n = model.size

    def solve(H: int) -> np.ndarray:
        size = 2 * H + 1
        big = np.zeros((size * n, size * n), dtype=complex)
        for i, k in enumerate(range(-H, H + 1)):
            r = slice(i * n, (i + 1) * n)
            w = base + 2 * k * omega
            big[r, r] = K - w * w * Mm + 1j * w * D
            if i > 0:
                big[r, (i - 1) * n:i * n] = Kp + 1j * (w - 2 * omega) * Dp
            if i < size - 1:
                big[r, (i + 1) * n:(i + 2) * n] = Km + 1j * (w + 2 * omega) * Dm
        rhs = np.zeros(size * n, dtype=complex)
        rhs[H * n:(H + 1) * n] = load
        return np.linalg.solve(big, rhs).reshape(size, n).T

    if not model.periodic(omega):
        return solve(0)   # the harmonics do not couple: the load's own is all of it
    H = HILL_START
    prev = solve(H)
    while True:
        cur = solve(H + 1)
        c0 = cur[:, [H + 1 + k for k in watched]]
        p0 = prev[:, [H + k for k in watched]]
        if np.abs(c0 - p0).max() <= BALANCE_TOL * max(float(np.abs(c0).max()), 1e-300):
            return cur
        H += 1
        if (HILL_WIDE if _wide(model, omega) else HILL_MAX) < H:
            raise SolverError(f"{what} at {omega * 30 / math.pi:,.0f} r/min: harmonic "
                              f"balance does not settle with {H} harmonics")
        prev = cur


def periodic_unbalance(model: RotorModel, omega: float,
                       forces: list[tuple[np.ndarray, complex]]) -> np.ndarray:
    """The steady response to unbalances (each its plane's motion beta (2, N) and
    U = m e exp(i phase), kg m) of a periodic rotor at the spin omega, by harmonic
    balance in the turning frame, where the unbalance's force stands still:
    q = sum_k q_k exp(i 2 k Omega t) (harmonic_balance with base 0), raised until the 1x
    response (k = 0 and -1) settles. The harmonics (N, 2 H + 1)."""
    F = np.zeros(model.size)
    for beta, U in forces:
        F += omega**2 * (U.real * beta[0] + U.imag * beta[1])
    return harmonic_balance(model, omega, F.astype(complex), 0.0, range(-1, 1),
                            "the unbalance response")


def gravity_response(model: RotorModel, omega: float, load: np.ndarray) -> np.ndarray:
    """The steady response of a rotor in the turning frame (rotating) to a load standing
    still in the stationary frame (its weight), at the spin omega (rad/s): seen from the
    shaft the load turns backwards, f(t) = Re[load exp(-i Omega t)], load = A (p_x - i p_y)
    (N,) for a load A = a_x + i a_y (N, or m/s^2 for a weight) and the modal forces
    p_x, p_y of a unit load along x and y at angle 0. By harmonic balance with base
    -Omega, q(t) = Re sum_k q_k exp(i (2 k - 1) Omega t), raised until the harmonics
    k = -1..2 (the stationary frame's sag and 2x parts) settle. The harmonics
    (N, 2 H + 1)."""
    if model.frame != "rotating":
        raise SolverError("a load standing still turns only in the rotating frame")
    return harmonic_balance(model, omega, load, -omega, range(-1, 3),
                            "the response to the weight")


def stationary_orders(beta: np.ndarray, q: np.ndarray) -> dict[int, complex]:
    """What a probe on the housing sees of gravity_response's harmonics q (N, 2 H + 1) at
    a plane whose motion in the turning frame is beta q (beta (2, N)): the coefficients
    c_j of its motion x + i y = sum_j c_j exp(i 2 j Omega t), j = -H-1..H+1 (orders 2 j:
    j = 0 the sag, j = 1 and -1 the 2x motion turning with and against the shaft; the
    2x orbit's major semi-axis |c_1| + |c_-1|). Turned back by Omega t,
    c_j = (a_j + i b_j) / 2 + conj(a_{1-j}) / 2 + i conj(b_{1-j}) / 2, a and b the
    plane's x and y harmonics."""
    H = (q.shape[1] - 1) // 2
    a, b = beta[0] @ q, beta[1] @ q

    def at(k: int) -> tuple[complex, complex]:
        return (complex(a[k + H]), complex(b[k + H])) if -H <= k <= H else (0j, 0j)

    out = {}
    for j in range(-H - 1, H + 2):
        (aj, bj), (ar, br) = at(j), at(1 - j)
        out[j] = 0.5 * (aj + 1j * bj) + 0.5 * (ar.conjugate() + 1j * br.conjugate())
    return out


def stationary_receptance(model: RotorModel, omega: float, w: float, force: np.ndarray,
                          probe: np.ndarray) -> np.ndarray:
    """The receptance (2, 2), m/N, of a rotor in the turning frame (rotating) at the
    spin omega: the x and y motion of the plane `probe` (its motion beta, (2, N)) at the
    frequency w (rad/s) under a unit force along x and along y, standing in the
    stationary frame, at w, on the plane `force`. Seen from the shaft such a force
    F cos(w t) is 1/2 Re[b exp(i (w + Omega) t)] + 1/2 Re[conj(b) exp(i (w - Omega) t)],
    b = p_x + i p_y along x and p_y - i p_x along y (p the plane's modal forces); each is
    solved by harmonic balance (its harmonics at the base + 2 k Omega), and the probe's
    motion turned back by Omega t is read at exp(i w t)."""
    px, py = force[0], force[1]
    H = np.zeros((2, 2), dtype=complex)
    tol = 1e-12 * max(abs(w), omega)
    for j, b in enumerate((px + 1j * py, py - 1j * px)):
        for base, load in ((w + omega, 0.5 * b), (w - omega, 0.5 * np.conj(b))):
            q = harmonic_balance(model, omega, load, base, range(-1, 2),
                                 "the frequency response")
            Hh = (q.shape[1] - 1) // 2
            a, c = probe[0] @ q, probe[1] @ q
            for k in range(-Hh, Hh + 1):
                nu = base + 2 * k * omega
                ak, ck = complex(a[k + Hh]), complex(c[k + Hh])
                # x_s = cos x_r - sin y_r, y_s = sin x_r + cos y_r: the terms at exp(i w t)
                if abs(nu + omega - w) <= tol:
                    H[:, j] += 0.5 * np.array([ak + 1j * ck, ck - 1j * ak])
                if abs(nu - omega - w) <= tol:
                    H[:, j] += 0.5 * np.array([ak - 1j * ck, ck + 1j * ak])
                if abs(-(nu - omega) - w) <= tol:
                    H[:, j] += 0.5 * np.array([np.conj(ak) + 1j * np.conj(ck),
                                               np.conj(ck) - 1j * np.conj(ak)])
                if abs(-(nu + omega) - w) <= tol:
                    H[:, j] += 0.5 * np.array([np.conj(ak) - 1j * np.conj(ck),
                                               np.conj(ck) + 1j * np.conj(ak)])
    return H


def unbalance_orders(beta: np.ndarray, q: np.ndarray) -> dict[int, complex]:
    """What a probe on the housing sees of periodic_unbalance's harmonics q (N, 2 H + 1)
    at a plane whose motion in the turning frame is beta q: the coefficients c_m of
    x + i y = sum_m c_m exp(i m Omega t), m odd (the turning frame's x_r + i y_r =
    sum_k (X_k + i Y_k) exp(i 2 k Omega t), turned by Omega t: c_{2k+1} = X_k + i Y_k).
    Order m's orbit has the major semi-axis |c_m| + |c_-m|: 1x the unbalance's own, 3x
    (and 5x, ...) what a shaft stiffer across one diameter in bearings that differ along
    x and y adds."""
    H = (q.shape[1] - 1) // 2
    X, Y = beta[0] @ q, beta[1] @ q
    return {2 * k + 1: complex(X[k + H] + 1j * Y[k + H]) for k in range(-H, H + 1)}


def floquet_roots(model: RotorModel, omega: float) -> Roots:
    """The Floquet exponents at the spin omega as fem.rotor.roots gives a constant
    rotor's roots: each form by its dominant harmonic (lam + i 2 Omega k and that
    harmonic's coefficients, the component drawn heavy), the oscillating ones
    (Im lam > 0), lowest first; the fastest growth of a form that does not oscillate
    as the stationary frame sees it kept (fem.rotor.still_seen)."""
    from shaftfem.fem.rotor import still_seen, whirl_index

    kept = _memo(model).roots
    if float(omega) in kept:
        return kept[float(omega)]
    h = converged_hill(model, omega)
    forms = h.forms
    assert forms is not None
    if h.top < math.inf:   # a widened speed: the forms reported there, settled
        low = h.settled
        forms = forms[:, :, low]
        h = replace(h, lam=h.lam[low], y=h.y[:, low], centroid=h.centroid[low],
                    residual=h.residual[low], forms=forms)
    energy = np.sum(np.abs(forms) ** 2, axis=1)             # (2H+1, 2N)
    # (two harmonics holding equal shares, a round rotor's in anisotropic supports: the
    # kept copy's own, k = 0, so that the choice does not flip from speed to speed)
    centre = np.zeros(energy.shape[0])
    centre[h.harmonics] = 1e-6
    k = np.argmax(energy * (1 + centre[:, None]), axis=0)
    cols = np.arange(h.lam.size)
    lam = h.lam + 2j * omega * (k - h.harmonics)
    y = forms[k, :, cols].T
    scale = math.sqrt(max(float(np.max(np.abs(model.omega2))), 1.0))
    still = (np.abs(lam.imag) <= 1e-9 * scale) | still_seen(model, omega, lam, y)
    keep = (lam.imag > 1e-9 * scale) & ~still
    divergence = float(max(0.0, lam.real[still].max())) if still.any() else 0.0
    lam, y = lam[keep], y[:, keep]
    # each form's harmonics beside its dominant one: their shares and whirl indices
    total = energy.sum(axis=0)
    d = np.arange(-SIDES, SIDES + 1)
    at = k[None, :] + d[:, None]                               # (2 S + 1, forms)
    inside = (at >= 0) & (at < energy.shape[0])
    share = np.where(inside, energy[np.clip(at, 0, energy.shape[0] - 1), cols[None, :]], 0.0)
    share = share / np.maximum(total, 1e-300)
    index = np.zeros_like(share)
    side_forms = np.zeros((d.size, forms.shape[1], cols.size), dtype=complex)
    for r in range(d.size):
        ys = forms[np.clip(at[r], 0, energy.shape[0] - 1), :, cols].T   # (N, forms)
        index[r] = whirl_index(model, ys)
        side_forms[r] = np.where(inside[r][None, :], ys, 0.0)
    share, index, side_forms = share[:, keep], index[:, keep], side_forms[:, :, keep]
    order = np.argsort(lam.imag)
    out = Roots(lam=lam[order], y=y[:, order],
                divergence=divergence if divergence > 1e-9 * scale else 0.0,
                sides=share[:, order], side_index=index[:, order],
                side_forms=side_forms[:, :, order])
    if len(kept) >= 512:
        kept.pop(next(iter(kept)))
    kept[float(omega)] = out
    return out


# a crossing of a periodic rotor stands where an exponent is seen on its order line: within
# this share of the spin (a curve's jump from one root to another crosses without one)
ON_LINE = 1e-3
# ... and a band locked to the line where two exponents stand on it (within LOCKED of the
# spin) with decays a period apart by more than SPLIT (a pair met there: a multiplier
# pair on the real axis; a lone exponent and its conjugate decay alike), lightly damped:
# decaying by less than e^-LIGHT a period on average (a log decrement below 1 at 1x; two
# overdamped roots stand still there too)
LOCKED = 1e-7
SPLIT = 1e-7
LIGHT = 0.5


def on_line(model: RotorModel, omega: float, order: int) -> tuple[np.ndarray, np.ndarray]:
    """How far each settled Floquet exponent at the spin omega stands from the order
    line (as a share of omega) and its decay per period (-Re lam T). The turning frame
    sees order m where Im lam = (m + 1) Omega modulo 2 Omega (the housing sees a form's
    harmonics at Im lam + (2 d + 1) Omega)."""
    return _on_line(converged_hill(model, omega), omega, order)


def _on_line(h: Hill, omega: float, order: int) -> tuple[np.ndarray, np.ndarray]:
    lam = h.lam[h.settled]
    r = np.mod(lam.imag - (order + 1) * omega + omega, 2 * omega) - omega
    return np.abs(r) / omega, -lam.real * math.pi / omega


def line_pair(model: RotorModel, omega: float, order: int) -> tuple[float, float]:
    """The least damped two forms on the order line at the spin omega (within ON_LINE):
    their mean whirl index as the housing sees it (fem.rotor.seen_whirl_index, every
    harmonic) and their mean decay per period (on_line); (0, 0) where none stands there.
    At a locked band's edge the pair meets in one form: the crossing's whirl and decay."""
    from shaftfem.fem.rotor import seen_whirl_index

    h = converged_hill(model, omega)
    assert h.forms is not None
    r, decay = _on_line(h, omega, order)
    on = r <= ON_LINE
    if not on.any():
        return 0.0, 0.0
    two = np.argsort(decay[on])[:2]
    forms = np.flatnonzero(h.settled)[on][two]
    index = seen_whirl_index(model, omega, h.lam[forms].imag, h.forms[:, :, forms])
    return float(np.mean(index)), float(np.mean(decay[on][two]))


def locked_pair(r: np.ndarray, decay: np.ndarray) -> bool:
    """Whether, of exponents standing r from an order line with their decays a period
    (on_line), a pair is locked to it (LOCKED, SPLIT, LIGHT): inside a band of speeds,
    not at one crossing."""
    d = np.sort(decay[r <= LOCKED])[:2]     # the least damped two
    return d.size == 2 and float(d[1] - d[0]) > SPLIT and float(d.mean()) <= LIGHT


def locked(model: RotorModel, omega: float, order: int) -> bool:
    """Whether a pair of Floquet exponents is locked to the order line at the spin omega
    (locked_pair)."""
    return locked_pair(*on_line(model, omega, order))


def lock_band(model: RotorModel, omega: float, order: int, lowest: float, highest: float,
              tol: float = 1e-7) -> tuple[float, float]:
    """The band of speeds (rad/s) about omega, where a pair is locked to the order line,
    within [lowest, highest]: each edge bracketed by steps doubling from 1e-3 of omega,
    then bisected to tol of it."""
    def edge(sign: int) -> float:
        inside, step = omega, 1e-3 * omega
        while True:
            out = min(max(omega + sign * step, lowest), highest)
            if not locked(model, out, order):
                break
            inside = out
            if out in (lowest, highest):
                return out
            step *= 2
        while abs(out - inside) > tol * omega:
            mid = 0.5 * (inside + out)
            if locked(model, mid, order):
                inside = mid
            else:
                out = mid
        return 0.5 * (inside + out)

    return edge(-1), edge(+1)


def any_roots(model: RotorModel, omega: float) -> Roots:
    """The rotor's roots at the spin omega: its Floquet exponents where its equations are
    periodic there (floquet_roots), else the constant system's (fem.rotor.roots)."""
    return floquet_roots(model, omega) if model.periodic(omega) else roots(model, omega)


def any_unbalance_response(model: RotorModel, omega: float,
                           forces: list[tuple[np.ndarray, complex]]) -> np.ndarray:
    """The steady unbalance response at the spin omega: by harmonic balance where the
    rotor is periodic (periodic_unbalance), else fem.rotor.unbalance_response."""
    if model.periodic(omega):
        return periodic_unbalance(model, omega, forces)
    return unbalance_response(model, omega, forces)


# the direct route's crossings hold when one more pair of harmonics moves none of them
# by more than this share of its speed
DIRECT_TOL = 1e-9


def periodic_order_roots(model: RotorModel, m: int, top: float = math.inf
                         ) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[str, ...]]:
    """Where a Floquet component of the undamped periodic rotor meets the turning frame's
    line f = m n (n the spin): an exponent i m Omega, its form
    q = sum_k q_k exp(i (m + 2k) Omega t). Hill's equations there,

        [K_0 - Omega^2 (c_k^2 M - i c_k G - K_2)] q_k + (K_c - i K_s)/2 q_(k-1)
                                                 + (K_c + i K_s)/2 q_(k+1) = 0,  c_k = m + 2k,

    are a linear eigenproblem in Omega^2 (constant, undamped bearings), as a rotor of
    constant coefficients' crossings are (fem.tracking.order_roots). Harmonics k = -H..H,
    H raised until the roots up to the spin `top` (rad/s) hold to DIRECT_TOL. Returns the
    speeds (rad/s, ascending), each one's share of the motion in the component met (its
    harmonic k = 0), that component's whirl index and its kind (bending, torsion, ...)."""
    import scipy.linalg

    from shaftfem.fem.rotor import dominant_kinds, whirl_index

    N = model.size
    K0 = model.matrices(1.0)[1] - model.K2
    _, _, Kc, Ks = model.periodic_parts(1.0)
    M, G = model.mass(0.0), model.G
    plus, minus = 0.5 * (Kc - 1j * Ks), 0.5 * (Kc + 1j * Ks)

    def solve(H: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        size = 2 * H + 1
        A = np.zeros((size * N, size * N), dtype=complex)
        B = np.zeros_like(A)
        for i, k in enumerate(range(-H, H + 1)):
            c = m + 2 * k
            at = slice(i * N, (i + 1) * N)
            A[at, at] = K0
            B[at, at] = c * c * M - 1j * c * G - model.K2
            if i > 0:
                A[at, (i - 1) * N:i * N] = plus
            if i < size - 1:
                A[at, (i + 1) * N:(i + 2) * N] = minus
        lam, X = scipy.linalg.eig(A, B)
        ok = (np.isfinite(lam) & (np.abs(lam.imag) <= 1e-7 * np.abs(lam)) & (lam.real > 0)
              & (lam.real <= top**2 * (1 + 1e-9)))
        X = X[:, ok].reshape(size, N, -1)
        centre = X[H]
        share = np.sum(np.abs(centre) ** 2, axis=0) / np.sum(np.abs(X) ** 2, axis=(0, 1))
        keep = share > 0
        order = np.argsort(lam.real[ok][keep])
        return (np.sqrt(lam.real[ok][keep][order]), share[keep][order],
                centre[:, keep][:, order])

    H = HILL_START
    speeds, share, centre = solve(H)
    while True:
        more = solve(H + HILL_STEP)
        held = all(speeds.size and np.min(np.abs(speeds / w - 1)) <= DIRECT_TOL
                   for w, s in zip(more[0], more[1]) if s >= 1e-3)
        speeds, share, centre = more
        H += HILL_STEP
        if held or H >= HILL_MAX:
            break
    if not held:
        raise UnsettledError(f"the crossings of the line {m} n in the turning frame: "
                             f"Hill's equations did not settle in {H} harmonics", top, H)
    return speeds, share, whirl_index(model, centre), tuple(dominant_kinds(model, centre))
