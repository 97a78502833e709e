"""Where an elastic stress has no limit: a re-entrant wedge's corner.

Near the edge of a wedge of material angle beta > pi the stress grows as r^(lambda - 1),
lambda the smallest root in (1/2, 1) of Williams' symmetric (opening) eigen-equation

    lambda sin(beta) + sin(lambda beta) = 0

(Williams, J. Appl. Mech. 19, 1952): 1/2 for a crack (beta = 2 pi), 0.5445 for a
right-angled re-entrant corner (beta = 3 pi / 2), towards 1 as the wedge flattens. A
finite-element stress there rises as the mesh is refined, by s^(1 - lambda) for elements
s times smaller, and never converges.
"""

from __future__ import annotations

import math


def wedge_exponent(beta: float) -> float:
    """Williams' lambda for a re-entrant wedge of material angle beta (rad, pi < beta <=
    2 pi): the stress near its edge grows as r^(lambda - 1)."""
    from scipy.optimize import brentq

    if not math.pi < beta <= 2 * math.pi:
        raise ValueError(f"a re-entrant wedge's angle lies in (pi, 2 pi], not {beta}")
    return float(brentq(lambda lam: lam * math.sin(beta) + math.sin(lam * beta),
                        0.5 - 1e-12, 1 - 1e-12))
