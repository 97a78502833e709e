"""Peterson's stress concentration factors for a shoulder fillet in a round shaft, by
Pilkey's curve fits of Peterson's charts (Pilkey & Pilkey, Peterson's Stress
Concentration Factors, 3rd ed., 2008, charts 3.4 tension, 3.10 bending, 3.12
torsion): the table a designer would look up, printed beside the K_t the solid gives.

    K_t = C1 + C2 x + C3 x^2 + C4 x^3,  x = 2 h / D,  C_i = a_i + b_i sqrt(h/r) + c_i h/r

with h = (D - d) / 2 the step's height and r the fillet's radius. K_t is the largest
principal stress (tension, bending) or the largest shear stress (torsion) over the
nominal stress of the smaller section d: 4 P / (pi d^2), 32 M / (pi d^3), 16 T / (pi d^3).
"""

from __future__ import annotations

import math

SOURCE = "Peterson's chart (Pilkey's fit)"

# (a, b, c) of C1..C4, by load and by the h / r range each row set holds for
_FITS: dict[str, tuple[tuple[float, float, tuple], ...]] = {
    "bending": (
        (0.1, 2.0, ((0.947, 1.206, -0.131), (0.022, -3.405, 0.915),
                    (0.869, 1.777, -0.555), (-0.810, 0.422, -0.260))),
        (2.0, 20.0, ((1.232, 0.832, -0.008), (-3.813, 0.968, -0.260),
                     (7.423, -4.868, 0.869), (-3.839, 3.070, -0.600)))),
    "tension": (
        (0.1, 2.0, ((0.926, 1.157, -0.099), (0.012, -3.036, 0.961),
                    (-0.302, 3.977, -1.744), (0.365, -2.098, 0.878))),
        (2.0, 20.0, ((1.200, 0.860, -0.022), (-1.805, -0.346, -0.038),
                     (2.198, -0.486, 0.165), (-0.593, -0.028, -0.106)))),
    "torsion": (
        (0.25, 4.0, ((0.905, 0.783, -0.075), (-0.437, -1.969, 0.553),
                     (1.557, 1.073, -0.578), (-1.061, 0.171, 0.086))),),
}


def shoulder_fillet(D: float, d: float, r: float, load: str) -> float | None:
    """Peterson's K_t of a shoulder fillet (D > d, fillet radius r, any one length unit)
    under `load` ("bending", "tension" or "torsion"); None outside the chart's range of
    h / r (the fit is not the chart there)."""
    h = 0.5 * (D - d)
    if r <= 0 or h <= 0:
        return None
    q = h / r
    fits = _FITS[load]
    for k, (lo, hi, rows) in enumerate(fits):
        # each row set from its lower end up to the next one's; the last to its end
        if lo <= q < hi or (k == len(fits) - 1 and lo <= q <= hi):
            c = [a + b * math.sqrt(q) + e * q for a, b, e in rows]
            x = 2 * h / D
            return c[0] + c[1] * x + c[2] * x**2 + c[3] * x**3
    return None
