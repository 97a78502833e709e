"""The resonance check of a shaft that turns ([rotor]): its critical speeds against
its operating speeds, and its whirl at the operating speeds against every other
source's harmonics.

- A harmonic of the shaft's own speed (a source at an operating speed, 1x always) is
  met where a whirl curve crosses its order line: the critical speed N_c, with the
  speed margin |N_c - N| / N from each operating speed N, or from an operating range
  ([rotor] speed_range_rpm) 0 inside it and measured to its nearer end outside. At 1x
  an unbalance drives forward whirl only on a shaft of revolution in isotropic
  bearings, so there backward 1x crossings are not judged;
  elsewhere (anisotropic bearings, a shaft that is not of revolution) both are. A
  crossing of a critically damped mode (AF below 2.5, an oil film's rigid-body roots)
  is not a critical speed to keep clear of: listed, never judged (API 684).
- Any other source's harmonic k f is met by the whirl frequencies at each operating
  speed, forward and backward, margin |f - k f| / (k f).
- Torsion and axial modes do not whirl: they meet every harmonic as at standstill.

- Stability, judged where the shaft runs (API 684): a whirling mode that grows, or
  whose log decrement is at or below [rotor] min_log_dec (API 684's 0.1 with criterion
  "api684"), at an operating speed or inside a running range fails; so does a
  divergence band inside the running range. Growth the shaft passes through below its
  range, onsets and bands beyond it are warnings with their speeds. Below the journals'
  lift-off the film's coefficients are placeholders: no verdict there.

The required margin is the scene's flat one, or with criterion "api684" that of each
mode's amplification factor AF = pi / log dec (none below AF 2.5; an undamped model
has none to give, and gets 17 % below and 27 % above the operating speed).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from shaftfem.checks.resonance import Approach, ResonanceVerdict, api684_margin
from shaftfem.fem.whirl import RPM

if TYPE_CHECKING:
    from shaftfem.fem.whirl import Campbell
    from shaftfem.scene.model import Scene



def amplification(log_dec: float) -> float:
    """A mode's amplification factor from its log decrement (fem.whirl's
    amplification_factor: pi / delta when light, never below 1/2)."""
    from shaftfem.fem.whirl import amplification_factor

    return amplification_factor(log_dec)


def forward_only(scene: Scene, frame: str) -> bool:
    """Whether an unbalance drives forward whirl only: a shaft of revolution in
    isotropic bearings (its backward modes it reaches only through the mesh's own
    small asymmetry)."""
    return scene.axisymmetric and (frame == "rotating" or all(
        s.bearing is None or s.bearing.isotropic for s in scene.held))


def span_margin(n_c: float, lo: float, hi: float) -> tuple[float, bool]:
    """A critical speed's separation margin from an operating span [lo, hi] (r/min; a
    single speed has lo = hi): 0 inside it, else the distance to the nearer end as a
    fraction of that end; and whether the critical speed lies above the span."""
    if lo <= n_c <= hi:
        return 0.0, False
    if n_c < lo:
        return (lo - n_c) / lo, False
    return (n_c - hi) / hi, True


def _span_text(lo: float, hi: float) -> str:
    return f"{lo:,.0f} r/min" if lo == hi else f"{lo:,.0f}-{hi:,.0f} r/min"


def stability_findings(c: Campbell) -> tuple[list[str], list[str], list[str]]:
    """What fails the turning shaft's stability (a mode that grows), what fails its
    required damping (a mode that decays, but with a log decrement at or below
    min_log_dec), and what is only warned of. Judged
    where API 684 judges it, where the shaft runs: a whirling mode that grows, or is
    damped less than required, at an operating speed or inside a running range fails,
    as does an onset of growth or a divergence band inside the running range. A band of
    growth the shaft passes through below its range, and an onset beyond it, are
    warnings with their speeds. Below the journals' lift-off there is no verdict."""
    rotor = c.rotor_scene.rotor
    assert rotor is not None
    spans = [(lo / RPM, hi / RPM) for lo, hi in rotor.spans]
    fails, short, warns = [], [], []
    st = c.stability
    if st is not None and not st.ok:
        for n, speed, f, whirl, d in [(st.curve, st.speed_rpm, st.frequency_hz, st.whirl,
                                       st.log_dec), *st.others]:
            if d < 0:
                fails.append(f"curve {n} ({whirl} whirl, {f:.2f} Hz) grows: log decrement "
                             f"{d:.3g} at {speed:,.0f} r/min")
            else:   # stable, but with less margin than required: no instability
                short.append(f"curve {n} ({whirl} whirl, {f:.2f} Hz) is damped less than "
                             f"required: log decrement {d:.3g} at {speed:,.0f} r/min, "
                             f"{st.required:g} required of {st.applies_text} "
                             "([rotor] min_log_dec, log_dec_modes)")
    elif st is not None and not st.judged:
        warns.append("stability not judged: no damping in the model (every log decrement is "
                     "zero); give the bearings' damping, or [rotor] min_log_dec")
    lift = c.lift_rpm
    below = [lo for lo, _ in spans if lo < lift]
    if below:
        warns.append(
            f"no stability verdict at {', '.join(f'{n:,.0f}' for n in below)} r/min: the "
            f"journals' films lift their journals only from {lift:,.0f} r/min (below it the "
            "journal runs on its shell and the film's coefficients are placeholders)"
            + ("" if st is not None else "; no operating speed lies above it, so the "
               "stability is not judged at all"))
    for n, whirl, a, b in (st.passed if st is not None else ()):
        warns.append(f"curve {n} ({whirl} whirl) grows from about {a:,.0f} to {b:,.0f} r/min, "
                     "below the running range: a run-up passes through it")

    opening = {o.speed_rpm: o for o in c.opening_onsets}
    for z in c.zones:
        if z.to_rpm < lift:
            continue   # below the lift-off the films' coefficients are placeholders
        o = next((o for n, o in opening.items()
                  if abs(n - z.from_rpm) <= 1e-6 * max(n, 1.0)), None)
        reach = ("to the diagram's end" if z.open else f"to {z.to_rpm:,.0f} r/min")
        if o is not None:
            text = (f"curve {o.curve_text} starts to grow at {o.speed_rpm:,.0f} r/min "
                    f"({o.frequency_hz:.2f} Hz) and grows {reach}")
            rest = [h for h in z.holds if h != f"curve {o.curve_text}"]
            if rest:
                text += " (the zone holds " + ", ".join(
                    h if h.startswith("curve") else
                    {"divergence": "a divergence", "parametric":
                     "a parametric resonance"}[h] for h in rest) + ")"
        else:
            kinds = {"divergence": "divergence (a mode locks to the shaft and grows)",
                     "parametric": "the periodic rotor's forms meet and grow: a parametric "
                                   "or combination resonance"}
            text = ("a zone of growth (" + "; ".join(
                kinds.get(h, f"{h} grows") for h in z.holds) + f") {z.span_text}")
        text += f", up to {z.growth_per_s:.3g} 1/s"
        hit = [sp for sp in spans if z.from_rpm <= sp[1] * (1 + 1e-9)
               and z.to_rpm >= sp[0] * (1 - 1e-9)]
        if hit:
            fails.append(text + f", inside the running range {_span_text(*hit[0])}")
        else:
            top = max(b for _, b in spans)
            gap = min(min(abs(z.from_rpm - b), abs(z.to_rpm - a)) / (b if z.from_rpm > b else a)
                      for a, b in spans)
            where = (f"{100 * gap:.1f} % above the highest operating speed ({top:,.0f} r/min)"
                     if z.from_rpm > top else
                     f"{100 * gap:.1f} % from the nearest running speed"
                     + (": a run-up passes through it" if z.to_rpm < min(a for a, _ in spans)
                        else ""))
            warns.append(text + ": " + where)
    return fails, short, warns


