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
"""

from __future__ import annotations

import math

BALL = 1.3e7
ROLLER = 1.0e9
ACROSS = {"ball": ((8, 0.46), (12, 0.64), (16, 0.73)),
          "roller": ((8, 0.49), (12, 0.66), (16, 0.74))}
DAMPING_TIME = 1.25e-5   # s: c = DAMPING_TIME k
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
