"""The journal bearings of Friswell's 5.9.1 rotor on plain journals
(tests/test_journal_bearing.friswell_journals), as shaftfem's film gives them: each
journal's load (its reaction to the rotor's weight) and its eight coefficients at every
speed of its table. ross takes these same bearings (benchmarks/ross_reference.py
--journals), so that the rotors, not the films, are compared.

    .venv/bin/python benchmarks/journal_tables.py tests/data/journal_591.json
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))


def main(path: str) -> None:
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.static import with_journal_loads
    from test_journal_bearing import friswell_journals

    scene = with_journal_loads(load_scene(friswell_journals()))
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
    main(sys.argv[1] if len(sys.argv) > 1 else "journal_591.json")
