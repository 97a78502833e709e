"""Element orders adapted on one mesh (workflows.order_adapt): each round's DOFs, largest
bound and largest true error, on the paper's shaft and its sharp-corner variant against
the NGSolve references of benchmarks/order_bounds.py, and on the plain cylinder (its
torsion mode against c_t / 2L).

    .venv/bin/python benchmarks/order_adaptive.py [SHAFT:SIZES:ORDER:TARGET_%[:BUDGET] ...]

SHAFT is paper, sharp or cylinder; SIZES away/grooves/floor edges in mm; BUDGET the DOF
budget (default 400,000, the tool's). Default: paper:10/5/5:4:0.1:250000. True errors
are absolute: on a coarse mesh the quadratic geometry's missing groove volume puts some
frequencies below the reference. Each case runs in a fresh process with a warm solid
(wall time and peak memory its own), without the adapted-orders cache.
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import in_fresh_process, machine, peak_mb  # noqa: E402, I001  (before NumPy)

import numpy as np  # noqa: E402

from order_bounds import REFERENCE_HZ, scene_of  # noqa: E402


def one(shaft: str, sizes_mm: tuple, order: int, target: float, budget: int) -> dict:
    from dataclasses import replace

    from shaftfem.runtime import RunOptions
    from shaftfem.workflows import order_adapt

    seen = []
    space = order_adapt._space

    def recorded(*args, **kwargs):
        out = space(*args, **kwargs)
        seen.append(out)
        return out

    order_adapt._space = recorded
    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = scene_of(shaft)
    scene = replace(scene, mesh=replace(scene.mesh, size=s, groove_size=g, edge_size=e,
                                        order=order))
    t = time.perf_counter()
    a = order_adapt.run_order_adaptive(scene, target, budget, RunOptions(use_cache=False))
    wall = time.perf_counter() - t

    def true_errors(f: np.ndarray, kinds: list[str]) -> tuple[np.ndarray, np.ndarray]:
        """Each compared mode's absolute true error, and its index among f."""
        if shaft == "cylinder":
            from references import torsion_hz

            m, L = scene.material, scene.shaft.length
            k = kinds.index("torsion")
            exact = torsion_hz(1, L, m.youngs_modulus, m.poisson_ratio, m.density)
            return np.array([abs(f[k] / exact - 1)]), np.array([k])
        rank = np.argsort(f)   # the shaft's ten modes in frequency order
        return np.abs(f[rank] / REFERENCE_HZ[shaft] - 1), rank

    rounds = []
    for r, space in zip(a.rounds, seen):
        true, _ = true_errors(space.frequencies, space.kinds)
        rounds.append((r.dofs, r.max_bound, float(np.max(true)), float(np.min(true))))
    true, at = true_errors(a.result.modes.frequencies, list(a.result.modes.kinds))
    eff = a.estimate.relative_error[at] / true
    return {"rounds": rounds, "wall": wall, "cad": a.result.timings.cad, "peak": peak_mb(),
            "why": a.why,
            "eff": (float(eff.min()), float(eff.max())), "holds": int(np.sum(eff >= 1)),
            "within3": int(np.sum((eff >= 1) & (eff <= 3))), "n": int(true.size)}


def main(cases: list[str]) -> None:
    print(f"machine: {machine()}; element orders adapted on one mesh\n")
    for case in cases:
        shaft, sizes, order, target, *budget = case.split(":")
        sz = tuple(float(x) for x in sizes.split("/"))
        dofs = int(budget[0]) if budget else 400_000
        r = in_fresh_process(one, shaft, sz, int(order), float(target) / 100, dofs)
        print(f"{shaft}, {sizes} mm, up to order {order}, target {target} %, budget "
              f"{dofs:,} DOFs: {r['wall']:.0f} s, peak {r['peak']:.0f} MB; last round's "
              f"effectivity {r['eff'][0]:.2f}-{r['eff'][1]:.2f} ({r['holds']}/{r['n']} hold, "
              f"{r['within3']} within 3); {r['why'] or 'reached'}")
        print("| round | DOFs | largest bound | largest true error | smallest true error |")
        print("|---|---|---|---|---|")
        for i, (d, b, hi, lo) in enumerate(r["rounds"], 1):
            # the first round has its recovery estimate only, no bound yet
            bound = "-" if i == 1 else f"{100 * b:.3f} %"
            print(f"| {i} | {d:,} | {bound} | {100 * hi:.3f} % | {100 * lo:.3f} % |",
                  flush=True)
        print()


if __name__ == "__main__":
    main(sys.argv[1:] or ["paper:10/5/5:4:0.1:250000"])
