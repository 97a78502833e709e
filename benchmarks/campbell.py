"""What the turning shaft costs: a Campbell diagram of 31 speeds, a critical speed map of
40 stiffnesses and a Level I screening of 20 Q against one `shaftfem modes` of the same
scene, each as a user runs them, warm (solid and mesh cached),
alternating, in fresh processes. Two rotors: the paper's shaft in its bearings
(geometry/paper2018_installed.toml with [rotor] added: 0 to 10,000 r/min, the grooved
shaft in the rotating frame), and the pump on two journal bearings
(examples/pump_on_journals.toml: their films' stiffness changes 30 times and more over
0 to 9,000 r/min; the journals' loads from the static solution in both runs).

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
    print(f"{machine()}; medians of {repeat} warm runs, alternating")
    print("| rotor | run | wall (s) | runs | ratio to modes | peak (GB) |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / "paper2018_turning.toml"
        scene.write_text((ROOT / "geometry" / "paper2018_installed.toml").read_text() + ROTOR)
        pump = Path(tmp) / "pump_on_journals.toml"
        pump.write_text((ROOT / "examples" / "pump_on_journals.toml").read_text().replace(
            "campbell_points = 37", "campbell_points = 31"))
        measure("paper's shaft, installed", scene, shaftfem, repeat)
        measure("pump on journals", pump, shaftfem, repeat)


def measure(rotor: str, scene: Path, shaftfem: str, repeat: int) -> None:
    """One row per run of `scene`: modes, the 31-speed Campbell diagram, the map."""
    commands = {"shaftfem modes (bound included)": [shaftfem, "modes", str(scene), "-q"],
                "shaftfem campbell, 31 speeds": [shaftfem, "campbell", str(scene), "-q"],
                "shaftfem ucs, 40 stiffnesses": [shaftfem, "ucs", str(scene), "-q"],
                "shaftfem level1, 20 Q": [shaftfem, "level1", str(scene), "-q"]}
    for command in commands.values():   # the solid and mesh into the cache
        run = run_measured(command)
        assert run["returncode"] in (0, 1), run["stderr"][-2000:]   # level1 may fail
    walls: dict[str, list[float]] = {name: [] for name in commands}
    peaks: dict[str, list[float]] = {name: [] for name in commands}
    for _ in range(repeat):
        for name, command in commands.items():
            run = run_measured(command)
            assert run["returncode"] in (0, 1), run["stderr"][-2000:]
            walls[name].append(run["wall"])
            peaks[name].append(run["peak"])
    base = statistics.median(walls["shaftfem modes (bound included)"])
    for name in commands:
        med = statistics.median(walls[name])
        print(f"| {rotor} | {name} | {med:.1f} | {', '.join(f'{w:.1f}' for w in walls[name])} | "
              f"{med / base:.2f} | {max(peaks[name]) / 1024:.1f} |", flush=True)


if __name__ == "__main__":
    main()
