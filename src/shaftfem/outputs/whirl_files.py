"""The whirl at the operating speeds as files and a picture: each complex mode shape
as a VTU with its real and imaginary parts (ParaView animates u(t) = Re(u e^{i w t})
with the Calculator filter `real*cos(t)-imag*sin(t)`), a .pvd collecting them, and
orbits.png: the orbit of the shaft's axis at stations along it for each mode."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from shaftfem.fem.whirl import Campbell

# Stations along the shaft where orbits are drawn, and the share of the radius about the
# axis whose nodes' mean motion stands for the axis there.
STATIONS = 9
NEAR_AXIS = 0.35


def _harmonic_points(c: Campbell, i: int) -> np.ndarray:
    """Operating speed i's modes at the mesh's points, each harmonic's (the rotor's own
    frame; one but on a periodic rotor), complex, (2 S + 1, m, n_points, 3)."""
    r = c.result
    forms = c.operating_shapes[i]                               # (2 S + 1, N, m)
    out = []
    for Y in forms:
        U = c.basis_shapes @ Y                                  # (3 n, m) complex
        out.append(r.system.at_points(U.real) + 1j * r.system.at_points(U.imag))
    return np.array(out)


def _shift(c: Campbell, i: int) -> float:
    """The spin (rad/s) of the frame the modes at operating speed i are solved in."""
    return c.operating_rpm[i] * math.pi / 30 if c.frame == "rotating" else 0.0


def complex_shapes(c: Campbell, i: int) -> np.ndarray:
    """Operating speed i's mode shapes at the mesh's points as the housing sees them at
    each mode's frequency, complex, (m, n_points, 3), scaled to a largest displacement
    of 1 (fem.rotor.seen_shape; the axial motion is the dominant harmonic's)."""
    from shaftfem.fem.rotor import seen_shape

    n = c.operating_rpm[i]
    rows = [w for w in c.operating if abs(w.speed_rpm - n) <= 1e-9 * n]
    H = _harmonic_points(c, i)
    S = (H.shape[0] - 1) // 2
    pts = H[S].copy()
    for k, w in enumerate(rows[:pts.shape[0]]):
        pts[k, :, 0], pts[k, :, 1] = seen_shape(
            _shift(c, i), 2 * math.pi * w.rotating_frame_hz, 2 * math.pi * w.frequency_hz,
            H[:, k, :, 0], H[:, k, :, 1])
    scale = np.abs(pts).reshape(pts.shape[0], -1).max(axis=1)
    return pts / scale[:, None, None]


def write_whirl_files(c: Campbell, folder: Path) -> list[Path]:
    """whirl_<rpm>_<k>.vtu for every reported mode at every operating speed, and whirl.pvd
    listing them."""
    from shaftfem.outputs.vtk import write_vtu
    from shaftfem.store import write_text

    folder.mkdir(parents=True, exist_ok=True)
    files: list[Path] = []
    entries: list[str] = []
    for i, n in enumerate(c.operating_rpm):
        rows = [w for w in c.operating if abs(w.speed_rpm - n) <= 1e-9 * n]
        shapes = complex_shapes(c, i)
        for w, u in zip(rows, shapes):
            name = f"whirl_{n:.0f}rpm_{w.mode:02d}.vtu"
            files.append(write_vtu(folder / name, c.result.mesh,
                                   {"real": u.real, "imag": u.imag,
                                    "amplitude": np.linalg.norm(np.abs(u), axis=1)},
                                   {"frequency_hz": w.frequency_hz, "speed_rpm": n,
                                    "whirl_index": w.whirl_index, "log_dec": w.log_dec}))
            entries.append(f'    <DataSet timestep="{len(entries)}" part="0" file="{name}"/>')
    pvd = ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
           + "\n".join(entries) + "\n  </Collection>\n</VTKFile>\n")
    files.append(write_text(folder / "whirl.pvd", pvd))
    return files


def orbits_figure(c: Campbell, i: int = 0, count: int = 4):
    """The orbits of the axis at STATIONS stations for the first `count` whirling modes at
    operating speed i as the housing sees them: the path each traces over one period of
    its frequency (an ellipse but where a rotating-frame mode shows the housing parts at
    other frequencies: fem.rotor.seen_orbit), a dot where t = 0 and an arrow the way it
    runs (forward: as the shaft turns)."""
    from matplotlib.figure import Figure

    from shaftfem.fem.rotor import seen_orbit

    r = c.result
    n = c.operating_rpm[i]
    rows = [w for w in c.operating if abs(w.speed_rpm - n) <= 1e-9 * n]
    keep = [k for k, w in enumerate(rows) if w.kind in ("bending", "mixed")][:count]
    H = _harmonic_points(c, i)
    pts = r.mesh.points
    radius = np.hypot(pts[:, 0], pts[:, 1])
    z = pts[:, 2]
    zs = np.linspace(z.min(), z.max(), STATIONS)
    slab = 0.5 * (zs[1] - zs[0])
    near = radius <= NEAR_AXIS * radius.max()
    fig = Figure(figsize=(9.0, 1.2 + 1.5 * max(len(keep), 1)))
    axes = fig.subplots(max(len(keep), 1), 1, squeeze=False)[:, 0]
    gap = 2.4
    at = [near & (np.abs(z - zj) <= slab) for zj in zs]    # the points standing for each
    for ax, k in zip(axes, keep):
        w = rows[k]
        t = np.linspace(0.0, 1.0 / w.frequency_hz, 73)
        X = np.array([[H[d, k, a, 0].mean() if a.any() else 0.0 for a in at]
                      for d in range(H.shape[0])])
        Y = np.array([[H[d, k, a, 1].mean() if a.any() else 0.0 for a in at]
                      for d in range(H.shape[0])])
        ox, oy = seen_orbit(_shift(c, i), 2 * math.pi * w.rotating_frame_hz, X, Y, t)
        scale = max(float(np.abs(ox + 1j * oy).max()), 1e-300)
        ox, oy = ox / scale, oy / scale
        colour = "tab:red" if w.whirl == "forward" else (
            "tab:blue" if w.whirl == "backward" else "tab:purple")
        for j in range(STATIONS):
            if not at[j].any():
                continue
            ax.plot(gap * j + ox[:, j], oy[:, j], color=colour, lw=1.2)
            ax.plot(gap * j + ox[0, j], oy[0, j], "o", color=colour, ms=3)
            if np.abs(ox[:, j] + 1j * oy[:, j]).max() > 0.15:   # where it can be seen
                ax.annotate("", (gap * j + ox[8, j], oy[8, j]), (gap * j + ox[4, j], oy[4, j]),
                            arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 1.2})
        ax.set_aspect("equal")
        ax.set_xlim(-1.3, gap * (STATIONS - 1) + 1.3)
        ax.set_ylim(-1.2, 1.2)
        ax.set_xticks([gap * j for j in range(STATIONS)])
        ax.set_xticklabels([f"{zj * 1e3:.0f}" for zj in zs], fontsize=7)
        ax.set_yticks([])
        ax.set_ylabel(f"mode {w.mode}\n{w.frequency_hz:.1f} Hz\n{w.whirl} "
                      f"{w.whirl_index:+.2f}", fontsize=8, rotation=0, ha="right", va="center")
    axes[-1].set_xlabel("station along the shaft, z in mm (the orbits to one scale per mode)",
                        fontsize=8)
    fig.suptitle(f"{r.scene.name}: orbits of the axis at {n:,.0f} r/min as the housing sees "
                 f"them (the shaft turns anticlockwise)", fontsize=9)
    return fig
