"""The heated film of a bore of pads against Fillon, Bligoud & Frene (1992)
(docs/journal-bearing.md, "The film's heating"): their 4-pad tilting-pad bearing, D 100
mm, L 70 mm, 75-degree pads, pivots at 0.5, preload 0.47 on a pad clearance of 148 um
(c_b 78.4 um), loaded between pads with 10 kN, ISO VG 32 supplied at 40 C (the rig as
Kim, Palazzolo & Gadangi (1994) and ross 3.1's tests/test_fluid_film_literature.py
tabulate it): the peak pad temperature at 1,000 to 4,000 r/min against the paper's own
thermo-elasto-hydrodynamic prediction and its measurement, and against ross 3.1's
thermohydrodynamic film on the same rig and oil (tests/data/fillon_ross.json, written by
`benchmarks/tilting_pad_reference.py --heat`). Twice: on rigid parts of their cold size,
and on parts grown by their heat with 20 mm pads (parts.pad_heat.grown), against ross's
pads deformed by their pressure and heat and its journal and shell grown
(tests/data/fillon_ross_grown.json, `--heat --grown`).

    .venv/bin/python benchmarks/pad_heat.py

About three minutes.
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


DATA = Path(__file__).parents[1] / "tests" / "data"
PADS = 0.02   # m, the pads' thickness, as ross's own test of this rig takes it


def main() -> None:
    bore = pads.tilting(0.7, 4, math.radians(75), 0.47, 0.5, math.radians(45))
    for title, name, thickness in (("rigid parts of their cold size", "fillon_ross.json", None),
                                   ("parts grown by their heat", "fillon_ross_grown.json",
                                    PADS)):
        ross = {r["speed_rpm"]: r for r in json.loads((DATA / name).read_text())["results"]}
        print(f"\n{title}\n")
        print("| r/min | peak pad temperature, C | ross 3.1 | paper's TEHD | measured | "
              "against TEHD | journal, C (ross) | eccentricity (ross) | hot clearance, um |")
        print("|---|---|---|---|---|---|---|---|---|")
        for n, tehd, measured in zip(SPEEDS, TEHD, MEASURED):
            h = pad_heat.heated(bore, 10e3, n * math.pi / 30, 0.05, 148e-6 * (1 - 0.47), 32,
                                40.0, thickness=thickness)
            r = ross[n]
            print(f"| {n:,.0f} | {h.peak:.1f} | {r['peak_c']:.1f} | {tehd} | {measured} | "
                  f"{h.peak - tehd:+.1f} | {h.journal:.1f} ({r['journal_c']:.1f}) | "
                  f"{math.hypot(*h.state.q[:2]):.3f} ({r['eccentricity']:.3f}) | "
                  f"{min(h.clearance) * 1e6:.1f} |")


if __name__ == "__main__":
    main()
