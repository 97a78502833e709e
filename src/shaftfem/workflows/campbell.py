"""The turning shaft: whirl frequencies against speed (the Campbell diagram), the
critical speeds where they cross the excitation orders, and how far the modal basis
they are solved on moves them.

One standstill modal run gives the basis (fem.rotor); every speed is then a small
dense eigenproblem on it. Frequencies are always given in the stationary frame, as a
vibration probe on the housing sees them: a rotating-frame mode at f_r is seen at
f_r + n (forward component) and |f_r - n| (backward component), n the spin in Hz;
each is reported at its larger component, the other beside it.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SceneError, SolverError, UnsettledError
from shaftfem.fem.whirl import (
    FORWARD,
    RPM,
    WHIRLING,
    Campbell,
    CriticalSpeed,
    CrossingCheck,
    Curve,
    FilmRow,
    Onset,
    Stability,
    Truncation,
    Whirl,
    growth_zones,
)
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene
from shaftfem.scene.schema import MAX_MODE_COUNT

if TYPE_CHECKING:
    from collections.abc import Callable

    from shaftfem.fem.result import ModalResult
    from shaftfem.fem.rotor import RotorModel
    from shaftfem.fem.tracking import Spectrum

# Of the basis, the whirl solved on this share too: its change is the truncation check.
CHECK_SHARE = 2 / 3
# Log decrements within this of zero are zero (an undamped model's round-off).
ROUND_OFF = 1e-9
# The direct route and the curves agree on a crossing's speed to this (relative).
AGREE = 1e-6
# API 684's least log decrement, with [resonance] criterion = "api684".
API684_LOG_DEC = 0.1
# The whirl frequencies may move by at most this (relative) between the basis and two
# thirds of it; else the basis is doubled (up to the largest mode count). Far below the
# discretisation's own bounds (0.1 % and more).
TRUNCATION = 1e-4
# A periodic rotor's zones of growth are checked by the monodromy matrix this far (a
# share of the speed) either side of each edge: the two routes' edges agree within it.
ZONE_SIDE = 1e-3
# ... and parametric zones are sought where two curves' frequencies meet 2 k n, |k| up to
# this (a zone of higher order is narrower by the forms' share in the far harmonics,
# geometrically small, and damping closes it)
PARAMETRIC_ORDER = 1
# a form grows in a zone where its log decrement falls below minus this: steel's own
# loss factor (1e-4 to 1e-3, a log decrement of 3e-4 and up) holds a slower growth
ZONE_LOG_DEC = 1e-4
PARAMETRIC_STEPS = 2   # regula falsi steps towards where two forms meet
# a zone's edge is sought in the step between a growing speed and one that does not
# grow, which may hold another zone: the step's ZONE_SPLITS parts are tried from the
# growing side before the bisection, so that it finds this zone's edge
ZONE_SPLITS = 4
# ... and not where the forms' mean decay rate is above this many times their coupling
PARAMETRIC_MARGIN = 2.0
# a curve whose turning-frame frequency moves by more than this many times the speed's
# step (Hz per Hz) jumps there (its dominant component changed): no meeting is sought
PARAMETRIC_SLOPE = 3.0
# Basis size when [rotor] does not give one: this many times the modes asked for ...
BASIS_FACTOR = 3
# ... and at least this many (the bearings' residual modes beside them keep their
# coefficients exact at every speed; the basis check doubles it where that is short).
BASIS_MIN = 18


def choose_frame(scene: Scene) -> tuple[str, str]:
    """The frame the scene's rotor is solved in, and why. A shaft that is not a solid
    of revolution in bearings that are not isotropic has equations periodic in time in
    either frame: it is solved in the frame turning with it, where only the bearings'
    deviatoric parts turn (at twice the spin), by Floquet theory (fem.floquet)."""
    rotor = scene.rotor
    if rotor is None:
        raise SceneError(f"{scene.source}: no [rotor] table: give the operating speed "
                         "([rotor] speed_rpm) to see the shaft turn")
    anisotropic = [s.name for s in scene.held if s.bearing is not None
                   and not s.bearing.isotropic]
    shape = ("a solid of revolution" if scene.axisymmetric else
             "not a solid of revolution (" + ", ".join(
                 w for w, on in (("keyways", bool(scene.shaft.keyways)),
                                 ("grooves", scene.grooves is not None),
                                 ("a STEP solid", scene.shaft.step is not None)) if on) + ")")
    if rotor.frame == "stationary" and not scene.axisymmetric:
        raise SceneError(f"{scene.source}: rotor.frame = \"stationary\": the shaft is {shape}; "
                         "the stationary frame takes shafts of revolution only: use \"rotating\" "
                         "or \"auto\"")
    periodic = (f"; bearing(s) {', '.join(anisotropic)} differ along x and y, so there the "
                "equations are periodic (period pi / Omega) and solved by Floquet theory"
                if anisotropic else "")
    if rotor.frame != "auto":
        return rotor.frame, (f"as [rotor] frame asks; the shaft is {shape}"
                             + (periodic if rotor.frame == "rotating" else ""))
    if scene.axisymmetric:
        return "stationary", (f"auto: the shaft is {shape}, so its modes are solved in the "
                              "stationary frame, gyroscopic moments included")
    return "rotating", (f"auto: the shaft is {shape}, so its modes are solved in the frame "
                        "turning with it (Coriolis and spin softening)"
                        + (periodic if anisotropic else ", its bearings isotropic"))


def basis_size(scene: Scene) -> int:
    """How many standstill modes the whirl is solved on."""
    assert scene.rotor is not None
    return scene.rotor.basis_modes or max(BASIS_FACTOR * scene.modes.count, BASIS_MIN)


def whirl_at(model: RotorModel, omega: float, count: int) -> list[Whirl]:
    """The lowest `count` modes at the spin omega (rad/s), in the stationary frame. A
    double pair (a shaft of revolution's, at standstill) is taken as its forward and
    its backward orbit (fem.tracking.spectrum)."""
    out = []
    for k, (f, direction, index, kind, f_r, other, share, decay, _) in enumerate(
            _seen(model, omega)[1][:count]):
        wd = 2 * math.pi * f
        decay = decay if abs(decay) > ROUND_OFF * wd else 0.0
        out.append(Whirl(speed_rpm=omega / RPM, mode=k + 1, frequency_hz=f, whirl=direction,
                         whirl_index=index, log_dec=2 * math.pi * decay / wd if wd > 0 else 0.0,
                         damping_ratio=decay / math.hypot(decay, wd), kind=kind,
                         rotating_frame_hz=f_r, companion_hz=other, companion_share=share))
    return out


def _harmonics(s: Spectrum) -> np.ndarray:
    """Each root's harmonics (2 S + 1, N, m) beside its dominant one (S = 0: a rotor
    of constant coefficients has one)."""
    return s.side_forms if s.side_forms is not None else s.y[None]


def _seen(model: RotorModel, omega: float) -> tuple[Spectrum, list[tuple]]:
    """The roots at the spin omega and each as the stationary frame sees it, lowest
    first: (frequency Hz, whirl, whirl index, kind, rotating-frame Hz, other component's
    Hz or None, its share of the motion, decay rate 1/s, its column among the roots).
    The whirl and its index are the whole mode's as the housing sees it: a rotating
    frame's mode shows it its forward and backward parts at f_r + n and f_r - n, a
    periodic rotor's each harmonic's at its own (fem.rotor.seen_lines)."""
    from shaftfem.fem.rotor import seen_whirl_index
    from shaftfem.fem.tracking import spectrum

    s = spectrum(model, omega)
    n = omega / (2 * math.pi)
    turning = model.frame == "rotating" and omega > 0
    seen = (seen_whirl_index(model, omega, 2 * math.pi * s.f, _harmonics(s)) if turning
            else s.index)
    rows = []
    for j, (f_r, w, kind, decay) in enumerate(zip(s.f, s.index, s.kinds, s.decay)):
        f, index, other, share = float(f_r), float(w), None, 0.0
        if turning and kind in WHIRLING:
            forward, backward = f_r + n, f_r - n
            index, share = float(seen[j]), 0.5 * (1 - abs(float(w)))
            # the component that carries more of the rotating-frame form gives the row
            f, other = (forward, abs(backward)) if w >= 0 else (abs(backward), forward)
        direction = ("forward" if index > FORWARD else "backward" if index < -FORWARD
                     else "mixed")
        rows.append((f, direction, index, kind, float(f_r), other, share, float(decay), j))
    rows.sort(key=lambda row: row[0])
    return s, rows


def mode_shapes(model: RotorModel, omega: float, count: int) -> np.ndarray:
    """The complex modal coordinates of whirl_at's rows at the spin omega (rad/s), in
    the same order, with their harmonics (2 S + 1, N, count; S = 0 but on a periodic
    rotor), each scaled to a largest entry of 1 in its dominant harmonic."""
    s, rows = _seen(model, omega)
    forms = _harmonics(s)[:, :, [row[-1] for row in rows[:count]]]
    S = (forms.shape[0] - 1) // 2
    y = forms[S]
    return forms / y[np.argmax(np.abs(y), axis=0), np.arange(y.shape[1])]


def dominant(whirl: str, component: str, share: float) -> str:
    """A crossing's whirl by the share that dominates its mode: a rotating-frame mode
    meets an order line with one component, and where that carries under half of the
    motion, the mode whirls the other way."""
    other = {"forward": "backward", "backward": "forward"}
    if component in other and share < 0.5:
        return other[component]
    return whirl


def once(crossings: list[CriticalSpeed]) -> list[CriticalSpeed]:
    """Each crossing once: where two rotating-frame curves meet an order line at one
    speed (to 1e-3 of it; a periodic rotor's pair locked to the speed), the one that
    carries more of its mode's motion stands for both (the less damped where they carry
    alike)."""
    kept: list[CriticalSpeed] = []
    for cs in sorted(crossings, key=lambda c: (c.speed_rpm, c.order)):
        i = next((i for i, k in enumerate(kept) if k.order == cs.order and k.component
                  and cs.component and abs(k.speed_rpm - cs.speed_rpm) <= 1e-3 * cs.speed_rpm),
                 None)
        if i is None:
            kept.append(cs)
        elif (cs.share, -cs.log_dec) > (kept[i].share, -kept[i].log_dec):
            kept[i] = cs
    return kept


def critical_speeds(model: RotorModel, curves: list[Curve], orders: tuple[int, ...],
                    top: float) -> tuple[list[CriticalSpeed], CrossingCheck]:
    """Every crossing of the curves with the order lines up to the spin `top` (rad/s),
    found on the curves and, where it applies, directly (fem.tracking); a crossing found
    directly on a reported mode and missed on the curves is added."""
    from shaftfem.fem.tracking import (
        component_whirl,
        curve_crossings,
        direct_applies,
        direct_crossings,
    )

    found = curve_crossings(model, curves, orders)
    out = once([CriticalSpeed(order=x.order, whirl=dominant(x.whirl, x.component, x.share),
                              speed_rpm=x.omega / RPM,
                              frequency_hz=x.order * x.omega / (2 * math.pi), mode=x.curve,
                              log_dec=x.log_dec if abs(x.log_dec) > ROUND_OFF else 0.0,
                              component=x.component, share=x.share) for x in found])
    lowest = min((float(c.speeds_rpm[0]) * RPM for c in curves), default=0.0)
    out = locked_bands(model, out, lowest, top)
    why = direct_applies(model)
    if why is not None:
        return out, CrossingCheck(False, why, on_curves=len(out))
    try:
        direct = direct_crossings(model, orders, top)
    except UnsettledError as e:   # a periodic rotor's crossings Hill's equations not settle
        return out, CrossingCheck(False, str(e), on_curves=len(out))
    unused = list(range(len(found)))
    worst, extra = 0.0, []
    for d in sorted(direct, key=lambda d: d.omega):
        near = [i for i in unused if found[i].order == d.order
                and abs(found[i].omega / d.omega - 1) <= 1e-3]
        if near:
            i = min(near, key=lambda i: abs(found[i].omega - d.omega))
            unused.remove(i)
            worst = max(worst, abs(found[i].omega / d.omega - 1))
            continue
        # a reported mode's crossing: below the highest reported curve at that speed
        f = d.order * d.omega / (2 * math.pi)
        tops = [float(np.interp(d.omega / RPM, c.speeds_rpm, c.seen_hz)) for c in curves
                if c.speeds_rpm[0] <= d.omega / RPM <= c.speeds_rpm[-1]]
        if tops and f <= max(tops):
            sign = 1 if d.component != "backward" else -1
            v = f if d.component == "" else sign * f
            extra.append(CriticalSpeed(order=d.order, whirl=component_whirl(d.component, v,
                                                                             d.index),
                                       speed_rpm=d.omega / RPM, frequency_hz=f, mode=0,
                                       component=d.component, found="direct"))
    check = CrossingCheck(True, "constant, undamped bearings", worst, len(out), len(direct),
                          len(extra), len(unused))
    return sorted(out + extra, key=lambda c: (c.speed_rpm, c.order)), check


# a band's edge within this share of a crossing already found is that crossing
SAME_EDGE = 1e-4


def locked_bands(model: RotorModel, crossings: list[CriticalSpeed], lowest: float,
                 top: float) -> list[CriticalSpeed]:
    """A periodic rotor's crossings as its exponents have them: one where no exponent is
    seen on its order line (ON_LINE: a followed curve that jumped from root to root) is
    none; one where a pair of exponents is locked to the line holds a band of speeds,
    whose two edges are the crossings (the unbalance response peaks there, the locked
    pair's multipliers meeting on the real axis), each band once (fem.floquet.lock_band,
    within [lowest, top] rad/s; an edge at either end is none; a crossing at an edge
    finds its band from beside it). An edge is the pair's:
    its whirl that of the form the pair meets in (fem.floquet.line_pair), its log
    decrement the pair's, whatever curve led to the band, so that the list does not
    depend on the speeds the curves were followed at. A band narrower than PAIR, a round
    shaft's pair split by its mesh, is the one crossing."""
    from shaftfem.fem.floquet import ON_LINE, line_pair, lock_band, locked, locked_pair, on_line
    from shaftfem.fem.tracking import PAIR, component_whirl

    kept: list[CriticalSpeed] = []
    bands: list[tuple[CriticalSpeed, float, float]] = []
    for cs in crossings:
        om = cs.speed_rpm * RPM
        if om <= 0 or not model.periodic(om):
            kept.append(cs)
            continue
        try:
            r, decay = on_line(model, om, cs.order)
            if not r.size or float(r.min()) > ON_LINE:
                continue
            if not locked_pair(r, decay):
                # a curve that met the line at a band's edge (the pair parts just there):
                # the band is found from beside it
                om = next((w for w in (om * (1 - SAME_EDGE), om * (1 + SAME_EDGE))
                           if lowest < w < top and locked(model, w, cs.order)), 0.0)
                if not om:
                    kept.append(cs)
                    continue
            if any(b.order == cs.order and lo <= om <= hi for b, lo, hi in bands):
                continue
            lo, hi = lock_band(model, om, cs.order, max(lowest, 1e-9), top)
        except UnsettledError:
            kept.append(cs)
            continue
        if hi - lo <= PAIR * om:
            # narrower than the split a mesh gives a round shaft's pair: one crossing
            kept.append(cs)
            continue
        bands.append((cs, lo, hi))
    edges: list[CriticalSpeed] = []
    for cs, lo, hi in bands:
        for edge in (lo, hi):
            if edge <= max(lowest, 1e-9) * (1 + 1e-9) or edge >= top * (1 - 1e-9):
                continue   # the band runs on past the diagram's end
            # the locked pair's whirl and decay a period T = pi / Omega, as a log
            # decrement over the seen whirl's period, order / 2 of T
            index, d = line_pair(model, edge, cs.order)
            log_dec = 2 * d / cs.order
            edges.append(replace(
                cs, whirl=component_whirl("", 1.0, index),
                speed_rpm=edge / RPM, frequency_hz=cs.order * edge / (2 * math.pi),
                log_dec=log_dec if abs(log_dec) > ROUND_OFF else 0.0, component="",
                share=1.0))
    # a crossing followed to a band's edge (a curve's stretch ending there) is that edge
    out = [cs for cs in kept if not any(
        e.order == cs.order and abs(e.speed_rpm / cs.speed_rpm - 1) <= SAME_EDGE for e in edges)]
    return sorted(out + edges, key=lambda c: (c.speed_rpm, c.order))


