"""The turning shaft's results as typed records: each complex mode at each speed in the
stationary frame (Whirl), the critical speeds, the onsets of instability, the modal
basis' check, the unbalance response (Bode curves and peaks), and the Campbell
diagram that holds them with the standstill run behind it. Made by workflows.campbell
and workflows.unbalance; read by the checks, the tables, the pictures and the files."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult

RPM = 2 * math.pi / 60           # rad/s per r/min
# A whirl index beyond these is forward (backward); between, the orbit is mixed.
FORWARD = 0.1
# Kinds of mode that whirl: bending; torsion and axial modes do not orbit.
WHIRLING = ("bending", "mixed")


@dataclass(frozen=True)
class Bode:
    """One probe's response against speed: its name and plane (m), speeds (r/min),
    amplitude along x (m), its phase (deg) and the orbit's major semi-axis (m)."""

    name: str
    z: float
    speeds_rpm: np.ndarray
    amplitude: np.ndarray
    phase_deg: np.ndarray
    major: np.ndarray


@dataclass(frozen=True)
class Peak:
    """A resonance peak at a probe: its speed (r/min), amplitude (m), the half-power
    speeds (r/min), the amplification factor N_c / (N_2 - N_1) (None where a half-power
    point lies outside the speeds), and against the nearest operating speed the actual
    and required separation margins (fractions; required None below AF 2.5)."""

    probe: str
    speed_rpm: float
    amplitude: float
    half_power_rpm: tuple[float, float] | None
    amplification: float | None
    margin: float
    required_margin: float | None

    @property
    def ok(self) -> bool:
        return self.required_margin is None or self.margin >= self.required_margin

    def as_dict(self) -> dict:
        return {"probe": self.probe, "speed_rpm": self.speed_rpm, "amplitude_m": self.amplitude,
                "half_power_rpm": list(self.half_power_rpm) if self.half_power_rpm else None,
                "amplification_factor": self.amplification, "separation_margin": self.margin,
                "required_margin": self.required_margin, "ok": self.ok}


@dataclass(frozen=True)
class UnbalanceResponse:
    """The response at every probe and its peaks."""

    bode: tuple[Bode, ...]
    peaks: tuple[Peak, ...]

    def as_dict(self) -> dict:
        return {"peaks": [p.as_dict() for p in self.peaks],
                "probes": [{"name": b.name, "z_mm": b.z * 1e3,
                            "speeds_rpm": b.speeds_rpm.tolist(),
                            "amplitude_m": b.amplitude.tolist(),
                            "phase_deg": b.phase_deg.tolist(),
                            "major_m": b.major.tolist()} for b in self.bode]}


@dataclass(frozen=True)
class Whirl:
    """One complex mode at one speed, in the stationary frame: speed (r/min), its
    number at that speed (from 1, by frequency), damped frequency (Hz), the whirl
    ("forward", "backward", "mixed"), the whirl index (+1 forward circular, -1
    backward), the log decrement and damping ratio, the kind of standstill mode it is
    most of, its frequency in the rotating frame (Hz; the same as frequency_hz in the
    stationary frame) and the other component's frequency (Hz; rotating frame, or
    None)."""

    speed_rpm: float
    mode: int
    frequency_hz: float
    whirl: str
    whirl_index: float
    log_dec: float
    damping_ratio: float
    kind: str
    rotating_frame_hz: float
    companion_hz: float | None = None

    def as_dict(self) -> dict:
        return {"speed_rpm": self.speed_rpm, "mode": self.mode,
                "frequency_hz": self.frequency_hz, "whirl": self.whirl,
                "whirl_index": self.whirl_index, "log_dec": self.log_dec,
                "damping_ratio": self.damping_ratio, "kind": self.kind,
                "rotating_frame_hz": self.rotating_frame_hz, "companion_hz": self.companion_hz}


@dataclass(frozen=True)
class CriticalSpeed:
    """Where a whirl curve crosses the excitation order line f = order x n / 60: the
    order, the whirl, the speed (r/min), the frequency there (Hz), and which curve
    (its number among the curves of that whirl, from 1)."""

    order: int
    whirl: str
    speed_rpm: float
    frequency_hz: float
    mode: int
    log_dec: float = 0.0

    def as_dict(self) -> dict:
        return {"order": self.order, "whirl": self.whirl, "speed_rpm": self.speed_rpm,
                "frequency_hz": self.frequency_hz, "mode": self.mode, "log_dec": self.log_dec}


