"""Order-5 assembly at about 250k DOFs: K and M of the paper's shaft on its cubic
16/12/12 mm mesh, this tree against an earlier revision in the same run.

    .venv/bin/python benchmarks/order_5_assembly.py [--baseline REV] [--repeat N]

Each measurement is a fresh process timing `discretise` (the basis and the sparsity) and
`assemble` (K, M and the rigid-translation guard) on the cached cubic mesh (meshed once
first, not timed); the two trees alternate (REV, default 52e128d, is checked out into a
temporary folder and run with PYTHONPATH pointing at it). Prints a Markdown table of
medians and the ratio of the totals.
"""

import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, options  # noqa: E402
from bound_intervals import coarse_scene  # noqa: E402
from cold_runs import checkout  # noqa: E402

RUN = """
import json, sys, time
import shaftfem.runtime
shaftfem.runtime.configure_threads()
from shaftfem.workflows import stages
from shaftfem.fem.assembly import assemble, discretise
from shaftfem.scene.load import load_scene
from shaftfem.workflows.pipeline import with_mesh

scene = with_mesh(load_scene(sys.argv[1]), order=5, geometry_order=3)
shape = stages.solid(scene)[1]
mesh = stages.mesh(shape, scene.shaft, scene.grooves, scene.mesh)
t0 = time.perf_counter()
d = discretise(mesh)
t1 = time.perf_counter()
system = assemble(mesh, scene.material, discretisation=d)
t2 = time.perf_counter()
print(json.dumps({"dofs": system.n_dofs, "nnz": int(system.K.nnz),
                  "discretise": t1 - t0, "assemble": t2 - t1}))
"""


def measure(src: Path | None, scene: Path) -> dict:
    env = dict(os.environ)
    if src is not None:
        env["PYTHONPATH"] = str(src)
    p = subprocess.run([sys.executable, "-c", RUN, str(scene)], capture_output=True,
                       text=True, env=env)
    if p.returncode != 0:
        raise SystemExit(p.stderr[-2000:])
    return json.loads(p.stdout.strip().splitlines()[-1])


def main(argv: list[str]) -> None:
    opts, _ = options(argv, {"--baseline": "52e128d", "--repeat": "3"})
    base = checkout(opts["--baseline"])
    scene = coarse_scene(base, base)   # the earlier tree's scene: both trees read it
    measure(None, scene)   # the cubic mesh, made once and cached, for both trees
    trees = {"this tree": None, opts["--baseline"]: base / "src"}
    runs: dict[str, list[dict]] = {name: [] for name in trees}
    print(f"machine: {machine()}; order 5, cubic 16/12/12, "
          f"{opts['--repeat']} runs each, alternating\n")
    for _ in range(int(opts["--repeat"])):
        for name, src in trees.items():
            r = measure(src, scene)
            runs[name].append(r)
            print(f"{name}: discretise {r['discretise']:.2f} s, assemble {r['assemble']:.2f} s",
                  flush=True)
    print("\n| tree | DOFs | nonzeros of K | discretise (s) | assemble (s) | total (s) |")
    print("|---|---|---|---|---|---|")
    totals = {}
    for name, rs in runs.items():
        med = {k: statistics.median(r[k] for r in rs) for k in ("discretise", "assemble")}
        totals[name] = statistics.median(r["discretise"] + r["assemble"] for r in rs)
        print(f"| {name} | {rs[0]['dofs']:,} | {rs[0]['nnz']:,} | {med['discretise']:.2f} | "
              f"{med['assemble']:.2f} | {totals[name]:.2f} |")
    print(f"\n{opts['--baseline']} / this tree: "
          f"{totals[opts['--baseline']] / totals['this tree']:.2f}")


if __name__ == "__main__":
    main(sys.argv[1:])
