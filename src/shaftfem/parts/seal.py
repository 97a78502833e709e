"""A plain annular seal (a pump's wear ring or balance drum, a liquid's interstage
seal): Black and Jenssen's short-seal model with Hirs' turbulent friction as Childs
(1983) writes it, the fluid entering at half the shaft's surface speed.

The leakage's mean axial velocity V solves

    dP = (1 + xi + 2 sigma) rho V^2 / 2,     sigma = lambda L / C,

with xi the inlet loss and lambda Hirs' friction factor on the axial and
circumferential Reynolds numbers Ra = 2 rho V C / mu, Rc = rho R Omega C / mu:

    lambda = n0 Ra^m0 (1 + (Rc / 2 Ra)^2)^((1 + m0) / 2).

With T = L / V the fluid's transit time, B = 1 + (1 + m0) / (1 + (Rc / 2 Ra)^2),
E = (1 + xi) / (2 (1 + xi + 2 sigma)) and mu3 = pi R dP / lambda:

    mu0 = 2 sigma^2 E (1 - m0) / (1 + xi + B sigma)
    mu1 = 2 sigma^2 (E / sigma + B / 2 (1/6 + E)) / (1 + xi + B sigma)
    mu2 = sigma (1/6 + E) / (1 + xi + B sigma)

    K = mu3 (mu0 - mu2 T^2 Omega^2 / 4)      k = mu3 mu1 T Omega / 2
    C = mu3 mu1 T                              c = mu3 mu2 T^2 Omega
    M = mu3 mu2 T^2

the force on the shaft being -[[K, k], [-k, K]] q - [[C, c], [-c, C]] q' - M q''.
At standstill K is Lomakin's stiffness: where the gap closes, the friction loss grows,
the inlet's loss falls, and the mean pressure there rises. A pump's pressure drop
goes as its head, with the square of the speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaftfem.scene.model import INLET_LOSS, AnnularSeal, BearingCoefficients

# Hirs' friction for smooth surfaces (Yamada's pipe data, as Childs uses them)
N0, M0 = 0.066, -0.25
__all__ = ["INLET_LOSS", "AnnularSeal", "coefficients", "speed_table", "state"]


@dataclass(frozen=True)
class SealState:
    """The seal at one speed: the leakage's axial velocity (m/s) and flow (m^3/s), the
    friction loss sigma, the Reynolds numbers, and its five coefficients: K, k (N/m),
    C, c (N s/m) and M (kg)."""

    velocity: float
    leakage: float
    sigma: float
    axial_reynolds: float
    circumferential_reynolds: float
    K: float
    k: float
    C: float
    c: float
    M: float


def pressure_drop(seal: AnnularSeal, omega: float) -> float:
    """The pressure drop (Pa) at the spin omega (rad/s): as the pump's head, ~ Omega^2."""
    return seal.pressure_drop * (omega / seal.rated) ** 2


def friction(seal: AnnularSeal, velocity: float, omega: float) -> tuple[float, float, float]:
    """Hirs' lambda and the Reynolds numbers Ra, Rc at the axial velocity (m/s) and spin."""
    nu = seal.viscosity / seal.density
    ra = 2 * velocity * seal.clearance / nu
    rc = 0.5 * seal.diameter * omega * seal.clearance / nu
    return N0 * ra**M0 * (1 + (rc / (2 * ra)) ** 2) ** ((1 + M0) / 2), ra, rc


def state(seal: AnnularSeal, omega: float) -> SealState:
    """The seal's leakage and coefficients at the spin omega > 0 (rad/s)."""
    dp = pressure_drop(seal, omega)
    xi, rho = seal.inlet_loss, seal.density
    # dP = (1 + xi + 2 sigma(V)) rho V^2 / 2, solved for V by fixed point (sigma varies
    # as V^m0: the iteration contracts by |m0| / 2 or faster)
    v = math.sqrt(2 * dp / ((1 + xi) * rho))
    for _ in range(200):
        lam, ra, rc = friction(seal, v, omega)
        sigma = lam * seal.length / seal.clearance
        new = math.sqrt(2 * dp / ((1 + xi + 2 * sigma) * rho))
        if abs(new - v) <= 1e-14 * v:
            break
        v = new
    v = new
    lam, ra, rc = friction(seal, v, omega)
    sigma = lam * seal.length / seal.clearance
    B = 1 + (1 + M0) / (1 + (rc / (2 * ra)) ** 2)
    E = (1 + xi) / (2 * (1 + xi + 2 * sigma))
    den = 1 + xi + B * sigma
    mu0 = 2 * sigma**2 * E * (1 - M0) / den
    mu1 = 2 * sigma**2 * (E / sigma + B / 2 * (1 / 6 + E)) / den
    mu2 = sigma * (1 / 6 + E) / den
    mu3 = math.pi * seal.diameter / 2 * dp / lam
    T = seal.length / v
    return SealState(
        velocity=v, leakage=math.pi * seal.diameter * seal.clearance * v, sigma=sigma,
        axial_reynolds=ra, circumferential_reynolds=rc,
        K=mu3 * (mu0 - mu2 * T**2 * omega**2 / 4), k=mu3 * mu1 * T * omega / 2,
        C=mu3 * mu1 * T, c=mu3 * mu2 * T**2 * omega, M=mu3 * mu2 * T**2)


def speed_table(seal: AnnularSeal, top: float, points: int = 41) -> tuple[list[float],
                                                                           list[SealState]]:
    """The seal's states at `points` speeds from 1 % of `top` to `top` (rad/s), evenly in
    speed (its coefficients go as about Omega^1 to Omega^2; below 1 % they are taken as
    none)."""
    speeds = [top * (0.01 + 0.99 * i / (points - 1)) for i in range(points)]
    return speeds, [state(seal, w) for w in speeds]


def coefficients(s: AnnularSeal, top: float) -> BearingCoefficients:
    """The seal's coefficients against speed up to `top` (rad/s, the Campbell diagram's
    end): none at standstill, where the pump makes no pressure."""
    speeds, states = speed_table(s, top)

    def row(name: str, sign: float = 1.0) -> tuple[float, ...]:
        return (0.0, *(sign * getattr(x, name) for x in states))

    return BearingCoefficients(speeds=(0.0, *speeds), kxx=row("K"), kxy=row("k"),
                               kyx=row("k", -1.0), kyy=row("K"), cxx=row("C"), cxy=row("c"),
                               cyx=row("c", -1.0), cyy=row("C"), mxx=row("M"), myy=row("M"))
