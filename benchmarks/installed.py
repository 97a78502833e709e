"""What the installed shaft costs: the paper's shaft in its bearings with its gear
(geometry/paper2018_installed.toml) against the same shaft hanging free, on the same
mesh, in one process, warm (solid and mesh cached).

    .venv/bin/python benchmarks/installed.py [REPEAT]

Prints the median time of assembly (with the seats' elimination), factorisation and
eigensolve of each, and the participation and response steps of the installed one.
"""

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine  # noqa: E402


def main() -> None:
    repeat = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    from shaftfem.fem.response import modal_basis, participation, response_sweep
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes

    scene = load_scene("paper2018_installed")
    run_modes(scene)  # mesh and solid into the cache
    rows = {"installed": [], "free-free, same mesh": []}
    extra = []
    for _ in range(repeat):
        for name, s in (("installed", scene), ("free-free, same mesh", scene.free())):
            r = run_modes(s)
            t = r.timings
            rows[name].append((t.assembly, t.solve, t.assembly + t.solve, r.modes.n_dofs))
            if name == "installed":
                t0 = time.perf_counter()
                basis = modal_basis(r)
                participation(basis)
                response_sweep(r, "x", basis=basis)
                extra.append(time.perf_counter() - t0)
    print(f"{machine()}; medians of {repeat} warm runs")
    print("| run | DOFs | assembly (s) | solve (s) | total (s) |")
    print("|---|---|---|---|---|")
    for name, rs in rows.items():
        med = [statistics.median(x[k] for x in rs) for k in range(3)]
        print(f"| {name} | {rs[0][3]} | {med[0]:.2f} | {med[1]:.2f} | {med[2]:.2f} |")
    print(f"participation and response (1200 frequencies): {statistics.median(extra):.2f} s")


if __name__ == "__main__":
    main()
