"""What the periodic rotor costs: `shaftfem campbell` of the keyed pump on journals
(examples/keyed_pump_on_journals.toml: Floquet exponents in the turning frame) against
the same pump without its keyway (examples/pump_on_journals.toml: constant coefficients
in the stationary frame), each as a user runs it, with a cold cache (a new
SHAFTFEM_CACHE each run: the solid, the mesh and the modes built every time),
alternating, in fresh processes; medians and the ratio of the medians.

    .venv/bin/python benchmarks/periodic_cost.py [REPEAT]
"""

import os
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, run_measured  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
ROTORS = {"round pump (stationary frame)": "pump_on_journals.toml",
          "keyed pump (Floquet, turning frame)": "keyed_pump_on_journals.toml"}


def main() -> None:
    repeat = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    shaftfem = str(ROOT / ".venv" / "bin" / "shaftfem")
    print(f"{machine()}; medians of {repeat} cold runs, alternating")
    walls: dict[str, list[float]] = {name: [] for name in ROTORS}
    for _ in range(repeat):
        for name, file in ROTORS.items():
            with tempfile.TemporaryDirectory() as cache:
                run = run_measured([shaftfem, "campbell", str(ROOT / "examples" / file), "-q"],
                                   env={**os.environ, "SHAFTFEM_CACHE": cache})
            assert run["returncode"] in (0, 1), run["stderr"][-2000:]
            walls[name].append(run["wall"])
    base = statistics.median(walls["round pump (stationary frame)"])
    print("| rotor | `shaftfem campbell` wall (s) | runs | ratio |")
    print("|---|---|---|---|")
    for name in ROTORS:
        med = statistics.median(walls[name])
        print(f"| {name} | {med:.1f} | {', '.join(f'{w:.1f}' for w in walls[name])} | "
              f"{med / base:.2f} |", flush=True)


if __name__ == "__main__":
    main()