def api684_peaks(scene: Scene) -> bool:
    """Whether the unbalance response's peaks are judged by API 684's margins (its
    criterion "api684"), not shown for information beside a flat margin."""
    return scene.criterion == "api684"


def judged_peak(scene: Scene, p) -> bool:
    """Whether an unbalance peak is judged against its margin (api684_peaks): a steady,
    damped one; a peak where a mode grows has no steady response, and one with no damping
    to bound it is judged by its critical speed."""
    return api684_peaks(scene) and not (p.unstable or p.unbounded)


def running_orbits(c: Campbell, anywhere: bool = False) -> list[tuple[str, float, float]]:
    """Each probe's largest unbalance orbit where the shaft runs (or `anywhere` on its
    Bode curve, as a run-up passes through it): its name, the orbit's major semi-axis
    (0-peak, m) and the speed (r/min), over its Bode curve at each operating speed and
    range (the range's ends and the curve's speeds and finite peaks inside)."""
    import numpy as np

    rotor = c.rotor_scene.rotor
    if c.unbalance is None or rotor is None:
        return []
    spans = [(lo / RPM, hi / RPM) for lo, hi in rotor.spans]
    if anywhere:
        spans = [(-math.inf, math.inf)]
    out = []
    for b in c.unbalance.bode:
        n, a = b.speeds_rpm, b.major
        at: list[tuple[float, float]] = []
        for lo, hi in spans:
            at += [(float(np.interp(x, n, a)), float(x)) for x in {lo, hi} if n[0] <= x <= n[-1]]
            inside = (n >= lo) & (n <= hi)
            at += [(float(y), float(x)) for y, x in zip(a[inside], n[inside])]
            at += [(p.amplitude, p.speed_rpm) for p in c.unbalance.peaks
                   if p.probe == b.name and lo <= p.speed_rpm <= hi
                   and not (p.unstable or p.unbounded)]
        if at:
            amp, speed = max(at)
            out.append((b.name, amp, speed))
    return out


