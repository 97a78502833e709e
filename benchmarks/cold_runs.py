"""Cold runs (nothing cached) and a geometry sweep, this tree against an earlier
revision in the same run, with the frequencies of both compared.

    .venv/bin/python benchmarks/cold_runs.py [--baseline REV] [--repeat N] [--no-sweep]

REV (default 24b4bc9) is checked out (src and geometry) into a temporary folder
and run by this Python with PYTHONPATH pointing at it, alternating with this
tree, each run in a fresh process with an empty cache. Prints Markdown tables:

* whole-process wall time (medians of N, default 3) of `shaftfem modes` on the
  paper's scene (bound included) and of `shaftfem modes paper2018_installed
  --no-estimate`, with the CAD and meshing seconds the runs report;
* the ten frequencies and the groove volume of each revision on both shipped
  scenes, the sharp-corner variant (root_radius_mm = 0) and a 60 mm-pitch variant;
* a geometry sweep: 8 variants (pitch 60-90 mm x depth 2.5, 3 mm, the scene's
  mesh) on 2 local Dask workers of one thread: wall time per variant, and the
  share of the workers' time spent in CAD and meshing.
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
from _common import machine, options  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "geometry" / "paper2018.toml"
VARIANTS = [{"grooves.pitch_mm": p, "grooves.depth_mm": d}
            for p in (60.0, 70.0, 80.0, 90.0) for d in (2.5, 3.0)]


def checkout(rev: str) -> Path:
    """`rev`'s src and geometry in a temporary folder."""
    tmp = Path(tempfile.mkdtemp(prefix="shaftfem-baseline-"))
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", rev, "src", "geometry"],
                             capture_output=True, check=True).stdout
    subprocess.run(["tar", "-x", "-C", str(tmp)], input=archive, check=True)
    return tmp


def cold(src: Path, args: list[str]) -> tuple[float, dict]:
    """One cold `shaftfem modes ARGS` of the source tree `src`: wall seconds and its JSON."""
    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "modes.json"
        env = {**os.environ, "PYTHONPATH": str(src), "SHAFTFEM_CACHE": str(Path(d) / "cache")}
        t = time.perf_counter()
        p = subprocess.run([sys.executable, "-m", "shaftfem", "modes", *args, "-q",
                            "--json", str(out)], capture_output=True, text=True, env=env)
        wall = time.perf_counter() - t
        if p.returncode != 0:
            raise SystemExit(f"{src}: shaftfem modes {' '.join(args)} failed:\n{p.stderr[-2000:]}")
        return wall, json.loads(out.read_text())


def variant_file(folder: Path, key: str, value: str) -> Path:
    """The paper's scene with one [grooves] key changed, as a scene file."""
    text = SCENE.read_text()
    lines = [f"{key} = {value}" if line.split("=")[0].strip() == key else line
             for line in text.splitlines()]
    path = folder / f"paper2018_{key}_{value}.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def sweep_child() -> None:
    """In a child process (PYTHONPATH: one revision): the 8 variants on 2 local Dask
    workers; prints wall seconds and the summed stage seconds as JSON."""
    from dask.distributed import Client, LocalCluster

    def one(overrides: dict) -> dict:
        from shaftfem.scene.load import load_scene
        from shaftfem.workflows.pipeline import run_modes

        r = run_modes(load_scene("paper2018", overrides=overrides))
        return {**dict(r.timings.items()), "f1": float(r.modes.frequencies[0])}

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        t = time.perf_counter()
        rows = client.gather(client.map(one, VARIANTS, pure=False))
        wall = time.perf_counter() - t
    print(json.dumps({"wall": wall, "rows": rows}))


