"""Charts as matplotlib Figures (study, sweeps): no pyplot, no backend switch.

`matplotlib.figure.Figure` renders to PNG through its own Agg canvas, so
drawing here never changes the caller's matplotlib state.
"""

from __future__ import annotations

from pathlib import Path

from shaftfem.store import atomic_path


def _figure(size: tuple[float, float]):
    from matplotlib.figure import Figure

    fig = Figure(figsize=size)
    return fig, fig.add_subplot()


def save_png(fig, path: str | Path, dpi: int = 110) -> Path:
    fig.tight_layout()
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format="png")
    return Path(path)


def study_figure(rows: list[dict]):
    """Log-log: the max relative frequency error against wall time, per element."""
    fig, ax = _figure((7, 4.5))
    for el in sorted({r["element"] for r in rows}):
        rs = sorted((r for r in rows if r["element"] == el), key=lambda r: r["total_s"])
        ax.loglog([r["total_s"] for r in rs], [r["max_rel_error"] for r in rs], "o-", label=el)
        for r in rs:
            ax.annotate(f"{r['size_mm']:g} mm", (r["total_s"], r["max_rel_error"]),
                        fontsize=7, textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel("wall time of the run, s")
    ax.set_ylabel("max relative frequency error, all modes")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return fig


def frequencies_figure(rows: list[dict], parameter: str, n_modes: int):
    """Each natural frequency against one swept parameter."""
    fig, ax = _figure((7, 4.5))
    x = [float(r[parameter]) for r in rows]
    for i in range(1, n_modes + 1):
        ax.plot(x, [float(r[f"f{i}_hz"]) for r in rows], "o", ms=4, label=f"mode {i}")
    ax.set_xlabel(parameter)
    ax.set_ylabel("natural frequency, Hz")
    ax.set_yscale("log")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return fig


def margin_figure(rows: list[dict], parameters: list[str]):
    """The smallest resonance margin over one or two swept parameters."""
    fig, ax = _figure((6, 4.5))
    margin = [100 * float(r["min_margin"]) for r in rows]
    if len(parameters) >= 2:
        sc = ax.scatter([float(r[parameters[0]]) for r in rows],
                        [float(r[parameters[1]]) for r in rows], c=margin, cmap="RdYlGn", s=80)
        ax.set_ylabel(parameters[1])
        fig.colorbar(sc, ax=ax, label="smallest separation margin, %")
    else:
        ax.plot([float(r[parameters[0]]) for r in rows], margin, "o")
        ax.set_ylabel("smallest separation margin, %")
    ax.set_xlabel(parameters[0])
    ax.grid(True, alpha=0.3)
    return fig


def sweep_plots(rows: list[dict], parameters: list[str], n_modes: int,
                out: str | Path) -> list[Path]:
    """PNG per swept parameter (each frequency against it) and a resonance-margin map."""
    ok = [r for r in rows if r["status"] == "ok"]
    out = Path(out)
    if not ok:
        return []
    # 'support[1].position_mm' -> frequencies_vs_support1_position_mm.png
    written = [save_png(frequencies_figure(ok, p, n_modes), out / "frequencies_vs_{}.png".format(
        p.replace(".", "_").replace("[", "").replace("]", ""))) for p in parameters]
    if ok[0].get("min_margin") not in (None, ""):
        written.append(save_png(margin_figure(ok, parameters), out / "resonance_margin.png"))
    if any(r.get("crit1_rpm") not in (None, "") for r in ok):
        written += [save_png(critical_figure(ok, p, parameters),
                             out / "critical_speeds_vs_{}.png".format(
                                 p.replace(".", "_").replace("[", "").replace("]", "")))
                    for p in parameters]
    return written


def critical_figure(rows: list[dict], parameter: str, parameters: list[str]):
    """A turning shaft's lowest two 1x critical speeds against a swept parameter (the
    other parameters' values as separate lines)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 4.5))
    ax = fig.subplots()
    others = [k for k in parameters if k != parameter]
    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        groups.setdefault(tuple(r[k] for k in others), []).append(r)
    for key, group in groups.items():
        group = sorted(group, key=lambda r: float(r[parameter]))
        x = [float(r[parameter]) for r in group]
        label = ", ".join(f"{k} {v}" for k, v in zip(others, key))
        for c, ls in (("crit1_rpm", "-"), ("crit2_rpm", "--")):
            pts = [(xi, float(r[c])) for xi, r in zip(x, group) if r.get(c) not in (None, "")]
            if pts:
                ax.plot(*zip(*pts), ls, marker="o", ms=3,
                        label=f"{'first' if c == 'crit1_rpm' else 'second'} 1x critical"
                        + (f" ({label})" if label else ""))
    ax.set_xlabel(parameter)
    ax.set_ylabel("critical speed, r/min")
    ax.set_title(f"Critical speeds against {parameter}", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return fig


def response_figure(fr, marks: list[tuple[str, float, float]], title: str = ""):
    """Transmissibility for base motion at the supports, in two panels: every mode
    solved (log frequency, from below the lowest harmonic), and the excitation band
    (linear, up to 1.5 x the highest harmonic) with the transmissibility at each
    harmonic marked and written. `marks`: (label, frequency Hz, transmissibility)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 4.5))
    wide, near = fig.subplots(1, 2, gridspec_kw={"width_ratios": [3, 2]})
    label = f"{fr.direction} at z = {fr.point[2] * 1e3:.0f} mm, zeta = {100 * fr.damping:g} %"
    f, t = fr.frequencies, fr.transmissibility
    low = min([hz for _, hz, _ in marks if hz > 0] + [f[-1] / 100]) / 2
    keep = f >= low
    wide.loglog(f[keep], t[keep], "-", lw=1.2, label=label)
    for _, hz, _ in marks:
        wide.axvline(hz, color="tab:red", ls="--", lw=0.8)
    wide.axhline(1.0, color="0.5", lw=0.6)
    wide.set_xlim(low, f[-1])
    wide.set_xlabel("excitation frequency, Hz (log)")
    wide.set_ylabel("transmissibility |u / u_base|")
    wide.set_title("every mode solved; dashed: excitation harmonics", fontsize=9)
    wide.grid(True, which="both", alpha=0.3)
    wide.legend(fontsize=8, loc="upper left")
    top = 1.5 * max(hz for _, hz, _ in marks) if marks else f[-1] / 5
    band = f <= top
    near.plot(f[band], t[band], "-", lw=1.2)
    near.axhline(1.0, color="0.5", lw=0.6)
    peak = max([float(t[band].max())] + [v for _, _, v in marks])
    for i, (text, hz, value) in enumerate(sorted(marks, key=lambda m: m[1])):
        near.plot([hz], [value], "o", color="tab:red", ms=5)
        # staggered heights keep neighbouring labels apart
        near.annotate(f"{text}\n{hz:.4g} Hz: x{value:.3g}", (hz, value), fontsize=7,
                      color="tab:red", ha="left", va="bottom", textcoords="offset points",
                      xytext=(4, 6 + 22 * (i % 3)))
    near.set_xlim(0, top)
    near.set_ylim(0, 1.45 * peak)
    near.set_xlabel("excitation frequency, Hz")
    near.set_title("the excitation band: transmissibility at each harmonic", fontsize=9)
    near.grid(True, alpha=0.3)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def modes_figure(frequencies, low, high, kinds: list[str],
                 harmonics: list[tuple[str, float]], margin: float):
    """Each natural frequency (Hz) as a marker with its interval [low, high] (None: not
    bounded), beside each excitation harmonic (label, Hz) with its band of +- `margin`
    (fraction): a mode inside a band is too near."""
    import numpy as np

    fig, ax = _figure((7.5, 3.2))
    f = np.asarray(frequencies, float)
    colours = {"bending": "tab:blue", "torsion": "tab:red", "axial": "tab:green",
               "mixed": "tab:grey"}
    for kind in dict.fromkeys(kinds):
        at = np.array([k == kind for k in kinds])
        ax.plot(f[at], np.flatnonzero(at) + 1, "o", color=colours.get(kind, "black"),
                label=kind)
    if low is not None and high is not None:
        ax.errorbar(f, np.arange(1, len(f) + 1), fmt="none", ecolor="black", capsize=3,
                    xerr=[f - np.asarray(low), np.asarray(high) - f], lw=1)
    for label, fk in harmonics:
        ax.axvspan(fk * (1 - margin), fk * (1 + margin), color="tab:orange", alpha=0.15, lw=0)
        ax.axvline(fk, color="tab:orange", lw=1)
        ax.annotate(label, (fk, len(f) + 0.9), fontsize=7, ha="right", va="top",
                    rotation=90, color="tab:orange")
    # excitations and modes often lie decades apart: a log axis shows both
    ax.set_xscale("log")
    ax.set_xlabel("frequency, Hz (orange: excitation harmonics and their required margin)")
    ax.set_ylabel("mode")
    ax.set_ylim(0.3, len(f) + 1)
    ax.grid(True, axis="x", alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    return fig


def static_figure(result):
    """The deflection line (um) along the shaft (mm), x and y, with the supports'
    reactions (N) marked (a workflows.static.StaticResult)."""
    s = result.solution
    fig, ax = _figure((8, 3.6))
    ax.plot(s.z * 1e3, s.y * 1e6, color="C0", label="y")
    if abs(s.x).max() > 1e-3 * max(abs(s.y).max(), 1e-300):
        ax.plot(s.z * 1e3, s.x * 1e6, color="C1", ls="--", label="x")
    for r in s.reactions:
        ax.axvline(r.position * 1e3, color="0.6", lw=0.8)
        fx, fy = (v if abs(v) >= 0.5 else 0.0 for v in r.force[:2])   # no "-0"
        ax.annotate(f"{r.name}\n{fx:,.0f}, {fy:,.0f} N", (r.position * 1e3, 0),
                    textcoords="offset points", xytext=(3, 6), fontsize=8, color="0.3")
    ax.axhline(0.0, color="0.8", lw=0.6)
    ax.set_xlabel("z (mm)")
    ax.set_ylabel("deflection (um)")
    ax.set_title(f"{result.scene.name}: static deflection line and reactions (x, y)")
    ax.legend(loc="best", fontsize=8)
    return fig


def level1_figure(r):
    """API 684 Level I: the first forward mode's log decrement against the applied
    cross-coupling Q, Q_0 and Q_A marked, API 617's 0.1 drawn."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.5, 4.5))
    ax = fig.subplots()
    ax.plot(r.q / 1e3, r.log_dec, "o-", ms=3, lw=1.5, label="first forward mode")
    ax.axhline(0.0, color="black", lw=0.8)
    ax.axhline(0.1, color="grey", lw=0.8, ls="--", label="log dec 0.1 (API 617)")
    if r.q0 is not None:
        ax.axvline(r.q0 / 1e3, color="crimson", lw=1.0, ls=":", label=f"Q_0 {r.q0 / 1e3:,.0f} N/mm")
    if r.qa is not None:
        ax.axvline(r.qa / 1e3, color="tab:green", lw=1.0, ls="--",
                   label=f"Q_A {r.qa / 1e3:,.0f} N/mm")
    ax.set_xlabel("applied cross-coupled stiffness Q, N/mm")
    ax.set_ylabel("log decrement")
    ax.set_title(f"API 684 Level I screening: {r.scene.name}, {r.speed_rpm:,.0f} r/min, "
                 f"Q at {r.plane * 1e3:g} mm", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def runup_figure(r):
    """The run-up's envelope (the orbit's largest radius in each turn) against speed
    beside the steady unbalance response, per probe, and the orbit at the first probe's
    peak."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 4.5))
    ax, ax2 = fig.subplots(1, 2, gridspec_kw={"width_ratios": (2.2, 1.0)})
    for k, (name, env, steady) in enumerate(zip(r.names, r.envelopes, r.steady)):
        line, = ax.plot(r.speeds_rpm, env * 1e6, lw=1.4, label=f"{name}: run")
        ax.plot(r.speeds_rpm, steady * 1e6, lw=1.0, ls="--", color=line.get_color(),
                label=f"{name}: steady")
        n, amp = r.peaks[k]
        ax.plot([n], [amp * 1e6], "o", color=line.get_color(), ms=4)
    kind = "run-up" if r.accel_rpm_per_s > 0 else "coast-down"
    ax.set_xlabel("speed, r/min")
    ax.set_ylabel("orbit radius, um (0-peak)")
    ax.set_title(f"{kind.capitalize()} at {abs(r.accel_rpm_per_s):,.4g} r/min per s: "
                 f"{r.scene.name}", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    xy = r.orbits[0] * 1e6
    ax2.plot(xy[0], xy[1], lw=1.0)
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.set_title(f"orbit at the peak, {r.names[0]} ({r.peaks[0][0]:,.0f} r/min)", fontsize=9)
    ax2.set_xlabel("x, um")
    ax2.set_ylabel("y, um")
    ax2.grid(True, alpha=0.3)
    return fig


def frf_figure(r):
    """|H_xx| against frequency at each speed (log), and its phase."""
    import numpy as np
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 6))
    ax, ph = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": (2, 1)})
    for n, row in zip(r.speeds_rpm, r.H):
        h = row[:, 0, 0]
        line, = ax.semilogy(r.frequencies_hz, np.abs(h) * 1e6, lw=1.3, label=f"{n:,.0f} r/min")
        ph.plot(r.frequencies_hz, np.degrees(np.unwrap(np.angle(h))), lw=1.0,
                color=line.get_color())
    ax.set_ylabel("|H_xx|, um/N")
    ax.set_title(f"Receptance at {r.probe_at * 1e3:g} mm, force at {r.force_at * 1e3:g} mm: "
                 f"{r.scene.name}", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ph.set_xlabel("frequency, Hz")
    ph.set_ylabel("phase, deg")
    ph.grid(True, alpha=0.3)
    return fig


def bearings_figure(cases):
    """Each speed-dependent bearing's and seal's stiffness and damping coefficients
    against speed, one row each, every case on it (`cases`: (name, Campbell run)
    pairs; solid the first, then dashed and dotted). None without such a bearing."""
    import numpy as np
    from matplotlib.figure import Figure

    first = cases[0][1]
    names = [s.name for s in first.rotor_scene.held if s.bearing is not None and s.bearing.speeds]
    if not names:
        return None
    fig = Figure(figsize=(10, 2.8 * len(names) + 0.6))
    axes = np.atleast_2d(fig.subplots(len(names), 2, squeeze=False))
    styles = ["-", "--", ":", "-."]
    colors = {"xx": "tab:blue", "xy": "tab:orange", "yx": "tab:green", "yy": "tab:red"}
    for row, name in enumerate(names):
        for j, (which, unit) in enumerate((("k", "N/mm"), ("c", "N s/mm"))):
            ax = axes[row, j]
            for i, (case, c) in enumerate(cases):
                s = next(x for x in c.rotor_scene.held if x.name == name)
                b = s.bearing
                # from a quarter of the lowest operating speed: near the film's lift-off
                # its damping runs off by tens, and hides what the running range sees
                low = min(lo for lo, _ in c.rotor_scene.rotor.spans) * 30 / np.pi
                lo = max(c.lift_rpm, 0.25 * low, 1e-3 * max(c.speeds_rpm))
                n = np.linspace(lo, max(c.speeds_rpm), 200)
                get = b.stiffness if which == "k" else b.damping
                values = np.array([get(v * np.pi / 30) for v in n]) / 1e3
                for (a, bb), key in (((0, 0), "xx"), ((0, 1), "xy"), ((1, 0), "yx"),
                                     ((1, 1), "yy")):
                    ax.plot(n, values[:, a, bb], styles[i % 4], color=colors[key], lw=1.2,
                            label=f"{which}{key}" if i == 0 else None)
                ax.plot([], [], styles[i % 4], color="grey", label=case)
            ax.axhline(0.0, color="black", lw=0.6)
            ax.set_title(f"{name}: {'stiffness' if which == 'k' else 'damping'}", fontsize=9)
            ax.set_ylabel(unit)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7, ncol=2)
        axes[row, 0].set_xlabel("speed, r/min")
        axes[row, 1].set_xlabel("speed, r/min")
    fig.suptitle("Bearing and seal coefficients against speed"
                 + (" (each case)" if len(cases) > 1 else ""), fontsize=10)
    return fig