def response_findings(c: Campbell) -> list[str]:
    """What the unbalance response fails: under API 684 (scene criterion "api684"), a
    peak (damped, steady) nearer the running range than the margin its half-power
    amplification factor requires (the standard's own reading of a critical speed; other
    criteria judge the crossings by their flat margin and show the peaks for
    information), and under any criterion an orbit above
    [rotor] amplitude_limit_um anywhere on the Bode plot's speeds (a seal's clearance is
    rubbed on the way up as at speed; running_orbits)."""
    rotor = c.rotor_scene.rotor
    if c.unbalance is None or rotor is None:
        return []
    out = [f"unbalance peak at {p.probe}: {p.speed_rpm:,.0f} r/min (AF {p.amplification:.1f}), "
           f"{p.margin * 100:.1f} % from where the shaft runs, {p.required_margin * 100:.1f} % "
           "required" for p in c.unbalance.peaks
           if judged_peak(c.rotor_scene, p) and p.required_margin is not None and not p.ok]
    limit = rotor.amplitude_limit
    if limit is not None:
        out += [f"unbalance orbit at {name}: {amp * 1e6:.3g} um at {n:,.0f} r/min, above the "
                f"{limit * 1e6:g} um limit ([rotor] amplitude_limit_um)"
                for name, amp, n in running_orbits(c, anywhere=True) if amp > limit]
    return out


