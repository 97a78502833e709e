"""The turning shaft's results as typed records: each complex mode at each speed in the
stationary frame (Whirl), the critical speeds, the onsets of instability, the modal
basis' check, the unbalance response (Bode curves and peaks), and the Campbell
diagram that holds them with the standstill run behind it. Made by workflows.campbell
and workflows.unbalance; read by the checks, the tables, the pictures and the files."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult
    from shaftfem.scene.model import Scene

RPM = 2 * math.pi / 60           # rad/s per r/min
# A whirl index beyond these is forward (backward); between, the orbit is mixed.
FORWARD = 0.1
# Kinds of mode that whirl: bending; torsion and axial modes do not orbit.
WHIRLING = ("bending", "mixed")


@dataclass(frozen=True)
class Bode:
    """One probe's response against speed, amplitudes 0-peak: its name and plane (m),
    speeds (r/min), amplitude along x (m), its phase (deg, a continuous lag), the
    orbit's major semi-axis (m), and the amplitude along y (m) and its phase (deg)."""

    name: str
    z: float
    speeds_rpm: np.ndarray
    amplitude: np.ndarray
    phase_deg: np.ndarray
    major: np.ndarray
    amplitude_y: np.ndarray | None = None
    phase_y_deg: np.ndarray | None = None
    # a periodic rotor's 3x orbit's major semi-axis (m), at the same speeds
    major_3x: np.ndarray | None = None


@dataclass(frozen=True)
class Peak:
    """A resonance peak at a probe: its speed (r/min), amplitude (the orbit's major
    semi-axis, 0-peak, m; infinite in a model with no damping), the half-power speeds
    (r/min), the amplification factor N_c / (N_2 - N_1) (None where a half-power point
    lies outside the speeds), and against the nearest operating speed or range the
    actual and required separation margins (fractions; required None below AF 2.5)."""

    probe: str
    speed_rpm: float
    amplitude: float
    half_power_rpm: tuple[float, float] | None
    amplification: float | None
    margin: float
    required_margin: float | None
    unstable: bool = False   # a mode grows there: no steady response, no AF
    unbounded: bool = False  # no damping in the model: the response has no finite peak

    @property
    def ok(self) -> bool:
        return self.required_margin is None or self.margin >= self.required_margin

    def as_dict(self) -> dict:
        return {"probe": self.probe, "speed_rpm": self.speed_rpm, "amplitude_m": self.amplitude,
                "half_power_rpm": list(self.half_power_rpm) if self.half_power_rpm else None,
                "amplification_factor": self.amplification, "separation_margin": self.margin,
                "required_margin": self.required_margin, "ok": self.ok,
                "unstable": self.unstable, "unbounded": self.unbounded}


@dataclass(frozen=True)
class WeightWhirl:
    """The 2x whirl a shaft stiffer across one diameter than across the other makes of
    its own weight, at a probe: the speed of its peak (r/min; the "secondary critical",
    near half a critical speed), the 2x orbit's major semi-axis there (0-peak, m) and at
    the highest operating speed (m), and the sag it whirls about there (m)."""

    probe: str
    speed_rpm: float
    amplitude: float
    at_operating: float
    sag: float
    # the 2x orbit's major semi-axis (m) at the speeds (r/min) it was drawn through
    speeds_rpm: tuple[float, ...] = ()
    curve: tuple[float, ...] = ()

    def as_dict(self) -> dict:
        return {"probe": self.probe, "peak_speed_rpm": self.speed_rpm,
                "peak_2x_m": self.amplitude, "at_operating_2x_m": self.at_operating,
                "sag_m": self.sag, "speeds_rpm": list(self.speeds_rpm),
                "major_2x_m": list(self.curve)}


