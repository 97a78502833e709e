"""Common shaft steels' static strengths, each row with its source and heat-treatment
state, and the technological size factor that carries them to another diameter.

Minimum values of the standards (a design uses the minimum): R_m and R_p0.2 (R_e) in
MPa at the test blank's diameter (mm) the standard states them for. The size factor is
the FKM guideline's (2012, section 3.2.1, quenched and tempered steels: a_d,m = 0.3,
a_d,p = 0.4, stated for d_eff,N = 16 mm); a precipitation-hardened stainless steel's
strengths do not fall with size in the standard's range (a_d = 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class ShaftSteel:
    """A steel's minimum R_m and R_p0.2 (MPa) at the test blank's diameter (mm), its
    size exponents a_d,m and a_d,p, FKM's material group, and where the numbers come
    from."""

    name: str
    tensile_strength_mpa: float
    yield_strength_mpa: float
    diameter_mm: float
    a_dm: float
    a_dp: float
    fkm_group: str
    source: str


STEELS = (
    ShaftSteel("40Cr", 980, 785, 25, 0.3, 0.4, "Steel",
               "GB/T 3077-2015, quenched and tempered, 25 mm blank"),
    ShaftSteel("41Cr4", 1000, 800, 16, 0.3, 0.4, "Steel",
               "EN ISO 683-2:2018, +QT, d <= 16 mm"),
    ShaftSteel("42CrMo4", 1100, 900, 16, 0.3, 0.4, "Steel",
               "EN ISO 683-2:2018, +QT, d <= 16 mm"),
    ShaftSteel("C45", 700, 490, 16, 0.3, 0.4, "Steel",
               "EN ISO 683-1:2018, +QT, d <= 16 mm"),
    ShaftSteel("34CrNiMo6", 1200, 1000, 16, 0.3, 0.4, "Steel",
               "EN ISO 683-2:2018, +QT, d <= 16 mm"),
    ShaftSteel("17-4PH", 1070, 1000, 16, 0.0, 0.0, "Stainless_Steel",
               "ASTM A564 / EN 10088-3 (1.4542), condition H1025 (P1070)"),
)


def shaft_steel(name: str) -> ShaftSteel | None:
    """The table's row for a [material] name (case and spaces aside), or None."""
    key = name.replace(" ", "").lower()
    return next((s for s in STEELS if s.name.lower() == key), None)


def size_factor(d_eff: float, d_blank: float, a_d: float) -> float:
    """FKM's technological size factor K_d from the blank's diameter to d_eff (both in
    mm): (1 - 0.7686 a_d log10(d_eff / 7.5 mm)) / (1 - 0.7686 a_d log10(d_blank /
    7.5 mm)), 1 where d_eff is not larger than the blank."""
    if d_eff <= d_blank or a_d == 0:
        return 1.0
    return ((1 - 0.7686 * a_d * math.log10(d_eff / 7.5))
            / (1 - 0.7686 * a_d * math.log10(d_blank / 7.5)))
