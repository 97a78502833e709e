"""The default scene end to end, cold (no cached solid or mesh) and warm, and CalculiX on the same mesh.

    .venv/bin/python benchmarks/end_to_end.py [MESH_MM]

MESH_MM: one size in mm (the scene's sizes scaled alike), or SIZE/GROOVE/EDGE
in mm, e.g. 8/2/2; default: the scene's own mesh.

Prints a Markdown table: per-stage wall times (s), peak memory (MB), and the
time ratio CalculiX / shaftfem measured in the same run on the same mesh.
Rows: cold (nothing cached), warm (solid and mesh cached: a re-run of an
unchanged scene) and "warm, new mesh" (solid cached, mesh rebuilt: a changed
mesh setting). CalculiX runs once with its defaults and once with both cores
for its solver (OMP_NUM_THREADS, CCX_NPROC_*); the faster counts.
"""

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import in_fresh_process, machine, peak_mb  # noqa: E402


def one(cache: str, mesh_mm: str | None, out: str) -> dict:
    os.environ["SHAFTFEM_CACHE"] = cache
    from dataclasses import replace

    from shaftfem.export import export_modes, write_calculix
    from shaftfem.pipeline import run_modes, with_mesh
    from shaftfem.scene import load_scene

    scene = replace(load_scene("paper2018"), max_dofs=20_000_000)  # research runs
    if mesh_mm and "/" in mesh_mm:
        s, g, e = (float(x) * 1e-3 for x in mesh_mm.split("/"))
        scene = replace(scene, mesh=replace(scene.mesh, size=s, groove_size=g, edge_size=e))
    elif mesh_mm:
        scene = with_mesh(scene, float(mesh_mm))
    t0 = time.perf_counter()
    r = run_modes(scene)
    t = time.perf_counter()
    export_modes(r, out)
    sec = dict(r.timings.items())
    sec["export"] = time.perf_counter() - t
    sec["total"] = time.perf_counter() - t0
    write_calculix(r, Path(out) / "shaft.inp")
    return {"seconds": sec, "dofs": r.modes.n_dofs, "peak_mb": peak_mb(),
            "solver": r.modes.factorizer, "f": r.modes.frequencies.tolist()}


def main() -> None:
    size = sys.argv[1] if len(sys.argv) > 1 else None
    cache = tempfile.mkdtemp(prefix="shaftfem-bench-")
    out = tempfile.mkdtemp(prefix="shaftfem-out-")
    try:
        cold = in_fresh_process(one, cache, size, out)
        warm = in_fresh_process(one, cache, size, out)
        shutil.rmtree(Path(cache) / "meshes")
        remesh = in_fresh_process(one, cache, size, out)
        ccx_s = None
        if shutil.which("ccx"):
            n = str(os.cpu_count())
            times = []
            for env in ({}, {"OMP_NUM_THREADS": n, "CCX_NPROC_EQUATION_SOLVER": n,
                             "CCX_NPROC_STIFFNESS": n, "CCX_NPROC_RESULTS": n}):
                t = time.perf_counter()
                subprocess.run(["ccx", "-i", "shaft"], cwd=out, capture_output=True, check=True,
                               env={**os.environ, **env})
                times.append(time.perf_counter() - t)
            print(f"CalculiX default / all cores: {times[0]:.1f} s / {times[1]:.1f} s")
            ccx_s = min(times)
    finally:
        shutil.rmtree(cache, ignore_errors=True)
    stages = ["cad", "mesh", "assembly", "factorisation", "eigensolve", "export", "total"]
    print(f"machine: {machine()}; paper2018, mesh {size + ' mm' if size else 'of the scene'}, "
          f"{warm['dofs']} DOFs, solver {warm['solver']}\n")
    print("| run | " + " | ".join(f"{s} (s)" for s in stages) + " | peak memory (MB) |")
    print("|---|" + "---|" * (len(stages) + 1))
    for name, r in (("cold", cold), ("warm", warm), ("warm, new mesh", remesh)):
        print(f"| {name} | " + " | ".join(f"{r['seconds'][s]:.1f}" for s in stages)
              + f" | {r['peak_mb']:.0f} |")
    if ccx_s is not None:
        ours = sum(warm["seconds"][s] for s in ("assembly", "factorisation", "eigensolve"))
        print(f"\nCalculiX 2.20 on the same mesh (assembly + solve, 16 eigenvalues): {ccx_s:.1f} s; "
              f"shaftfem assembly + factorisation + eigensolve: {ours:.1f} s "
              f"(CalculiX / shaftfem = {ccx_s / ours:.2f}); shaftfem warm total {warm['seconds']['total']:.1f} s")
    else:
        print("\nccx not installed: no CalculiX timing")


if __name__ == "__main__":
    main()
