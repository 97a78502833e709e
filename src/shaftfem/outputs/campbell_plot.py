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


def campbell_figure(c: Campbell):
    """Whirl frequency (Hz) against speed (r/min); below it the log decrement of each
    curve when the bearings damp."""
    import numpy as np
    from matplotlib.figure import Figure

    damped = any(abs(w.log_dec) > 1e-9 for w in c.whirl)
    if damped:
        fig = Figure(figsize=(8, 7.5))
        ax, dec = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    else:
        fig, ax = _figure((8, 5.5))
    top_rpm = max(c.speeds_rpm)
    fmax = max(w.frequency_hz for w in c.whirl) * 1.05
    for n in c.operating_rpm:
        ax.axvspan(n * (1 - BAND), n * (1 + BAND), color="gold", alpha=0.3, lw=0)
        ax.axvline(n, color="goldenrod", lw=1)
    for whirl in ("forward", "backward", "mixed", "none"):
        for k, (s, f) in enumerate(c.curves(whirl)):
            ax.plot(s, f, "-" if whirl != "none" else ":", color=COLOURS[whirl], lw=1.6,
                    label=LABELS[whirl] if k == 0 else None)
    speeds = np.array([0.0, top_rpm])
    for order in c.orders:
        ax.plot(speeds, order * speeds / 60.0, "--", color="black", lw=0.9)
        end = min(top_rpm, fmax * 60.0 / order)
        ax.annotate(f"{order}x", (end, order * end / 60.0), fontsize=8,
                    textcoords="offset points", xytext=(-14, 4))
    for cs in c.critical_speeds:
        ax.plot(cs.speed_rpm, cs.frequency_hz, "o", mfc="white", color=COLOURS[cs.whirl], ms=7,
                mew=1.8)
        # forward labels above and left, backward below and right: a pair's two crossings
        # lie close together
        up = cs.whirl == "forward"
        ax.annotate(f"{cs.speed_rpm:,.0f} r/min", (cs.speed_rpm, cs.frequency_hz), fontsize=7,
                    color=COLOURS[cs.whirl], textcoords="offset points",
                    xytext=(-52, 6) if up else (6, -12))
    ax.plot([], [], "o", mfc="white", color="black", label="critical speed")
    ax.axvspan(0, 0, color="gold", alpha=0.3, label="operating speed")
    ax.set_xlim(0, top_rpm)
    ax.set_ylim(0, fmax)
    if damped:
        for whirl in ("forward", "backward", "mixed"):
            for s, d in c.decrements(whirl):
                dec.plot(s, d, "-", color=COLOURS[whirl], lw=1.2)
        dec.axhline(0.0, color="black", lw=0.8)
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
