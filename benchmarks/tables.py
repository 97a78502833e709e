"""Every measured table of the docs, by the page and section it stands in, and the
script that makes it: one entry point for the benchmarks.

    .venv/bin/python benchmarks/tables.py --list          # the tables and their commands
    .venv/bin/python benchmarks/tables.py NAME [NAME ...]  # make those tables (NAME: a key below)
    .venv/bin/python benchmarks/tables.py --all            # make every table (hours)

Each script runs its cases in fresh processes, repeats them, and prints its Markdown
table with the machine's description; the tables go to stdout one after another. The
NGSolve tables need the NGSolve venv (docs/contributing.md, "Benchmarks").
"""

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).parent

# key: (page and section, script and its arguments as the page cites them)
TABLES = {
    "end-to-end": ("performance: The default run, end to end", ["end_to_end.py"]),
    "pictures": ("performance: Pictures and the HTML report", ["pictures.py"]),
    "assembly-routes": ("performance: What makes the solve fast (assembly)",
                        ["assembly_routes.py", "8", "3"]),
    "warm-start": ("performance: What makes the solve fast (warm starts)", ["warm_start.py"]),
    "order-5-assembly": ("performance: Order-5 assembly at 250k DOFs",
                         ["order_5_assembly.py"]),
    "growth": ("performance: Growth with the number of DOFs", ["growth.py"]),
    "installed": ("performance: Installed shafts", ["installed.py", "3"]),
    "campbell": ("performance: Turning shafts", ["campbell.py", "3"]),
    "periodic-cost": ("performance: Periodic rotors", ["periodic_cost.py", "3"]),
    "strength-cost": ("performance: The strength check", ["strength_cost.py", "3"]),
    "crossing-grids": ("verification: Critical speeds whatever the grid", ["crossing_grids.py"]),
    "floquet-1d": ("verification: A periodic rotor against an independent 1D Floquet model",
                   ["floquet_1d.py"]),
    "ucs-examples": ("verification: The critical speed map on every example",
                     ["ucs_examples.py"]),
    "rotor-verification": ("verification: Turning shafts against ross",
                           ["rotor_verification.py"]),
    "verification": ("verification: The bounds' verification matrix",
                     ["verification.py", "--write"]),
    "profiles": ("performance: Stepped shafts, tubes and STEP files", ["profiles.py"]),
    "cold-runs": ("performance: First runs and geometry changes", ["cold_runs.py"]),
    "study-cost": ("performance: A study's cost", ["study_cost.py"]),
    "sweeps": ("performance: Sweeps", ["sweeps.py"]),
    "bound-intervals": ("accuracy: How far each frequency is from converged",
                        ["bound_intervals.py"]),
    "adaptive": ("accuracy: Accuracy on request: adaptive meshes",
                 ["adaptive.py", "4,3,2", "1,0.6"]),
    "sizes-for-0.1": ("accuracy: How fine the paper's shaft must be for 0.1 %",
                      ["sizes_for_0_1.py", "4,3,2.5,2,1.6,1.2,1.0"]),
    "orders": ("accuracy: Higher orders", ["orders.py"]),
    "cubic-geometry": ("accuracy: Higher orders (cubic geometry)", ["cubic_geometry.py"]),
    "order-bounds": ("accuracy: Cubic geometry, and the bound at orders 3 and 4",
                     ["order_bounds.py"]),
    "order-adaptive": ("accuracy: Element orders adapted on one mesh",
                       ["order_adaptive.py", "paper:10/5/5:4:0.1:250000"]),
    "ngsolve-same-mesh": ("accuracy and verification: Against NGSolve, the same mesh",
                          ["ngsolve_same_mesh.py"]),
    "work-precision": ("accuracy: Against NGSolve, work against precision (README's picture)",
                       ["work_precision.py"]),
    "time-to-accuracy": ("accuracy: Time to 0.1 % from cold", ["time_to_accuracy.py"]),
    "cubic-functions": ("accuracy: Cubic functions added to P2",
                        ["cubic_functions.py", "4,3,4/2", "0.5,0.8,0.95,1"]),
    "stability": ("verification: the stability checks", ["stability.py"]),
    "paper-unknowns": ("case study: the paper's unknowns", ["paper_unknowns.py"]),
    "notch-factors": ("verification: Notch stresses against NGSolve", ["notch_factors.py"]),
    "pad-bearings": ("verification: Bearings of pads", ["pad_bearings.py"]),
    "pad-cost": ("performance: Tilting pads", ["pad_cost.py", "3"]),
    "pad-whirl": ("journal-bearing: The pads in the rotor model", ["pad_whirl.py"]),
    "pad-heat": ("journal-bearing: The film's heating", ["pad_heat.py"]),
}


def main(argv: list[str]) -> int:
    if not argv or argv == ["--list"]:
        width = max(map(len, TABLES))
        for key, (where, command) in TABLES.items():
            print(f"{key:<{width}}  {where}\n{'':<{width}}  "
                  f"python benchmarks/{' '.join(command)}")
        return 0
    keys = list(TABLES) if argv == ["--all"] else argv
    unknown = [k for k in keys if k not in TABLES]
    if unknown:
        print(f"tables.py: no table {', '.join(unknown)} (see --list)", file=sys.stderr)
        return 2
    for key in keys:
        where, command = TABLES[key]
        print(f"\n## {where}\n", flush=True)
        done = subprocess.run([sys.executable, str(HERE / command[0]), *command[1:]])
        if done.returncode != 0:
            print(f"tables.py: {key} failed (exit {done.returncode})", file=sys.stderr)
            return done.returncode
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
