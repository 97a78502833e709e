"""Why cubic elements (P3) on the paper's shaft sit twice as far from the reference as
NGSolve's order 3 at the same DOFs: one candidate cause at a time.

    .venv/bin/python benchmarks/p3_causes.py

Each row changes one thing against the shipped P3 run (8 / 4 / 4 mm, quadrature
of order 4 for K and 6 for M) and prints the largest error over the ten modes
against the NGSolve order-3 reference of docs/verification.md (itself perhaps 0.05 % high).
Rows run in fresh processes (about 4-5 GB each).
"""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from _common import in_fresh_process, machine  # noqa: E402

REFERENCE_HZ = np.array([432.02, 443.35, 1193.91, 1222.42, 2333.47, 2381.62, 2731.30,
                         3814.81, 3883.84, 4448.27])
ROWS = [("as shipped", (8, 4, 4), None),
        ("quadrature raised to 6 (K) / 8 (M)", (8, 4, 4), (6, 8)),
        ("6 mm away from the grooves", (6, 4, 4), None),
        ("3 mm on the groove faces and edges", (8, 3, 3), None),
        ("3 mm at the floor edges (the fillets) only", (8, 4, 3), None),
        ("2 mm at the floor edges only", (8, 4, 2), None)]


def one(sizes_mm: tuple, rules: tuple | None) -> tuple[int, list]:
    from dataclasses import replace

    import shaftfem.fem.assembly as assembly
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes

    if rules:
        assembly.STIFFNESS_INTORDER[3], assembly.MASS_INTORDER[3] = rules
    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = load_scene("paper2018")
    scene = replace(scene, max_dofs=2_000_000,
                    mesh=replace(scene.mesh, order=3, size=s, groove_size=g, edge_size=e))
    r = run_modes(scene)
    return r.modes.n_dofs, list(map(float, r.modes.frequencies))


def main() -> None:
    print(f"machine: {machine()}; paper2018, P3 on the curved P2 geometry\n")
    print("| change | DOFs | largest error | frequencies moved against the shipped run |\n"
          "|---|---|---|---|")
    first = None
    for name, sizes, rules in ROWS:
        n, f = in_fresh_process(one, sizes, rules)
        f = np.array(f)
        first = f if first is None else first
        err = np.max(np.abs(f / REFERENCE_HZ - 1))
        moved = np.max(np.abs(f / first - 1))
        print(f"| {name} | {n} | {100 * err:.3f} % | {moved:.1e} |")


if __name__ == "__main__":
    main()