def check_whirl(c: Campbell, required: float | None = None) -> ResonanceVerdict:
    """The turning shaft's verdict: its critical speeds against where it runs, its whirl
    at the operating speeds against the other sources, and its stability."""
    scene = c.rotor_scene
    rotor = scene.rotor
    assert rotor is not None
    speeds = [om * 60 / (2 * math.pi) for om in rotor.speeds]
    spans = [(lo / RPM, hi / RPM) for lo, hi in rotor.spans]
    own = [e for e in scene.excitations if any(abs(e.frequency * 60 - n) <= 1e-9 * n
                                               for n in speeds)]
    others = [e for e in scene.excitations if e not in own]
    api = scene.criterion == "api684" and required is None
    flat = required if required is not None else scene.required_margin
    isotropic = c.frame == "rotating" or all(
        s.bearing is None or s.bearing.isotropic for s in scene.held)
    judged = [cs for cs in c.critical_speeds
              if not (cs.order == 1 and cs.whirl == "backward" and forward_only(scene, c.frame))]
    out = []
    for lo, hi in spans:
        for cs in judged:
            # inside a zone of growth the rotor has no steady response to resonate in: the
            # zone is judged (stability_findings), not a margin from the crossing
            if any(z.from_rpm < cs.speed_rpm < z.to_rpm for z in c.zones):
                continue
            margin, above = span_margin(cs.speed_rpm, lo, hi)
            need = api684_margin(amplification(cs.log_dec), above=above) if api else flat
            curve = f"curve {cs.mode}" if cs.mode else "found directly"
            edge = min(max(cs.speed_rpm, lo), hi)   # the running speed nearest to it
            # API 684: a critically damped crossing (AF < 2.5) needs no margin, whatever
            # the criterion; it is listed, never judged
            damped = (f", critically damped (AF {cs.amplification:.2g}): no margin required"
                      if cs.critically_damped else "")
            out.append(Approach(mode=cs.mode, frequency=cs.frequency_hz,
                                kind=f"{cs.whirl} whirl ({curve}), critical at "
                                     f"{cs.speed_rpm:,.0f} r/min{damped}",
                                source=f"shaft at {_span_text(lo, hi)}", order=cs.order,
                                excitation=cs.order * edge / 60, margin=margin,
                                required=0.0 if cs.critically_damped else need,
                                exempt=cs.critically_damped))
    rows = {n: [w for w in c.operating if abs(w.speed_rpm - n) <= 1e-9 * n] for n in speeds}
    for n, ws in rows.items():
        for w in ws:
            still = w.kind not in ("bending", "mixed")
            for e in others + (own if still else []):
                for k in e.orders:
                    fk = k * e.frequency
                    need = api684_margin(amplification(w.log_dec)) if api else flat
                    kind = w.kind if still else f"{w.kind}, {w.whirl} whirl at {n:,.0f} r/min"
                    out.append(Approach(mode=w.mode, frequency=w.frequency_hz, kind=kind,
                                        source=e.name, order=k, excitation=fk,
                                        margin=abs(w.frequency_hz - fk) / fk, required=need))
    out.sort(key=lambda a: (a.exempt, a.margin - a.required))
    fails, short, warns = stability_findings(c)
    if c.coverage:
        warns.append(c.coverage)
    warns += [(f"journal bearing {f.bearing!r} at {f.speed_rpm:,.0f} r/min: " + (
        "its film does not lift the journal (eccentricity above "
        f"{f.eccentricity:.2f}); the coefficients there are the film's at that eccentricity"
        if not f.lifted else f"minimum film {f.min_film_um:.1f} um, below its "
        f"{f.limit_um:g} um limit (min_film_um)")) for f in c.films if f.thin]
    warns += [f"journal bearing {f.bearing!r} at {f.speed_rpm:,.0f} r/min: its pads run at "
              f"{f.pad_peak_c:.1f} C, above their {f.pad_limit_c:g} C limit "
              "(pad_temperature_limit_c)" for f in c.films if f.hot]
    check = c.crossing_check
    basis = (f"the shaft turning at {', '.join(_span_text(lo, hi) for lo, hi in spans)} "
             f"({c.frame} frame): critical speeds from 0 to {max(c.speeds_rpm):,.0f} r/min "
             f"(orders {', '.join(f'{k}x' for k in c.orders)}, every curve, found on the "
             "curves followed by shape"
             + (" and directly" if check is not None and check.applies else "")
             + ") against the running "
             + ("range" if rotor.ranges else "speed") + ("; whirl frequencies there against "
                                  + ", ".join(e.name for e in others) if others else "")
             + (" (backward 1x crossings left out: an unbalance drives forward whirl only on "
                "a shaft of revolution in isotropic bearings)" if scene.axisymmetric
                and isotropic and any(cs.whirl == "backward" and cs.order == 1
                                      for cs in c.critical_speeds) else "")
             + (". API 684 margins from each mode's log decrement" if api else "")
             + ("; no bearing damping, so no amplification factor: the margin is API 684's "
                "for a lightly damped mode" if api and not any(
                    s.bearing is not None for s in scene.held) else "")
             + (f"; stability: least log decrement {c.stability.log_dec:.3g} (curve "
                f"{c.stability.curve} at {c.stability.speed_rpm:,.0f} r/min), required above "
                f"{c.stability.required:g}" if c.stability is not None and c.stability.judged
                else ""))
    return ResonanceVerdict(approaches=out, required=flat, free_free=not scene.held,
                            free_free_intended=scene.free_free_intended or scene.hanging_free,
                            turning=basis, unstable=fails, underdamped=short,
                            warnings=warns, response=response_findings(c))


def with_level1(verdict: ResonanceVerdict, level1) -> ResonanceVerdict:
    """The verdict with API 684's Level I screening (workflows.level1) in it: a failed
    screening fails it, one without Q_A is a warning."""
    from dataclasses import replace

    if level1.passed is None:
        return replace(verdict, warnings=[*verdict.warnings, "Level I: no Q_A (give [rotor] "
                                          "level1_qa_n_per_mm or the stages' power): Q_0 "
                                          + ("-" if level1.q0 is None else
                                             f"{level1.q0 / 1e3:,.1f} N/mm")])
    if level1.passed:
        return verdict
    ratio = "-" if level1.ratio is None else f"{level1.ratio:.2f}"
    dec = "-" if level1.log_dec_a is None else f"{level1.log_dec_a:.3f}"
    return replace(verdict, underdamped=[*verdict.underdamped, (
        f"Level I screening fails API 617's criteria: Q_0 / Q_A = {ratio} (2 required), log "
        f"decrement at Q_A {dec} (0.1 required): a Level II analysis is required")])
