"""Cubic meshing of the paper's shaft, this tree against an earlier revision in the same
run: the wall time of `mesh_shape` (not cached; the solid cached) and how many elements
each meshing left to straighten.

    .venv/bin/python benchmarks/cubic_meshing.py [--baseline REV] [--repeat N] [SIZES ...]

SIZES is away/grooves/floor edges in mm (default 16/12/12), meshed for order 5 on cubic
geometry. REV (default 8774487, whose mesher ran gmsh's optimisers on one thread) is
checked out (src) into a temporary folder and run alternately with this tree, each
meshing in a fresh process. Prints a Markdown table of medians (N, default 3).
"""

import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
from _common import machine, options  # noqa: E402
from cold_runs import ROOT, checkout  # noqa: E402

ONE = """
import json, sys, time
from dataclasses import replace
from shaftfem.cad.mesh import mesh_shape
from shaftfem.cad.solid import build_shape
from shaftfem.scene.load import load_scene
s, g, e = (float(x) * 1e-3 for x in sys.argv[1].split("/"))
scene = load_scene("paper2018")
settings = replace(scene.mesh, size=s, groove_size=g, edge_size=e, order=5, geometry_order=3)
shape = build_shape(scene.shaft, scene.grooves)
t = time.perf_counter()
mesh = mesh_shape(shape, scene.shaft, scene.grooves, settings, use_cache=False)
print(json.dumps({"wall": time.perf_counter() - t, "straightened": mesh.straightened,
                  "elements": mesh.n_elements}))
"""


def meshing(src: Path, sizes: str) -> dict:
    """One cubic meshing by the source tree `src` in a fresh process (its solid cached)."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    p = subprocess.run([sys.executable, "-c", ONE, sizes], capture_output=True, text=True,
                       env=env)
    if p.returncode != 0:
        raise SystemExit(f"{src}: meshing {sizes} failed:\n{p.stderr[-2000:]}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def main(argv: list) -> None:
    opts, sizes = options(argv, {"--baseline": "8774487", "--repeat": "3"})
    rev, repeat = opts["--baseline"], int(opts["--repeat"])
    sizes = sizes or ["16/12/12"]
    base = checkout(rev) / "src"
    trees = {rev: base, "this tree": ROOT / "src"}
    print(f"machine: {machine()}; paper2018, order 5 on cubic geometry, {repeat} meshings "
          f"each, alternating\n")
    print("| sizes (mm) | source | elements | wall, median (s) | walls (s) | straightened |")
    print("|---|---|---|---|---|---|")
    for sz in sizes:
        runs: dict = {name: [] for name in trees}
        for _ in range(repeat):
            for name, src in trees.items():
                runs[name].append(meshing(src, sz))
        for name, rs in runs.items():
            walls = [r["wall"] for r in rs]
            print(f"| {sz} | {name} | {rs[0]['elements']:,} | {statistics.median(walls):.1f} | "
                  f"{', '.join(f'{w:.1f}' for w in walls)} | "
                  f"{', '.join(str(r['straightened']) for r in rs)} |", flush=True)


if __name__ == "__main__":
    t0 = time.perf_counter()
    main(sys.argv[1:])
    print(f"\n({time.perf_counter() - t0:.0f} s in all)")
