"""Time to 0.1 % on the paper's shaft: shaftfem's best configuration against NGSolve
order 3 on its own mesh of the same STEP, in one run, alternating, repeated.

    .venv/bin/python benchmarks/time_to_accuracy.py [--repeat 3] [OURS ...] [--own S/G:P:SAFETY]

OURS is away/grooves/floor edges in mm, the order and the geometry's order
(default 16/12/12:5:3: order 5 on the cubic mesh). Each shaftfem case is a fresh
process timed from the cached solid to the frequencies: meshing (not cached), assembly,
factorisation, eigensolve, with nothing from an earlier solve; no bound. Each NGSolve
case (default 16/8:3:0.25, the work-precision benchmark's) is a fresh process of the
NGSolve venv timed from the STEP file to the frequencies. True errors are the largest of
the ten frequencies against the NGSolve order-3 reference of docs/verification.md.
Prints a Markdown table of medians and the ratio of the medians.
"""

import statistics
import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
from _common import in_fresh_process, machine, options  # noqa: E402, I001  (before NumPy)

import ngsolve_same_mesh as same  # noqa: E402


def main(argv: list) -> None:
    opts, ours = options(argv, {"--repeat": "3", "--own": "16/8:3:0.25"})
    repeat, own = int(opts["--repeat"]), opts["--own"]
    ours = ours or ["16/12/12:5:3"]
    print(f"machine: {machine()}; paper2018, {repeat} runs each, alternating\n")
    step = str(same.step_file())
    runs: dict = {}
    for _ in range(repeat):
        for spec in ours:
            sizes, order, geometry = spec.split(":")
            r = in_fresh_process(same.ours_to_accuracy,
                                 tuple(float(x) for x in sizes.split("/")),
                                 int(order), int(geometry))
            runs.setdefault(("shaftfem", spec), []).append(r)
            print(f"shaftfem {spec}: {r['wall']:.1f} s, {r['dofs']:,} DOFs, "
                  f"{100 * same.error(r['f']):.3f} %", flush=True)
        r = same.ngsolve_own_mesh(step, own)
        runs.setdefault(("NGSolve", own), []).append(r)
        print(f"NGSolve {own}: {r['wall']:.1f} s, {r['dofs']:,} DOFs, "
              f"{100 * same.error(r['f']):.3f} %", flush=True)
    print("\n| code | case | DOFs | wall, median (s) | walls (s) | largest true error |")
    print("|---|---|---|---|---|---|")
    medians = {}
    for (code, spec), rs in runs.items():
        walls = [r["wall"] for r in rs]
        medians[code, spec] = statistics.median(walls)
        errors = sorted(100 * same.error(r["f"]) for r in rs)
        print(f"| {code} | {spec} | {rs[0]['dofs']:,} | {medians[code, spec]:.1f} | "
              f"{', '.join(f'{w:.1f}' for w in walls)} | "
              f"{errors[0]:.3f}-{errors[-1]:.3f} % |")
    for spec in ours:
        print(f"\nNGSolve {own} / shaftfem {spec}: "
              f"{medians['NGSolve', own] / medians['shaftfem', spec]:.2f}")


if __name__ == "__main__":
    main(sys.argv[1:])
