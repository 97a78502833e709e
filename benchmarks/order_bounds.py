"""The error bounds of orders 3 to 5 (from the lower orders inside the same space)
against independent references: the paper's shaft and its sharp-corner variant against
NGSolve (docs/verification.md), the plain cylinder's torsion mode against c_t / 2L.

    .venv/bin/python benchmarks/order_bounds.py [CASE ...]

CASE is shaft:sizes:order[:geometry], shaft one of paper, sharp, cylinder, sizes
away/grooves/floor edges in mm, geometry the degree of the elements' map (2, the
default, or 3: cubic), both cached. Default: the
table of docs/accuracy.md. Each run is a fresh process: a
`run_bounded` on the scene's fixed mesh, bound included (wall time, warm solid).
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
sys.path.insert(0, str(Path(__file__).parents[1] / "tests"))
from _common import PAPER_REFERENCE_HZ, in_fresh_process, machine, peak_mb  # noqa: E402, I001  (before NumPy)

import numpy as np  # noqa: E402

# NGSolve on netgen's meshes (docs/verification.md): the paper's shaft (_common) and
# its sharp-corner variant (order 3 (458k DOFs, geometric
# refinement towards the sharp edges; 0.12-0.26 % from its order 2)
REFERENCE_HZ = {
    "paper": np.array(PAPER_REFERENCE_HZ),
    "sharp": np.array([429.59, 441.52, 1187.85, 1217.83, 2323.38, 2373.88, 2720.06,
                       3800.88, 3873.06, 4435.12]),
}
DEFAULT = ["paper:10/5/5:4", "paper:8/4/4:3", "paper:16/8/8:4", "sharp:8/4/4:3",
           "cylinder:16/16/16:4"]


def scene_of(shaft: str):
    from dataclasses import replace

    from shaftfem.scene.load import load_scene

    if shaft == "cylinder":
        return load_scene("plain_cylinder")
    scene = load_scene("paper2018")
    if shaft == "sharp":
        scene = replace(scene, grooves=replace(scene.grooves, root_radius=0.0))
    return scene


def one(shaft: str, sizes_mm: tuple, order: int, geometry: int = 2) -> dict:
    from dataclasses import replace

    from shaftfem.workflows.bounded import run_bounded

    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = scene_of(shaft)
    scene = replace(scene, max_dofs=5_000_000, target_error=None,
                    mesh=replace(scene.mesh, size=s, groove_size=g, edge_size=e, order=order,
                                 geometry_order=geometry))
    t = time.perf_counter()
    b = run_bounded(scene)
    wall = time.perf_counter() - t
    f, bound = b.result.modes.frequencies, b.estimate.relative_error
    if shaft == "cylinder":  # the torsion mode against the closed form
        from references import torsion_hz

        m, L = scene.material, scene.shaft.length
        k = b.result.modes.kinds.index("torsion")
        true = np.array([f[k] / torsion_hz(1, L, m.youngs_modulus, m.poisson_ratio,
                                           m.density) - 1])
        bound = bound[k:k + 1]
    else:
        true = f / REFERENCE_HZ[shaft] - 1
    return {"dofs": b.result.modes.n_dofs, "wall": wall, "peak": peak_mb(),
            "true": np.abs(true).tolist(), "bound": bound.tolist(),
            "method": b.estimate.method}


def main(args: list[str]) -> None:
    print(f"machine: {machine()}; bounds of orders 3 to 5 against references\n")
    print("| shaft | sizes (mm) | order | geometry | DOFs | wall (s) | peak (MB) | largest true error "
          "| bounds | effectivity (bound / true) | holds |\n|---|---|---|---|---|---|---|---|---|---|---|")
    for case in args or DEFAULT:
        shaft, sizes, order, *geometry = case.split(":")
        mm = tuple(float(x) for x in sizes.split("/"))
        g = int(geometry[0]) if geometry else 2
        r = in_fresh_process(one, shaft, mm, int(order), g)
        true, bound = np.array(r["true"]), np.array(r["bound"])
        eff = bound / true
        kind = "cubic" if g == 3 else "quadratic"
        print(f"| {shaft} | {sizes} | {order} | {kind} | {r['dofs']} | {r['wall']:.0f} | {r['peak']:.0f} "
              f"| {100 * true.max():.3g} % | {100 * bound.min():.2g}-{100 * bound.max():.2g} % "
              f"| {eff.min():.3g}-{eff.max():.3g} | {int(np.sum(bound >= true))}/{true.size} |",
              flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