@dataclass(frozen=True)
class UnbalanceResponse:
    """The response at every probe and its peaks."""

    bode: tuple[Bode, ...]
    peaks: tuple[Peak, ...]
    damped: bool = True   # False: no damping in the model, every peak unbounded

    def as_dict(self) -> dict:
        return {"amplitudes": "0-peak", "damped": self.damped,
                "peaks": [p.as_dict() for p in self.peaks],
                "probes": [{"name": b.name, "z_mm": b.z * 1e3,
                            "speeds_rpm": b.speeds_rpm.tolist(),
                            "amplitude_m": b.amplitude.tolist(),
                            "phase_deg": b.phase_deg.tolist(),
                            "amplitude_y_m": (None if b.amplitude_y is None
                                              else b.amplitude_y.tolist()),
                            "phase_y_deg": (None if b.phase_y_deg is None
                                            else b.phase_y_deg.tolist()),
                            "major_m": b.major.tolist(),
                            **({"major_3x_m": b.major_3x.tolist()} if b.major_3x is not None
                               else {})} for b in self.bode]}


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
    companion_share: float = 0.0     # the other component's share of the motion

    def as_dict(self) -> dict:
        return {"speed_rpm": self.speed_rpm, "mode": self.mode,
                "frequency_hz": self.frequency_hz, "whirl": self.whirl,
                "whirl_index": self.whirl_index, "log_dec": self.log_dec,
                "damping_ratio": self.damping_ratio, "kind": self.kind,
                "rotating_frame_hz": self.rotating_frame_hz, "companion_hz": self.companion_hz,
                "companion_share": self.companion_share}


def seen(f_s: np.ndarray, index: np.ndarray, n: np.ndarray | float, frame: str) -> np.ndarray:
    """The frequency (Hz) the housing sees of a root's larger component: the root
    itself in the stationary frame; in the rotating frame its forward component
    f_s + n where its whirl index is positive, else its backward one f_s - n."""
    if frame == "stationary":
        return np.abs(f_s)
    return np.where(index >= 0, np.abs(f_s + n), np.abs(f_s - n))


def label(index: float) -> str:
    """A whirl index's word: forward, backward, or mixed between -FORWARD and FORWARD."""
    return "forward" if index > FORWARD else "backward" if index < -FORWARD else "mixed"


@dataclass(frozen=True)
class Curve:
    """One whirl curve: a mode family followed from speed to speed by its shape
    (fem.tracking), numbered from 1 by its first speed and frequency there. At each of
    its speeds (r/min): its frequency in the frame it is solved in (Hz; in the rotating
    frame signed, the form continuous along the curve), decay rate (1/s, negative where
    it grows), whirl index (+1 forward circular, -1 backward) and kind; its unit modal
    coordinates (N, points) follow the curve too."""

    number: int
    frame: str
    speeds_rpm: np.ndarray
    signed_hz: np.ndarray
    decay: np.ndarray
    index: np.ndarray
    kinds: tuple[str, ...]
    shapes: np.ndarray = field(repr=False)
    gaps: tuple[int, ...] = ()   # steps i -> i + 1 over which it did not oscillate
    # why it starts after the diagram's first speed, or ends before its last
    # (fem.tracking: "pair", two real roots meet and whirl; "split", the pair parts into
    # two real roots; "shape", its shape turned past the match); "" where it does not
    began: str = ""
    ended: str = ""
    # a periodic rotor's Floquet form: its shares of the motion in the harmonics
    # d = -S..S from the dominant one (seen at signed_hz + 2 d n in the turning frame)
    # and their whirl indices, (2 S + 1, points); zero where not periodic
    sides: np.ndarray | None = field(default=None, repr=False)
    side_index: np.ndarray | None = field(default=None, repr=False)

    @property
    def seen_hz(self) -> np.ndarray:
        """The frequency the housing sees at each speed (Hz): its larger component (a
        curve that never orbits, torsion or axial, its own frequency in either frame)."""
        if not self.whirling:
            return np.abs(self.signed_hz)
        return seen(self.signed_hz, self.index, self.speeds_rpm / 60.0, self.frame)

    @property
    def log_dec(self) -> np.ndarray:
        """The log decrement at each speed, per cycle of the frequency seen."""
        f = self.seen_hz
        return np.where(f > 0, self.decay / np.where(f > 0, f, 1.0), 0.0)

    @property
    def whirl(self) -> list[str]:
        """The whirl seen at each speed, by the larger component's sense (rotating frame)
        or the index (stationary)."""
        if self.frame == "stationary":
            return [label(w) for w in self.index]
        n = self.speeds_rpm / 60.0
        out = []
        for f, w, nn in zip(self.signed_hz, self.index, n):
            v = f + nn if w >= 0 else f - nn
            out.append("forward" if (w >= 0) == (v > 0) else "backward")
        return out

    @property
    def whirling(self) -> bool:
        """Whether it orbits (bending) at any of its speeds."""
        return any(k in WHIRLING for k in self.kinds)

    def rows(self) -> list[dict]:
        """One dict per speed: what campbell.csv holds."""
        return [{"speed_rpm": float(s), "curve": self.number, "frequency_hz": float(f),
                 "whirl": w, "whirl_index": float(i), "log_dec": float(d), "kind": k}
                for s, f, w, i, d, k in zip(self.speeds_rpm, self.seen_hz, self.whirl,
                                            self.index, self.log_dec, self.kinds)]


