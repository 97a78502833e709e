"""The journal bearings of Friswell's 5.9.1 rotor on plain journals
(tests/test_journal_bearing.friswell_journals), as shaftfem's film gives them: each
journal's load (its reaction to the rotor's weight) and its eight coefficients at every
speed of its table. ross takes these same bearings (benchmarks/ross_reference.py
--journals), so that the rotors, not the films, are compared.

    .venv/bin/python benchmarks/journal_tables.py tests/data/journal_591.json

With --case, the same rotor with its tolerances (tests/test_tolerance_cases.
friswell_tolerances: 45 to 55 um, 16 to 24 mPa s) in its case "min clearance, cold
oil" (45 um, 24 mPa s), as `check` runs it (workflows.cases):

    .venv/bin/python benchmarks/journal_tables.py --case tests/data/journal_591_tight.json
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))


def main(path: str, case: bool = False) -> None:
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.cases import case_scene, cases_of
    from shaftfem.workflows.static import equipped
    from test_journal_bearing import friswell_journals
    from test_tolerance_cases import friswell_tolerances

    if case:
        ranged = load_scene(friswell_tolerances())
        tight = next(c for c in cases_of(ranged) if c.name == "min clearance, cold oil")
        scene = equipped(case_scene(ranged, tight))
    else:
        scene = equipped(load_scene(friswell_journals()))
    out = {"source": "shaftfem's film (shaftfem.parts.journal); N/m, N s/m, rad/s",
           "bearings": []}
    for s in scene.supports:
        b = s.bearing
        out["bearings"].append({
            "name": s.name, "position_m": s.position, "load_n": s.journal.load,
            "speeds": list(b.speeds),
            **{k: list(getattr(b, k)) for k in ("kxx", "kxy", "kyx", "kyy",
                                                 "cxx", "cxy", "cyx", "cyy")}})
    Path(path).write_text(json.dumps(out, indent=1))
    print(f"wrote {path}")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--case"]
    main(args[0] if args else "journal_591.json", "--case" in sys.argv)
