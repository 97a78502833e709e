"""What tilting pads cost: `shaftfem campbell` of examples/compressor_on_tilting_pads.toml
against the same rotor on plain journals of the same bore, length, clearance and oil,
each as a user runs it (a fresh process, the CLI): cold (an empty cache: the bearings'
film tables are solved) once, warm (the cache from that run) REPEAT times; the ratio of
the medians.

    .venv/bin/python benchmarks/pad_cost.py [REPEAT] [--fed]

`--fed`: both fed 8 l/min at 45 C (oil_supply_temperature_c in place of the film's 55 C):
the tilting pads' coefficients then come from their heated film, solved at each run (it
is kept for the process, not on disk); the plain journals' from their heat balance.
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


def fed(text: str) -> str:
    """The scene's journals fed 8 l/min at 45 C in place of their film's 55 C."""
    return text.replace("oil_temperature_c = 55.0",
                        "oil_supply_temperature_c = 45.0\noil_flow_l_min = 8.0")


def plain(folder: Path, feed: bool = False) -> Path:
    """The compressor with plain journals in place of its tilting pads."""
    text = PADS.read_text().replace('bore = "tilting_pad"', 'bore = "plain"')
    path = folder / "compressor_on_plain_journals.toml"
    path.write_text("\n".join(line for line in (fed(text) if feed else text).splitlines()
                              if not line.startswith(PAD_KEYS)) + "\n")
    return path


def pads(folder: Path, feed: bool = False) -> Path:
    """The compressor on its tilting pads (fed, with `feed`)."""
    if not feed:
        return PADS
    path = folder / "compressor_on_fed_tilting_pads.toml"
    path.write_text(fed(PADS.read_text()))
    return path


def timed(scene: Path, cache: str, out: str) -> float:
    run = run_measured([sys.executable, "-m", "shaftfem", "campbell", str(scene), "-q",
                        "--out", out], env={**os.environ, "SHAFTFEM_CACHE": cache})
    if run["returncode"] not in (0, 1):
        raise SystemExit(f"campbell {scene}: exit {run['returncode']}\n{run['stderr'][-2000:]}")
    return run["wall"]


def main() -> None:
    feed = "--fed" in sys.argv
    numbers = [a for a in sys.argv[1:] if a != "--fed"]
    repeat = int(numbers[0]) if numbers else 3
    print(f"{machine()}; warm: medians of {repeat} runs, each in a fresh process"
          + ("; fed 8 l/min at 45 C" if feed else ""))
    print("| bearings | campbell cold (s) | campbell warm (s) |")
    print("|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        scenes = {"5-pad tilting pads": pads(Path(folder), feed),
                  "plain journals": plain(Path(folder), feed)}
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