def onsets(model: RotorModel, curves: list[Curve]) -> list[Onset]:
    """Every speed where a whirling curve starts to grow (its decay rate falls through
    zero, refined by root finding on the model; or from a neutral stretch, an undamped
    rotor's, at the stretch's last speed; or at the curve's first speed if it grows
    there), with where it stops growing again and its fastest growth in between."""
    from scipy.optimize import brentq

    from shaftfem.fem.tracking import REACH, _at

    def through_zero(c: Curve, i: int) -> float:
        """The speed (rad/s) between points i and i + 1 where the decay is zero."""
        d = c.decay
        lo, hi = c.speeds_rpm[i] * RPM, c.speeds_rpm[i + 1] * RPM
        f0, f1 = float(c.signed_hz[i]), float(c.signed_hz[i + 1])
        reach = REACH * (hi - lo) / (2 * math.pi) + 1e-3 * max(abs(f0), abs(f1))

        def decay(om: float) -> float:
            return _at(model, om, c.shapes[:, i], f0 + (f1 - f0) * (om - lo) / (hi - lo),
                       reach)[1]

        try:
            return float(brentq(decay, lo, hi, xtol=1e-10 * hi))
        except ValueError:
            return float(lo + d[i] * (hi - lo) / (d[i] - d[i + 1]))

    out = []
    for c in curves:
        if not c.whirling:
            continue
        scale = ROUND_OFF * 2 * math.pi * np.maximum(c.seen_hz, 1.0)
        d = c.decay
        state = np.where(d < -scale, -1, np.where(d > scale, 1, 0))
        last = len(d) - 1
        i = 0
        while i <= last:
            if state[i] >= 0:
                i += 1
                continue
            a = i
            while i <= last and state[i] < 0:
                i += 1
            b = i - 1                                   # growing from a to b
            if a == 0:
                om = float(c.speeds_rpm[0]) * RPM
            elif state[a - 1] > 0:
                om = through_zero(c, a - 1)
            else:                                       # neutral, then growing
                om = float(c.speeds_rpm[a - 1]) * RPM
            if b == last:
                until = None
            elif state[b + 1] > 0:
                until = through_zero(c, b) / RPM
            else:
                until = float(c.speeds_rpm[b + 1])
            k = a + int(np.argmin(d[a:b + 1]))
            lo, hi = c.speeds_rpm[max(a - 1, 0)] * RPM, c.speeds_rpm[a] * RPM
            t = 0.0 if hi <= lo else (om - lo) / (hi - lo)
            j = a if a == 0 else (a - 1 if t < 0.5 else a)
            f = float(c.seen_hz[a] if a == 0
                      else (1 - t) * c.seen_hz[a - 1] + t * c.seen_hz[a])
            out.append(Onset(om / RPM, c.whirl[j], c.number, f,
                             until_rpm=until, growth_per_s=float(-d[k]),
                             fastest_rpm=float(c.speeds_rpm[k])))
    return sorted(out, key=lambda o: o.speed_rpm)


