"""How the grooves' modelled root kink decides whether a crossing's stress converges.

The grooves' cutter reaches FILLET_CROSSING of the root radius below the floor, so that
OpenCASCADE cuts the floor transversally: the root fillet meets the floor at a kink of
acos(1 - FILLET_CROSSING), a re-entrant edge whose elastic stress has no limit (Williams:
sigma ~ r^(lambda - 1)). This refines one crossing's hottest spot again and again (the
spot of largest value each round, elements shrunk 4 times within two of its sizes) on a
short shaft with two crossing grooves under the paper shaft's 22 kN axial force, and
prints its peak at each round, for the construction's kink and for one ten times
shallower.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/groove_root_kink.py [0.03 0.003]

Each crossing value is a separate process (its own cache: the solid's cache key does not
hold the constant). About 5 minutes each on 2 cores.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

SCENE = Path(__file__).with_name("groove_root_kink.toml")
ROUNDS = 4


def one(crossing: float) -> None:
    from dataclasses import replace

    import shaftfem.cad.profile as profile
    from shaftfem.checks.singular import wedge_exponent
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows import strength as ws

    profile.FILLET_CROSSING = crossing
    ws.MAX_REFINEMENTS, ws.REFINED, ws.SHRINK_MAX = ROUNDS, 1, 4.0
    # the spot of largest value first, refined within two of its own sizes only
    ws._upper = ws._utilisation
    ws._reach = lambda size, radius: ws.REACH * size
    seen: list[tuple[int, float, float, float]] = []
    spots = ws._spots

    def spy(scene, fine, coarse, before, *rest):
        out = spots(scene, fine, coarse, before, *rest)
        top = out[0]
        seen.append((fine.dofs, top.z, top.size, top.peak))
        return out

    ws._spots = spy
    scene = load_scene(SCENE)
    ws.run_strength(replace(scene, max_dofs=1_500_000))
    kink = math.degrees(math.acos(1 - crossing))
    lam = wedge_exponent(math.pi + math.radians(kink))
    print(f"root kink {kink:.1f} deg (stress ~ r^{lam - 1:.3f}):")
    for n, (dofs, z, size, peak) in enumerate(seen):
        print(f"  mesh {n}: {dofs:>9,} DOFs  spot z {z * 1e3:6.1f} mm  element {size * 1e3:6.3f} mm"
              f"  peak {peak / 1e6:6.1f} MPa")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--one":
        one(float(sys.argv[2]))
        sys.exit()
    for c in [float(a) for a in sys.argv[1:]] or [0.03, 0.003]:
        with tempfile.TemporaryDirectory() as cache:
            subprocess.run([sys.executable, __file__, "--one", str(c)], check=True,
                           env=dict(os.environ, SHAFTFEM_CACHE=cache))
