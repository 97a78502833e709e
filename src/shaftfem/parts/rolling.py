"""A rolling bearing's radial stiffness from its elements and load (Hertz contact).

A ball's contact deflects as its load to the power 2/3 (Hertz: point contact), a
roller's nearly linearly (line contact). Summed over the loaded elements of a bearing
under a radial load F, Gargiulo's fits of these (1980, as Friswell et al. 2010,
section 5.6 give them in SI) are, along the load, for n balls of diameter d or
n rollers of effective length l at contact angle alpha:

    k_ball   = 1.3e7 n^(2/3) d^(1/3) F^(1/3) cos(alpha)^(5/3)     N/m  (d in m, F in N)
    k_roller = 1.0e9 n^0.9   l^0.8   F^0.1   cos(alpha)^1.9

Across the load fewer elements carry it: the stiffness there is a share of that, 0.46,
0.64 and 0.73 for 8, 12 and 16 balls (0.49, 0.66, 0.74 for rollers), between them
on the parabola through these three points. Damping is slight in rolling bearings:
1.25e-5 s times the stiffness, the middle of the usual 0.25e-5 to 2.5e-5 s.

An angular-contact ball bearing under an axial preload has every ball loaded. There
the load is shared ball by ball (`preloaded`): each ball's two contacts deflect as
Palmgren's law for steel balls on steel races, delta = C_P Q^(2/3) d^(-1/3) with
C_P = 4.36e-8 (m, N), the ball at angle psi_j deflecting by
delta_a sin(alpha) + delta_r cos(alpha) cos(psi_j), and the stiffness is the sum of
the balls' 3 Q_j / (2 delta_j) projected on x and y, with the rings held axially
where the preload puts them (a position preload: a spindle's pair of bearings).
Gargiulo's fit above is this same bearing under radial load alone, its load shared
by Stribeck's 4.37 (within 1 % of it solved ball by ball: tests/test_rolling_bearing.py).
"""

from __future__ import annotations

import math

from shaftfem.scene.model import BearingCoefficients, RollingBearing

BALL = 1.3e7
ROLLER = 1.0e9
ACROSS = {"ball": ((8, 0.46), (12, 0.64), (16, 0.73)),
          "roller": ((8, 0.49), (12, 0.66), (16, 0.74))}
DAMPING_TIME = 1.25e-5   # s: c = DAMPING_TIME k
PALMGREN = 4.36e-8       # m N^(-2/3) m^(1/3): a steel ball's two contacts
# the element counts the across-load share is known for (the parabola's reach)
ELEMENTS = (6, 24)


def across(kind: str, n: int) -> float:
    """The stiffness across the load over that along it, for n elements."""
    (x0, y0), (x1, y1), (x2, y2) = ACROSS[kind]
    return (y0 * (n - x1) * (n - x2) / ((x0 - x1) * (x0 - x2))
            + y1 * (n - x0) * (n - x2) / ((x1 - x0) * (x1 - x2))
            + y2 * (n - x0) * (n - x1) / ((x2 - x0) * (x2 - x1)))


def stiffness(kind: str, n: int, size: float, load: float, angle: float = 0.0
              ) -> tuple[float, float]:
    """(along the load, across it), N/m, for n balls of diameter `size` (m) or n rollers
    of effective length `size` (m), radial load `load` (N), contact angle `angle` (rad)."""
    if kind == "ball":
        k = BALL * n ** (2 / 3) * size ** (1 / 3) * load ** (1 / 3) * math.cos(angle) ** (5 / 3)
    else:
        k = ROLLER * n**0.9 * size**0.8 * load**0.1 * math.cos(angle) ** 1.9
    return k, across(kind, n) * k


def ball_loads(n: int, d: float, angle: float, axial: float, radial: float
               ) -> tuple[float, float, list[float], list[float]]:
    """A ball bearing's rings displaced (delta_a, delta_r, m) so that its n balls of
    diameter d (m) at contact angle `angle` (rad) carry the axial and radial loads (N),
    each ball's normal load Q_j (N) and deflection delta_j (m), ball j at 2 pi j / n
    from the radial load."""
    psi = [2 * math.pi * j / n for j in range(n)]
    sa, ca = math.sin(angle), math.cos(angle)
    c = PALMGREN * d ** (-1 / 3)

    def loads(da: float, dr: float) -> tuple[list[float], list[float]]:
        dn = [max(da * sa + dr * ca * math.cos(p), 0.0) for p in psi]
        return [(x / c) ** 1.5 for x in dn], dn

    def radial_for(da: float) -> float:
        """delta_r carrying the radial load at this delta_a (bisection: monotone)."""
        lo, hi = -da * sa / ca if ca > 0 else 0.0, 1e-2
        lo = max(lo, -1e-2)
        for _ in range(80):   # the bracket to 1e-26 m
            mid = 0.5 * (lo + hi)
            q, _ = loads(da, mid)
            if sum(x * ca * math.cos(p) for x, p in zip(q, psi)) < radial:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    lo, hi = 0.0, 1e-2
    for _ in range(80):   # delta_a carrying the axial load (monotone in it)
        mid = 0.5 * (lo + hi)
        q, _ = loads(mid, radial_for(mid))
        if sum(q) * sa < axial:
            lo = mid
        else:
            hi = mid
    da = 0.5 * (lo + hi)
    dr = radial_for(da)
    q, dn = loads(da, dr)
    return da, dr, q, dn


def preloaded(n: int, d: float, angle: float, preload: float, load: float = 0.0
              ) -> tuple[float, float]:
    """(along the radial load, across it), N/m, of an angular-contact ball bearing of n
    balls of diameter d (m) at contact angle `angle` (rad, > 0) under an axial preload
    and a radial load (N): the balls' contact stiffnesses 3 Q / (2 delta) summed."""
    _, _, q, dn = ball_loads(n, d, angle, preload, load)
    ca = math.cos(angle)
    k = [1.5 * x / y if y > 0 else 0.0 for x, y in zip(q, dn)]
    psi = [2 * math.pi * j / n for j in range(n)]
    along = sum(kj * (ca * math.cos(p)) ** 2 for kj, p in zip(k, psi))
    across = sum(kj * (ca * math.sin(p)) ** 2 for kj, p in zip(k, psi))
    return along, across


def coefficients(b: RollingBearing) -> BearingCoefficients:
    """The bearing's constant coefficients: its stiffness along its load and across it
    (`stiffness`, or `preloaded` for an angular-contact bearing under an axial preload)
    turned onto the load's direction, and damping DAMPING_TIME times that."""
    if b.preload is not None:
        along, across_ = preloaded(b.elements, b.size, b.contact_angle, b.preload, b.load)
    else:
        along, across_ = stiffness(b.kind, b.elements, b.size, b.load, b.contact_angle)
    c, s = math.cos(b.load_angle), math.sin(b.load_angle)
    # along the load's direction (c, s), across it (-s, c)
    kxx, kyy = along * c * c + across_ * s * s, along * s * s + across_ * c * c
    kxy = (along - across_) * c * s
    d = DAMPING_TIME
    return BearingCoefficients(speeds=(), kxx=(kxx,), kxy=(kxy,), kyx=(kxy,), kyy=(kyy,),
                               cxx=(d * kxx,), cxy=(d * kxy,), cyx=(d * kxy,), cyy=(d * kyy,))
