"""Time to 0.1 % on the paper's shaft: shaftfem's best configuration against NGSolve
order 3 on its own mesh of the same STEP, in one run, alternating, repeated.

    .venv/bin/python benchmarks/time_to_accuracy.py [--repeat 3] [OURS ...] [--own S/G:P:SAFETY]
                                                    [--cli SPEC[,SPEC]]

OURS is away/grooves/floor edges in mm, the order and the geometry's order
(default 16/12/12:5:3: order 5 on the cubic mesh). Each shaftfem case is a fresh
process timed from the cached solid to the frequencies: meshing (not cached), assembly,
factorisation, eigensolve, with nothing from an earlier solve; no bound. Each NGSolve
case (default 16/8:3:0.25, the work-precision benchmark's) is a fresh process of the
NGSolve venv timed from the STEP file to the frequencies. True errors are the largest of
the ten frequencies against the NGSolve order-4 reference of docs/verification.md.
With --cli SPEC[,SPEC...] (SPEC as OURS), each round also runs `shaftfem modes` as a
user would on geometry/paper2018.toml with its [mesh] set to SPEC, from an empty cache
(the CAD solid built, the bound included), timed from the command to its exit.
Prints a Markdown table of medians, with each case's largest peak memory (a process's
own, measured by wait4), and the ratio of the medians.
"""

import json
import os
import statistics
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
from _common import in_fresh_process, machine, options, run_measured  # noqa: E402, I001

import ngsolve_same_mesh as same  # noqa: E402


def main(argv: list) -> None:
    opts, ours = options(argv, {"--repeat": "3", "--own": "16/8:3:0.25", "--cli": ""})
    repeat, own = int(opts["--repeat"]), opts["--own"]
    clis = [c for c in opts["--cli"].split(",") if c]
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
        for spec in clis:
            r = cli_run(spec)
            runs.setdefault(("shaftfem modes", spec), []).append(r)
            print(f"shaftfem modes {spec}: {r['wall']:.1f} s, {r['dofs']:,} DOFs, "
                  f"{100 * same.error(r['f']):.3f} %, bounds {r['bounds']}", flush=True)
        r = same.ngsolve_own_mesh(step, own)
        runs.setdefault(("NGSolve", own), []).append(r)
        print(f"NGSolve {own}: {r['wall']:.1f} s, {r['dofs']:,} DOFs, "
              f"{100 * same.error(r['f']):.3f} %", flush=True)
    print("\n| code | case | DOFs | wall, median (s) | walls (s) | largest true error "
          "| bounds | peak memory, largest (MB) |")
    print("|---|---|---|---|---|---|---|---|")
    medians = {}
    for (code, spec), rs in runs.items():
        walls = [r["wall"] for r in rs]
        medians[code, spec] = statistics.median(walls)
        errors = sorted(100 * same.error(r["f"]) for r in rs)
        print(f"| {code} | {spec} | {rs[0]['dofs']:,} | {medians[code, spec]:.1f} | "
              f"{', '.join(f'{w:.1f}' for w in walls)} | "
              f"{errors[0]:.3f}-{errors[-1]:.3f} % | {rs[0].get('bounds', '(none)')} | "
              f"{max(r['peak'] for r in rs):.0f} |")
    for spec in ours:
        print(f"\nNGSolve {own} / shaftfem {spec}: "
              f"{medians['NGSolve', own] / medians['shaftfem', spec]:.2f}")
    for spec in clis:
        print(f"NGSolve {own} / shaftfem modes {spec}: "
              f"{medians['NGSolve', own] / medians['shaftfem modes', spec]:.2f}")


def scene_text(spec: str) -> str:
    """geometry/paper2018.toml with its [mesh] table set to SPEC (sizes:order:geometry)."""
    import re

    sizes, order, geometry = spec.split(":")
    away, grooves, edges = sizes.split("/")
    text = (HERE.parent / "geometry" / "paper2018.toml").read_text()
    mesh = (f"[mesh]\nelement_size_mm = {away}\ngroove_element_size_mm = {grooves}\n"
            f"edge_element_size_mm = {edges}\norder = {order}\ngeometry_order = {geometry}\n")
    return re.sub(r"\[mesh\]\n(?:[^\[\n][^\n]*\n|\n)*?(?=\n\[)", mesh, text, count=1)


def cli_run(spec: str) -> dict:
    """`shaftfem modes --json` on the paper's shaft meshed as SPEC, from an empty cache:
    wall time, DOFs, frequencies, the bounds' range and the peak memory (MB) of the
    command."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "modes.json"
        scene = Path(tmp) / "paper2018.toml"
        scene.write_text(scene_text(spec))
        done = run_measured([sys.executable, "-m", "shaftfem", "modes", str(scene), "-q",
                             "--json", str(out)],
                            env={**os.environ, "SHAFTFEM_CACHE": str(Path(tmp) / "c")})
        if done["returncode"]:
            raise SystemExit(done["stderr"][-3000:])
        data = json.loads(out.read_text())
    modes = data["modes"]
    bounds = [m["error_bound_percent"] for m in modes]
    return {"wall": done["wall"], "dofs": data["dofs"], "f": [m["frequency_hz"] for m in modes],
            "bounds": f"{min(bounds):.2f}-{max(bounds):.2f} %", "peak": done["peak"]}


if __name__ == "__main__":
    main(sys.argv[1:])
