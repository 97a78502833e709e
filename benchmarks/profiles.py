"""The cost of shafts given as profiles and STEP files: whole-process wall time of
`shaftfem modes SCENE` (bound included), cold (an empty cache) and warm (the same
cache again), medians of N, alternating the scenes, each run in a fresh process.

    .venv/bin/python benchmarks/profiles.py [--repeat N]

Scenes: examples/stepped_shaft.toml (three sections with shoulder fillets and chamfers,
a keyway, two bearings and a keyed sprocket), examples/tube.toml, examples/step_shaft.toml
(the keyed stepped shaft from a STEP file), and the paper's shaft for comparison. Prints a
Markdown table (docs/performance.md, "Stepped shafts, tubes and STEP files").
"""

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, options  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SCENES = {"stepped, keyed, on bearings": ROOT / "examples" / "stepped_shaft.toml",
          "tube": ROOT / "examples" / "tube.toml",
          "STEP file (keyed stepped)": ROOT / "examples" / "step_shaft.toml",
          "paper2018 (for comparison)": ROOT / "geometry" / "paper2018.toml"}


def run(scene: Path, cache: Path) -> float:
    """Wall seconds of one `shaftfem modes SCENE` with the cache folder `cache`."""
    env = {**os.environ, "SHAFTFEM_CACHE": str(cache)}
    t = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "shaftfem", "modes", str(scene), "-q"],
                       capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t
    if p.returncode != 0:
        raise SystemExit(f"shaftfem modes {scene} failed:\n{p.stderr[-2000:]}")
    return wall


def main(argv: list[str]) -> None:
    opts, _ = options(argv, {"--repeat": "3"})
    n = int(opts["--repeat"])
    times: dict[str, dict[str, list[float]]] = {k: {"cold": [], "warm": []} for k in SCENES}
    for _ in range(n):
        for name, scene in SCENES.items():
            with tempfile.TemporaryDirectory() as d:
                times[name]["cold"].append(run(scene, Path(d)))
                times[name]["warm"].append(run(scene, Path(d)))
    print(f"{machine()}; `shaftfem modes SCENE`, bound included, whole process; "
          f"medians of {n} (range)\n")
    print("| scene | cold (s) | warm (s) |")
    print("|---|---|---|")
    for name, t in times.items():
        cells = [f"{statistics.median(v):.1f} ({min(v):.1f}-{max(v):.1f})"
                 for v in (t["cold"], t["warm"])]
        print(f"| {name} | {cells[0]} | {cells[1]} |")


if __name__ == "__main__":
    main(sys.argv[1:])
