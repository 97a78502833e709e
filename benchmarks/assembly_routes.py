"""Stiffness assembly: scikit-fem's vector-valued form against shaftfem's route
(30x30 element blocks from scikit-fem's scalar basis, one batched product per
chunk of elements, summed into 3x3 blocks), on the same P2 mesh in the same run.

    .venv/bin/python benchmarks/assembly_routes.py [ELEMENT_SIZE_MM] [REPEAT]

Prints the median time of each route over REPEAT runs (default 3), their ratio,
and how far apart the two matrices are.
"""

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine  # noqa: E402


def main(size_mm: float, repeat: int) -> None:
    import numpy as np

    from shaftfem.fem.assembly import (
        STIFFNESS_INTORDER,
        _gradients,
        _sum_over_chunks,
        discretise,
        elasticity_blocks,
        stiffness,
    )
    from shaftfem.runtime import assembly_threads
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows import stages
    from shaftfem.workflows.pipeline import with_mesh

    scene = with_mesh(load_scene("paper2018"), size_mm)
    shape = stages.solid(scene)[1]
    mesh = stages.mesh(shape, scene.shaft, scene.grooves, scene.mesh)
    lam, mu = scene.material.lame

    def blocks():
        d = discretise(mesh)
        grad = _gradients(d.basis)
        n = grad.shape[2]
        return d.pattern.matrix(_sum_over_chunks(
            lambda c: elasticity_blocks(grad[c], d.basis.dx[c], lam, mu).reshape(
                c.stop - c.start, n, n, 9), grad.shape[0], n, 9, d.pattern, assembly_threads()), 3)

    def vector_form():
        return stiffness(mesh.to_skfem(), 2, lam, mu)

    times = {}
    for name, fn in (("blocks", blocks), ("vector", vector_form)):
        runs = []
        for _ in range(repeat):
            t = time.perf_counter()
            K = fn()
            runs.append(time.perf_counter() - t)
        times[name] = (statistics.median(runs), K)
    (t_fast, K_fast), (t_vec, K_vec) = times["blocks"], times["vector"]
    x = np.random.default_rng(0).standard_normal(K_fast.shape[0])
    diff = np.linalg.norm(K_fast @ x - K_vec @ x) / np.linalg.norm(K_vec @ x)
    print(f"machine: {machine()}; P2 mesh at {size_mm:g} mm: {mesh.n_elements} elements, "
          f"{K_fast.shape[0]} DOFs, rule of order {STIFFNESS_INTORDER[2]}, medians of {repeat}")
    print(f"  scikit-fem vector form      : {t_vec:7.2f} s (one thread)")
    print(f"  scalar-basis 30x30 blocks   : {t_fast:7.2f} s (shaftfem; vector form / blocks = "
          f"{t_vec / t_fast:.2f})")
    print(f"  same matrix: |K_fast x - K_vec x| / |K_vec x| = {diff:.1e}")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 8.0,
         int(sys.argv[2]) if len(sys.argv) > 2 else 3)