# API 684: below this amplification factor a mode is critically damped (no margin).
CRITICALLY_DAMPED_AF = 2.5


@dataclass(frozen=True)
class CriticalSpeed:
    """Where a whirl curve crosses the excitation order line f = order x n / 60: the
    order, the whirl there, the speed (r/min), the frequency there (Hz), which curve
    (its number, from 1: Campbell.curves), its log decrement there, the component
    met ("" in the stationary frame; "forward" or "backward" of a rotating-frame
    mode) and its share of the motion, and how it was found ("curve": on the
    followed curve; "direct": only by the eigenproblem in the speed squared)."""

    order: int
    whirl: str
    speed_rpm: float
    frequency_hz: float
    mode: int
    log_dec: float = 0.0
    component: str = ""
    share: float = 1.0
    found: str = "curve"

    @property
    def amplification(self) -> float:
        """The amplification factor (amplification_factor)."""
        return amplification_factor(self.log_dec)

    @property
    def critically_damped(self) -> bool:
        """API 684: a crossing of a mode with AF below 2.5 is critically damped; it
        needs no separation margin (an oil film's heavily damped rigid-body roots)."""
        return self.amplification < CRITICALLY_DAMPED_AF

    def as_dict(self) -> dict:
        return {"order": self.order, "whirl": self.whirl, "speed_rpm": self.speed_rpm,
                "frequency_hz": self.frequency_hz, "curve": self.mode, "log_dec": self.log_dec,
                "amplification_factor": (None if math.isinf(self.amplification)
                                         else self.amplification),
                "critically_damped": self.critically_damped,
                "component": self.component, "share": self.share, "found": self.found}


@dataclass(frozen=True)
class CrossingCheck:
    """The crossings found twice: whether the direct route (undamped crossings as a
    linear eigenproblem in the speed squared, fem.tracking) applies and why not, the
    largest relative difference between the routes' speeds, how many crossings each
    found, and those found directly but not on the curves (added to the list)."""

    applies: bool
    why: str
    largest_difference: float | None = None
    on_curves: int = 0
    direct: int = 0
    direct_only: int = 0
    curves_only: int = 0

    def as_dict(self) -> dict:
        return {"direct_route_applies": self.applies, "why": self.why,
                "largest_difference": self.largest_difference, "on_curves": self.on_curves,
                "direct": self.direct, "found_directly_only": self.direct_only,
                "found_on_curves_only": self.curves_only}


