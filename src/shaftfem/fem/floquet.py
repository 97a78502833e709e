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
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SolverError
from shaftfem.fem.rotor import Roots, roots, unbalance_response

if TYPE_CHECKING:
    from shaftfem.fem.rotor import RotorModel

# Hill's harmonics: from this many, raised by HILL_STEP while the exponents kept move by
# more than HILL_TOL (relative to the largest frequency among them), up to HILL_MAX.
HILL_START = 2
HILL_STEP = 2
HILL_TOL = 1e-7
HILL_MAX = 12
# ... watching this share of the exponents, the lowest, those damped at most this
# ratio (-Re lam / |lam|).
WATCHED = 2 / 3
OVERDAMPED = 0.5
# The monodromy's steps: at least this many a period, and so many that the fastest
# mode turns by at most a quarter turn in a step.
MONODROMY_STEPS = 256


# the harmonics the last converged solve of each model took (a model's neighbouring
# speeds need about as many): where the next solve starts
_LAST: dict[int, int] = {}
# the roots of the last speeds solved (a Campbell run asks the same speed again: its
# curves, its rows, its bands)
_ROOTS: dict[tuple, Roots] = {}


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


def hill(model: RotorModel, omega: float, harmonics: int) -> Hill:
    """The Floquet exponents at the spin omega (rad/s) by Hill's method with harmonics
    -H..H: x = exp(lam t) sum_k x_k exp(i 2 k Omega t) gives
    (lam + i 2 k Omega) x_k = A x_k + A_+ x_{k-1} + A_- x_{k+1}, A_+- = (A_c -+ i A_s) / 2."""
    f = first_order(model, omega)
    m = f.A.shape[0]
    H = harmonics
    size = 2 * H + 1
    Ap, Am = 0.5 * (f.Ac - 1j * f.As), 0.5 * (f.Ac + 1j * f.As)
    big = np.zeros((size * m, size * m), dtype=complex)
    for i, k in enumerate(range(-H, H + 1)):
        rows = slice(i * m, (i + 1) * m)
        big[rows, rows] = f.A - 2j * k * omega * np.eye(m)
        if i > 0:
            big[rows, (i - 1) * m:i * m] = Ap
        if i < size - 1:
            big[rows, (i + 1) * m:(i + 2) * m] = Am
    lam, V = np.linalg.eig(big)
    V = V.reshape(size, m, -1)
    weight = np.sum(np.abs(V) ** 2, axis=1)                  # (size, all)
    norm = np.sqrt(weight.sum(axis=0))
    weight = weight / weight.sum(axis=0)
    ks = np.arange(-H, H + 1)
    centroid = ks @ weight
    keep = one_copy(lam, centroid, omega, m)
    residual = (np.linalg.norm(Ap @ V[-1][:, keep], axis=0)
                + np.linalg.norm(Am @ V[0][:, keep], axis=0)) / norm[keep]
    n = m // 2
    return Hill(lam=lam[keep], y=V[H, :n, keep].T, centroid=centroid[keep], harmonics=H,
                residual=residual)


def one_copy(lam: np.ndarray, centroid: np.ndarray, omega: float, m: int) -> np.ndarray:
    """Which of Hill's eigenvalues to keep, m of them: of each exponent's copies
    (lam + i 2 Omega k, their harmonics' centroids shifted by k) the most central one.
    A copy is recognised by its exponent modulo i 2 Omega and its centroid a whole
    number away from one kept."""
    scale = max(float(np.abs(lam).max()), omega, 1.0)
    kept: list[int] = []
    for j in np.argsort(np.abs(centroid), kind="stable"):
        copy = False
        for i in kept:
            d = lam[j] - lam[i]
            turns = d.imag / (2 * omega)
            shift = centroid[j] - centroid[i]
            if (abs(d.real) <= 1e-6 * scale and abs(turns - round(turns)) <= 1e-6 * scale / omega
                    and round(turns) != 0 and abs(shift - round(shift)) < 0.25
                    and round(shift) != 0):
                copy = True
                break
        if not copy:
            kept.append(int(j))
        if len(kept) == m:
            break
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


def converged_hill(model: RotorModel, omega: float) -> Hill:
    """Hill's exponents with H raised until the lower WATCHED of them (what the basis
    check vouches for; the basis' top converges last), but for the forms damped beyond
    OVERDAMPED, have truncation residuals of at most HILL_TOL of the largest among
    them: their forms hold next to nothing in the outermost harmonics. A SolverError if
    HILL_MAX harmonics do not settle them."""
    key = id(model)
    H = max(HILL_START, _LAST.get(key, HILL_START) - HILL_STEP)
    while True:
        h = hill(model, omega, H)
        low = np.sort(np.abs(h.lam))[int(WATCHED * (h.lam.size - 1))]
        watched = (np.abs(h.lam) <= low * (1 + 1e-9)) & not_overdamped(h.lam)
        worst = float(h.residual[watched].max()) / max(float(low), omega, 1.0)
        if worst <= HILL_TOL:
            _LAST[key] = H
            return h
        if H >= HILL_MAX:
            raise SolverError(f"Hill's method at {omega * 30 / math.pi:,.0f} r/min: the Floquet "
                              f"forms still reach the outermost of {H} harmonics (residual "
                              f"{worst:.2g})")
        H += HILL_STEP


