"""The Campbell diagram as a matplotlib Figure: whirl frequency against speed,
forward and backward told apart, the excitation order lines, the critical speeds
marked and the operating speeds shaded."""

from __future__ import annotations

from typing import TYPE_CHECKING

from shaftfem.outputs.plots import _figure

if TYPE_CHECKING:
    from shaftfem.fem.whirl import Campbell

COLOURS = {"forward": "tab:red", "backward": "tab:blue", "mixed": "tab:purple",
           "none": "tab:grey"}
LABELS = {"forward": "forward whirl", "backward": "backward whirl", "mixed": "mixed whirl",
          "none": "torsion, axial (no whirl)"}
# An operating speed's band on the diagram: this share of it on either side.
BAND = 0.05


def _runs(labels: list[str]) -> list[tuple[int, int, str]]:
    """The runs of equal labels along a curve: (first, last inclusive, label), each
    sharing its end point with the next so the line is unbroken."""
    out, start = [], 0
    for i in range(1, len(labels) + 1):
        if i == len(labels) or labels[i] != labels[start]:
            out.append((start, min(i, len(labels) - 1), labels[start]))
            start = i
    return out


def campbell_figure(c: Campbell):
    """Whirl frequency (Hz) against speed (r/min), each curve a mode family followed by
    its shape and coloured by its whirl where it has it; in the rotating frame a mode's
    smaller component drawn thin. Below, each curve's log decrement when the bearings
    damp."""
    import numpy as np
    from matplotlib.figure import Figure

    from shaftfem.fem.tracking import component_lines, component_whirl

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
    for cv in c.curves:
        whirls = cv.whirling
        for comp, v, share in component_lines(cv):
            # each point drawn as its component's share says: heavy where it carries
            # most of the motion, thin where it is the smaller part, not where it is none
            weight = ["heavy" if x >= 0.5 else "thin" if x >= 0.02 else "" for x in share]
            if not whirls:
                words = ["none"] * v.size
            else:
                words = [component_whirl(comp, float(x), float(w)) if k in ("bending", "mixed")
                         else "none" for x, w, k in zip(v, cv.index, cv.kinds)]
            for a, b, key in _runs([f"{w}|{h}" for w, h in zip(words, weight)]):
                word, how = key.split("|")
                if not how:
                    continue
                heavy = how == "heavy"
                ax.plot(cv.speeds_rpm[a:b + 1], np.abs(v[a:b + 1]),
                        "-" if word != "none" else ":", color=COLOURS[word],
                        lw=1.6 if heavy else 0.6,
                        label=LABELS[word] if word not in labelled and heavy else None)
                if heavy:
                    labelled.add(word)
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
    for cs in c.critical_speeds:
        ax.plot(cs.speed_rpm, cs.frequency_hz, "o", mfc="none", color=COLOURS[cs.whirl], ms=8,
                mew=1.8)
        # forward labels above and left, backward below and right: a pair's two crossings
        # lie close together
        up = cs.whirl == "forward"
        ax.annotate(f"{cs.speed_rpm:,.0f}", (cs.speed_rpm, cs.frequency_hz), fontsize=7,
                    color=COLOURS[cs.whirl], textcoords="offset points",
                    xytext=(-30, 6) if up else (6, -12))
    ax.plot([], [], "o", mfc="none", color="black", label="critical speed, r/min")
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


def bode_figure(c: Campbell):
    """Amplitude (um) and phase (deg) of the unbalance response against speed at every
    probe, its peaks marked and the operating speeds shaded."""
    from matplotlib.figure import Figure

    assert c.unbalance is not None
    fig = Figure(figsize=(8, 6))
    amp, phase = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    for n in c.operating_rpm:
        for ax in (amp, phase):
            ax.axvspan(n * (1 - BAND), n * (1 + BAND), color="gold", alpha=0.3, lw=0)
    labelled = set()
    for b in c.unbalance.bode:
        line, = amp.semilogy(b.speeds_rpm, b.amplitude * 1e6, lw=1.5,
                             label=f"{b.name} ({b.z * 1e3:g} mm)")
        phase.plot(b.speeds_rpm, b.phase_deg, lw=1.2, color=line.get_color())
        for p in c.unbalance.peaks:
            if p.probe == b.name:
                amp.plot(p.speed_rpm, p.amplitude * 1e6, "o", mfc="white",
                         color=line.get_color())
                if round(p.speed_rpm, -1) in labelled:   # another probe's peak says it
                    continue
                labelled.add(round(p.speed_rpm, -1))
                af = f", AF {p.amplification:.1f}" if p.amplification else ""
                amp.annotate(f"{p.speed_rpm:,.0f} r/min{af}", (p.speed_rpm, p.amplitude * 1e6),
                             fontsize=7, textcoords="offset points", xytext=(5, 3))
    top = max([float(b.amplitude.max()) for b in c.unbalance.bode]
              + [p.amplitude for p in c.unbalance.peaks]) * 1e6
    amp.set_ylim(top * 1e-4, top * 3)   # four decades: the slow end's tiny response aside
    amp.set_ylabel("amplitude along x, um")
    amp.set_title(f"Unbalance response: {c.result.scene.name}", fontsize=10)
    amp.grid(True, which="both", alpha=0.3)
    amp.legend(fontsize=8)
    phase.set_ylabel("phase, deg")
    phase.set_xlabel("shaft speed, r/min")
    phase.set_yticks([-180, -90, 0, 90, 180])
    phase.grid(True, alpha=0.3)
    return fig