@dataclass(frozen=True)
class Stability:
    """The least damped whirling mode where the shaft runs (its operating speeds and
    ranges, above the journals' lift-off): its
    curve, speed (r/min), frequency (Hz), whirl and log decrement; the required
    minimum log decrement and whether it is judged (an undamped model's decrements are
    zero: judged only where the scene sets min_log_dec or a mode grows)."""

    curve: int
    speed_rpm: float
    frequency_hz: float
    whirl: str
    log_dec: float
    required: float
    judged: bool
    growing: bool
    # every other whirling curve that fails too: (curve, speed r/min, Hz, whirl, log dec)
    others: tuple[tuple[int, float, float, str, float], ...] = ()
    # the operating speeds below the journals' lift-off, where no verdict is given
    unjudged_rpm: tuple[float, ...] = ()
    # the bands below the running range where a whirling curve grows (a run-up passes
    # them): (curve, whirl, from r/min, to r/min) sampled on the diagram's speeds
    passed: tuple[tuple[int, str, float, float], ...] = ()
    # the modes the required log decrement applies to: "forward", "first_forward", "all"
    modes: str = "forward"
    # on tilting pads (their tilts coordinates of the model): the same mode's log
    # decrement at that speed with the pads' synchronously reduced 2x2 coefficients, as
    # tools that reduce them give it (None: no tilting pads)
    reduced_log_dec: float | None = None

    @property
    def applies_text(self) -> str:
        return {"forward": "every forward mode", "first_forward": "the first forward mode",
                "all": "every whirling mode"}[self.modes]

    @property
    def ok(self) -> bool:
        if self.growing:
            return False
        return not self.judged or self.log_dec > self.required

    def as_dict(self) -> dict:
        return {"curve": self.curve, "speed_rpm": self.speed_rpm,
                "frequency_hz": self.frequency_hz, "whirl": self.whirl,
                "log_dec": self.log_dec, "required_min_log_dec": self.required,
                "judged": self.judged, "growing": self.growing, "ok": self.ok,
                "required_of": self.modes,
                "log_dec_with_pads_reduced_at_spin": self.reduced_log_dec,
                "others_failing": [{"curve": n, "speed_rpm": sp, "frequency_hz": f,
                                    "whirl": w, "log_dec": d}
                                   for n, sp, f, w, d in self.others],
                "not_judged_below_lift_off_rpm": list(self.unjudged_rpm),
                "growth_below_running_range": [
                    {"curve": n, "whirl": w, "from_rpm": a, "to_rpm": b}
                    for n, w, a, b in self.passed]}


@dataclass(frozen=True)
class Onset:
    """Where a whirl curve's log decrement falls through zero: the speed (r/min) from
    which that mode grows, its whirl, its curve (Campbell.curves' number) and its
    frequency there (Hz)."""

    speed_rpm: float
    whirl: str
    mode: int
    frequency_hz: float
    # where it stops growing again (r/min; None: it grows to the diagram's end), and its
    # fastest growth on the way (1/s) with the speed it is met at (r/min)
    until_rpm: float | None = None
    growth_per_s: float = 0.0
    fastest_rpm: float = 0.0

    @property
    def curve_text(self) -> str:
        return f"{self.mode} ({self.whirl} whirl)"

    def as_dict(self) -> dict:
        return {"speed_rpm": self.speed_rpm, "whirl": self.whirl, "curve": self.mode,
                "frequency_hz": self.frequency_hz, "until_rpm": self.until_rpm,
                "growth_per_s": self.growth_per_s, "fastest_at_rpm": self.fastest_rpm}


def amplification_factor(log_dec: float) -> float:
    """A mode's amplification factor AF = 1 / (2 zeta) from its log decrement delta,
    zeta = delta / sqrt(4 pi^2 + delta^2): pi / delta for light damping (API 684's
    form), never below 1/2 (a critically damped root's); infinite undamped."""
    if log_dec <= 0:
        return math.inf
    return math.sqrt(4 * math.pi**2 + log_dec**2) / (2 * log_dec)


@dataclass(frozen=True)
class GrowthZone:
    """A band of speeds (r/min) where the rotor grows: the union of every overlapping
    cause (an onset's span, a divergence, a periodic rotor's parametric zone), its
    fastest growth (1/s) and where it is met, and what it holds. `open` where it runs to
    the diagram's end (the rotor may grow beyond it too)."""

    from_rpm: float
    to_rpm: float
    growth_per_s: float
    fastest_rpm: float
    holds: tuple[str, ...]
    open: bool = False

    @property
    def span_text(self) -> str:
        return (f"from {self.from_rpm:,.0f} r/min to the diagram's end ({self.to_rpm:,.0f})"
                if self.open else f"from {self.from_rpm:,.0f} to {self.to_rpm:,.0f} r/min")

    @property
    def growth_text(self) -> str:
        g = self.growth_per_s
        return (f"fastest growth {g:.3g} 1/s at {self.fastest_rpm:,.0f} r/min (doubling in "
                f"{math.log(2) / g:.3g} s)" if g > 0 else "growth too slow to rate")

    def as_dict(self) -> dict:
        return {"from_rpm": self.from_rpm, "to_rpm": self.to_rpm,
                "to_diagram_end": self.open, "growth_per_s": self.growth_per_s,
                "fastest_at_rpm": self.fastest_rpm, "holds": list(self.holds)}


