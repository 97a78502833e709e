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
