"""The undamped critical speed map as API 684 draws it: each branch's critical speed
against the bearings' stiffness, log-log, the scene's bearings' stiffness against speed
over it (their crossings with the branches marked), and beside it each branch's
deflected line at the soft and the stiff end."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from shaftfem.fem.whirl import UcsMap


def ucs_figure(m: UcsMap):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 5.5))
    grid = fig.add_gridspec(2, 2, width_ratios=(1.6, 1.0))
    ax = fig.add_subplot(grid[:, 0])
    k = m.stiffness / 1e3
    for i, row in enumerate(m.speeds_rpm):
        ax.loglog(k, row, lw=1.6, label=f"branch {i + 1}")
    styles = {"x": "--", "y": ":"}
    for b in m.bearings:
        for d, kd in (("x", b.kxx), ("y", b.kyy)):
            ax.loglog(kd / 1e3, b.speeds_rpm, color="black", lw=1.0, ls=styles[d],
                      label=f"{b.name}: k{d}{d}")
        for _, _, kc, n in b.crossings:
            ax.plot(kc / 1e3, n, "o", ms=5, mfc="none", mec="crimson")
    ax.set_xlim(k[0], k[-1])
    ok = m.speeds_rpm[np.isfinite(m.speeds_rpm) & (m.speeds_rpm > 0)]
    low = float(ok.min()) if ok.size else 1.0
    ax.set_ylim(low / 1.5, (float(ok.max()) if ok.size else 10.0) * 1.5)
    ax.set_xlabel("bearing stiffness, N/mm (every bearing alike)")
    ax.set_ylabel("undamped critical speed, r/min")
    ax.set_title(f"Undamped critical speed map: {m.scene.name}\n{m.title}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    # a shaft not of revolution: each bending pair is split by its two principal planes
    # lower right: under the first branch's stiff-end plateau, where no branch runs
    ax.legend(fontsize=7, loc="lower right", title_fontsize=7, framealpha=0.9,
              title=None if m.scene.axisymmetric else
              "not a solid of revolution: each bending mode\nis two branches, one per "
              "principal plane")
    for j, (lines, where) in enumerate(((m.soft_lines, k[0]), (m.stiff_lines, k[-1]))):
        sub = fig.add_subplot(grid[j, 1])
        for i, amp in enumerate(lines):
            sub.plot(m.z * 1e3, amp, lw=1.3, label=f"branch {i + 1}")
        for s in m.scene.supports:
            sub.axvline(s.position * 1e3, color="black", lw=0.7, ls="--")
        sub.set_ylim(0, 1.1)
        sub.set_title(f"shapes at {where:.3g} N/mm", fontsize=9)
        sub.grid(True, alpha=0.3)
        if j == 1:
            sub.set_xlabel("position along the shaft, mm")
        sub.set_ylabel("deflection (largest 1)", fontsize=8)
    return fig