def growth_zones(parts: list[tuple[float, float, float, float, str]], top_rpm: float
                 ) -> tuple[GrowthZone, ...]:
    """The growth bands `parts` (from, to r/min, fastest growth 1/s, where, what) merged
    where they overlap or touch: one zone of growth is one band, whatever found it."""
    out: list[GrowthZone] = []
    for lo, hi, g, at, what in sorted(parts):
        last = out[-1] if out else None
        if last is not None and lo <= last.to_rpm * (1 + 1e-6):
            faster = g > last.growth_per_s
            out[-1] = GrowthZone(
                last.from_rpm, max(hi, last.to_rpm), max(g, last.growth_per_s),
                at if faster else last.fastest_rpm,
                last.holds + ((what,) if what not in last.holds else ()))
        else:
            out.append(GrowthZone(lo, hi, g, at, (what,)))
    return tuple(replace(z, open=z.to_rpm >= top_rpm * (1 - 1e-9)) for z in out)


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
class FilmRow:
    """A journal bearing at one operating speed (shaftfem.parts.journal): eccentricity
    ratio, attitude angle (deg), minimum film (um), Sommerfeld number, its K (N/m) and
    C (N s/m) as (xx, xy, yx, yy), its least allowed film (um), and whether the film
    lifts the journal at all there (below its table's heaviest row it does not)."""

    bearing: str
    speed_rpm: float
    eccentricity: float
    attitude_deg: float
    min_film_um: float
    sommerfeld: float
    K: tuple[float, ...]
    C: tuple[float, ...]
    limit_um: float
    lifted: bool = True
    # an oil given by its supply temperature (parts.heat): its supply and the film's
    # effective temperature (C; on tilting pads their heated films' mean), the film's
    # friction power (W) and side flow (m^3/s: the oil the feed must make up; on tilting
    # pads the supply their leading edges draw);
    # with the supply's flow (m^3/s), the drain's temperature (C)
    supply_c: float | None = None
    film_c: float | None = None
    power_w: float | None = None
    side_flow: float | None = None
    flow: float | None = None
    drain_c: float | None = None
    # tilting pads fed at a supply temperature: the pads' peak temperature from their
    # heated film (parts.pad_heat) and its limit (C)
    pad_peak_c: float | None = None
    pad_limit_c: float | None = None
    pad_peaks_c: tuple[float, ...] = ()   # each pad's, from the first after the load's line
    # ... and of the friction power, what the films give the journal (W), which it sheds
    # along the shaft, not into the drain
    journal_w: float | None = None
    # the least of the pads' clearances at their pivots, the parts grown by their heat (um)
    hot_clearance_um: float | None = None

    @property
    def hot(self) -> bool:
        return self.pad_peak_c is not None and self.pad_limit_c is not None and \
            self.pad_peak_c > self.pad_limit_c

    @property
    def thin(self) -> bool:
        return not self.lifted or self.min_film_um < self.limit_um

    @property
    def starved(self) -> bool:
        """Whether the supply's flow is less than the film's side flow (the oil it loses
        through its ends, which the feed must make up; on tilting pads, the supply oil
        their leading edges draw)."""
        return self.flow is not None and self.side_flow is not None and \
            self.flow < self.side_flow

    def as_dict(self) -> dict:
        names = ("xx", "xy", "yx", "yy")
        return {"bearing": self.bearing, "speed_rpm": self.speed_rpm,
                "eccentricity": self.eccentricity, "attitude_deg": self.attitude_deg,
                "min_film_um": self.min_film_um, "sommerfeld": self.sommerfeld,
                **{f"k{n}_n_per_m": k for n, k in zip(names, self.K)},
                **{f"c{n}_n_s_per_m": c for n, c in zip(names, self.C)},
                "min_film_limit_um": self.limit_um, "lifted": self.lifted,
                **({} if self.film_c is None else {
                    "supply_temperature_c": self.supply_c, "film_temperature_c": self.film_c,
                    "friction_power_w": self.power_w,
                    "side_flow_l_min": (self.side_flow or 0.0) * 60e3,
                    "supply_flow_l_min": None if self.flow is None else self.flow * 60e3,
                    "drain_temperature_c": self.drain_c, "starved": self.starved}),
                **({} if self.pad_peak_c is None else {
                    "peak_pad_temperature_c": self.pad_peak_c,
                    "pad_peak_temperatures_c": list(self.pad_peaks_c),
                    "journal_heat_w": self.journal_w,
                    "hot_clearance_um": self.hot_clearance_um,
                    "pad_temperature_limit_c": self.pad_limit_c})}


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
    divergent_growth: tuple[float, ...] = ()   # each band's fastest growth rate, 1/s
    # a periodic rotor's zones where it grows while it oscillates (parametric and
    # combination resonances, bands above an onset): (from, to r/min, fastest growth 1/s)
    parametric: tuple[tuple[float, float, float], ...] = ()
    # where the rotor grows, whatever found it (onsets' spans, divergence, parametric
    # zones), overlapping bands merged: what the reader is told and the check judges
    zones: tuple[GrowthZone, ...] = ()
    # at each operating speed, the reported modes' complex shapes on the standstill modes
    # (N, count): u = Phi y, in the model's frame
    operating_shapes: tuple[np.ndarray, ...] = ()
    # the crossings against the direct route (largest relative difference; None where
    # it does not apply: speed-dependent or damped bearings)
    synchronous_check: float | None = None
    crossing_check: CrossingCheck | None = None
    # the whirl curves, followed by shape (those among the modes asked at some speed)
    curves: tuple[Curve, ...] = ()
    stability: Stability | None = None
    ranges_rpm: tuple[tuple[float, float], ...] = ()   # operating speed ranges
    # the scene the diagram was drawn for (its [rotor] may differ from the basis run's)
    scene: Scene | None = None
    # where the highest order line leaves the frequencies searched for crossings
    coverage: str | None = None
    # each journal bearing at each operating speed
    films: tuple[FilmRow, ...] = ()
    # the speed (r/min) from which every journal's film lifts its journal (0: none)
    lift_rpm: float = 0.0
    # the 2x whirl the shaft's weight drives (a rotor not of revolution, turning frame)
    weight_2x: tuple[WeightWhirl, ...] = ()
    # the basis the whirl is solved on, as nodal shapes (3 n, N): the standstill modes
    # and the bearings' residual modes (None: the standstill modes alone)
    basis: np.ndarray | None = field(default=None, repr=False, compare=False)

    @property
    def basis_shapes(self) -> np.ndarray:
        """u = basis_shapes @ y for the whirl's modal coordinates y."""
        return self.result.modes.shapes if self.basis is None else self.basis

    @property
    def opening_onsets(self) -> tuple[Onset, ...]:
        """The onsets where the rotor starts to grow: each that opens a zone of growth
        (one inside a zone an earlier cause opened is part of that zone)."""
        return tuple(o for o in self.onsets if any(
            abs(o.speed_rpm - z.from_rpm) <= 1e-6 * max(z.from_rpm, 1.0) for z in self.zones))

    @property
    def stable_above_rpm(self) -> float | None:
        """The speed (r/min) above which the diagram shows no growth (None: it grows to
        the diagram's end; 0: it grows nowhere)."""
        if not self.zones:
            return 0.0
        last = self.zones[-1]
        return None if last.open else last.to_rpm

    @property
    def rotor_scene(self) -> Scene:
        """The scene whose speeds, sources and criteria the diagram answers."""
        return self.scene if self.scene is not None else self.result.scene

    def as_dict(self) -> dict:
        """The JSON of `shaftfem campbell` (its names are read by scripts)."""
        t = self.truncation
        return {"frame": self.frame, "frame_reason": self.why,
                "operating_speeds_rpm": list(self.operating_rpm),
                "operating_ranges_rpm": [list(r) for r in self.ranges_rpm],
                "orders": list(self.orders),
                "whirl": [w.as_dict() for w in self.whirl],
                "operating": [w.as_dict() for w in self.operating],
                "critical_speeds": [c.as_dict() for c in self.critical_speeds],
                "instability_onsets": [o.as_dict() for o in self.opening_onsets],
                "divergent_rpm": [list(band) for band in self.divergent],
                "divergent_growth_per_s": list(self.divergent_growth),
                "parametric_zones": [{"from_rpm": lo, "to_rpm": hi, "growth_per_s": g}
                                     for lo, hi, g in self.parametric],
                "zones": [z.as_dict() for z in self.zones],
                "stable_above_rpm": self.stable_above_rpm,
                "synchronous_check": self.synchronous_check,
                "crossing_check": (None if self.crossing_check is None
                                   else self.crossing_check.as_dict()),
                "stability": None if self.stability is None else self.stability.as_dict(),
                "basis": {"modes": t.size, "checked_against": t.smaller,
                          "largest_change": t.change, "speeds_rpm": list(t.speeds_rpm)},
                "unbalance": None if self.unbalance is None else self.unbalance.as_dict(),
                "weight_2x": [w.as_dict() for w in self.weight_2x],
                "journal_bearings": [f.as_dict() for f in self.films],
                "journals_lift_off_rpm": self.lift_rpm,
                "notes": list(self.notes)}

    def csv_rows(self) -> list[dict]:
        """campbell.csv: one row per curve and speed."""
        return [row for c in self.curves for row in c.rows()]