@dataclass(frozen=True)
class Onset:
    """Where a whirl curve's log decrement falls through zero: the speed (r/min) from
    which that mode grows, its whirl, its curve (from 1 among that whirl's) and its
    frequency there (Hz)."""

    speed_rpm: float
    whirl: str
    mode: int
    frequency_hz: float

    def as_dict(self) -> dict:
        return {"speed_rpm": self.speed_rpm, "whirl": self.whirl, "mode": self.mode,
                "frequency_hz": self.frequency_hz}


@dataclass(frozen=True)
class Truncation:
    """The modal basis' check: the whirl frequencies of the reported modes solved on
    the whole basis (`size` modes) and on its first `smaller`, at each checked speed;
    `change` the largest relative move between the two (a fraction)."""

    size: int
    smaller: int
    speeds_rpm: tuple[float, ...]
    change: float


@dataclass(frozen=True)
class Campbell:
    """The whirl of the turning shaft: the frame and why, the speeds (r/min) of the
    diagram, every mode at each (`whirl`), the operating speeds' rows (`operating`),
    the critical speeds, the excitation orders, the basis check, and the standstill
    run behind it."""

    frame: str
    why: str
    speeds_rpm: tuple[float, ...]
    whirl: tuple[Whirl, ...]
    operating: tuple[Whirl, ...]
    operating_rpm: tuple[float, ...]
    critical_speeds: tuple[CriticalSpeed, ...]
    orders: tuple[int, ...]
    truncation: Truncation
    result: ModalResult
    notes: tuple[str, ...] = field(default=())
    unbalance: UnbalanceResponse | None = None
    onsets: tuple[Onset, ...] = ()
    divergent: tuple[tuple[float, float], ...] = ()   # speed bands (r/min) where it diverges
    # at each operating speed, the reported modes' complex shapes on the standstill modes
    # (N, count): u = Phi y, in the model's frame
    operating_shapes: tuple[np.ndarray, ...] = ()
    # the 1x crossings against the synchronous eigenproblem (largest relative difference;
    # None where that eigenproblem does not apply: rotating frame, speed-dependent or
    # damped bearings)
    synchronous_check: float | None = None

    def as_dict(self) -> dict:
        """The JSON of `shaftfem campbell` (its names are read by scripts)."""
        t = self.truncation
        return {"frame": self.frame, "frame_reason": self.why,
                "operating_speeds_rpm": list(self.operating_rpm), "orders": list(self.orders),
                "whirl": [w.as_dict() for w in self.whirl],
                "operating": [w.as_dict() for w in self.operating],
                "critical_speeds": [c.as_dict() for c in self.critical_speeds],
                "instability_onsets": [o.as_dict() for o in self.onsets],
                "divergent_rpm": [list(band) for band in self.divergent],
                "synchronous_check": self.synchronous_check,
                "basis": {"modes": t.size, "checked_against": t.smaller,
                          "largest_change": t.change, "speeds_rpm": list(t.speeds_rpm)},
                "unbalance": None if self.unbalance is None else self.unbalance.as_dict(),
                "notes": list(self.notes)}

    def decrements(self, whirl: str) -> list[tuple[np.ndarray, np.ndarray]]:
        """As `curves`, the log decrement of each curve instead of its frequency."""
        return self.curves(whirl, "log_dec")

    def curves(self, whirl: str, value: str = "frequency_hz"
               ) -> list[tuple[np.ndarray, np.ndarray]]:
        """The diagram's curves of one whirl ("forward", "backward", "mixed", or "none"
        for the modes that do not orbit: torsion, axial): (speeds r/min, frequencies Hz)
        of the k-th lowest mode of that whirl at each speed, for k = 1, 2, ..."""
        by_speed: dict[float, list[Whirl]] = {}
        for w in self.whirl:
            if category(w) == whirl:
                by_speed.setdefault(w.speed_rpm, []).append(w)
        n = max((len(v) for v in by_speed.values()), default=0)
        out = []
        for k in range(n):
            pts = [(s, getattr(sorted(v, key=lambda w: w.frequency_hz)[k], value))
                   for s, v in sorted(by_speed.items()) if len(v) > k]
            out.append((np.array([p[0] for p in pts]), np.array([p[1] for p in pts])))
        return out


def category(w: Whirl) -> str:
    """How a mode is drawn: its whirl, or "none" for a mode that does not orbit."""
    return w.whirl if w.kind in WHIRLING else "none"
