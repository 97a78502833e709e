"""Warm runs from the last solve against warm runs from the shift hint alone.

    .venv/bin/python benchmarks/warm_start.py [SCENE ...] [--repeat N]

SCENE: scene names or files (default: paper2018). Each is run once through the CLI
(`shaftfem modes`, the bound included) to fill the cache, then N times (default 3)
each way, alternating, every run a fresh process with the solid and mesh cached:

- "shift hint": the kept solves (`solves/` in the cache) removed first, so every
  solve is factorised at the scene's last proven shift and searches below it with
  Lanczos (the warm run before solves were kept);
- "last solve": each solve (the mode's own and those of its bound) refines the
  shapes its last run kept on that mesh, factorised once at its shift.

Prints a Markdown table of the medians: wall time of the whole process, its
peak memory, and the largest difference between the two ways' frequencies.
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, options  # noqa: E402


def cli_run(scene: str, out: Path) -> tuple[float, float, list[float]]:
    """(wall s, peak MB, frequencies Hz) of one `shaftfem modes SCENE --json` process."""
    t = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "shaftfem", "modes", scene, "--json", str(out)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"shaftfem modes {scene} failed (exit {status})")
    f = [m["frequency_hz"] for m in json.loads(out.read_text())["modes"]]
    return wall, usage.ru_maxrss / 1024, f  # Linux: ru_maxrss in kB


def main(scenes: list[str], repeat: int) -> None:
    from shaftfem.store import cache_dir

    solves = cache_dir() / "solves"
    out = Path(tempfile.mkdtemp(prefix="shaftfem-warm-")) / "modes.json"
    print(machine())
    print("| scene | DOFs | warm from | wall (s), median | peak (MB), median | "
          "largest frequency difference |")
    print("|---|---|---|---|---|---|")
    for scene in scenes:
        cli_run(scene, out)  # fills the cache
        dofs = json.loads(out.read_text())["dofs"]
        runs: dict[str, list] = {"shift hint": [], "last solve": []}
        for _ in range(repeat):
            for f in solves.glob("*.npz"):
                f.unlink()
            runs["shift hint"].append(cli_run(scene, out))
            runs["last solve"].append(cli_run(scene, out))
        f0 = runs["shift hint"][0][2]
        for way, rs in runs.items():
            diff = max(abs(a / b - 1) for r in rs for a, b in zip(r[2], f0))
            print(f"| {Path(scene).stem} | {dofs} | {way} | "
                  f"{statistics.median(r[0] for r in rs):.1f} | "
                  f"{statistics.median(r[1] for r in rs):.0f} | {diff:.1e} |", flush=True)


if __name__ == "__main__":
    opts, scenes = options(sys.argv[1:], {"--repeat": "3"})
    main(scenes or ["paper2018"], int(opts["--repeat"]))
