"""What the turning shaft costs: a Campbell diagram of the paper's shaft in its bearings
(geometry/paper2018_installed.toml with [rotor] added: 31 speeds from 0 to 10,000 r/min,
the grooved shaft in the rotating frame) against one `shaftfem modes` of the same scene,
both as a user runs them, warm (solid and mesh cached), alternating, in fresh processes.

    .venv/bin/python benchmarks/campbell.py [REPEAT]

The Campbell run holds everything it prints: the standstill basis (30 modes), the spin's
matrices, 31 speeds, the critical speeds refined by root finding, the stability and
divergence bands, and the basis check (the same whirl on two thirds of the basis).
"""

import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, run_measured  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
ROTOR = """
[rotor]
speed_rpm = 80.0
max_speed_rpm = 10000.0
campbell_points = 31
"""


def main() -> None:
    repeat = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    shaftfem = str(ROOT / ".venv" / "bin" / "shaftfem")
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / "paper2018_turning.toml"
        scene.write_text((ROOT / "geometry" / "paper2018_installed.toml").read_text() + ROTOR)
        commands = {"shaftfem modes (bound included)": [shaftfem, "modes", str(scene), "-q"],
                    "shaftfem campbell, 31 speeds": [shaftfem, "campbell", str(scene), "-q"]}
        for command in commands.values():   # the solid and mesh into the cache
            run = run_measured(command)
            assert run["returncode"] == 0, run["stderr"][-2000:]
        walls: dict[str, list[float]] = {name: [] for name in commands}
        peaks: dict[str, list[float]] = {name: [] for name in commands}
        for _ in range(repeat):
            for name, command in commands.items():
                run = run_measured(command)
                assert run["returncode"] == 0, run["stderr"][-2000:]
                walls[name].append(run["wall"])
                peaks[name].append(run["peak"])
    base = statistics.median(walls["shaftfem modes (bound included)"])
    print(f"{machine()}; medians of {repeat} warm runs, alternating")
    print("| run | wall (s) | runs | ratio to modes | peak (GB) |")
    print("|---|---|---|---|---|")
    for name in commands:
        med = statistics.median(walls[name])
        print(f"| {name} | {med:.1f} | {', '.join(f'{w:.1f}' for w in walls[name])} | "
              f"{med / base:.2f} | {max(peaks[name]) / 1024:.1f} |")


if __name__ == "__main__":
    main()