def lift_speed(scene: Scene) -> float:
    """The speed (rad/s) from which every journal's film lifts its journal (0 without
    journals): below it the films' coefficients are placeholders, and no stability
    verdict rests on them."""
    from shaftfem.parts.journal import lift_off

    return max((lift_off(s.journal) for s in scene.held if s.journal is not None),
               default=0.0)


def least_damped(scene: Scene, curves: list[Curve], lift: float) -> Stability | None:
    """The least damped whirling mode where the shaft runs (its operating speeds and
    ranges, as API 684 judges stability), against the required least log decrement
    ([rotor] min_log_dec; 0, or API 684's 0.1 with criterion "api684"); and every band
    below the running range where a mode grows (a run-up passes through it: a warning).
    Speeds below the journals' lift-off `lift` (r/min, lift_speed) are not judged. An
    undamped model (every decrement zero to round-off) is judged only when min_log_dec
    is set; a mode that grows always fails."""
    rotor = scene.rotor
    assert rotor is not None
    spans = [(lo / RPM * (1 - 1e-9), hi / RPM * (1 + 1e-9)) for lo, hi in rotor.spans]
    start = min(lo for lo, _ in spans)

    def running(n: float) -> bool:
        return n >= lift and any(lo <= n <= hi for lo, hi in spans)

    worst = []   # each whirling curve's least damped point where the shaft runs
    passed: list[tuple[int, str, float, float]] = []   # growth bands below the range
    for c in curves:
        if not c.whirling:
            continue
        seen_hz, logdec, words = c.seen_hz, c.log_dec, c.whirl
        best = None
        grow: list[float] = []
        for i, n in enumerate(c.speeds_rpm):
            if c.kinds[i] not in WHIRLING:
                continue
            d = float(logdec[i])
            if abs(d) <= 1e-6:
                d = 0.0
            if running(float(n)):
                if best is None or d < best[0]:
                    best = (d, c.number, float(n), float(seen_hz[i]), words[i])
            elif lift <= n < start and d < 0:
                grow.append(float(n))
        if best is not None:
            worst.append(best)
        if grow:
            passed.append((c.number, words[0], min(grow), max(grow)))
    if not worst:
        return None
    worst.sort()
    required = (rotor.min_log_dec if rotor.min_log_dec is not None
                else API684_LOG_DEC if scene.criterion == "api684" else 0.0)
    # the required log decrement holds for the modes [rotor] log_dec_modes names (API
    # 684: the forward modes, or the first of them); a mode that grows fails whatever it is
    forward = sorted((f, n) for _, n, _, f, w in worst if w == "forward")
    applies = {"all": {n for _, n, _, _, _ in worst}, "forward": {n for _, n in forward},
               "first_forward": {n for _, n in forward[:1]}}[rotor.log_dec_modes]
    held = [x for x in worst if x[1] in applies or x[0] < 0] or worst
    d, number, speed, f, whirl = held[0]
    damped = any(abs(float(x)) > 1e-6 for c in curves if c.whirling for x in c.log_dec)
    judged = damped or rotor.min_log_dec is not None
    failing = tuple((n, s, fr, w, x) for x, n, s, fr, w in held[1:]
                    if x < 0 or (judged and n in applies and x <= required))
    below = [n for n in sorted({lo / RPM for lo, _ in rotor.spans}) if n < lift]
    return Stability(curve=number, speed_rpm=speed, frequency_hz=f, whirl=whirl, log_dec=d,
                     required=required, judged=judged and number in applies, growing=d < 0,
                     others=failing, unjudged_rpm=tuple(below), passed=tuple(passed),
                     modes=rotor.log_dec_modes)


