"""Closed-form and independent references for a free-free solid cylinder (SI units).

None of this uses shaftfem: the tests compare the 3D finite-element results
with these.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import expm
from scipy.optimize import brentq


def torsion_hz(n: int, length: float, E: float, nu: float, rho: float) -> float:
    """f_n = n c_t / (2 L), c_t = sqrt(G / rho): exact for a circular section in 3D."""
    G = E / (2 * (1 + nu))
    return n * math.sqrt(G / rho) / (2 * length)


def axial_love_hz(n: int, length: float, radius: float, E: float, nu: float, rho: float) -> float:
    """Rod frequency n c / 2L with Love's lateral-inertia correction.

    omega = c k / sqrt(1 + nu^2 k^2 r_p^2), r_p^2 = R^2 / 2 (polar radius of gyration).
    """
    k = n * math.pi / length
    c = math.sqrt(E / rho)
    return c * k / math.sqrt(1 + (nu * k) ** 2 * radius**2 / 2) / (2 * math.pi)


def timoshenko_free_free_hz(n_modes: int, length: float, radius: float, E: float, nu: float,
                            rho: float) -> list[float]:
    """First bending frequencies of a free-free Timoshenko beam (Cowper's shear factor).

    Transfer matrix of the state (w, w', psi, psi') over the length; free ends
    mean zero moment (psi' = 0) and zero shear (w' - psi = 0). Frequencies are the
    roots of the 2x2 determinant of the end conditions, bracketed by sign changes.
    """
    G = E / (2 * (1 + nu))
    A = math.pi * radius**2
    I = math.pi * radius**4 / 4
    kappa = 6 * (1 + nu) / (7 + 6 * nu)

    def det(omega: float) -> float:
        w2 = omega**2
        S = np.array([
            [0.0, 1.0, 0.0, 0.0],
            [-rho * A * w2 / (kappa * G * A), 0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0, 1.0],
            [0.0, -kappa * G * A / (E * I), (kappa * G * A - rho * I * w2) / (E * I), 0.0],
        ])
        T = expm(S * length)
        # states at x = 0 that satisfy the free-end conditions: psi' = 0, w' = psi
        B = np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 1.0], [0.0, 0.0]])
        C = np.array([[0.0, 1.0, -1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
        return float(np.linalg.det(C @ T @ B))

    # scan in omega from well above 0 (the rigid modes) upwards
    c = math.sqrt(E / rho)
    w_max = (n_modes + 2) ** 2 * 25 * c * radius / (2 * length**2)
    grid = np.linspace(1e-3 * w_max, w_max, 20000)
    vals = np.array([det(w) for w in grid])
    roots = []
    for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]):
        if np.sign(fa) != np.sign(fb):
            roots.append(brentq(det, a, b, xtol=1e-12, rtol=1e-14))
            if len(roots) == n_modes:
                break
    return [w / (2 * math.pi) for w in roots]


def timoshenko_ss_hz(n: int, span: float, radius: float, E: float, nu: float,
                     rho: float) -> float:
    """Bending mode n of a simply supported Timoshenko beam (closed form, Cowper's
    shear factor): the lower root of
    rho^2 I / (k G) w^4 - (rho A + rho I k_n^2 (1 + E / (k G))) w^2 + E I k_n^4 = 0."""
    G = E / (2 * (1 + nu))
    A, I = math.pi * radius**2, math.pi * radius**4 / 4
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    k = n * math.pi / span
    a = rho**2 * I / (kappa * G)
    b = -(rho * A + rho * I * k**2 * (1 + E / (kappa * G)))
    c = E * I * k**4
    return math.sqrt((-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)) / (2 * math.pi)


def timoshenko_beam_hz(n_modes: int, length: float, radius: float, E: float, nu: float,
                       rho: float, pins: tuple[float, ...], disk: tuple | None = None,
                       n_el: int = 1600) -> list[float]:
    """Bending frequencies of a 1D Timoshenko beam FE in one plane: linear elements
    with one-point shear (no locking), consistent mass with rotary inertia, pinned
    (w = 0) at the axial positions `pins`. `disk` = (z0, z1, mass, diametral inertia):
    a rigid part whose hub makes z0..z1 rigid (EI, kGA x 1e3), its mass and inertia at
    the hub's middle. Positions must fall on element ends (L / n_el)."""
    G = E / (2 * (1 + nu))
    A, I = math.pi * radius**2, math.pi * radius**4 / 4
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    h = length / n_el
    z = np.linspace(0.0, length, n_el + 1)
    n = 2 * (n_el + 1)                      # (w, psi) per node
    K = np.zeros((n, n))
    M = np.zeros((n, n))
    for e in range(n_el):
        stiff = 1.0
        if disk is not None and disk[0] - 1e-12 <= z[e] and z[e + 1] <= disk[1] + 1e-12:
            stiff = 1e3
        dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3]
        Kb = stiff * E * I / h * np.array([[0, 0, 0, 0], [0, 1, 0, -1], [0, 0, 0, 0],
                                           [0, -1, 0, 1]])
        B = np.array([-1 / h, -0.5, 1 / h, -0.5])
        Ks = stiff * kappa * G * A * h * np.outer(B, B)
        lin = h / 6 * np.array([[2, 1], [1, 2]])
        Me = np.zeros((4, 4))
        Me[np.ix_([0, 2], [0, 2])] = rho * A * lin
        Me[np.ix_([1, 3], [1, 3])] = rho * I * lin
        K[np.ix_(dofs, dofs)] += Kb + Ks
        M[np.ix_(dofs, dofs)] += Me
    if disk is not None:
        mid = int(round((disk[0] + disk[1]) / 2 / h))
        M[2 * mid, 2 * mid] += disk[2]
        M[2 * mid + 1, 2 * mid + 1] += disk[3]
    held = [2 * int(round(p / h)) for p in pins]
    keep = np.setdiff1d(np.arange(n), held)
    from scipy.linalg import eigh

    lam = eigh(K[np.ix_(keep, keep)], M[np.ix_(keep, keep)], eigvals_only=True,
               subset_by_index=[0, n_modes - 1])
    return list(np.sqrt(lam) / (2 * math.pi))


