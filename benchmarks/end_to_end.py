"""The default scene end to end, cold and warm, against CalculiX on the same mesh,
and against an earlier shaftfem (a git revision) in the same run.

    .venv/bin/python benchmarks/end_to_end.py [MESH_MM] [--baseline REV] [--repeat N]

MESH_MM: one size in mm (the scene's sizes scaled alike), or SIZE/GROOVE/EDGE
in mm, e.g. 8/2/2; default: the scene's own mesh. --baseline REV: also time
that revision's warm run (checked out into a temporary folder, run with the
same cache, so it solves the very same mesh). --repeat N (default 3): warm
runs and CalculiX runs are repeated N times and their medians printed (the
machine is shared).

Prints Markdown tables: per-stage wall times (s) and peak memory (MB) of a cold
run (nothing cached), warm runs (solid and mesh cached: a re-run of an
unchanged scene) and a "warm, new mesh" run (solid cached, mesh rebuilt);
then CalculiX's time (its defaults, and both cores for its solver: the faster
median counts) over shaftfem's assembly + factorisation + eigensolve.
"""

import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import in_fresh_process, machine, peak_mb  # noqa: E402

STAGES = ["cad", "mesh", "assembly", "solve", "export", "total"]
SOLVE = ("assembly", "solve")


def one(cache: str, mesh_mm: str | None, out: str, export: bool = True) -> dict:
    """One run of the default scene in this process; what it took."""
    os.environ["SHAFTFEM_CACHE"] = cache
    from dataclasses import replace

    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    scene = replace(load_scene("paper2018"), max_dofs=20_000_000)  # research runs
    if mesh_mm and "/" in mesh_mm:
        s, g, e = (float(x) * 1e-3 for x in mesh_mm.split("/"))
        scene = replace(scene, mesh=replace(scene.mesh, size=s, groove_size=g, edge_size=e))
    elif mesh_mm:
        scene = with_mesh(scene, float(mesh_mm))
    t0 = time.perf_counter()
    r = run_modes(scene)
    sec = dict(r.timings.items())
    sec["export"] = 0.0
    if export:
        from shaftfem.outputs.calculix import write_calculix
        from shaftfem.outputs.export import export_modes

        t = time.perf_counter()
        export_modes(r, out)
        sec["export"] = time.perf_counter() - t
        write_calculix(r, Path(out) / "shaft.inp")
    sec["total"] = time.perf_counter() - t0
    return {"seconds": sec, "dofs": r.modes.n_dofs, "peak_mb": peak_mb(),
            "solver": r.modes.factoriser, "f": list(map(float, r.modes.frequencies)),
            "residual": float(max(r.modes.residuals))}


def median_run(runs: list[dict]) -> dict:
    out = dict(runs[0])
    out["seconds"] = {s: statistics.median(r["seconds"][s] for r in runs) for s in runs[0]["seconds"]}
    out["peak_mb"] = statistics.median(r["peak_mb"] for r in runs)
    return out


