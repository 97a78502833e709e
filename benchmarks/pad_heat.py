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
(tests/data/fillon_ross_grown.json, `--heat --grown`). Last, the synchronously reduced
stiffness and damping of the heat balance's one film temperature on the cold clearance
against the heated, grown film's (what the rotor model takes) and ross's.

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
from shaftfem.parts import heat, journal, pad_heat, pads  # noqa: E402
from shaftfem.scene.model import JournalBearing, JournalBore  # noqa: E402

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


def coefficients() -> None:
    """The balance's K_xx and C_xx (the pads isotropic here) against the heated film's
    on grown parts (what the rotor model takes), and ross's on its deformed and grown
    film (massless pads)."""
    c = 148e-6 * (1 - 0.47)
    spec = JournalBore(kind="tilting_pad", pads=4, arc=math.radians(75), preload=0.47)
    b = journal.with_oil(JournalBearing(
        diameter=0.1, length=0.07, clearance=c, viscosity=None, load=10e3, bore=spec,
        oil_iso_vg=32, oil_supply_temperature=40.0, pad_thickness=PADS))
    journal.remember(pads.film_table(spec, round(b.ratio, 9)))
    print("\nsynchronous coefficients: the heat balance's film against the heated film on "
          "grown parts (what the rotor model takes) and ross's\n")
    ross = {r["speed_rpm"]: r for r in
            json.loads((DATA / "fillon_ross_grown.json").read_text())["results"]}
    print("| r/min | film, C | K_xx, MN/m | heated, grown | off | ross 3.1 | C_xx, kN s/m | "
          "heated, grown | off | ross 3.1 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n in SPEEDS:
        w = n * math.pi / 30
        h = heat.heat_balance(b, w, 40.0)
        op = journal.operating(heat.running(b, h), w)
        hot = pad_heat.heated_operating(b, pad_heat.heated_at(b, w), w, op)
        k, d = hot.K[0, 0], hot.C[0, 0]
        r = ross[n]
        print(f"| {n:,.0f} | {h.effective:.1f} | {op.K[0, 0] / 1e6:.1f} | {k / 1e6:.1f} | "
              f"{op.K[0, 0] / k - 1:+.1%} | {r['kxx'] / 1e6:.1f} | {op.C[0, 0] / 1e3:.1f} | "
              f"{d / 1e3:.1f} | {op.C[0, 0] / d - 1:+.1%} | {r['cxx'] / 1e3:.1f} |")


if __name__ == "__main__":
    main()
    coefficients()