def reduced_reading(model: RotorModel, st: Stability | None) -> Stability | None:
    """The judged mode's log decrement read again with the tilting pads' synchronously
    reduced coefficients (the mode of the same whirl nearest in frequency): how far
    reducing the pads at the spin, as tools that do not keep their tilts do, moves it."""
    if st is None or not model.tilting:
        return st
    whirls = [w for w in whirl_at(replace(model, reduced=True), st.speed_rpm * RPM,
                                  max(2 * model.size, 1)) if w.whirl == st.whirl]
    if not whirls:
        return st
    near = min(whirls, key=lambda w: abs(w.frequency_hz - st.frequency_hz))
    return replace(st, reduced_log_dec=near.log_dec)


def divergent_bands(model: RotorModel, speeds: np.ndarray
                    ) -> list[tuple[float, float, float, float]]:
    """The speed bands where a root grows without oscillating: their edges (r/min),
    found by bisection between the diagram's speeds (to 1e-9 of the speed), and the
    fastest growth met in the band (1/s, over the diagram's speeds in it and its
    middle) with the speed it is met at (r/min)."""
    from shaftfem.fem.floquet import any_roots as roots

    def rate(omega: float) -> float:
        return roots(model, omega).divergence

    def band(lo: float, hi: float) -> tuple[float, float, float, float]:
        inside = [float(w) for w in speeds if lo <= w <= hi] + [0.5 * (lo + hi)]
        g, at = max((rate(w), w) for w in inside)
        return lo / RPM, hi / RPM, g, at / RPM

    values = [rate(om) for om in speeds]
    # two diverging speeds in a row may hold two bands (the soft and the stiff diameter's
    # of two modes): their middle is tried, as parametric_zones does
    between = [(w, v) for w in (0.5 * (speeds[i] + speeds[i + 1])
                                for i in range(len(speeds) - 1)
                                if values[i] > 0 and values[i + 1] > 0)
               for v in [rate(w)] if v <= 0]
    points = np.asarray(speeds, dtype=float)
    if between:
        merged = sorted([*zip(points, values), *between])
        points, values = np.array([w for w, _ in merged]), [v for _, v in merged]
    return [band(lo, hi) for lo, hi, _, _ in growth_spans(rate, points, values)]


def growth_spans(rate: Callable[[float], float], points: np.ndarray, values: list[float]
                 ) -> list[tuple[float, float, int, int]]:
    """The runs of `points` (rad/s, ascending) where `values` (rate at each) is positive:
    each run's edges (rad/s), bisected on rate between its first point and the one
    before, its last and the one after (to 1e-9 of the speed; the ends of `points` where
    a run reaches them), and the indices of its first and last point."""
    def edge(lo: float, hi: float, inside_high: bool) -> float:
        # the step may hold another zone beside this one: the bracket is narrowed first
        # to the last of ZONE_SPLITS parts, from the side inside, that still grows
        inner = np.linspace(lo, hi, ZONE_SPLITS + 1)[1:-1]
        for t in (inner[::-1] if inside_high else inner):
            grows = rate(t) > 0
            if inside_high:
                lo, hi = (lo, t) if grows else (t, hi)
            else:
                lo, hi = (t, hi) if grows else (lo, t)
            if not grows:
                break
        while hi - lo > 1e-9 * hi:
            mid = 0.5 * (lo + hi)
            if (rate(mid) > 0) == inside_high:
                hi = mid
            else:
                lo = mid
        return 0.5 * (lo + hi)

    spans, start, first = [], 0.0, -1
    for i, v in enumerate(values):
        if v > 0 and first < 0:
            start = points[0] if i == 0 else edge(points[i - 1], points[i], True)
            first = i
        if v <= 0 and first >= 0:
            spans.append((float(start), edge(points[i - 1], points[i], False), first, i - 1))
            first = -1
    if first >= 0:
        spans.append((float(start), float(points[-1]), first, len(values) - 1))
    return spans


def _onset_s_own(start: float, unstable: list[Onset], curves: list[Curve]) -> bool:
    """Whether a zone of growth starting at `start` (r/min) is a curve's own growth past
    its onset: an onset at or below it whose curve still grows there. The zone's edge
    lies a little above the onset (a form counts as growing from a log decrement of
    -ZONE_LOG_DEC), by as much as the curve's damping falls slowly."""
    by_number = {c.number: c for c in curves}
    for o in unstable:
        c = by_number.get(o.mode)
        if c is None:
            continue
        if abs(o.speed_rpm - start) <= 1e-4 * start:
            return True
        if o.speed_rpm < start and float(np.interp(start, c.speeds_rpm, c.decay)) < 0:
            return True
    return False


