"""An end-milled keyseat of Peterson's proportions against the chart's reading: a 32 mm
bar with a keyseat b = d/4 = 8 mm wide, t = d/8 = 4 mm deep, 40 mm long, its floor
corners r = 0.02 d = 0.64 mm, in bending and torsion (benchmarks/notch_factors.py's bar,
loads and nominal stresses). `shaftfem strength`'s worst spot in the keyseat, as
K_t = sigma_vM,max / sigma_vM,nom with its bound, beside the chart's K_t as Shigley's
Table 7-1 reads Peterson's charts for an end-mill keyseat at r/d = 0.02 (Budynas and
Nisbett, Shigley's Mechanical Engineering Design, 9th ed., Table 7-1: bending 2.14,
torsion 3.0; the charts' K_t is the largest principal stress over the nominal, in
torsion over tau_nom: in pure shear at the surface the same as the von Mises ratio; in
bending the von Mises ratio is the lower).

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/keyseat_chart.py

About 10 minutes on 2 cores (no independent reference: see notch_factors.py for the
DIN 10 x 5 keyway's).
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import notch_factors as nf  # noqa: E402

CHART = {"bending": 2.14, "torsion": 3.0}   # Shigley 9th ed., Table 7-1, r/d = 0.02


def main() -> int:
    print("| load | shaftfem K_t (von Mises) | its bound | chart (Shigley, Table 7-1) | "
          "shaftfem / chart - 1 | spot | DOFs | s |")
    print("|---|---|---|---|---|---|---|---|")
    for load, chart in CHART.items():
        name = f"keyseat 8x4 r0.64, {load}"
        nf.SHAPES[name] = (nf.keyed(32, 40, 8, 4, 0.64), load, 32, (125, 175), None)
        with tempfile.TemporaryDirectory() as d:
            o = nf.ours(name, 2.0, Path(d))
        if "error" in o:
            print(f"| {load} | {o['error']} |")
            continue
        bound = "unknown" if o["bound"] is None else f"{o['bound']:.2%}"
        print(f"| {load} | {o['kt']:.4f} | {bound} | {chart:.2f} | {o['kt'] / chart - 1:+.1%} "
              f"| {o['feature']} at {o['z_mm']:.1f} mm | {o['dofs'][-1]:,} | {o['wall']:.0f} |",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
