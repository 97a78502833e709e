"""Where the paper shaft's crossings converge: `shaftfem strength paper2018_installed` with
a refinement the product does not make by default, to see what the default's wide bounds
hold. Each round refines every spot still above the target (not the three that may be
the worst), within two of its own element sizes once they are under a twentieth of the
local radius (the rounds before keep theirs), for ROUNDS rounds within BUDGET DOFs.
Prints each round's spots: place, peak, bound, element size.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/crossings_refined.py [ROUNDS] [BUDGET]

Defaults 4 and 1,000,000: about 9 minutes and 12 GB on 2 cores.
"""

from __future__ import annotations

import sys
from dataclasses import replace

from shaftfem.scene.load import load_scene
from shaftfem.workflows import strength as ws


def main(rounds: int = 4, budget: int = 1_000_000) -> None:
    ws.MAX_REFINEMENTS, ws.REFINED = rounds, ws.MAX_SPOTS + 1
    ws._reach = lambda size, radius: (ws.REACH * size if size < 0.05 * radius
                                      else max(ws.REACH * size, 0.1 * radius))
    spots = ws._spots

    def shown(scene, fine, coarse, before, *rest):
        out = spots(scene, fine, coarse, before, *rest)
        print(f"mesh of {fine.dofs:,} DOFs:")
        for n, s in enumerate(out[:9], 1):
            bound = "unknown" if s.bound is None else f"+-{100 * s.bound:.1f} %"
            print(f"  {n} z {1e3 * s.z:6.1f} mm {s.peak / 1e6:6.1f} MPa {bound:>11}"
                  f"  element {1e3 * s.size:.3f} mm{'' if s.resolved else '  unresolved'}")
        return out

    ws._spots = shown
    scene = load_scene("paper2018_installed")
    ws.run_strength(replace(scene, max_dofs=budget))


if __name__ == "__main__":
    main(*[int(a) for a in sys.argv[1:3]])