def parametric_zones(model: RotorModel, path: np.ndarray, curves: list[Curve],
                     divergent: list[tuple[float, float, float, float]]
                     ) -> list[tuple[float, float, float, bool, float]]:
    """The zones (r/min) where a periodic rotor grows, their fastest growth (1/s),
    whether it grows there without oscillating (a divergence the diagram's speeds
    missed) or while it oscillates (parametric and combination resonances, bands above
    an onset), and where the fastest growth is met (r/min).
    Sought on the diagram's speeds and, whatever the grid, where two curves' turning-
    frame frequencies f_a + f_b or f_a - f_b (a = b too) meet 2 k n (n the speed, Hz,
    |k| up to PARAMETRIC_ORDER): Floquet exponents are one modulo i 2 Omega, and two
    forms that meet so can lock and grow. Edges by bisection on the growth (to 1e-9 of
    the speed); a band the divergence already holds is left to it."""
    from shaftfem.fem.floquet import any_roots
    from shaftfem.fem.tracking import REACH, _at

    def rate(omega: float) -> float:
        r = any_roots(model, omega)
        g = r.lam.real - growth_floor(r.lam, omega)
        return max(float(g.max(initial=-math.inf)), r.divergence or -math.inf)

    def still(omega: float) -> bool:   # grows without oscillating (a divergence)
        r = any_roots(model, omega)
        return r.divergence > 0 and r.divergence >= float(r.lam.real.max(initial=-math.inf))

    def meeting(a: Curve, i: int, b: Curve, j: int, sign: int, k: int, F0: float,
                F1: float) -> list[float]:
        """Where (f_a + sign f_b) / (2 n) - k falls through zero between the curves'
        speeds i and i + 1 (j and j + 1 of b), by regula falsi on the curves followed by
        shape (rad/s): the speeds tried."""
        w0, w1 = a.speeds_rpm[i] * RPM, a.speeds_rpm[i + 1] * RPM
        reach = REACH * (w1 - w0) / (2 * math.pi)

        def F(w: float) -> float:
            t = (w - w0) / (w1 - w0)
            fa = _at(model, w, a.shapes[:, i], (1 - t) * a.signed_hz[i]
                     + t * a.signed_hz[i + 1], reach + 1e-3 * abs(a.signed_hz[i]))[0]
            fb = _at(model, w, b.shapes[:, j], (1 - t) * b.signed_hz[j]
                     + t * b.signed_hz[j + 1], reach + 1e-3 * abs(b.signed_hz[j]))[0]
            return math.pi * (fa + sign * fb) / w - k

        tried = []
        for _ in range(PARAMETRIC_STEPS):
            w = w0 - F0 * (w1 - w0) / (F1 - F0)
            if not w0 < w < w1:
                break
            tried.append(float(w))
            Fw = F(w)
            if Fw == 0.0 or rate(w) > 0:
                break
            if (Fw > 0) == (F0 > 0):
                w0, F0, F1 = w, Fw, 0.5 * F1   # (Illinois: the stale end halved)
            else:
                w1, F1, F0 = w, Fw, 0.5 * F0
        return tried

    def held_apart(a: Curve, i: int, b: Curve, j: int) -> bool:
        """Whether the two forms' mean decay rate beats PARAMETRIC_MARGIN times what the
        turning parts couple them by, |y_a^H K_+- y_b| / (2 sqrt(w_a w_b)) (first-order
        theory: no zone opens where the damping exceeds the coupling)."""
        w = a.speeds_rpm[i] * RPM
        if w not in parts:   # (every pair asks the same speeds)
            parts[w] = model.periodic_parts(w)[2:]
        Kc, Ks = parts[w]
        ya, yb = a.shapes[:, i], b.shapes[:, j]
        ya, yb = ya / np.linalg.norm(ya), yb / np.linalg.norm(yb)
        couple = max(abs(ya.conj() @ (Kc - 1j * Ks) @ yb),
                     abs(ya.conj() @ (Kc + 1j * Ks) @ yb),
                     abs(ya.conj() @ (Kc - 1j * Ks) @ yb.conj()),
                     abs(ya.conj() @ (Kc + 1j * Ks) @ yb.conj())) / 2
        wa = max(2 * math.pi * abs(a.signed_hz[i]), w)
        wb = max(2 * math.pi * abs(b.signed_hz[j]), w)
        return 0.5 * (a.decay[i] + b.decay[j]) > PARAMETRIC_MARGIN * couple / (
            2 * math.sqrt(wa * wb))

    parts: dict[float, tuple[np.ndarray, ...]] = {}
    speeds = {float(w) for w in path if w > 0 and model.periodic(float(w))}
    grid = np.array(sorted(speeds))
    if grid.size < 2:
        return []
    lo_rpm = grid[0] / RPM
    # the candidates between the diagram's speeds: each curve's frequency linear there
    for a in curves:
        for b in curves:
            if b.number < a.number:
                continue
            for sign in ((1,) if a is b else (1, -1)):
                for i in range(len(a.speeds_rpm) - 1):
                    n0, n1 = a.speeds_rpm[i], a.speeds_rpm[i + 1]
                    if n0 < lo_rpm or n1 <= n0:
                        continue
                    j = np.flatnonzero(np.isclose(b.speeds_rpm, n0))
                    if not j.size or j[0] + 1 >= len(b.speeds_rpm):
                        continue
                    g0 = a.signed_hz[i] + sign * b.signed_hz[j[0]]
                    g1 = a.signed_hz[i + 1] + sign * b.signed_hz[j[0] + 1]
                    r0, r1 = 30 * g0 / n0, 30 * g1 / n1   # (f_a +- f_b) / (2 n)
                    ks = [k for k in range(-PARAMETRIC_ORDER, PARAMETRIC_ORDER + 1)
                          if (r0 - k) * (r1 - k) < 0]
                    step = PARAMETRIC_SLOPE * (n1 - n0) / 60
                    # (a sign that flips is the form's sense kept, not a jump)
                    jumps = (abs(abs(a.signed_hz[i + 1]) - abs(a.signed_hz[i])) > step
                             or abs(abs(b.signed_hz[j[0] + 1]) - abs(b.signed_hz[j[0]])) > step)
                    if not ks or jumps or held_apart(a, i, b, int(j[0])):
                        continue
                    for k in ks:
                        speeds.update(meeting(a, i, b, int(j[0]), sign, k, r0 - k, r1 - k))
    points = np.array(sorted(speeds))
    values = [rate(w) for w in points]

    # two growing speeds in a row may hold two zones: their middle is tried
    between = [(w, v) for w, v in ((0.5 * (points[i] + points[i + 1]), None)
                                    for i in range(len(points) - 1)
                                    if values[i] > 0 and values[i + 1] > 0)
               for v in [rate(w)] if v <= 0]
    if between:
        merged = sorted([*zip(points, values), *between])
        points, values = np.array([w for w, _ in merged]), [v for _, v in merged]

    zones = []
    for lo, hi, first, last in growth_spans(rate, points, values):
        at = first + int(np.argmax(values[first:last + 1]))
        zones.append((lo / RPM, hi / RPM, values[at], still(points[at]), points[at] / RPM))
    held = [(b[0], b[1]) for b in divergent]
    return [z for z in zones
            if not any(lo <= 0.5 * (z[0] + z[1]) <= hi for lo, hi in held)]


def growth_floor(lam: np.ndarray, omega: float) -> np.ndarray:
    """The growth rate (1/s) each exponent must pass to count as growing in a zone: a log
    decrement below -ZONE_LOG_DEC (an undamped mode that the periodic coefficients
    leave a few millionths from neutral, the torsion of a keyed pump on journals, is
    held by any structure's own damping), and round-off."""
    return (ZONE_LOG_DEC / (2 * math.pi) * np.abs(lam.imag)
            + ROUND_OFF * np.maximum(np.abs(lam), omega))


def with_sides(model: RotorModel, cv: Curve) -> Curve:
    """The curve with its Floquet form's shares in the harmonics beside its dominant one
    at each of its speeds where the rotor is periodic (fem.floquet.SIDES either side),
    read from the roots there: the root of its frequency and decay (a curve that keeps
    the form's conjugate sees its harmonics mirrored)."""
    from shaftfem.fem.floquet import SIDES, any_roots

    size = 2 * SIDES + 1
    share, index = np.zeros((size, cv.speeds_rpm.size)), np.zeros((size, cv.speeds_rpm.size))
    for i, n in enumerate(cv.speeds_rpm):
        w = float(n) * RPM
        if w <= 0 or not model.periodic(w):
            continue
        r = any_roots(model, w)
        if r.sides is None or r.side_index is None or not r.lam.size:
            continue
        f = 2 * math.pi * cv.signed_hz[i]
        j = int(np.argmin(np.abs(np.abs(r.lam.imag) - abs(f)) + np.abs(r.lam.real + cv.decay[i])))
        flip = (f < 0) != (r.lam.imag[j] < 0)
        share[:, i] = r.sides[::-1, j] if flip else r.sides[:, j]
        index[:, i] = -r.side_index[::-1, j] if flip else r.side_index[:, j]
    return replace(cv, sides=share, side_index=index)


def zones_agree(model: RotorModel, edges: list[float], lowest: float, highest: float
                ) -> str | None:
    """Hill's method against the monodromy matrix at the edges (rad/s) of a periodic
    rotor's zones of growth (divergence bands, onsets): at ZONE_SIDE of the speed either
    side of each edge, both routes must agree on whether the rotor grows (the fastest
    growth ln |mu| / T of every form against Hill's largest Re lam), or a SolverError.
    The edges at the diagram's ends are not edges; None without edges to check."""
    from shaftfem.fem.floquet import apart, converged_hill, multipliers

    checked = []
    for w in edges:
        if not lowest < w < highest or not model.periodic(w):
            continue
        for side in (w * (1 - ZONE_SIDE), w * (1 + ZONE_SIDE)):
            lam = converged_hill(model, side).lam
            mono = np.log(multipliers(model, side).astype(complex)) * side / math.pi
            # each of Hill's exponents against the monodromy's nearest (frequency modulo
            # 2 Omega): its growth by the other route
            partner = mono[np.argmin(apart(lam, mono, side), axis=1)]
            floor = growth_floor(lam, side)
            hill, other = bool(np.any(lam.real > floor)), bool(np.any(partner.real > floor))
            if hill != other:
                g = float(lam.real.max())
                m = float(partner.real.max())
                raise SolverError(
                    f"at {side / RPM:,.1f} r/min, {100 * ZONE_SIDE:g} % from the edge of a zone "
                    f"of growth at {w / RPM:,.1f} r/min, Hill's method says the rotor "
                    f"{'grows' if hill else 'decays'} ({g:.3g} 1/s) and the monodromy "
                    f"matrix that it {'grows' if other else 'decays'} ({m:.3g} 1/s): "
                    "no stability verdict rests on either")
        checked.append(w / RPM)
    if not checked:
        return None
    return (f"the edges of the zones of growth ({', '.join(f'{n:,.0f}' for n in checked)} "
            f"r/min): Hill's method and the monodromy matrix agree whether the rotor grows "
            f"{100 * ZONE_SIDE:g} % either side of each")


