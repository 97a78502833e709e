"""Bearings of pads against the literature and an independent code (docs/verification.md,
"Bearings of pads"):

- fixed-geometry bores (two axial grooves, L/D 0.5 and 1; elliptical, preload 0.5)
  against Lund & Thomsen's (1978) tables: eccentricity, attitude and the eight
  coefficients, in their frame and units (tests/test_pads.py holds the rows);
- tilting pads against ross 3.1's TiltingPad, isoviscous (tests/data/tilting_pads_ross.json,
  made by benchmarks/tilting_pad_reference.py): eccentricity and the synchronously
  reduced coefficients.

    .venv/bin/python benchmarks/pad_bearings.py

About a minute.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).parents[1]
sys.path.insert(0, str(Path(__file__).parent))
sys.path.insert(0, str(ROOT / "tests"))
import _common  # noqa: E402, F401  (one BLAS thread, as the CLI)
from shaftfem.parts import pads  # noqa: E402
from test_pads import (  # noqa: E402
    ELLIPTICAL,
    TWO_AXIAL_GROOVE,
    lund_thomsen_frame,
    ross_cases,
)

NAMES = ("Kxx", "Kxy", "Kyx", "Kyy", "Bxx", "Bxy", "Byy")


def literature() -> None:
    print("| bore | S | eps (table) | attitude, deg (table) | largest coefficient "
          "difference | where |")
    print("|---|---|---|---|---|---|")
    cases = [(f"two axial grooves, L/D {r:g}", pads.two_axial_groove(r), rows)
             for r, rows in TWO_AXIAL_GROOVE.items()]
    cases.append(("elliptical, preload 0.5, L/D 1", pads.elliptical(1.0, 0.5), ELLIPTICAL))
    for name, bore, rows in cases:
        for S, eps, phi, *table in rows:
            e, att, ours = lund_thomsen_frame(bore, S)
            rel = [(abs(a / b - 1), n, a, b) for a, b, n in zip(ours, table, NAMES)
                   if abs(b) >= 0.5]
            worst = max(rel)
            small = [f"{n} {a:.3f} ({b:.2f})" for a, b, n in zip(ours, table, NAMES)
                     if abs(b) < 0.5]
            print(f"| {name} | {S:g} | {e:.3f} ({eps:.3f}) | {att:.2f} ({phi:.2f}) | "
                  f"{worst[0]:.1%} ({worst[1]} {worst[2]:.3f} against {worst[3]:.2f}) | "
                  f"{', '.join(small)} |", flush=True)


def tilting() -> None:
    ref = json.loads((ROOT / "tests" / "data" / "tilting_pads_ross.json").read_text())
    print(f"\nreference: {ref['source']}\n")
    print("| bearing | r/min | eccentricity (ross) | kxx | kyy | cxx | cyy | largest cross "
          "term over the direct ones, shaftfem / ross |")
    print("|---|---|---|---|---|---|---|---|")
    for name, _, r, state, K, C in ross_cases():
        cells = []
        for M, kind in ((K, "k"), (C, "c")):
            for (i, j), ij in ((0, 0), "xx"), ((1, 1), "yy"):
                cells.append(f"{M[i, j] / r[kind + ij] - 1:+.2%}")
        cross = max(abs(K[0, 1]), abs(K[1, 0])) / max(abs(K[0, 0]), abs(K[1, 1]))
        theirs = max(abs(r["kxy"]), abs(r["kyx"])) / max(abs(r["kxx"]), abs(r["kyy"]))
        print(f"| {name} | {r['speed_rpm']:,.0f} | {math.hypot(*state.q[:2]):.4f} "
              f"({r['eccentricity']:.4f}) | {' | '.join(cells)} | {cross:.1e} / "
              f"{theirs:.1e} |", flush=True)


if __name__ == "__main__":
    literature()
    tilting()
