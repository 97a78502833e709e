"""The heated film of a bore of pads against Fillon, Bligoud & Frene (1992)
(docs/journal-bearing.md, "The film's heating"): their 4-pad tilting-pad bearing, D 100
mm, L 70 mm, 75-degree pads, pivots at 0.5, preload 0.47 on a pad clearance of 148 um
(c_b 78.4 um), loaded between pads with 10 kN, ISO VG 32 supplied at 40 C (the rig as
Kim, Palazzolo & Gadangi (1994) and ross 3.1's tests/test_fluid_film_literature.py
tabulate it): the peak pad temperature at 1,000 to 4,000 r/min against the paper's own
thermo-elasto-hydrodynamic prediction and its measurement, and against ross 3.1's
thermohydrodynamic film on the same rig and oil (tests/data/fillon_ross.json, written by
`benchmarks/tilting_pad_reference.py --heat`).

    .venv/bin/python benchmarks/pad_heat.py

About two minutes.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

import _common  # noqa: E402, F401  (one BLAS thread, as the CLI)
from shaftfem.parts import pad_heat, pads  # noqa: E402

SPEEDS = (1000.0, 2000.0, 3000.0, 4000.0)
TEHD = (43.7, 53.4, 63.2, 72.9)        # C, the paper's prediction
MEASURED = (49.5, 59.5, 67.5, 76.5)    # C


ROSS = Path(__file__).parents[1] / "tests" / "data" / "fillon_ross.json"


def main() -> None:
    ross = {r["speed_rpm"]: r for r in json.loads(ROSS.read_text())["results"]}
    bore = pads.tilting(0.7, 4, math.radians(75), 0.47, 0.5, math.radians(45))
    print("| r/min | peak pad temperature, C | ross 3.1 THD | paper's TEHD | measured | "
          "against TEHD | journal, C (ross) | eccentricity (ross) |")
    print("|---|---|---|---|---|---|---|---|")
    for n, tehd, measured in zip(SPEEDS, TEHD, MEASURED):
        h = pad_heat.heated(bore, 10e3, n * math.pi / 30, 0.05, 148e-6 * (1 - 0.47), 32, 40.0)
        r = ross[n]
        print(f"| {n:,.0f} | {h.peak:.1f} | {r['peak_c']:.1f} | {tehd} | {measured} | "
              f"{h.peak - tehd:+.1f} | {h.journal:.1f} ({r['journal_c']:.1f}) | "
              f"{math.hypot(*h.state.q[:2]):.3f} ({r['eccentricity']:.3f}) |")


if __name__ == "__main__":
    main()