def timoshenko_rotor_hz(n_modes: int, length: float, radius: float, E: float, nu: float,
                        rho: float, bearings: list[tuple[float, float]],
                        part: tuple | None = None, n_el: int = 1100) -> list[float]:
    """Bending frequencies of a 1D Timoshenko beam FE in one plane (linear elements,
    one-point shear, consistent mass with rotary inertia; Hutchinson's shear coefficient
    for a circular section) on bearings (z, k): a spring k (N/m) on w at z, math.inf
    for a pin. `part` = (z0, z1, mass, diametral inertia, joint): joint "rigid" makes
    z0..z1 a rigid segment (EI, kGA x 1e4) with the mass and inertia at its middle;
    "distributing" puts them on the hub's mean w and mean psi over z0..z1 (trapezoid
    weights) and stiffens nothing. Positions must fall on element ends (L / n_el)."""
    from scipy.linalg import eigh

    G = E / (2 * (1 + nu))
    A, I = math.pi * radius**2, math.pi * radius**4 / 4
    kappa = 6 * (1 + nu) ** 2 / (7 + 12 * nu + 4 * nu**2)
    h = length / n_el
    z = np.linspace(0.0, length, n_el + 1)
    n = 2 * (n_el + 1)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    rigid = part is not None and part[4] == "rigid"
    for e in range(n_el):
        hub = rigid and part[0] - 1e-12 <= z[e] and z[e + 1] <= part[1] + 1e-12
        stiff = 1e4 if hub else 1.0
        dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3]
        B = np.array([-1 / h, -0.5, 1 / h, -0.5])
        K[np.ix_(dofs, dofs)] += stiff * (
            E * I / h * np.array([[0, 0, 0, 0], [0, 1, 0, -1], [0, 0, 0, 0], [0, -1, 0, 1]])
            + kappa * G * A * h * np.outer(B, B))
        lin = h / 6 * np.array([[2, 1], [1, 2]])
        M[np.ix_(dofs[::2], dofs[::2])] += rho * A * lin
        M[np.ix_(dofs[1::2], dofs[1::2])] += rho * I * lin
    if part is not None:
        i0, i1 = int(round(part[0] / h)), int(round(part[1] / h))
        w = np.zeros(i1 - i0 + 1)
        if rigid:
            w[(i1 - i0) // 2] = 1.0
        else:
            w[:] = 1.0
            w[0] = w[-1] = 0.5
            w /= w.sum()
        for comp, mass in ((0, part[2]), (1, part[3])):
            a = np.zeros(n)
            a[2 * np.arange(i0, i1 + 1) + comp] = w
            M += mass * np.outer(a, a)
    pinned = []
    for zb, k in bearings:
        i = 2 * int(round(zb / h))
        if math.isinf(k):
            pinned.append(i)
        else:
            K[i, i] += k
    keep = np.setdiff1d(np.arange(n), pinned)
    lam = eigh(K[np.ix_(keep, keep)], M[np.ix_(keep, keep)], eigvals_only=True,
               subset_by_index=[0, n_modes - 1])
    return list(np.sqrt(lam) / (2 * math.pi))


def hollow_shear_factor(nu: float, m: float) -> float:
    """Cowper's shear coefficient of a circular tube, m = inner / outer radius (a solid
    bar at m = 0: 6 (1 + nu) / (7 + 6 nu))."""
    a = (1 + m * m) ** 2
    return 6 * (1 + nu) * a / ((7 + 6 * nu) * a + (20 + 12 * nu) * m * m)


def profile_elements(segments: list[tuple[float, float, float, float]], n_el: int
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Element ends z (n_el + 1,) and each element's outer and inner radius at its middle,
    for segments (length, outer radius at start, at end, inner radius), m; element ends
    fall on the segments' ends."""
    total = sum(s[0] for s in segments)
    z, ro, ri = [0.0], [], []
    z0 = 0.0
    for length, r0, r1, rin in segments:
        k = max(2, round(n_el * length / total))
        t = (np.arange(k) + 0.5) / k
        z += list(z0 + length * (np.arange(1, k + 1) / k))
        ro += list(r0 + (r1 - r0) * t)
        ri += [rin] * k
        z0 += length
    return np.array(z), np.array(ro), np.array(ri)


def timoshenko_profile_hz(n_modes: int, segments: list[tuple[float, float, float, float]],
                          E: float, nu: float, rho: float, pins: tuple[float, ...] = (),
                          n_el: int = 1200) -> list[float]:
    """The lowest elastic bending frequencies of a stepped, conical or hollow shaft as a 1D
    Timoshenko beam in one plane (linear elements, one-point shear, consistent mass with
    rotary inertia, Cowper's coefficient for a tube), each element's section that at its
    middle: free-free (its two rigid modes left out) or pinned (w = 0) at `pins` (m)."""
    from scipy.linalg import eigh

    G = E / (2 * (1 + nu))
    z, ro, ri = profile_elements(segments, n_el)
    n = 2 * len(z)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    for e in range(len(z) - 1):
        h = z[e + 1] - z[e]
        A = math.pi * (ro[e] ** 2 - ri[e] ** 2)
        I = math.pi * (ro[e] ** 4 - ri[e] ** 4) / 4
        kappa = hollow_shear_factor(nu, ri[e] / ro[e])
        dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3]
        B = np.array([-1 / h, -0.5, 1 / h, -0.5])
        K[np.ix_(dofs, dofs)] += (E * I / h * np.array([[0, 0, 0, 0], [0, 1, 0, -1],
                                                        [0, 0, 0, 0], [0, -1, 0, 1]])
                                  + kappa * G * A * h * np.outer(B, B))
        lin = h / 6 * np.array([[2, 1], [1, 2]])
        M[np.ix_(dofs[::2], dofs[::2])] += rho * A * lin
        M[np.ix_(dofs[1::2], dofs[1::2])] += rho * I * lin
    held = [2 * int(np.argmin(np.abs(z - p))) for p in pins]
    keep = np.setdiff1d(np.arange(n), held)
    lam = eigh(K[np.ix_(keep, keep)], M[np.ix_(keep, keep)], eigvals_only=True,
               subset_by_index=[0, n_modes + 1])
    f = np.sqrt(np.abs(lam)) / (2 * math.pi)
    return list((f[2:] if not pins else f)[:n_modes])


def rod_profile_hz(n_modes: int, segments: list[tuple[float, float, float, float]],
                   modulus: float, rho: float, polar: bool, n_el: int = 1200) -> list[float]:
    """The lowest free-free frequencies of a stepped rod, 1D, linear elements: torsion
    (`polar`: stiffness G J, inertia rho J; exact in 3D for a uniform circular section)
    or axial (E A, rho A; no lateral inertia). `modulus` is G or E."""
    from scipy.linalg import eigh

    z, ro, ri = profile_elements(segments, n_el)
    n = len(z)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    for e in range(n - 1):
        h = z[e + 1] - z[e]
        a = (math.pi * (ro[e] ** 4 - ri[e] ** 4) / 2 if polar
             else math.pi * (ro[e] ** 2 - ri[e] ** 2))
        K[e:e + 2, e:e + 2] += modulus * a / h * np.array([[1, -1], [-1, 1]])
        M[e:e + 2, e:e + 2] += rho * a * h / 6 * np.array([[2, 1], [1, 2]])
    lam = eigh(K, M, eigvals_only=True, subset_by_index=[1, n_modes])
    return list(np.sqrt(lam) / (2 * math.pi))
