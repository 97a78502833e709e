"""What tilting pads cost: `shaftfem campbell` of examples/compressor_on_tilting_pads.toml
against the same rotor on plain journals of the same bore, length, clearance and oil,
each as a user runs it (a fresh process, the CLI): cold (an empty cache: the bearings'
film tables are solved) once, warm (the cache from that run) REPEAT times; the ratio of
the medians.

    .venv/bin/python benchmarks/pad_cost.py [REPEAT]
"""

import os
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, run_measured  # noqa: E402

ROOT = Path(__file__).parents[1]
PADS = ROOT / "examples" / "compressor_on_tilting_pads.toml"
PAD_KEYS = ("pads =", "pad_arc_deg", "preload =", "pivot_offset", "load_between_pads")


def plain(folder: Path) -> Path:
    """The compressor with plain journals in place of its tilting pads."""
    text = PADS.read_text().replace('bore = "tilting_pad"', 'bore = "plain"')
    path = folder / "compressor_on_plain_journals.toml"
    path.write_text("\n".join(line for line in text.splitlines()
                              if not line.startswith(PAD_KEYS)) + "\n")
    return path


def timed(scene: Path, cache: str, out: str) -> float:
    run = run_measured([sys.executable, "-m", "shaftfem", "campbell", str(scene), "-q",
                        "--out", out], env={**os.environ, "SHAFTFEM_CACHE": cache})
    if run["returncode"] not in (0, 1):
        raise SystemExit(f"campbell {scene}: exit {run['returncode']}\n{run['stderr'][-2000:]}")
    return run["wall"]


def main() -> None:
    repeat = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    print(f"{machine()}; warm: medians of {repeat} runs, each in a fresh process")
    print("| bearings | campbell cold (s) | campbell warm (s) |")
    print("|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        scenes = {"5-pad tilting pads": PADS, "plain journals": plain(Path(folder))}
        times = {}
        for name, scene in scenes.items():
            with tempfile.TemporaryDirectory() as cache:
                cold = timed(scene, cache, folder + "/out")
                warm = statistics.median(timed(scene, cache, folder + "/out")
                                         for _ in range(repeat))
            times[name] = (cold, warm)
            print(f"| {name} | {cold:.1f} | {warm:.1f} |", flush=True)
    (pc, pw), (jc, jw) = times["5-pad tilting pads"], times["plain journals"]
    print(f"\ntilting pads / plain journals: cold {pc / jc:.2f}, warm {pw / jw:.2f}")


if __name__ == "__main__":
    main()
