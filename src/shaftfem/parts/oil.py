"""A lubricating oil's dynamic viscosity from its ISO VG grade and temperature.

ISO 3448 names a grade by its kinematic viscosity at 40 C (mm^2/s, the grade's
mid-point). Between temperatures the viscosity follows Walther's line (ASTM D341):

    log10(log10(nu + 0.7)) = A - B log10(T),   T in K,

through the grade at 40 C and, at 100 C, the viscosity of a paraffinic mineral oil of
viscosity index near 100 (VI100_AT_100C: typical datasheet values). The density falls
by DENSITY_FALL per kelvin from DENSITY_15C. An oil's own datasheet value, given as
viscosity_mpa_s, is better than any of this.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

# ISO VG grade -> kinematic viscosity at 100 C (mm^2/s) of a VI-100 mineral oil
VI100_AT_100C = {10: 2.6, 15: 3.3, 22: 4.3, 32: 5.4, 46: 6.8, 68: 8.7, 100: 11.4, 150: 14.7,
                 220: 18.7, 320: 23.7, 460: 30.0, 680: 38.0}
DENSITY_15C = 870.0       # kg/m^3
DENSITY_FALL = 0.00065    # per K, of the density at 15 C


def kinematic(grade: int, temperature_c: float | np.ndarray) -> Any:
    """The kinematic viscosity (m^2/s) of ISO VG `grade` at `temperature_c` (C; a float
    or an array of them, as is the result)."""
    def walther(nu: float) -> float:
        return math.log10(math.log10(nu + 0.7))

    t1, t2 = math.log10(313.15), math.log10(373.15)
    w1, w2 = walther(float(grade)), walther(VI100_AT_100C[grade])
    B = (w1 - w2) / (t2 - t1)
    w = w1 - B * (np.log10(np.add(temperature_c, 273.15)) - t1)
    nu = (10 ** (10 ** w) - 0.7) * 1e-6
    return float(nu) if np.ndim(nu) == 0 else nu


def density(temperature_c: float | np.ndarray) -> Any:
    """The oil's density (kg/m^3) at `temperature_c` (C)."""
    return DENSITY_15C * (1 - DENSITY_FALL * (temperature_c - 15.0))


def dynamic(grade: int, temperature_c: float | np.ndarray) -> Any:
    """The dynamic viscosity (Pa s) of ISO VG `grade` at `temperature_c` (C; a float or
    an array of them, as is the result)."""
    return kinematic(grade, temperature_c) * density(temperature_c)
