"""Error against DOFs and time for the paper's shaft at element orders 2, 3 and 4
(hierarchical for 3 and 4), on meshes of several sizes.

    .venv/bin/python benchmarks/orders.py [SIZES:ORDER ...]

SIZES is away/grooves/floor edges in mm, e.g. 12/6/6:4 (default: a ladder). Each run is
a fresh process (its peak memory its own) with the solid cached: the time is that of a
warm `run_modes` without the error bound (mesh, assembly, factorisation, eigensolve).
True errors are against the NGSolve order-4 reference of docs/verification.md (541k
DOFs on netgen's curved mesh; 0.04-0.08 % from its order 3).
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import PAPER_REFERENCE_HZ, in_fresh_process, machine, peak_mb  # noqa: E402, I001  (before NumPy)

import numpy as np  # noqa: E402

REFERENCE_HZ = np.array(PAPER_REFERENCE_HZ)
DEFAULT = ["8/4/4:2", "4/2/2:2", "12/6/6:3", "8/4/4:3", "16/8/8:4", "12/6/6:4", "10/5/5:4"]


def one(sizes_mm: tuple, order: int) -> dict:
    from dataclasses import replace

    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes

    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = load_scene("paper2018")
    scene = replace(scene, max_dofs=2_000_000,
                    mesh=replace(scene.mesh, order=order, size=s, groove_size=g, edge_size=e))
    run_modes(replace(scene, mesh=replace(scene.mesh, order=2)))  # solid and mesh cached
    t = time.perf_counter()
    r = run_modes(scene)
    wall = time.perf_counter() - t
    return {"dofs": r.modes.n_dofs, "f": list(map(float, r.modes.frequencies)), "wall": wall,
            "timings": r.timings, "peak": peak_mb(), "residual": float(r.modes.residuals.max())}


def main(args: list[str]) -> None:
    print(f"machine: {machine()}; paper2018, warm run_modes without the bound\n")
    print("| sizes (mm) | order | DOFs | assembly (s) | solve (s) | wall (s) | peak memory (MB) "
          "| largest true error | smallest true error | largest residual |\n"
          "|---|---|---|---|---|---|---|---|---|---|")
    for spec in args or DEFAULT:
        sizes, order = spec.split(":")
        mm = tuple(float(x) for x in sizes.split("/"))
        r = in_fresh_process(one, mm, int(order))
        err = np.abs(np.array(r["f"]) / REFERENCE_HZ - 1)
        tm = r["timings"]
        print(f"| {sizes} | {order} | {r['dofs']} | {tm.assembly:.1f} | {tm.solve:.1f} | "
              f"{r['wall']:.1f} | {r['peak']:.0f} | {100 * err.max():.3f} % | "
              f"{100 * err.min():.3f} % | {r['residual']:.1e} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
