"""Charts as matplotlib Figures (study, sweeps): no pyplot, no backend switch.

`matplotlib.figure.Figure` renders to PNG through its own Agg canvas, so
drawing here never changes the caller's matplotlib state.
"""

from __future__ import annotations

from pathlib import Path

from .store import atomic_path


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
    return written


def response_figure(fr, harmonics: list[tuple[str, float]], title: str = ""):
    """Transmissibility against frequency (log scale) for base motion at the supports,
    with each excitation harmonic (label, Hz) marked."""
    fig, ax = _figure((7.5, 4.5))
    ax.semilogy(fr.frequencies, fr.transmissibility, "-", lw=1.2,
                label=f"{fr.direction} at z = {fr.point[2] * 1e3:.0f} mm, "
                f"zeta = {100 * fr.damping:g} %")
    top = fr.frequencies[-1]
    for label, f in harmonics:
        if f <= top:
            ax.axvline(f, color="tab:red", ls="--", lw=0.8)
            ax.annotate(label, (f, 1.0), rotation=90, fontsize=7, color="tab:red",
                        textcoords="offset points", xytext=(3, 4))
    ax.axhline(1.0, color="0.5", lw=0.6)
    ax.set_xlim(0, top)
    ax.set_xlabel("excitation frequency, Hz")
    ax.set_ylabel("transmissibility |u / u_base|")
    if title:
        ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    return fig
