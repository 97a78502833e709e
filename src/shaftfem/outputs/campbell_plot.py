"""The Campbell diagram as a matplotlib Figure: whirl frequency against speed,
forward and backward told apart, the excitation order lines, the critical speeds
marked and the operating speeds shaded."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.fem.whirl import CRITICALLY_DAMPED_AF, WHIRLING
from shaftfem.outputs.plots import _figure

if TYPE_CHECKING:
    from shaftfem.fem.whirl import Campbell

COLOURS = {"forward": "tab:red", "backward": "tab:blue", "mixed": "tab:purple",
           "none": "tab:grey"}
LABELS = {"forward": "forward whirl", "backward": "backward whirl", "mixed": "mixed whirl",
          "none": "torsion, axial (no whirl)"}
# An operating speed's band on the diagram: this share of it on either side.
BAND = 0.05
# a periodic rotor's side harmonic is drawn where it holds at least this share
SIDE_SHARE = 0.05


def _runs(labels: list[str]) -> list[tuple[int, int, str]]:
    """The runs of equal labels along a curve: (first, last inclusive, label), each
    sharing its end point with the next so the line is unbroken."""
    out, start = [], 0
    for i in range(1, len(labels) + 1):
        if i == len(labels) or labels[i] != labels[start]:
            out.append((start, min(i, len(labels) - 1), labels[start]))
            start = i
    return out


# API 684's critically damped roots: AF = pi / log dec below 2.5
DAMPED_LOG_DEC = math.pi / CRITICALLY_DAMPED_AF


def campbell_figure(c: Campbell):
    """Whirl frequency (Hz) against speed (r/min), each curve a mode family followed by
    its shape and coloured by its whirl where it has it; in the rotating frame a mode's
    smaller component drawn thin. Below, each curve's log decrement when the bearings
    damp."""
    import numpy as np
    from matplotlib.figure import Figure

    from shaftfem.fem.tracking import component_lines, component_whirl, side_lines

    damped = any(np.any(np.abs(cv.log_dec) > 1e-6) for cv in c.curves)
    if damped:
        fig = Figure(figsize=(8, 7.5))
        ax, dec = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    else:
        fig, ax = _figure((8, 5.5))
    top_rpm = max(c.speeds_rpm)
    shown = [float(np.max(cv.seen_hz)) for cv in c.curves] or [1.0]
    fmax = max(shown) * 1.05
    for lo, hi in c.ranges_rpm:
        ax.axvspan(lo, hi, color="gold", alpha=0.3, lw=0)
    for n in c.operating_rpm:
        if not any(lo <= n <= hi for lo, hi in c.ranges_rpm):
            ax.axvspan(n * (1 - BAND), n * (1 + BAND), color="gold", alpha=0.3, lw=0)
        ax.axvline(n, color="goldenrod", lw=1)
    labelled = set()
    sides_drawn = mid_range = thin_drawn = False
    for cv in c.curves:
        whirls = cv.whirling
        for comp, v, share in component_lines(cv):
            # each point drawn as its component's share says: heavy where it carries
            # most of the motion, thin where it is the smaller part, not where it is none
            weight = ["heavy" if x >= 0.5 else "thin" if x >= 0.02 else "" for x in share]
            # a critically damped root (AF below 2.5, API 684) drawn faint: it is no mode
            # to keep clear of (an oil film's rigid-body roots)
            weight = [w + ("~" if w and d > DAMPED_LOG_DEC else "")
                      for w, d in zip(weight, cv.log_dec)]
            if not whirls:
                words = ["none"] * v.size
            else:
                words = [component_whirl(comp, float(x), float(w)) if k in ("bending", "mixed")
                         else "none" for x, w, k in zip(v, cv.index, cv.kinds)]
            for a, b, key in _runs([f"{w}|{h}" for w, h in zip(words, weight)]):
                word, how = key.split("|")
                if not how:
                    continue
                heavy, faint = how.startswith("heavy"), how.endswith("~")
                ax.plot(cv.speeds_rpm[a:b + 1], np.abs(v[a:b + 1]),
                        "-" if word != "none" else ":", color=COLOURS[word],
                        lw=1.6 if heavy else 0.6, alpha=0.25 if faint else 1.0,
                        label=(LABELS[word] if word not in labelled and heavy and not faint
                               else None))
                if heavy and not faint:
                    labelled.add(word)
                thin_drawn = thin_drawn or (not heavy and word != "none")
        # a periodic rotor's form: its harmonics beside the dominant one, thin by their
        # share of the motion (a line of its own in the housing's spectrum)
        for comp, v, share in side_lines(cv):
            for a, b, key in _runs(["y" if x >= SIDE_SHARE else "" for x in share]):
                if not key:
                    continue
                word = component_whirl(comp, float(v[a]), 0.0)
                ax.plot(cv.speeds_rpm[a:b + 1], np.abs(v[a:b + 1]), "-", color=COLOURS[word],
                        lw=0.3 + 1.2 * float(np.max(share[a:b + 1])), alpha=0.6)
                sides_drawn = True
        # where it starts or ends mid-range, said why in the notes (curve_notes)
        for i, why in ((0, cv.began), (-1, cv.ended)):
            if why and float(cv.seen_hz[i]) < fmax:
                ax.plot(cv.speeds_rpm[i], float(cv.seen_hz[i]), "|", color="dimgrey", ms=7)
                mid_range = True
        end = cv.speeds_rpm[-1]
        if end >= 0.6 * top_rpm and cv.seen_hz[-1] < fmax:
            ax.annotate(str(cv.number), (end, float(cv.seen_hz[-1])), fontsize=6,
                        color="dimgrey", textcoords="offset points", xytext=(2, -2))
    speeds = np.array([0.0, top_rpm])
    for order in c.orders:
        ax.plot(speeds, order * speeds / 60.0, "--", color="black", lw=0.9)
        end = min(top_rpm, fmax * 60.0 / order)
        ax.annotate(f"{order}x", (end, order * end / 60.0), fontsize=8,
                    textcoords="offset points", xytext=(-14, 4))
    placed: list[tuple[str, float]] = []
    for cs in c.critical_speeds:
        if cs.critically_damped:   # API 684: no critical speed (AF < 2.5)
            continue
        ax.plot(cs.speed_rpm, cs.frequency_hz, "o", mfc="none", color=COLOURS[cs.whirl], ms=8,
                mew=1.8)
        # forward labels above and left, backward below and right: a pair's two crossings
        # lie close together; labels of one whirl within 6 % of the axis stacked
        up = cs.whirl == "forward"
        near = sum(1 for w, n in placed if w == cs.whirl
                   and abs(n - cs.speed_rpm) < 0.06 * top_rpm)
        placed.append((cs.whirl, cs.speed_rpm))
        ax.annotate(f"{cs.speed_rpm:,.0f}", (cs.speed_rpm, cs.frequency_hz), fontsize=7,
                    color=COLOURS[cs.whirl], textcoords="offset points",
                    xytext=(-30, 6 + 9 * near) if up else (6, -12 - 9 * near))
    ax.plot([], [], "o", mfc="none", color="black", label="critical speed, r/min")
    if mid_range:
        ax.plot([], [], "|", color="dimgrey", ms=7,
                label="a curve starts or ends: two real roots meet or part (notes)")
    if any(np.any(cv.log_dec > DAMPED_LOG_DEC) for cv in c.curves if cv.whirling):
        ax.plot([], [], "-", color="black", alpha=0.25, lw=1.6,
                label="critically damped (AF < 2.5): no critical speed")
    if any(s.journal is not None for s in c.rotor_scene.supports):
        # an oil film's whirl turns at a little under half the shaft's speed
        ax.plot(speeds, 0.5 * speeds / 60.0, ":", color="black", lw=0.9)
        end = min(top_rpm, fmax * 120.0)
        ax.annotate("0.5x", (end, 0.5 * end / 60.0), fontsize=8, textcoords="offset points",
                    xytext=(-18, 4))
    opening = c.opening_onsets
    for o in opening:
        ax.plot(o.speed_rpm, o.frequency_hz, "X", color="tab:red", ms=8,
                label="onset of instability" if o is opening[0] else None)
        ax.annotate(f"grows from {o.speed_rpm:,.0f}", (o.speed_rpm, o.frequency_hz), fontsize=7,
                    color="tab:red", textcoords="offset points", xytext=(6, 6))
        if damped:
            dec.axvline(o.speed_rpm, color="tab:red", lw=0.8, ls=":")
    # where the rotor grows (onsets to where their curves decay again, divergence,
    # parametric zones), overlapping causes as one zone: hatched; above the last zone
    # the rotor is stable, and drawn so
    for i, z in enumerate(c.zones):
        for axis in ([ax, dec] if damped else [ax]):
            axis.axvspan(z.from_rpm, z.to_rpm, facecolor="none", edgecolor="tab:red",
                         hatch="//", lw=0, alpha=0.35,
                         label="unstable" if i == 0 and axis is ax else None)
        if z.holds != (z.holds[0],) or not z.holds[0].startswith("curve "):
            # low beside the zone's right edge: clear of the legend at the top
            ax.annotate(f"grows {z.from_rpm:,.0f}-{z.to_rpm:,.0f}\nup to "
                        f"{z.growth_per_s:.3g} 1/s", (z.to_rpm, (0.03 + 0.09 * (i % 2)) * fmax),
                        fontsize=7, color="tab:red", ha="left", va="bottom",
                        textcoords="offset points", xytext=(3, 0))
    if thin_drawn:
        ax.plot([], [], "-", color="grey", lw=0.6,
                label="thin: a mode's smaller whirl component (2 to 50 % of its motion)")
    if sides_drawn:
        ax.plot([], [], "-", color="grey", lw=0.6, alpha=0.6,
                label="Floquet form's other harmonics (width: share)")
    ax.axvspan(0, 0, color="gold", alpha=0.3, label="operating speed" + (
        " range" if c.ranges_rpm else ""))
    ax.set_xlim(0, top_rpm)
    ax.set_ylim(0, fmax)
    if damped:
        for cv in c.curves:
            if not cv.whirling:
                continue
            d = cv.log_dec
            for a, b, word in _runs(cv.whirl):
                dec.plot(cv.speeds_rpm[a:b + 1], d[a:b + 1], "-", color=COLOURS[word], lw=1.2)
        dec.axhline(0.0, color="black", lw=0.8)
        if c.stability is not None and c.stability.required > 0:
            dec.axhline(c.stability.required, color="tab:red", lw=0.8, ls="--")
        # the panel shows the margin that is judged: the least log decrements where the
        # shaft runs stay legible, heavily damped roots run off its top (said there)
        values = np.concatenate([cv.log_dec for cv in c.curves if cv.whirling] or [np.zeros(1)])
        least = c.stability.log_dec if c.stability is not None else float(values.min())
        need = c.stability.required if c.stability is not None else 0.0
        top = max(4 * abs(least), 3 * need, 0.5)
        if values.max() > top:
            low = min(float(values.min()), 0.0)
            dec.set_ylim(low - 0.05 * (top - low), top)
            dec.annotate(f"clipped at {top:.2g}: heavily damped roots above (up to "
                         f"{values.max():.3g})", (0.99, 0.93), xycoords="axes fraction",
                         ha="right", va="top", fontsize=7, color="dimgrey")
        for lo, hi in c.ranges_rpm:
            dec.axvspan(lo, hi, color="gold", alpha=0.3, lw=0)
        dec.set_ylabel("log decrement")
        dec.set_xlabel("shaft speed, r/min")
        dec.grid(True, alpha=0.3)
    else:
        ax.set_xlabel("shaft speed, r/min")
    ax.set_ylabel("whirl frequency, Hz (stationary frame)")
    ax.set_title(f"Campbell diagram: {c.result.scene.name} ({c.frame} frame)", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    return fig


def weight_figure(c: Campbell):
    """The 2x whirl the shaft's weight drives (a shaft stiffer across one diameter than
    across the other) against speed at every probe: the 2x orbit's major semi-axis,
    0-peak, its peak marked with its speed, the running speeds shaded, half of each 1x
    critical speed dotted (where the peak is expected)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 4.5))
    ax = fig.subplots()
    for lo, hi in c.ranges_rpm:
        ax.axvspan(lo, hi, color="gold", alpha=0.3, lw=0)
    for n in c.operating_rpm:
        if not any(lo <= n <= hi for lo, hi in c.ranges_rpm):
            ax.axvspan(n * (1 - BAND), n * (1 + BAND), color="gold", alpha=0.3, lw=0,
                       label="running speed" if n == c.operating_rpm[0] else None)
    halves = sorted({round(cs.speed_rpm / 2, 6) for cs in c.critical_speeds
                     if cs.order == 1 and not cs.critically_damped})
    for i, h in enumerate(halves):
        ax.axvline(h, ls=":", lw=0.9, color="grey",
                   label="half a 1x critical speed" if i == 0 else None)
    for i, w in enumerate(c.weight_2x):
        line, = ax.semilogy(w.speeds_rpm, [a * 1e6 for a in w.curve], lw=max(2.6 - 0.6 * i, 1.0),
                            label=f"{w.probe}")
        ax.plot([w.speed_rpm], [w.amplitude * 1e6], "o", color=line.get_color(), ms=5)
        ax.annotate(f"{w.speed_rpm:,.0f} r/min, {w.amplitude * 1e6:.3g} um",
                    (w.speed_rpm, w.amplitude * 1e6), textcoords="offset points",
                    xytext=(6, 4 - 12 * i), fontsize=7, color=line.get_color())
    ax.set_xlabel("shaft speed, r/min")
    ax.set_ylabel("2x orbit, major semi-axis, um (0-peak)")
    ax.set_title(f"The weight's 2x whirl: {c.result.scene.name} (a shaft stiffer across one "
                 "diameter)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    return fig


def bode_figure(c: Campbell):
    """The unbalance response against speed at every probe, 0-peak: the orbit's major
    semi-axis (solid), its x (dashed) and y (dotted) amplitudes where they differ, a
    periodic rotor's 3x orbit (dash-dotted), the
    peaks marked, the running speeds or range shaded, the scene's amplitude limit drawn;
    below, the phase of x as one continuous lag."""
    import numpy as np
    from matplotlib.figure import Figure

    assert c.unbalance is not None
    scene = c.rotor_scene
    limit = scene.rotor.amplitude_limit if scene.rotor is not None else None
    fig = Figure(figsize=(8, 6.5))
    amp, phase = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    for lo, hi in c.ranges_rpm:
        for ax in (amp, phase):
            ax.axvspan(lo, hi, color="gold", alpha=0.3, lw=0)
    for n in c.operating_rpm:
        if not any(lo <= n <= hi for lo, hi in c.ranges_rpm):
            for ax in (amp, phase):
                ax.axvspan(n * (1 - BAND), n * (1 + BAND), color="gold", alpha=0.3, lw=0)
    labelled = set()
    ellipses = thirds = False
    low, high = [], []
    for i, b in enumerate(c.unbalance.bode):
        um = b.major * 1e6
        # thinner for each probe drawn later: one that reads as another shows as its core
        line, = amp.semilogy(b.speeds_rpm, um, lw=max(3.0 - 0.6 * i, 1.0),
                             label=f"{b.name} ({b.z * 1e3:g} mm)")
        colour = line.get_color()
        elliptic = b.amplitude_y is not None and np.any(
            np.abs(b.amplitude - b.amplitude_y) > 0.02 * np.maximum(b.major, 1e-300))
        if elliptic and b.amplitude_y is not None:
            ellipses = True
            amp.semilogy(b.speeds_rpm, b.amplitude * 1e6, "--", lw=0.9, color=colour)
            amp.semilogy(b.speeds_rpm, b.amplitude_y * 1e6, ":", lw=1.1, color=colour)
        if b.major_3x is not None and np.any(b.major_3x > 0):
            thirds = True
            amp.semilogy(b.speeds_rpm, b.major_3x * 1e6, "-.", lw=0.9, color=colour)
        # thinner for each probe drawn later: a phase equal to another's shows as its core
        phase.plot(b.speeds_rpm, b.phase_deg, lw=max(3.2 - 0.7 * i, 0.8), color=colour)
        finite = um[np.isfinite(um) & (um > 0)]
        if finite.size:
            high.append(float(finite.max()))
        for lo, hi in [*c.ranges_rpm, *((n * (1 - BAND), n * (1 + BAND))
                                        for n in c.operating_rpm)]:
            inside = um[(b.speeds_rpm >= lo) & (b.speeds_rpm <= hi) & (um > 0)]
            if inside.size:
                low.append(float(inside.min()))
        for p in c.unbalance.peaks:
            if p.probe != b.name:
                continue
            y = p.amplitude * 1e6 if math.isfinite(p.amplitude) else float(np.max(um))
            amp.plot(p.speed_rpm, y, "o", mfc="none", color=colour)
            if round(p.speed_rpm, -1) in labelled:   # another probe's peak says it
                continue
            labelled.add(round(p.speed_rpm, -1))
            what = (", unbounded" if p.unbounded else ", unstable" if p.unstable else
                    f", AF {p.amplification:.1f}" if p.amplification else "")
            amp.annotate(f"{p.speed_rpm:,.0f} r/min{what}", (p.speed_rpm, y),
                         fontsize=7, textcoords="offset points", xytext=(5, 3))
    if limit is not None:
        amp.axhline(limit * 1e6, color="tab:red", lw=1.0, ls="-.",
                    label=f"limit {limit * 1e6:g} um")
        high.append(limit * 1e6)
    top = max(high) if high else 1.0
    # the running range's response stays legible beside the peaks
    bottom = min([top * 1e-4, *(x / 3 for x in low)])
    amp.set_ylim(bottom, top * 3)
    amp.plot([], [], "k-", lw=1.5, label="orbit's major semi-axis")
    if ellipses:
        amp.plot([], [], "k--", lw=0.9, label="along x")
        amp.plot([], [], "k:", lw=1.1, label="along y")
    if thirds:
        amp.plot([], [], "k-.", lw=0.9, label="3x orbit's major semi-axis")
    amp.set_ylabel("amplitude, um (0-peak)")
    amp.set_title(f"Unbalance response: {scene.name}"
                  + ("" if c.unbalance.damped else " (no damping: unbounded at the criticals)"),
                  fontsize=10)
    amp.grid(True, which="both", alpha=0.3)
    amp.legend(fontsize=7, loc="upper left")
    phase.set_ylabel("phase of x, deg")
    phase.set_xlabel("shaft speed, r/min")
    phase.grid(True, alpha=0.3)
    return fig


# The deflected line is read in this many slices along the shaft.
SLICES = 60


# the modes drawn where no 1x critical speed lies in the range
NEAREST_SHAPES = 2


def deflected_lines(c: Campbell) -> list[tuple[str, np.ndarray, np.ndarray, np.ndarray]]:
    """At each judged 1x critical speed, the shape of its curve along the shaft: (label,
    z of each slice mm, the orbit's major semi-axis there, scaled to a largest of 1, and
    the phase of its dominant circular whirl there, deg, 0 where it is largest), each
    slice the mass-weighted mean motion of its nodes."""
    import numpy as np

    r = c.result
    nodes, mass = r.system.nodes, r.system.mass_scalar.diagonal()
    edges = np.linspace(nodes[:, 2].min(), nodes[:, 2].max(), SLICES + 1)
    slot = np.clip(np.searchsorted(edges, nodes[:, 2], side="right") - 1, 0, SLICES - 1)
    weight = np.bincount(slot, mass, SLICES)
    z = 0.5 * (edges[1:] + edges[:-1]) * 1e3
    out = []
    curves = {cv.number: cv for cv in c.curves}
    picked = []   # (label, curve, index of its speed)
    for cs in c.critical_speeds:
        cv = curves.get(cs.mode)
        if cs.order != 1 or cv is None or cs.critically_damped:
            continue
        i = int(np.argmin(np.abs(cv.speeds_rpm - cs.speed_rpm)))
        picked.append((f"{cs.whirl} {cs.speed_rpm:,.0f} r/min (curve {cs.mode})", cv, i))
    if not picked:
        # no 1x critical speed in the range: the shapes of the lightly damped whirling
        # modes nearest it from above, at the diagram's top speed, so the reader sees
        # what the shaft would do first
        top = []
        for cv in c.curves:
            if not cv.whirling or cv.kinds[-1] not in WHIRLING:
                continue
            if cv.log_dec[-1] >= DAMPED_LOG_DEC:
                continue
            top.append((float(cv.seen_hz[-1]), cv))
        for f, cv in sorted(top, key=lambda t: t[0])[:NEAREST_SHAPES]:
            picked.append((f"nearest: curve {cv.number}, {cv.whirl[-1]} {f:.1f} Hz at "
                           f"{cv.speeds_rpm[-1]:,.0f} r/min (no 1x critical in the range)",
                           cv, len(cv.speeds_rpm) - 1))
    for label, cv, i in picked:
        u = c.basis_shapes @ cv.shapes[:, i]
        x = np.bincount(slot, mass * u[0::3].real, SLICES) + 1j * np.bincount(
            slot, mass * u[0::3].imag, SLICES)
        y = np.bincount(slot, mass * u[1::3].real, SLICES) + 1j * np.bincount(
            slot, mass * u[1::3].imag, SLICES)
        x, y = x / weight, y / weight
        major = 0.5 * (np.abs(x + 1j * y) + np.abs(x - 1j * y))
        # the circular whirl that carries most of the orbit: its phase along the shaft
        # tells a cylindrical shape (ends in phase) from a conical one (180 deg apart)
        a, b = 0.5 * (x + 1j * y), 0.5 * (x - 1j * y)
        circle = a if np.linalg.norm(a) >= np.linalg.norm(b) else b
        phase = np.degrees(np.angle(circle / circle[int(np.argmax(np.abs(circle)))]))
        out.append((label, z, major / major.max(), phase))
    return out


def critical_shapes_figure(c: Campbell):
    """The deflected shape along the shaft at each 1x critical speed (API 684's mode
    shape plot): the orbit's major semi-axis against the axial position, and below it
    the phase of the whirl, the bearings' and parts' planes marked."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 6.5))
    ax, lower = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    scene = c.rotor_scene
    for s in scene.held:
        for axis in (ax, lower):
            axis.axvline(s.position * 1e3, color="black", lw=0.8, ls="--")
        ax.annotate(s.name, (s.position * 1e3, 1.02), fontsize=7, ha="center",
                    xycoords=("data", "axes fraction"))
    for a in scene.attachments:
        for axis in (ax, lower):
            axis.axvline(a.position * 1e3, color="grey", lw=0.8, ls=":")
    lines = deflected_lines(c)
    for label, z, major, phase in lines:
        ax.plot(z, major, lw=1.5, label=label)
        lower.plot(z, phase, lw=1.2)
    if not lines:
        ax.text(0.5, 0.5, "no 1x critical speed in the range", transform=ax.transAxes,
                ha="center")
    # the whole shaft, whatever the lines and marks reach
    ends = c.result.system.nodes[:, 2]
    ax.set_xlim(float(ends.min()) * 1e3, float(ends.max()) * 1e3)
    lower.set_xlabel("position along the shaft, mm")
    lower.set_ylabel("phase of the whirl, deg")
    lower.set_ylim(-185, 185)
    lower.set_yticks([-180, -90, 0, 90, 180])
    lower.grid(True, alpha=0.3)
    ax.set_ylabel("orbit's major semi-axis (largest 1)")
    ax.set_ylim(0, 1.1)
    ax.set_title(f"Deflected shape at the critical speeds: {scene.name}", fontsize=10,
                 pad=14)
    ax.grid(True, alpha=0.3)
    if lines:
        ax.legend(fontsize=7)
    return fig
