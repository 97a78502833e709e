"""Sweep speed-up from one to two Dask worker processes (same variants, same machine).

    .venv/bin/python benchmarks/sweeps.py [MESH_SIZE_MM]
"""

import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine  # noqa: E402
from shaftfem.workflows.sweep import run_sweep  # noqa: E402
from shaftfem.workflows.sweep_file import Sweep


def main() -> None:
    size = float(sys.argv[1]) if len(sys.argv) > 1 else 10.0
    variants = [{"shaft.length_mm": L, "shaft.diameter_mm": d}
                for L in (500.0, 550.0, 600.0, 650.0) for d in (30.0, 32.0)]
    sweep = Sweep(base="plain_cylinder", mesh_size_mm=size, variants=variants,
                  parameters=["shaft.length_mm", "shaft.diameter_mm"])
    times = {}
    for workers in (1, 2):
        with tempfile.TemporaryDirectory() as d:
            t = time.perf_counter()
            rows = run_sweep(sweep, Path(d) / "r.csv", workers=workers)
            times[workers] = time.perf_counter() - t
            assert all(r["status"] == "ok" for r in rows)
    print(f"machine: {machine()}; {len(variants)} variants of plain_cylinder at {size:g} mm")
    print("| workers | wall time (s) | speed-up |\n|---|---|---|")
    for w, t in times.items():
        print(f"| {w} | {t:.1f} | {times[1] / t:.2f} |")


if __name__ == "__main__":
    main()