def routes_agree(model: RotorModel, speeds: tuple[float, ...]) -> str:
    """Hill's method against the monodromy matrix at the operating `speeds` (rad/s) of a
    periodic rotor: what they agree within, or a SolverError where they disagree."""
    from shaftfem.fem.floquet import RESOLVED, ROUTES_TOL, growth_apart

    worst = 0.0
    for omega in speeds:
        if not model.periodic(omega):
            continue
        d = growth_apart(model, omega)
        if d > ROUTES_TOL:
            raise SolverError(f"at {omega / RPM:,.0f} r/min Hill's method and the monodromy "
                              f"matrix disagree on a Floquet exponent by {d:.2g} of it "
                              f"(they must agree within {ROUTES_TOL:g}): no stability verdict "
                              "rests on either")
        worst = max(worst, d)
    return (f"Floquet exponents at the operating speed(s): Hill's method and the monodromy "
            f"matrix agree within {worst:.1g} of each (the forms decaying by less than "
            f"{RESOLVED:g} a period)")


def truncation(model: RotorModel, speeds: tuple[float, ...], count: int) -> Truncation:
    """The roots of the `count` reported modes on the whole basis against its first
    CHECK_SHARE, at `speeds` (rad/s): the largest relative change of the eigenvalue
    (for a lightly damped mode, of its frequency)."""
    smaller = max(count + 1, math.ceil(CHECK_SHARE * model.size))
    smaller = min(smaller, model.size)
    change = 0.0
    def root(w: Whirl) -> complex:   # the eigenvalue, Hz: -sigma + i f
        return w.frequency_hz * complex(-w.log_dec / (2 * math.pi), 1.0)

    for omega in speeds:
        full = whirl_at(model, omega, count)
        part = whirl_at(model.truncated(smaller), omega, count)
        if model.periodic(omega):
            # a Floquet exponent is one modulo i 2 Omega: its dominant component may be
            # the other copy on the smaller basis (a form with near-equal shares)
            # (the overdamped forms, which Hill's method does not settle, left out)
            from shaftfem.fem.floquet import matched_change, not_overdamped

            def exponents(ws: list[Whirl]) -> np.ndarray:
                lam = np.array([2 * math.pi * w.rotating_frame_hz
                                * complex(-w.log_dec / (2 * math.pi), 1.0) for w in ws])
                return lam[not_overdamped(lam)]
            a_, b_ = exponents(full), exponents(part)
            if a_.size:
                change = max(change, matched_change(a_, b_, omega) / float(np.abs(a_).max()))
            continue
        for a, b in zip(full, part):
            # a heavily damped root (a rotor on oil films at a few hertz) moves little in
            # the complex plane though its frequency moves by a large share of itself
            change = max(change, abs(root(b) - root(a)) / abs(root(a)))
    return Truncation(size=model.size, smaller=smaller,
                      speeds_rpm=tuple(o / RPM for o in speeds), change=change)


def turning(scene: Scene, options: RunOptions = RunOptions()
            ) -> tuple[ModalResult, RotorModel, str]:
    """The scene's standstill modes (the basis), the turning shaft on them, and why its
    frame: built once per scene in a process (`_MODELS`), so that a study's Campbell
    diagram, Level I, run-up and receptance share it; a tolerance case (the same shaft,
    only its bearings' coefficients changed) turns on the nominal case's basis, which
    holds the bearings' static shapes (its residual modes) and so takes any
    coefficients exactly to first order (tests/test_journal_bearing.py: 1e-6 for 32
    times the stiffness). A basis that [rotor] basis_modes does not fix is doubled while
    the reported whirl still moves by more than TRUNCATION on it."""
    from shaftfem.workflows.static import equipped

    scene = equipped(scene, options)
    key, shaft_key = _model_keys(scene, options)
    if key in _MODELS:
        _MODELS[key] = _MODELS.pop(key)   # the last used is the last to go
        return _MODELS[key]
    shared = _MODELS.get(shaft_key)
    if shared is not None:
        out = _on_basis(scene, *shared)
        if out is not None:
            return _kept(key, shaft_key, out)
    return _kept(key, shaft_key, _turned(scene, options))


# The rotor models built in this process, by the content of their scene (and by their
# shaft's alone, for the tolerance cases): few, each a basis of tens of MB at most.
_MODELS: dict[str, tuple[ModalResult, RotorModel, str]] = {}
KEPT_MODELS = 3


def _model_keys(scene: Scene, options: RunOptions) -> tuple[str, str]:
    """A scene's key, and its shaft's: the scene with its bearings' coefficients and
    their declarations left out (what a tolerance case changes)."""
    import hashlib

    bare = replace(scene, supports=tuple(
        replace(s, bearing=None, journal=None, seal=None, tolerance=None)
        if s.journal is not None or s.seal is not None else s for s in scene.supports))

    def key(what: Scene, kind: str) -> str:
        return kind + hashlib.sha256(f"{options.factoriser}|{what!r}".encode()).hexdigest()

    return key(scene, "scene:"), key(bare, "shaft:")


def _kept(key: str, shaft_key: str, out: tuple[ModalResult, RotorModel, str]
          ) -> tuple[ModalResult, RotorModel, str]:
    _MODELS.pop(key, None)
    _MODELS[key] = out
    _MODELS.setdefault(shaft_key, out)
    while len(_MODELS) > 2 * KEPT_MODELS:
        _MODELS.pop(next(iter(_MODELS)))
    return out


def _on_basis(scene: Scene, result: ModalResult, model: RotorModel, why: str
              ) -> tuple[ModalResult, RotorModel, str] | None:
    """The scene turning on another case's basis: its bearings' coefficients in the
    model, the basis (and its standstill run) as they are; None where the scene is not
    one of those cases (another frame, other bearings) or where the whirl would still
    move on a larger basis."""
    frame, _ = choose_frame(scene)
    coefficients = {s.name: s.bearing for s in scene.held if s.bearing is not None}
    names = {b.name for b in model.bearings if not b.name.endswith(" (stage)")}
    if frame != model.frame or names != set(coefficients):
        return None
    bearings = tuple(b if b.name not in coefficients
                     else replace(b, coefficients=coefficients[b.name])
                     for b in model.bearings)
    rotor = scene.rotor
    assert rotor is not None
    moved = replace(model, bearings=bearings)
    speeds = tuple(sorted({*rotor.speeds, rotor.max_speed}))
    if (not rotor.basis_modes and model.size - model.residual < MAX_MODE_COUNT
            and truncation(moved, speeds, scene.modes.count).change > TRUNCATION):
        return None
    return result, moved, why