def monodromy(model: RotorModel, omega: float, steps: int | None = None) -> np.ndarray:
    """The monodromy matrix (2 N, 2 N): the first-order state after one period
    T = pi / omega from each unit state, by fourth-order Magnus steps (two Gauss
    points; each step's exponential exact for a constant system)."""
    import scipy.linalg

    f = first_order(model, omega)
    T = math.pi / omega
    fastest = math.sqrt(max(float(np.max(model.omega2)), 1.0))
    if steps is None:
        steps = max(MONODROMY_STEPS, math.ceil(4 * fastest * T / (0.5 * math.pi)))
    h = T / steps
    c1, c2 = 0.5 - math.sqrt(3) / 6, 0.5 + math.sqrt(3) / 6
    Phi = np.eye(f.A.shape[0])
    for j in range(steps):
        A1, A2 = f.at((j + c1) * h), f.at((j + c2) * h)
        Om = 0.5 * h * (A1 + A2) + (math.sqrt(3) / 12) * h * h * (A2 @ A1 - A1 @ A2)
        Phi = scipy.linalg.expm(Om) @ Phi
    return Phi


def multipliers(model: RotorModel, omega: float, steps: int | None = None) -> np.ndarray:
    """The Floquet multipliers mu = exp(lam T) from the monodromy matrix."""
    return np.linalg.eigvals(monodromy(model, omega, steps))


def routes_apart(model: RotorModel, omega: float) -> float:
    """How far Hill's exponents lie from the monodromy's (both at the spin omega): the
    largest distance of a pair, each exponent's growth rate ln |mu| / T and its
    frequency modulo 2 omega, over the largest |lam| (a fraction)."""
    lam = converged_hill(model, omega).lam
    T = math.pi / omega
    mono = np.log(multipliers(model, omega).astype(complex)) / T
    scale = max(float(np.abs(lam).max()), omega, 1.0)
    return matched_change(lam, mono, omega) / scale


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
        except SolverError:
            return False
        return True

    positive = [float(w) for w in speeds if w > 0]
    floor = positive[-1]
    for w in positive[::-1]:
        if not settles(w):
            return floor
        floor = w
    while floor / 2 >= lowest and settles(floor / 2):
        floor /= 2
    return floor


def periodic_unbalance(model: RotorModel, omega: float,
                       forces: list[tuple[np.ndarray, complex]]) -> np.ndarray:
    """The steady response to unbalances (each its plane's motion beta (2, N) and
    U = m e exp(i phase), kg m) of a periodic rotor at the spin omega, by harmonic
    balance in the turning frame, where the unbalance's force stands still:
    q = sum_k q_k exp(i 2 k Omega t), and for each harmonic m
    (K - (2 m Omega)^2 M + i 2 m Omega D) q_m + (K_+ + i 2 (m-1) Omega D_+) q_{m-1}
    + (K_- + i 2 (m+1) Omega D_-) q_{m+1} = F delta_m0. The harmonics (N, 2 H + 1),
    H raised until the 1x response (k = 0 and -1) moves by at most HILL_TOL."""
    D, K = model.matrices(omega)
    Dc, Ds, Kc, Ks = model.periodic_parts(omega)
    Mm = model.mass(omega)
    Kp, Km, Dp, Dm = (0.5 * (Kc - 1j * Ks), 0.5 * (Kc + 1j * Ks), 0.5 * (Dc - 1j * Ds),
                      0.5 * (Dc + 1j * Ds))
    n = model.size
    F = np.zeros(n)
    for beta, U in forces:
        F += omega**2 * (U.real * beta[0] + U.imag * beta[1])

    def solve(H: int) -> np.ndarray:
        size = 2 * H + 1
        big = np.zeros((size * n, size * n), dtype=complex)
        for i, m in enumerate(range(-H, H + 1)):
            r = slice(i * n, (i + 1) * n)
            w = 2 * m * omega
            big[r, r] = K - w * w * Mm + 1j * w * D
            if i > 0:
                big[r, (i - 1) * n:i * n] = Kp + 2j * (m - 1) * omega * Dp
            if i < size - 1:
                big[r, (i + 1) * n:(i + 2) * n] = Km + 2j * (m + 1) * omega * Dm
        rhs = np.zeros(size * n, dtype=complex)
        rhs[H * n:(H + 1) * n] = F
        return np.linalg.solve(big, rhs).reshape(size, n).T

    H = HILL_START
    prev = solve(H)
    while True:
        cur = solve(H + HILL_STEP)
        c0, p0 = cur[:, H + HILL_STEP - 1:H + HILL_STEP + 1], prev[:, H - 1:H + 1]
        if np.abs(c0 - p0).max() <= HILL_TOL * max(float(np.abs(c0).max()), 1e-300):
            return cur
        H += HILL_STEP
        if H > HILL_MAX:
            raise SolverError(f"the unbalance response at {omega * 30 / math.pi:,.0f} r/min: "
                              f"harmonic balance does not settle with {H} harmonics")
        prev = cur


def floquet_roots(model: RotorModel, omega: float) -> Roots:
    """The Floquet exponents at the spin omega as fem.rotor.roots gives a constant
    rotor's roots: the oscillating ones (Im lam > 0, the dominant harmonic's
    frequency), lowest first, with their forms' k = 0 coefficients; the fastest growth
    of a non-oscillating one kept (a multiplier real and above 1)."""
    key = (id(model), model.size, float(model.omega2.sum()), float(omega))
    if key in _ROOTS:
        return _ROOTS[key]
    h = converged_hill(model, omega)
    scale = math.sqrt(max(float(np.max(np.abs(model.omega2))), 1.0))
    keep = h.lam.imag > 1e-9 * scale
    still = np.abs(h.lam.imag) <= 1e-9 * scale
    divergence = float(max(0.0, h.lam.real[still].max())) if still.any() else 0.0
    lam, y = h.lam[keep], h.y[:, keep]
    order = np.argsort(lam.imag)
    out = Roots(lam=lam[order], y=y[:, order],
                divergence=divergence if divergence > 1e-9 * scale else 0.0)
    if len(_ROOTS) >= 512:
        _ROOTS.pop(next(iter(_ROOTS)))
    _ROOTS[key] = out
    return out


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