def category(w: Whirl) -> str:
    """How a mode is drawn: its whirl, or "none" for a mode that does not orbit."""
    return w.whirl if w.kind in WHIRLING else "none"


@dataclass(frozen=True)
class BearingCurve:
    """A scene bearing's direct stiffnesses against speed (N/m, r/min), and where each
    meets a branch: (branch, direction "x" or "y", stiffness N/m, speed r/min)."""

    name: str
    speeds_rpm: np.ndarray
    kxx: np.ndarray
    kyy: np.ndarray
    crossings: tuple[tuple[int, str, float, float], ...]


@dataclass(frozen=True)
class UcsMap:
    """The map: the stiffnesses (N/m), each branch's frequency there (branches, n) Hz,
    its deflected line at the soft and the stiff end ((branches, slices) each, largest
    1, at z m), the scene's bearing curves, the reference stiffness of the basis, the
    basis' size and how far the map moves on two thirds of it."""

    scene: Scene
    stiffness: np.ndarray
    frequencies: np.ndarray
    z: np.ndarray
    soft_lines: np.ndarray
    stiff_lines: np.ndarray
    bearings: tuple[BearingCurve, ...]
    reference: float
    basis: int
    change: float
    # "forward" or "backward": synchronous critical speeds (gyroscopic moments at
    # Omega = omega); "standstill": the natural frequencies at rest
    kind: str = "forward"

    @property
    def title(self) -> str:
        """What the branches are, in words."""
        return ("natural frequencies at standstill (as 1x speeds)" if self.kind == "standstill"
                else f"synchronous {self.kind} critical speeds (gyroscopic moments at "
                "Omega = omega)")

    @property
    def speeds_rpm(self) -> np.ndarray:
        """Each branch's critical speed, r/min: its frequency as a speed (1x)."""
        return 60.0 * self.frequencies

    def as_dict(self) -> dict:
        return {"kind": self.kind, "title": self.title,
                "stiffness_n_per_mm": [float(k) / 1e3 for k in self.stiffness],
                "branches": [{"branch": i + 1,
                              "critical_speed_rpm": [None if not np.isfinite(v) else float(v)
                                                     for v in self.speeds_rpm[i]]}
                             for i in range(self.frequencies.shape[0])],
                "bearings": [{"name": b.name, "speeds_rpm": [float(v) for v in b.speeds_rpm],
                              "kxx_n_per_mm": [float(v) / 1e3 for v in b.kxx],
                              "kyy_n_per_mm": [float(v) / 1e3 for v in b.kyy],
                              "crossings": [{"branch": i + 1, "direction": d,
                                             "stiffness_n_per_mm": k / 1e3, "speed_rpm": n}
                                            for i, d, k, n in b.crossings]}
                             for b in self.bearings],
                "basis": {"modes": self.basis, "reference_stiffness_n_per_mm":
                          self.reference / 1e3, "largest_change_on_two_thirds": self.change}}