def _turned(scene: Scene, options: RunOptions) -> tuple[ModalResult, RotorModel, str]:
    """The scene's basis and rotor model, built."""
    from shaftfem.fem.rotor import rotor_model
    from shaftfem.workflows.pipeline import run_modes, with_modes

    frame, why = choose_frame(scene)
    if frame == "rotating":
        # the basis is turned with the shaft past the bearings: made on their mean stiffness
        # it looks alike from every angle (a periodic rotor's deviatoric part then acts on
        # a basis that does not favour the angle the standstill run was made at)
        scene = replace(scene, supports=tuple(
            replace(s, mean_seat=True) if s.bearing is not None and not s.bearing.isotropic
            else s for s in scene.supports))
    if scene.mesh.order > 2:
        raise SceneError(f"{scene.source}: element order {scene.mesh.order}: the turning shaft "
                         "takes orders 1 and 2")
    size = basis_size(scene)
    rotor = scene.rotor
    assert rotor is not None
    if rotor.basis_modes and rotor.basis_modes < scene.modes.count + 2:
        raise SceneError(f"{scene.source}: [rotor] basis_modes = {rotor.basis_modes}: the "
                         f"basis must hold the {scene.modes.count} modes asked and more to "
                         f"check them on: at least {scene.modes.count + 2} (or leave it out)")
    speeds = tuple(sorted({*rotor.speeds, rotor.max_speed}))
    while True:
        result = run_modes(with_modes(scene, count=size), options)
        options.say(f"whirl on {result.modes.count} standstill modes, {frame} frame")
        model = rotor_model(result, frame)
        if model.periodic(rotor.max_speed):
            from shaftfem.fem.floquet import widen

            model = widen(model, rotor.speeds, scene.modes.count + 2)
            options.say("periodic rotor: Floquet exponents by Hill's method at every speed "
                        "(a slow run: minutes on a rotor in journals)")
        # the basis is enlarged while the whirl still moves on it (from two thirds of it)
        if rotor.basis_modes:
            return result, model, why
        change = truncation(model, speeds, scene.modes.count).change
        if change <= TRUNCATION:
            return result, model, why
        if size >= MAX_MODE_COUNT:
            raise SolverError(
                f"{scene.source}: the whirl does not settle on the standstill modes: on "
                f"{size} of them it still moves by {change * 100:.2g} % from two thirds of "
                f"them (at most {TRUNCATION * 100:g} % allowed): check the bearings' and "
                "parts' inputs (a stiffness or clearance off by a unit makes modes the "
                "basis cannot hold), or fix [rotor] basis_modes to take the whirl as it is")
        size = min(2 * size, MAX_MODE_COUNT)
        options.say(f"the whirl still moves on the basis by {change * 100:.2g} %: {size} "
                    "standstill modes")


def run_campbell(scene: Scene, options: RunOptions = RunOptions(),
                 speeds_rpm: np.ndarray | None = None) -> Campbell:
    """The scene's shaft turning: its standstill modes, then the whirl at every speed of
    the Campbell diagram (`speeds_rpm`, default 0 to [rotor] max_speed_rpm at
    [rotor] campbell_points) and at the operating speeds, the critical speeds, the
    stability and the basis check, and the unbalance response."""
    from shaftfem.workflows.static import equipped

    scene = equipped(scene, options)
    result, model, why = turning(scene, options)
    return campbell_of(scene, result, model, why, speeds_rpm)


def campbell_of(scene: Scene, result: ModalResult, model: RotorModel, why: str,
                speeds_rpm: np.ndarray | None = None) -> Campbell:
    """run_campbell's diagram of the turning shaft `model` on the standstill `result`."""
    from shaftfem.fem.tracking import reach, reported, track

    rotor = scene.rotor
    assert rotor is not None
    frame = model.frame
    count = scene.modes.count
    grid = (np.linspace(0.0, rotor.max_speed, rotor.points) if speeds_rpm is None
            else np.asarray(speeds_rpm, dtype=float) * RPM)
    orders = rotor_orders(scene)
    # the curves the basis check vouches for, and those below the highest order line
    # within the part of the basis it checks them on
    within = max(count + 1, math.ceil(CHECK_SHARE * model.size))
    ends = [w for span in rotor.spans for w in span]
    floor = 0.0
    if any(model.periodic(float(w)) for w in grid if w > 0):
        from shaftfem.fem.floquet import HILL_MAX, HILL_WIDE, solved_from

        floor = solved_from(model, grid, 0.01 * float(grid.max()))
    while True:
        periodic_note = None
        if floor > 0:
            # the curves start where Hill's method settles (their steps are halved between
            # speeds: from standstill they would reach below it)
            periodic_note = (f"periodic rotor: solved by Floquet theory from "
                             f"{floor / RPM:,.0f} r/min; below it the Floquet forms spread over "
                             "more harmonics than the diagram's solves take (up to "
                             f"{HILL_MAX}), and no crossing is searched there"
                             + ("; the operating speeds below it are solved with up to "
                                f"{HILL_WIDE} harmonics" if any(0 < w < floor for w in rotor.speeds)
                                else ""))
            grid = np.union1d([floor], grid[grid >= floor])
        # the curves pass through every operating speed and range end
        path = np.union1d(grid, [w for w in ends if grid.min() <= w <= grid.max()])
        try:
            every = track(model, path, count + 2)
            curves = reported(every, count, max(orders), within)
            if periodic_note:
                curves = [with_sides(model, cv) for cv in curves]
            rows = [whirl_at(model, om, count) for om in grid]
            critical, check = critical_speeds(model, curves, orders, float(grid.max()))
            break
        except UnsettledError as e:
            # a speed between the diagram's that Hill's method does not settle (slow
            # spins do not settle alike): the diagram starts above it
            above = path[path > e.omega * (1 + 1e-9)]
            if floor <= 0 or e.omega >= min((w for w in rotor.speeds if w > 0),
                                            default=math.inf) or above.size < 2:
                raise
            floor = float(above[0])
    operating = [w for om in rotor.speeds for w in whirl_at(model, om, count)]
    shapes = tuple(mode_shapes(model, om, count) for om in rotor.speeds)
    basis = truncation(model, tuple(sorted({*rotor.speeds, float(grid.max())})), count)
    notes = [periodic_note] if periodic_note else []
    if periodic_note:
        notes.append(routes_agree(model, rotor.speeds))
    if not scene.held:
        notes.append("the shaft hangs free (no [[support]]): its whirl is a free rotor's")
    if not any(s.bearing is not None and np.any(np.array(s.bearing.cxx + s.bearing.cyy
                                                         + s.bearing.cxy + s.bearing.cyx))
               for s in scene.held):
        neutral = all(abs(float(x)) <= 1e-6 for c in curves if c.whirling for x in c.log_dec)
        notes.append("no bearing has damping (kind = \"bearing\" with cxx_n_s_per_mm ...): "
                     + ("the log decrements are zero and no amplification factor can be given"
                        if neutral else "the log decrements come from the cross-coupling and "
                        "the parts' forces alone, and no amplification factor can be given"))
    top_rpm = float(grid.max()) / RPM
    searched = reach(every, within, top_rpm)
    coverage = None
    if max(orders) * top_rpm / 60.0 > searched:
        coverage = (f"the {max(orders)}x line reaches {max(orders) * top_rpm / 60:.0f} Hz at "
                     f"{top_rpm:,.0f} r/min, and the crossings are searched up to "
                     f"{searched:.0f} Hz there (the lower two thirds of the "
                    f"{model.size}-mode basis): raise [rotor] basis_modes to search higher")
        notes.append(coverage)
    if check.direct_only:
        notes.append(f"{check.direct_only} crossing(s) found only by the direct route were "
                     "added: the diagram's curves missed them")
    lift = lift_speed(scene) / RPM
    # below the journals' lift-off the journal runs on its shell and the film's
    # coefficients are placeholders: no crossing there is a critical speed
    shell = [cs for cs in critical if cs.speed_rpm < lift]
    if shell:
        critical = [cs for cs in critical if cs.speed_rpm >= lift]
        notes.append(f"{len(shell)} crossing(s) below the journals' lift-off ({lift:,.0f} "
                     "r/min) left out: the journal runs on its shell there, and the film's "
                     "coefficients are placeholders")
    stability = reduced_reading(model, least_damped(scene, curves, lift))
    unstable = onsets(model, curves)
    # a root stands at zero frequency in the turning frame where the 1x line crosses it:
    # between two such crossings (the soft and the stiff diameter's critical speeds of a
    # shaft not of revolution) it may diverge, in a band narrower than the grid's step
    ones = sorted(cs.speed_rpm * RPM for cs in critical if cs.order == 1)
    between = [0.5 * (a + b) for a, b in zip(ones, ones[1:])
               if float(path.min()) < a and b < float(path.max())]
    bands = divergent_bands(model, np.union1d(path, between) if between else path)
    zones: list[tuple[float, float, float, float]] = []
    top = float(path.max()) / RPM
    if periodic_note:
        found = parametric_zones(model, path, curves, bands)
        bands = sorted([*bands, *((z[0], z[1], z[2], z[4]) for z in found if z[3])])
        # a zone that an onset opens and the diagram's end closes is the onset's own
        zones = [(z[0], z[1], z[2], z[4]) for z in found if not z[3] and not (
            z[1] >= top * (1 - 1e-9) and _onset_s_own(z[0], unstable, curves))]
        agree = zones_agree(model, [w * RPM for b in [*bands, *zones] for w in b[:2]]
                            + [o.speed_rpm * RPM for o in unstable],
                            float(path.min()), float(path.max()))
        if agree:
            notes.append(agree)
    response = None
    if scene.unbalances:
        from shaftfem.workflows.unbalance import forward_only, unbalance_response

        driven = [cs.speed_rpm for cs in critical if cs.order == 1
                  and not cs.critically_damped
                  and not (forward_only(scene, frame) and cs.whirl == "backward")]
        response = unbalance_response(scene, result, model, criticals=driven)
    from shaftfem.workflows.unbalance import weight_whirl

    weight = weight_whirl(scene, result, model)
    return Campbell(frame=frame, why=why, speeds_rpm=tuple(grid / RPM),
                    whirl=tuple(w for r in rows for w in r), operating=tuple(operating),
                    operating_rpm=tuple(om / RPM for om in rotor.speeds),
                    critical_speeds=tuple(critical), orders=orders, truncation=basis,
                    result=result, notes=tuple(notes), unbalance=response,
                    onsets=tuple(unstable), divergent=tuple(b[:2] for b in bands),
                    divergent_growth=tuple(b[2] for b in bands),
                    parametric=tuple(z[:3] for z in zones),
                    zones=growth_zones(
                        [(lo, hi, g, at, "divergence") for lo, hi, g, at in bands]
                        + [(lo, hi, g, at, "parametric") for lo, hi, g, at in zones]
                        + [(o.speed_rpm, top if o.until_rpm is None else o.until_rpm,
                            o.growth_per_s, o.fastest_rpm, f"curve {o.curve_text}")
                           for o in unstable], top),
                    operating_shapes=shapes,
                    synchronous_check=check.largest_difference, crossing_check=check,
                    curves=tuple(curves), stability=stability,
                    ranges_rpm=tuple((lo / RPM, hi / RPM) for lo, hi in rotor.ranges),
                    scene=scene, coverage=coverage, films=film_rows(scene),
                    lift_rpm=lift, weight_2x=weight,
                    basis=model.shapes)


