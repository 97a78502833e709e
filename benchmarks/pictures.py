"""`shaftfem design` from cold: where its time goes, the pictures above all, this tree
against an earlier revision in the same run.

    .venv/bin/python benchmarks/pictures.py [--baseline REV] [--repeat N] [SCENE]

Each run is a fresh process with an empty cache and a new output folder, the two trees
alternating (REV, default 52e128d, is checked out into a temporary folder and run with
PYTHONPATH pointing at it). The run's own progress lines (their elapsed seconds) split
its wall time: up to the pictures, the pictures (geometry.png, modes.png and a GIF per
mode), and report.html where the tree writes one. Prints a Markdown table of medians.
"""

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

LINE = re.compile(r"^\[\s*([\d.]+) s\] (.*)$")


def design(src: Path | None, scene: str) -> dict:
    """One cold `shaftfem design SCENE` of the tree `src` (None: this one): the wall
    time and the seconds of its phases, from its progress lines."""
    with tempfile.TemporaryDirectory() as d:
        env = {**os.environ, "SHAFTFEM_CACHE": str(Path(d) / "cache")}
        if src is not None:
            env["PYTHONPATH"] = str(src)
        t = time.perf_counter()
        p = subprocess.run([sys.executable, "-m", "shaftfem", "design", scene, "--out",
                            str(Path(d) / "out")], capture_output=True, text=True, env=env)
        wall = time.perf_counter() - t
    if p.returncode not in (0, 4):
        raise SystemExit(f"shaftfem design {scene} failed:\n{p.stderr[-2000:]}")
    marks = [(float(m[1]), m[2]) for m in map(LINE.match, p.stderr.splitlines()) if m]

    def at(text: str) -> float | None:
        return next((s for s, msg in marks if msg.startswith(text)), None)

    start, done = at("rendering pictures"), at("report written")
    html = at("report.html")
    last_picture = max((s for s, msg in marks if msg.startswith("picture ")), default=None)
    pictures_end = last_picture or html or done
    return {"wall": wall, "before pictures": start, "pictures": pictures_end - start,
            "report.html": (done - html) if html is not None else None,
            "frames": sum(msg.startswith("picture mode_") for _, msg in marks)}


def main(argv: list[str]) -> None:
    opts, rest = options(argv, {"--baseline": "52e128d", "--repeat": "3"})
    scene = rest[0] if rest else "paper2018"
    base = checkout(opts["--baseline"])
    runs: dict[str, list[dict]] = {"this tree": [], opts["--baseline"]: []}
    print(f"machine: {machine()}; shaftfem design {scene}, cold, "
          f"{opts['--repeat']} runs each, alternating\n")
    for _ in range(int(opts["--repeat"])):
        for name, src in (("this tree", None), (opts["--baseline"], base / "src")):
            r = design(src, scene)
            runs[name].append(r)
            print(f"{name}: " + ", ".join(f"{k} {v:.1f}" for k, v in r.items()
                                          if isinstance(v, float)), flush=True)

    def med(rs: list[dict], key: str) -> str:
        values = [r[key] for r in rs if r[key] is not None]
        if not values:
            return "-"
        return f"{statistics.median(values):.1f} ({min(values):.1f}-{max(values):.1f})"

    print("\n| tree | whole run (s) | up to the pictures (s) | pictures (s) | report.html (s) |")
    print("|---|---|---|---|---|")
    for name, rs in runs.items():
        print(f"| {name} | {med(rs, 'wall')} | {med(rs, 'before pictures')} | "
              f"{med(rs, 'pictures')} | {med(rs, 'report.html')} |")


if __name__ == "__main__":
    main(sys.argv[1:])