@dataclass(frozen=True)
class Level1:
    """API 684's Level I screening (workflows.level1): at the speed (r/min), Q (N/m)
    applied at the plane z (m, and why there), the first forward mode's log decrement
    at each Q and without any, Q_0 where it is zero (None: not unstable below 1e13 N/m,
    or unstable already), the anticipated Q_A (N/m, and where from; None: not known),
    the log decrement there, Q_0 / Q_A, whether API 617's criteria pass (None: no Q_A),
    and the mode's frequency without Q (Hz)."""

    scene: Scene
    speed_rpm: float
    plane: float
    plane_why: str
    q: np.ndarray
    log_dec: np.ndarray
    log_dec_0: float
    q0: float | None
    qa: float | None
    qa_from: str
    log_dec_a: float | None
    ratio: float | None
    passed: bool | None
    frequency_hz: float

    def as_dict(self) -> dict:
        def num(v):
            return None if v is None or not math.isfinite(v) else float(v)
        return {"speed_rpm": self.speed_rpm, "plane_mm": self.plane * 1e3,
                "plane": self.plane_why, "criteria": "API 617 8th ed. (2014) 2.6.5: "
                "Q_0 / Q_A >= 2 and log dec at Q_A >= 0.1",
                "q_n_per_mm": [float(q) / 1e3 for q in self.q],
                "log_dec": [float(v) for v in self.log_dec], "log_dec_without_q": self.log_dec_0,
                "q0_n_per_mm": None if self.q0 is None else self.q0 / 1e3,
                "qa_n_per_mm": None if self.qa is None else self.qa / 1e3, "qa_from": self.qa_from,
                "log_dec_at_qa": num(self.log_dec_a), "q0_over_qa": num(self.ratio),
                "passed": self.passed, "first_forward_hz": self.frequency_hz}


