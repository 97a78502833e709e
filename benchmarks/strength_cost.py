"""What the strength check costs: `shaftfem strength` of a scene against its `shaftfem
modes`, each as a user runs it (a fresh process, the CLI), cold (an empty cache) once
and warm (the cache from that run) REPEAT times; the ratio of the warm medians.

    .venv/bin/python benchmarks/strength_cost.py [REPEAT] [SCENE ...]

Default scenes: the paper's installed shaft and examples/gear_shaft.toml.
"""

import os
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, run_measured  # noqa: E402

ROOT = Path(__file__).parents[1]
SCENES = ["paper2018_installed", str(ROOT / "examples" / "gear_shaft.toml")]


def timed(command: str, scene: str, cache: str) -> float:
    run = run_measured([sys.executable, "-m", "shaftfem", command, scene, "-q"],
                       env={**os.environ, "SHAFTFEM_CACHE": cache})
    if run["returncode"] not in (0, 1):
        raise SystemExit(f"{command} {scene}: exit {run['returncode']}\n{run['stderr'][-2000:]}")
    return run["wall"]


def main() -> None:
    repeat = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    scenes = sys.argv[2:] or SCENES
    print(f"{machine()}; warm: medians of {repeat} runs, each in a fresh process")
    print("| scene | modes cold (s) | strength cold (s) | modes warm (s) | strength warm (s) "
          "| strength / modes, warm |")
    print("|---|---|---|---|---|---|")
    for scene in scenes:
        with tempfile.TemporaryDirectory() as cache:
            cold = {c: timed(c, scene, cache) for c in ("modes", "strength")}
            warm = {c: statistics.median(timed(c, scene, cache) for _ in range(repeat))
                    for c in ("modes", "strength")}
        print(f"| {Path(scene).stem} | {cold['modes']:.1f} | {cold['strength']:.1f} | "
              f"{warm['modes']:.1f} | {warm['strength']:.1f} | "
              f"{warm['strength'] / warm['modes']:.2f} |")


if __name__ == "__main__":
    main()
