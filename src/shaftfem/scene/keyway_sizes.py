"""Keyway sizes for a shaft diameter: DIN 6885-1 (parallel keys, high form), the same
widths as ISO/R 773.

Each row: shaft diameters above `over` up to `to` (mm) take a key b x h (mm) and a
keyway depth t1 (mm) in the shaft. Source: DIN 6885-1:1968-08, Table 1 (the sizes
repeated in ISO/R 773:1969 and in the usual handbooks, e.g. Roloff/Matek, Table 12-2).
"""

from __future__ import annotations

# (over, to, b, h, t1), mm
DIN_6885_1: tuple[tuple[float, float, float, float, float], ...] = (
    (6, 8, 2, 2, 1.2),
    (8, 10, 3, 3, 1.8),
    (10, 12, 4, 4, 2.5),
    (12, 17, 5, 5, 3.0),
    (17, 22, 6, 6, 3.5),
    (22, 30, 8, 7, 4.0),
    (30, 38, 10, 8, 5.0),
    (38, 44, 12, 8, 5.0),
    (44, 50, 14, 9, 5.5),
    (50, 58, 16, 10, 6.0),
    (58, 65, 18, 11, 7.0),
    (65, 75, 20, 12, 7.5),
    (75, 85, 22, 14, 9.0),
    (85, 95, 25, 14, 9.0),
    (95, 110, 28, 16, 10.0),
    (110, 130, 32, 18, 11.0),
    (130, 150, 36, 20, 12.0),
    (150, 170, 40, 22, 13.0),
    (170, 200, 45, 25, 15.0),
    (200, 230, 50, 28, 17.0),
)


def keyway_size(diameter_mm: float) -> tuple[float, float] | None:
    """(width b, depth t1) in mm of the keyway DIN 6885-1 gives a shaft of this
    diameter, or None outside the table (6 to 230 mm)."""
    for over, to, b, _, t1 in DIN_6885_1:
        if over < diameter_mm <= to:
            return float(b), float(t1)
    return None