@dataclass(frozen=True)
class RunUp:
    """A run-up or coast-down (workflows.runup) at accel_rpm_per_s: per probe (names),
    the orbit's largest radius in each turn of the shaft (m) at its mean speed (r/min),
    the steady unbalance response's major semi-axis at the same speeds (m), the peak
    (speed r/min, radius m), the orbit (x, y; m) over the turns around the peak; and the
    number of time steps."""

    scene: Scene
    accel_rpm_per_s: float
    names: tuple[str, ...]
    speeds_rpm: np.ndarray
    envelopes: tuple[np.ndarray, ...]
    steady: tuple[np.ndarray, ...]
    peaks: tuple[tuple[float, float], ...]
    orbits: tuple[np.ndarray, ...] = field(repr=False)
    steps: int = 0

    def as_dict(self) -> dict:
        return {"accel_rpm_per_s": self.accel_rpm_per_s, "steps": self.steps,
                "speeds_rpm": [float(v) for v in self.speeds_rpm],
                "probes": [{"name": n, "peak_speed_rpm": p[0], "peak_um": p[1] * 1e6,
                            "steady_peak_um": float(s.max()) * 1e6,
                            "steady_peak_speed_rpm": float(self.speeds_rpm[int(np.argmax(s))]),
                            "envelope_um": [float(v) * 1e6 for v in e]}
                           for n, p, e, s in zip(self.names, self.peaks, self.envelopes,
                                                 self.steady)]}


@dataclass(frozen=True)
class Receptance:
    """The running machine's receptance (workflows.frf): a force on the section at
    force_at (m), the response of the section at probe_at (m); H (speeds, frequencies,
    2, 2) complex, m/N: row the response along x, y, column the force along x, y."""

    scene: Scene
    force_at: float
    probe_at: float
    frequencies_hz: np.ndarray
    speeds_rpm: np.ndarray
    H: np.ndarray = field(repr=False)

    def as_dict(self) -> dict:
        return {"force_mm": self.force_at * 1e3, "probe_mm": self.probe_at * 1e3,
                "frequencies_hz": [float(f) for f in self.frequencies_hz],
                "speeds": [{"speed_rpm": float(n),
                            "hxx_um_per_n": [float(abs(h[0, 0])) * 1e6 for h in row],
                            "hyy_um_per_n": [float(abs(h[1, 1])) * 1e6 for h in row],
                            "hxx_phase_deg": [math.degrees(float(np.angle(h[0, 0])))
                                              for h in row]}
                           for n, row in zip(self.speeds_rpm, self.H)]}