def pads_figure(c):
    """Each tilting pads' bearing's stiffness and damping at the first operating speed
    against the whirl's frequency over the spin (its tilts condensed at each whirl), the
    synchronous value and the judged mode's whirl marked (a Campbell run `c`). None
    without tilting pads."""
    import numpy as np
    from matplotlib.figure import Figure

    held = [s for s in c.rotor_scene.held if s.bearing is not None and s.bearing.pads]
    if not held:
        return None
    w = c.rotor_scene.rotor.speeds[0]
    ratios = np.geomspace(0.1, 4.0, 120)
    fig = Figure(figsize=(10, 2.8 * len(held) + 0.6))
    axes = np.atleast_2d(fig.subplots(len(held), 2, squeeze=False))
    colors = {"xx": "tab:blue", "xy": "tab:orange", "yx": "tab:green", "yy": "tab:red"}
    judged = None if c.stability is None else c.stability.frequency_hz * 2 * np.pi / w
    for row, s in enumerate(held):
        pairs = [s.bearing.at_whirl(w, r * w) for r in ratios]
        for j, (what, unit) in enumerate((("stiffness", "N/mm"), ("damping", "N s/mm"))):
            ax = axes[row, j]
            values = np.array([p[j] for p in pairs]) / 1e3
            for (a, b), key in (((0, 0), "xx"), ((0, 1), "xy"), ((1, 0), "yx"), ((1, 1), "yy")):
                ax.plot(ratios, values[:, a, b], color=colors[key], lw=1.2,
                        label=f"{'kc'[j]}{key}")   # the table's names: kxx, cxx
            ax.axvline(1.0, color="black", lw=0.8, ls="--", label="synchronous")
            if judged is not None:
                ax.axvline(judged, color="tab:purple", lw=0.8, ls=":",
                           label=f"judged mode ({c.stability.frequency_hz:.1f} Hz)")
            ax.axhline(0.0, color="black", lw=0.6)
            ax.set_xscale("log")
            ax.set_title(f"{s.name}: {what} at {w * 30 / np.pi:,.0f} r/min", fontsize=9)
            ax.set_ylabel(unit)
            ax.set_xlabel("whirl frequency / spin")
            ax.grid(True, alpha=0.3, which="both")
            ax.legend(fontsize=7, ncol=2)
    fig.suptitle("Tilting pads' coefficients against the whirl's frequency (the tilts "
                 "condensed at each)", fontsize=10)
    return fig


