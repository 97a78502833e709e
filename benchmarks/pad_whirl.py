"""Where keeping the tilting pads' tilts matters (docs/journal-bearing.md, "The pads in
the rotor model"): examples/compressor_on_tilting_pads.toml across its speed range, the
first forward mode's frequency and log decrement with every pad's tilt a coordinate of
the rotor model, against the same rotor with the pads' synchronously reduced 2x2
coefficients (what tools that reduce the pads give): at each speed each model's first
forward lateral mode (its lowest forward root with a damping ratio below 0.5: the
films' nearly overdamped roots left out), and the mode with the tilts whose shape is
nearest the reduced model's first forward mode (largest MAC).

    .venv/bin/python benchmarks/pad_whirl.py

About two minutes.
"""

from __future__ import annotations

import math
import sys
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).parents[1]
sys.path.insert(0, str(Path(__file__).parent))

import _common  # noqa: E402, F401  (one BLAS thread, as the CLI)
from shaftfem import RunOptions, load_scene  # noqa: E402
from shaftfem.fem.rotor import dominant_kinds, roots, whirl_index  # noqa: E402
from shaftfem.workflows.campbell import turning  # noqa: E402


def forward(model, omega):
    """The forward lateral roots at omega with a damping ratio below 0.5, lowest
    frequency first: (Hz, log dec, modal shapes)."""
    import numpy as np

    r = roots(model, omega)
    lateral = np.array([k not in ("axial", "torsion") for k in dominant_kinds(model, r.y)])
    keep = (whirl_index(model, r.y) > 0) & (-r.lam.real / np.abs(r.lam) < 0.5) & lateral
    lam = r.lam[keep]
    return lam.imag / (2 * math.pi), -2 * math.pi * lam.real / lam.imag, r.y[:, keep]


def main() -> None:
    scene = load_scene(ROOT / "examples" / "compressor_on_tilting_pads.toml")
    _, model, _ = turning(scene, RunOptions())
    reduced = replace(model, reduced=True)
    import numpy as np

    print("| speed, r/min | first forward, reduced | first forward, with the tilts | "
          "the reduced one's mode with the tilts (MAC) | log dec, reduced over with the "
          "tilts |")
    print("|---|---|---|---|---|")
    for rpm in range(1000, 14001, 1000):
        w = rpm * math.pi / 30
        fr, dr, yr = forward(reduced, w)
        ff, df, yf = forward(model, w)
        mac = np.abs(yf.conj().T @ yr[:, 0])**2 / (
            np.sum(np.abs(yf)**2, axis=0) * np.sum(np.abs(yr[:, 0])**2))
        j = int(np.argmax(mac))
        print(f"| {rpm:,} | {fr[0]:.1f} Hz, {dr[0]:.3f} | {ff[0]:.1f} Hz, {df[0]:.3f} | "
              f"{ff[j]:.1f} Hz, {df[j]:.3f} ({mac[j]:.2f}) | {dr[0] / df[j]:.2f} |")


if __name__ == "__main__":
    main()
