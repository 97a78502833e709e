"""Stiffness assembly: scikit-fem's generic vector form against shaftfem's scalar-block route.

Both assemble the same K of 3D isotropic elasticity on the same P2 mesh; the
script checks they agree and prints the time of each, and the ratio, measured
in the same run.

    .venv/bin/python benchmarks/assembly_routes.py [ELEMENT_SIZE_MM]
"""

import sys
import time

import numpy as np
from skfem import Basis, BilinearForm, ElementTetP2, ElementVector
from skfem.helpers import ddot, sym_grad, trace

from shaftfem.assembly import STIFFNESS_INTORDER, stiffness
from shaftfem.pipeline import with_mesh
from shaftfem.scene import load_scene


def main(size_mm: float) -> None:
    from shaftfem.geometry import build_shape
    from shaftfem.mesh import mesh_shape

    scene = with_mesh(load_scene("paper2018"), size_mm)
    shape = build_shape(scene.shaft, scene.grooves)
    mesh = mesh_shape(shape.brep, scene.shaft, scene.grooves, scene.mesh).to_skfem()
    lam, mu = scene.material.lame

    t0 = time.perf_counter()
    scalar = Basis(mesh, ElementTetP2(), intorder=STIFFNESS_INTORDER[2])
    K_fast = stiffness(scalar, lam, mu)
    t_fast = time.perf_counter() - t0

    @BilinearForm
    def elasticity(u, v, _):
        eps_u, eps_v = sym_grad(u), sym_grad(v)
        return lam * trace(eps_u) * trace(eps_v) + 2 * mu * ddot(eps_u, eps_v)

    t0 = time.perf_counter()
    vector = Basis(mesh, ElementVector(ElementTetP2()), intorder=STIFFNESS_INTORDER[2])
    K_vec = elasticity.assemble(vector).tocsr()
    t_vec = time.perf_counter() - t0

    # scikit-fem's vector DOFs are numbered node-major too (3 n + c); compare on a vector
    x = np.random.default_rng(0).standard_normal(K_fast.shape[0])
    diff = np.linalg.norm(K_fast @ x - K_vec @ x) / np.linalg.norm(K_vec @ x)
    print(f"P2 mesh at {size_mm:g} mm: {mesh.nelements} elements, {K_fast.shape[0]} DOFs")
    print(f"  scikit-fem vector form : {t_vec:7.2f} s")
    print(f"  scalar 30x30 blocks    : {t_fast:7.2f} s   ({t_vec / t_fast:.1f}x faster)")
    print(f"  same matrix: |K_fast x - K_vec x| / |K_vec x| = {diff:.1e}")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 8.0)
