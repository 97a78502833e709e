"""Every shipped rotor's critical speed map against its Campbell diagram: each bearing
curve's crossings with the synchronous forward map (`run_ucs`) beside the 1x forward
critical speeds of the rotor that curve stands for (`crossing_scene`: every bearing on
that curve's stiffness against speed, isotropic and undamped), found on the Campbell
diagram's curves (`run_campbell`). The two share the mesh and nothing else: the map is
an eigenproblem in the speed squared at each stiffness, the diagram follows its roots
along the speed.

    .venv/bin/python benchmarks/ucs_examples.py [--mesh-size MM] [EXAMPLE.toml ...]
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def compare(path: Path, mesh_mm: float | None) -> list[tuple[str, str, int, float, float]]:
    """(bearing, direction, branch, map's crossing r/min, Campbell's r/min) of each
    crossing below the rotor's top speed (or, none there, of its lowest two)."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.campbell import run_campbell
    from shaftfem.workflows.pipeline import with_mesh
    from shaftfem.workflows.ucs import crossing_scene, run_ucs

    scene = with_mesh(load_scene(path), mesh_mm)
    assert scene.rotor is not None
    top = scene.rotor.max_speed * 30 / math.pi
    m = run_ucs(scene)
    rows, seen = [], {}
    for curve in m.bearings:
        for direction in sorted({d for _, d, _, _ in curve.crossings}):
            # the crossings below the rotor's top speed, or (none there) the lowest two,
            # the diagram then run past them
            met = sorted(n for _, d, _, n in curve.crossings if d == direction)
            met = [n for n in met if n <= top] or met[:2]
            if not met:
                continue
            k = curve.kxx if direction == "x" else curve.kyy
            key = (tuple(k), tuple(curve.speeds_rpm))   # bearings alike: one diagram
            if key not in seen:
                alike = crossing_scene(m.scene, curve, direction)
                over = max(top, 1.1 * met[-1]) * math.pi / 30
                alike = replace(alike, rotor=replace(alike.rotor, max_speed=over))
                c = run_campbell(alike)
                seen[key] = sorted(x.speed_rpm for x in c.critical_speeds
                                   if x.order == 1 and x.whirl == "forward")
            forward = seen[key]
            for i, n in enumerate(met):
                near = min(forward, key=lambda f: abs(f / n - 1)) if forward else float("nan")
                rows.append((curve.name, direction, i + 1, n, near))
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("examples", nargs="*", type=Path)
    ap.add_argument("--mesh-size", type=float, default=None)
    args = ap.parse_args()
    from shaftfem.scene.toml_reading import read_toml

    paths = args.examples or sorted(p for p in (ROOT / "examples").glob("*.toml")
                                    if "rotor" in read_toml(p))
    print("| example | bearing | along | crossing | map (r/min) | Campbell 1x (r/min) | "
          "difference |")
    print("|---|---|---|---|---|---|---|")
    worst = 0.0
    for p in paths:
        for name, d, i, n, f in compare(p, args.mesh_size):
            worst = max(worst, abs(f / n - 1))
            print(f"| {p.name} | {name} | {d} | {i} | {n:,.1f} | {f:,.1f} | "
                  f"{100 * (f / n - 1):+.3f} % |")
        sys.stdout.flush()
    print(f"largest difference {100 * worst:.3f} %")


if __name__ == "__main__":
    main()