def baseline_runs(rev: str, cache: str, mesh_mm: str | None, repeat: int) -> list[dict]:
    """Warm runs of revision `rev` (its own source, this run's cache and mesh)."""
    root = Path(__file__).resolve().parents[1]
    tmp = Path(tempfile.mkdtemp(prefix="shaftfem-baseline-"))
    try:
        archive = subprocess.run(["git", "-C", str(root), "archive", rev, "src", "geometry"],
                                 capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", str(tmp)], input=archive, check=True)
        env = {**os.environ, "PYTHONPATH": str(tmp / "src"), "OPENBLAS_NUM_THREADS": "1"}
        cmd = [sys.executable, __file__, "--child", cache, mesh_mm or "", str(tmp)]
        runs = []
        for i in range(repeat + 1):  # the first one warms whatever that revision caches
            p = subprocess.run(cmd, capture_output=True, text=True, env=env)
            if p.returncode != 0:
                raise SystemExit(f"baseline {rev} failed:\n{p.stderr[-2000:]}")
            if i:
                runs.append(json.loads(p.stdout.strip().splitlines()[-1]))
        return runs
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def calculix(out: str, repeat: int) -> tuple[float, float]:
    """Median seconds of CalculiX on the deck: its defaults, and both cores."""
    n = str(os.cpu_count())
    meds = []
    for env in ({}, {"OMP_NUM_THREADS": n, "CCX_NPROC_EQUATION_SOLVER": n,
                     "CCX_NPROC_STIFFNESS": n, "CCX_NPROC_RESULTS": n}):
        times = []
        for _ in range(repeat):
            t = time.perf_counter()
            subprocess.run(["ccx", "-i", "shaft"], cwd=out, capture_output=True, check=True,
                           env={**os.environ, **env})
            times.append(time.perf_counter() - t)
        meds.append(statistics.median(times))
    return meds[0], meds[1]


def main() -> None:
    args = sys.argv[1:]
    if args and args[0] == "--child":  # a baseline revision's warm run, as JSON
        cache, mesh_mm, _src = args[1:4]
        print(json.dumps(one(cache, mesh_mm or None, tempfile.mkdtemp(), export=False)))
        return
    rev = args[args.index("--baseline") + 1] if "--baseline" in args else None
    repeat = int(args[args.index("--repeat") + 1]) if "--repeat" in args else 3
    positional = [a for i, a in enumerate(args)
                  if not a.startswith("--") and (i == 0 or not args[i - 1].startswith("--"))]
    size = positional[0] if positional else None
    cache = tempfile.mkdtemp(prefix="shaftfem-bench-")
    out = tempfile.mkdtemp(prefix="shaftfem-out-")
    try:
        cold = in_fresh_process(one, cache, size, out)
        warms = [in_fresh_process(one, cache, size, out) for _ in range(repeat)]
        base = baseline_runs(rev, cache, size, repeat) if rev else None
        shutil.rmtree(Path(cache) / "meshes")
        remesh = in_fresh_process(one, cache, size, out)
        ccx = calculix(out, repeat) if shutil.which("ccx") else None
    finally:
        shutil.rmtree(cache, ignore_errors=True)
    warm = median_run(warms)
    print(f"machine: {machine()}; paper2018, mesh {size + ' mm' if size else 'of the scene'}, "
          f"{warm['dofs']} DOFs, solver {warm['solver']}; medians of {repeat} runs\n")
    print("| run | " + " | ".join(f"{s} (s)" for s in STAGES) + " | peak memory (MB) |")
    print("|---|" + "---|" * (len(STAGES) + 1))
    rows = [("cold", cold), ("warm", warm), ("warm, new mesh", remesh)]
    if base:
        rows.insert(2, (f"warm, {rev} (before)", median_run(base)))
    for name, r in rows:
        print(f"| {name} | " + " | ".join(f"{r['seconds'][s]:.1f}" for s in STAGES)
              + f" | {r['peak_mb']:.0f} |")
    worst = max(r["residual"] for r in warms)
    print(f"\nlargest elastic residual over the warm runs: {worst:.1e}")
    if base:
        diff = max(abs(a / b - 1) for a, b in zip(warm["f"], base[0]["f"]))
        print(f"frequencies against {rev}: largest relative difference {diff:.1e}")
    if ccx is None:
        print("ccx not installed: no CalculiX timing")
        return
    best = min(ccx)
    print(f"\nCalculiX 2.20 on the same mesh (16 eigenvalues), default / both cores: "
          f"{ccx[0]:.1f} s / {ccx[1]:.1f} s")
    for name, r in rows[1:-1]:
        ours = sum(r["seconds"][s] for s in SOLVE)
        print(f"- {name}: assembly + factorisation + eigensolve {ours:.2f} s, "
              f"**CalculiX / shaftfem = {best / ours:.2f}**; warm total (run_modes) "
              f"{r['seconds']['total'] - r['seconds']['export']:.2f} s")


if __name__ == "__main__":
    main()
