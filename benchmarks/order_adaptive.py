"""Element orders adapted on one mesh (workflows.order_adapt) on the paper's shaft: each
round's DOFs, largest bound and largest true error against the NGSolve reference of
docs/verification.md, beside uniform orders on the same mesh.

    .venv/bin/python benchmarks/order_adaptive.py [SIZES:ORDER:TARGET_%[:BUDGET] ...]

SIZES is away/grooves/floor edges in mm, BUDGET the DOF budget (default
10/5/5:4:0.1:400000, the tool's default budget). True errors are absolute: on a coarse
mesh the quadratic geometry's missing groove volume puts some frequencies below the
reference. Each case runs in a fresh process with a warm solid (wall time and peak
memory its own), without the adapted-orders cache.
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import in_fresh_process, machine, peak_mb  # noqa: E402, I001  (before NumPy)

import numpy as np  # noqa: E402

# NGSolve order 3, 1.06M DOFs on netgen's mesh (docs/verification.md; perhaps 0.05 % high)
REFERENCE_HZ = np.array([432.02, 443.35, 1193.91, 1222.42, 2333.47, 2381.62, 2731.30,
                         3814.81, 3883.84, 4448.27])


def one(sizes_mm: tuple, order: int, target: float, budget: int) -> dict:
    from dataclasses import replace

    from shaftfem.runtime import RunOptions
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows import order_adapt

    seen = []
    solve = order_adapt._solve

    def recorded(*args, **kwargs):
        out = solve(*args, **kwargs)
        seen.append(out[2])
        return out

    order_adapt._solve = recorded
    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = load_scene("paper2018")
    scene = replace(scene, mesh=replace(scene.mesh, size=s, groove_size=g, edge_size=e,
                                        order=order))
    t = time.perf_counter()
    a = order_adapt.run_order_adaptive(scene, target, budget, RunOptions(use_cache=False))
    wall = time.perf_counter() - t
    rounds = []
    for r, space in zip(a.rounds, seen):
        # modes in frequency order: the shaft's ten are all there
        true = np.abs(np.sort(space.frequencies) / REFERENCE_HZ - 1)
        rounds.append((r.dofs, r.max_bound, float(np.max(true)), float(np.min(true))))
    rank = np.argsort(a.result.modes.frequencies)
    true = np.abs(a.result.modes.frequencies[rank] / REFERENCE_HZ - 1)
    eff = a.estimate.relative_error[rank] / true
    return {"rounds": rounds, "wall": wall, "peak": peak_mb(), "why": a.why,
            "eff": (float(eff.min()), float(eff.max())), "holds": int(np.sum(eff >= 1))}


def main(cases: list[str]) -> None:
    print(f"machine: {machine()}; paper2018, element orders adapted on one mesh\n")
    for case in cases:
        sizes, order, target, *budget = case.split(":")
        sz = tuple(float(x) for x in sizes.split("/"))
        dofs = int(budget[0]) if budget else 400_000
        r = in_fresh_process(one, sz, int(order), float(target) / 100, dofs)
        print(f"{sizes} mm, up to order {order}, target {target} %, budget {dofs:,} DOFs: "
              f"{r['wall']:.0f} s, "
              f"peak {r['peak']:.0f} MB; effectivity {r['eff'][0]:.2f}-{r['eff'][1]:.2f} "
              f"({r['holds']}/10 hold); {r['why'] or 'reached'}")
        print("| round | DOFs | largest bound | largest true error | smallest true error |")
        print("|---|---|---|---|---|")
        for i, (d, b, hi, lo) in enumerate(r["rounds"], 1):
            # the first round has its recovery estimate only, no bound yet
            bound = "-" if i == 1 else f"{100 * b:.3f} %"
            print(f"| {i} | {d:,} | {bound} | {100 * hi:.3f} % | {100 * lo:.3f} % |")
        print()


if __name__ == "__main__":
    main(sys.argv[1:] or ["10/5/5:4:0.1:400000"])