def hot_spots_figure(result):
    """The shaft's surface unrolled (z in mm along, the angle about the axis in degrees
    across), coloured by the degree of utilisation (the larger of FKM's fatigue a_BK and
    yield a_SK: 1 uses up the required safety), with each hot spot numbered as in the
    table, filled with its own utilisation (its local model's where it had one), and the
    bands where loads enter shaded (a workflows.strength.StrengthResult)."""
    import numpy as np
    from matplotlib import patheffects

    scene = result.scene
    surface = result.surface
    points = surface.points
    values = np.fmax(surface.fatigue_utilisation, surface.yield_utilisation)
    fig, ax = _figure((9, 3.8))
    r = np.hypot(points[:, 0], points[:, 1])
    order = np.argsort(r)        # the outer surface drawn over the groove floors
    angle = np.degrees(np.arctan2(points[:, 1], points[:, 0])) % 360
    judged = order[np.isfinite(values[order])]
    bands = order[~np.isfinite(values[order])]
    ax.scatter(points[bands, 2] * 1e3, angle[bands], c="0.75", s=2, rasterized=True)
    # each spot filled with its own utilisation: a spot bounded in a local model reads
    # above the whole's coarser field round it (the paper's crossings: 0.36 on a field
    # that tops at 0.33), and one colour scale holds both
    used = [max(s.fkm.fatigue_utilisation, s.fkm.yield_utilisation) for s in result.spots]
    top = max([float(np.max(values[judged], initial=0.0)), *used, 1e-9])
    art = ax.scatter(points[judged, 2] * 1e3, angle[judged], c=values[judged], s=2,
                     cmap="inferno", vmin=0.0, vmax=top, rasterized=True)
    fig.colorbar(art, ax=ax, label="utilisation max(a_BK, a_SK)")
    for s in scene.held:
        ax.axvspan(s.seat[0] * 1e3, s.seat[1] * 1e3, color="0.85", alpha=0.6, lw=0)
    outline = [patheffects.withStroke(linewidth=2.5, foreground="white")]
    # spots closer than a label's size share one label ("4,5")
    span = float(np.ptp(points[:, 2])) * 1e3
    where = [(s.z * 1e3, np.degrees(s.angle) % 360) for s in result.spots]
    groups: list[list[int]] = []
    if where:
        ax.scatter([z for z, _ in where], [a for _, a in where], c=used, cmap="inferno",
                   vmin=0.0, vmax=top, s=81, edgecolors="C0", linewidths=1.5, zorder=3)
    for k, (z, a) in enumerate(where, 1):
        for g in groups:
            z0, a0 = where[g[0] - 1]
            if abs(z0 - z) < 0.03 * span and abs((a0 - a + 180) % 360 - 180) < 20:
                g.append(k)
                break
        else:
            groups.append([k])
    for g in groups:
        z, a = where[g[0] - 1]
        # a spot at the top edge is labelled below it, inside the axes
        ax.annotate(",".join(map(str, g)), (z, a), textcoords="offset points",
                    xytext=(5, -13 if a > 330 else 5), fontsize=9, color="C0",
                    weight="bold", path_effects=outline)
    ax.set_xlabel("z along the shaft (mm)")
    ax.set_ylabel("angle about the axis (deg)")
    # a little past 0 and 360 deg, so that a spot's circle on either edge is whole
    ax.set_ylim(-12, 372)
    ax.set_yticks(range(0, 361, 60))
    ax.set_title(f"{scene.name}: hot spots on the unrolled surface (load bands grey)")
    return fig