def sweep(src: Path) -> dict:
    with tempfile.TemporaryDirectory() as d:
        env = {**os.environ, "PYTHONPATH": f"{src}:{ROOT / 'benchmarks'}",
               "SHAFTFEM_CACHE": str(Path(d) / "cache"), "OMP_NUM_THREADS": "1",
               "MKL_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
        p = subprocess.run([sys.executable, __file__, "--sweep-child"], capture_output=True,
                           text=True, env=env)
        if p.returncode != 0:
            raise SystemExit(f"{src}: sweep failed:\n{p.stderr[-2000:]}")
        return json.loads(p.stdout.strip().splitlines()[-1])


def main() -> None:
    args = sys.argv[1:]
    if args == ["--sweep-child"]:
        sweep_child()
        return
    opts, _ = options(args, {"--baseline": "24b4bc9", "--repeat": "3"})
    rev, repeat = opts["--baseline"], int(opts["--repeat"])
    base = checkout(rev)
    trees = {f"{rev} (before)": base / "src", "this tree": ROOT / "src"}
    runs = {"modes (paper2018, bound included)": [],
            "modes paper2018_installed --no-estimate": ["paper2018_installed", "--no-estimate"]}
    work = Path(tempfile.mkdtemp(prefix="shaftfem-cold-"))
    try:
        print(f"machine: {machine()}; medians of {repeat} cold runs (empty cache), "
              "whole process\n")
        print("| run | revision | wall (s) | CAD (s) | mesh (s) |\n|---|---|---|---|---|")
        results: dict[tuple[str, str], dict] = {}
        for name, cmd in runs.items():
            walls: dict[str, list] = {t: [] for t in trees}
            for _ in range(repeat):
                for tree, src in trees.items():  # alternating: the machine's noise is shared
                    wall, data = cold(src, cmd)
                    walls[tree].append((wall, data))
            for tree in trees:
                w = statistics.median(x[0] for x in walls[tree])
                cad = statistics.median(x[1]["timings_s"]["cad"] for x in walls[tree])
                mesh = statistics.median(x[1]["timings_s"]["mesh"] for x in walls[tree])
                print(f"| {name} | {tree} | {w:.1f} | {cad:.1f} | {mesh:.1f} |")
                results[(name, tree)] = walls[tree][0][1]
        print("\n| scene | largest relative frequency difference | groove volume, CAD / "
              "analytic (mm^3), before | this tree |\n|---|---|---|---|")
        cases = {"paper2018": [], "paper2018_installed": ["paper2018_installed"],
                 "sharp corners": [str(variant_file(work, "root_radius_mm", "0.0"))],
                 "60 mm pitch": [str(variant_file(work, "pitch_mm", "60.0"))]}
        for name, cmd in cases.items():
            if name == "paper2018":
                pair = [results[("modes (paper2018, bound included)", t)] for t in trees]
            elif name == "paper2018_installed":
                pair = [results[("modes paper2018_installed --no-estimate", t)] for t in trees]
            else:
                pair = [cold(src, [*cmd, "--no-estimate"])[1] for src in trees.values()]
            fa, fb = ([m["frequency_hz"] for m in d["modes"]] for d in pair)
            diff = max(abs(a / b - 1) for a, b in zip(fa, fb))
            vols = [f"{d['groove_volume_mm3']['cad']:.3f} / {d['groove_volume_mm3']['analytic']:.3f}"
                    for d in pair]
            print(f"| {name} | {diff:.1e} | {vols[0]} | {vols[1]} |")
        if "--no-sweep" in args:
            return
        print(f"\nGeometry sweep: {len(VARIANTS)} variants (pitch x depth, the scene's mesh), "
              "2 local workers of one thread, empty cache\n")
        print("| revision | wall (s) | per variant (s) | CAD + meshing share | speed-up |\n"
              "|---|---|---|---|---|")
        sweeps = {tree: sweep(src) for tree, src in trees.items()}
        first = sweeps[f"{rev} (before)"]["wall"]
        for tree, s in sweeps.items():
            total = sum(r["total"] for r in s["rows"])
            share = sum(r["cad"] + r["mesh"] for r in s["rows"]) / total
            print(f"| {tree} | {s['wall']:.1f} | {s['wall'] / len(VARIANTS):.1f} | "
                  f"{100 * share:.0f} % | {first / s['wall']:.2f} |")
        fa, fb = ([r["f1"] for r in s["rows"]] for s in sweeps.values())
        print(f"\nsweep f1, largest relative difference between the revisions: "
              f"{max(abs(a / b - 1) for a, b in zip(fa, fb)):.1e}")
    finally:
        shutil.rmtree(base, ignore_errors=True)
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