def film_rows(scene: Scene) -> tuple[FilmRow, ...]:
    """Each journal bearing at each operating speed and range end: its film there."""
    import math

    from shaftfem.parts import heat, oil, pad_heat
    from shaftfem.parts.journal import operating

    rotor = scene.rotor
    if rotor is None:
        return ()
    speeds = sorted({*rotor.speeds, *(w for span in rotor.spans for w in span)})
    rows = []
    for s in scene.held:
        b = s.journal
        if b is None:
            continue
        for w in speeds:
            supply = b.oil_supply_temperature
            h = None if supply is None or w <= 0 else heat.heat_balance(b, w, supply)
            op = operating(b if h is None else heat.running(b, h), w)
            warm: dict = {}
            if supply is not None and h is not None:
                power, into_oil, side = h.power, h.power, h.side_flow
                film_c = h.effective
                if b.bore is not None and b.bore.kind == "tilting_pad" and w > 0:
                    try:
                        thd = pads_heat(b, w)
                    except ValueError as e:
                        raise SceneError(
                            f"{scene.source}: journal bearing {s.name!r} at {w / RPM:,.0f} "
                            f"r/min: {e} (its oil_supply_temperature_c, radial_clearance_um "
                            "and pad_thickness_mm set its pads' heated film)") from None
                    op = pad_heat.heated_operating(b, thd, w, op)
                    peaks = tuple(float(t.max()) for t in thd.surface)
                    # the friction, the supply drawn and the drain from the same heated
                    # film as the peaks (each pad's shear at its own viscosity), with
                    # the share the journal takes and sheds along the shaft
                    power, into_oil, side = thd.power, thd.power - thd.journal_power, thd.fresh
                    film_c = thd.journal   # the films' mean, as the coefficients have it
                    warm.update(pad_peak_c=max(peaks), pad_limit_c=b.pad_limit,
                                pad_peaks_c=peaks, journal_w=thd.journal_power,
                                hot_clearance_um=min(thd.clearance) * 1e6)
                # the supply carries off the film's heat: it drains warmer by H / (rho c Q)
                drain = None if b.oil_flow is None else supply + into_oil / (
                    oil.density(supply) * heat.SPECIFIC_HEAT * b.oil_flow)
                warm.update(supply_c=supply, film_c=film_c, power_w=power,
                            side_flow=side, flow=b.oil_flow, drain_c=drain)
            rows.append(FilmRow(
                bearing=s.name, speed_rpm=w / RPM, eccentricity=op.eccentricity,
                attitude_deg=math.degrees(op.attitude), min_film_um=op.min_film * 1e6,
                sommerfeld=op.sommerfeld, K=tuple(float(v) for v in op.K.ravel()),
                C=tuple(float(v) for v in op.C.ravel()), limit_um=b.min_film * 1e6,
                lifted=not op.beyond, **warm))
    return tuple(rows)


def pads_heat(b, omega: float):
    """A tilting pads' journal's heated film (parts.pad_heat.PadsHeat) at the spin omega
    (rad/s), fed at its supply temperature, its parts grown by their heat: its pads from
    the first past the load's line in the journal's turn."""
    from shaftfem.parts import journal, pad_heat

    return pad_heat.heated_at(journal.with_oil(b), omega)


def whirl_table(scene: Scene, speed_rpm: float, options: RunOptions = RunOptions()
                ) -> Campbell:
    """The shaft turning at one speed (r/min): the scene's [rotor] with that speed as its
    operating one (a scene without [rotor] takes its defaults)."""
    from shaftfem.scene.model import Rotor

    omega = speed_rpm * RPM
    rotor = scene.rotor or Rotor(speeds=(omega,), max_speed=omega)
    scene = replace(scene, rotor=replace(rotor, speeds=(omega,), max_speed=omega, ranges=()))
    return run_campbell(scene, options, np.array([0.0, speed_rpm]))


def speed_grid(start_rpm: float, stop_rpm: float, count: int) -> np.ndarray:
    """`count` speeds from start to stop, r/min."""
    return np.linspace(start_rpm, stop_rpm, count)


def rotor_orders(scene: Scene) -> tuple[int, ...]:
    """The excitation orders of the shaft's own speed: 1x always, and the orders of
    every [[excitation]] that runs at an operating speed of the shaft."""
    rotor = scene.rotor
    assert rotor is not None
    orders = {1}
    for e in scene.excitations:
        if any(abs(e.frequency * 2 * math.pi - om) <= 1e-9 * om for om in rotor.speeds):
            orders.update(e.orders)
    return tuple(sorted(orders))
