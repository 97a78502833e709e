"""The 2018 paper's own figures, kept apart from the general modules.

Fu, Zhang, Ji, Xia: the double-helix cam shaft of a substrate-block seedling
transplanter (Jiangsu Agricultural Sciences 2018, 46(6): 204-206). Used only
by `shaftfem paper`, which sets our results beside what the paper states;
never as an input.
"""

from __future__ import annotations

from dataclasses import dataclass

# Sizing results the paper states (mm), for comparison with equations (1)-(9).
SIZING_MM = {"P": 80.0, "d2": 29.88, "D": 32.0, "D0": 32.3, "L": 320.0, "B": 360.0}

# Table 2: ANSYS, 1 mm elements, free-free, rigid-body modes not listed (Hz).
TABLE2_HZ = (432.16, 433.60, 1158.30, 1166.40, 2149.90, 2195.20, 3500.60, 3594.30,
             3687.50, 5257.80)


@dataclass(frozen=True)
class SizingComparison:
    symbol: str
    ours_mm: float
    paper_mm: float

    @property
    def matches(self) -> bool:
        return abs(self.ours_mm - self.paper_mm) <= 0.005 * max(1.0, abs(self.paper_mm))

    @property
    def difference_percent(self) -> float:
        return 100 * (self.ours_mm / self.paper_mm - 1)


@dataclass(frozen=True)
class ModeComparison:
    mode: int
    paper_hz: float
    ours_hz: float
    kind: str
    paper_ratio: float   # f / f1 in the paper
    ours_ratio: float    # f / f1 here

    @property
    def difference_percent(self) -> float:
        return 100 * (self.ours_hz / self.paper_hz - 1)


def compare_sizing(sizing) -> list[SizingComparison]:
    """Our equations (1)-(9) against the paper's stated results (a sizing.SizingResult)."""
    return [SizingComparison(k, sizing[k], v) for k, v in SIZING_MM.items()]


def compare_modes(frequencies, kinds: list[str]) -> list[ModeComparison]:
    """Mode by mode: the paper's Table 2 beside our frequencies, with ratios to mode 1."""
    return [ModeComparison(mode=i + 1, paper_hz=p, ours_hz=float(f), kind=k,
                           paper_ratio=p / TABLE2_HZ[0], ours_ratio=float(f / frequencies[0]))
            for i, (p, f, k) in enumerate(zip(TABLE2_HZ, frequencies, kinds))]


def nearest_to(frequency: float) -> float:
    """The paper's Table 2 frequency nearest to `frequency` (Hz)."""
    return min(TABLE2_HZ, key=lambda p: abs(p - frequency))
