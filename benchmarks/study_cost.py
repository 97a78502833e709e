"""What a study costs against its Campbell diagram, this tree against an earlier revision
in the same run: each command a fresh process, medians of N.

    .venv/bin/python benchmarks/study_cost.py [--baseline REV] [--repeat N] [--part P]

REV (default 789c61b, before the rotor model was shared; `none`: this tree alone) is
checked out into a temporary folder and run by this Python with PYTHONPATH pointing at
it, alternating with this tree. P: `pumps`, `paper` or `all` (default). Prints Markdown
tables:

* `shaftfem design` and `shaftfem campbell` of examples/pump_on_journals.toml and
  examples/keyed_pump_on_journals.toml (whose [rotor] runs the run-up at 1,500 r/min
  per s in design), each cold (an empty cache), and design's time over campbell's;
* `shaftfem modes` of the paper's shaft warm (its cache filled by a run before) and
  `shaftfem design` of it cold, with where the time goes (the steps the runs report).
"""

from __future__ import annotations

import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, options  # noqa: E402
from cold_runs import checkout  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PUMPS = ("pump_on_journals", "keyed_pump_on_journals")


def run(src: Path, args: list[str], cache: Path) -> tuple[float, str]:
    """`shaftfem ARGS` of the source tree `src` with the cache `cache`: wall seconds and
    what it printed; a failure (exit 2 or more) stops the benchmark."""
    env = {**os.environ, "PYTHONPATH": str(src), "SHAFTFEM_CACHE": str(cache)}
    t = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "shaftfem", *args], capture_output=True,
                       text=True, env=env, stdin=subprocess.DEVNULL)
    wall = time.perf_counter() - t
    if p.returncode >= 2:
        raise SystemExit(f"{src}: shaftfem {' '.join(args)} failed:\n{p.stderr[-2000:]}")
    return wall, p.stdout + p.stderr


def steps(text: str) -> dict[str, float]:
    """The step times of a modal run's `time:` line (cad, mesh, assembly, solve, bound)."""
    line = next((x for x in text.splitlines() if x.startswith("time: ")), "")
    return {k: float(v) for k, v in re.findall(r"(\w+) ([\d.]+) s", line)}


def cold(src: Path, args: list[str]) -> tuple[float, str]:
    with tempfile.TemporaryDirectory() as d:
        return run(src, [*args, "--out", str(Path(d) / "out")] if args[0] == "design"
                   else args, Path(d) / "cache")


def main() -> None:
    opts, _ = options(sys.argv[1:], {"--baseline": "789c61b", "--repeat": "3",
                                     "--part": "all"})
    rev, repeat, part = opts["--baseline"], int(opts["--repeat"]), opts["--part"]
    trees = {"this tree": ROOT / "src"}
    if rev != "none":   # --baseline none: this tree alone
        trees = {f"{rev} (before)": checkout(rev) / "src", **trees}
    print(f"machine: {machine()}; medians of {repeat}, each run a fresh process\n")
    if part in ("all", "pumps"):
        pumps(trees, repeat)
    if part in ("all", "paper"):
        paper(trees, repeat)


def pumps(trees: dict[str, Path], repeat: int) -> None:
    print("| scene | revision | campbell, cold (s) | design, cold (s) | design / campbell |")
    print("|---|---|---|---|---|")
    for name in PUMPS:
        scene = str(ROOT / "examples" / f"{name}.toml")
        walls: dict[str, dict[str, list[float]]] = {t: {"campbell": [], "design": []}
                                                    for t in trees}
        for _ in range(repeat):
            for tree, src in trees.items():
                for command in ("campbell", "design"):
                    extra = ["--no-html"] if command == "design" else []
                    walls[tree][command].append(cold(src, [command, scene, *extra])[0])
        for tree in trees:
            c = statistics.median(walls[tree]["campbell"])
            d = statistics.median(walls[tree]["design"])
            print(f"| {name} | {tree} | {c:.1f} | {d:.1f} | {d / c:.2f} |", flush=True)


def paper(trees: dict[str, Path], repeat: int) -> None:
    print("\n| paper2018 | revision | wall (s) | cad | mesh | assembly | solve | bound |")
    print("|---|---|---|---|---|---|---|---|")
    warm: dict[str, list] = {t: [] for t in trees}
    cold_design: dict[str, list] = {t: [] for t in trees}
    with tempfile.TemporaryDirectory() as d:
        for tree, src in trees.items():
            run(src, ["modes"], Path(d) / tree / "cache")   # fills the cache
        for _ in range(repeat):   # the trees alternate, so that the machine's pace is shared
            for tree, src in trees.items():
                warm[tree].append(run(src, ["modes"], Path(d) / tree / "cache"))
                cold_design[tree].append(cold(src, ["design"]))
    for tree in trees:
        for what, runs in (("modes, warm", warm[tree]), ("design, cold", cold_design[tree])):
            wall = statistics.median(w for w, _ in runs)
            parts = [statistics.median(steps(t).get(k, 0.0) for _, t in runs)
                     for k in ("cad", "mesh", "assembly", "solve", "bound")]
            print(f"| {what} | {tree} | {wall:.1f} | "
                  + " | ".join(f"{p:.1f}" for p in parts) + " |", flush=True)


if __name__ == "__main__":
    main()
