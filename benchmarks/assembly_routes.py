"""Stiffness assembly: scikit-fem's vector form (what shaftfem uses) against 30x30
element blocks built from scikit-fem's scalar basis (a trial found the latter
several times faster with an older scikit-fem).

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

import scipy.sparse as sp

from shaftfem.assembly import STIFFNESS_INTORDER
from shaftfem.pipeline import with_mesh
from shaftfem.scene import load_scene


def block_stiffness(basis, lam: float, mu: float) -> sp.csr_matrix:
    """K[(i,a), (j,b)] = lam D_ab[i,j] + mu D_ba[i,j] + mu delta_ab sum_c D_cc[i,j],
    D_ab[i, j] = int d_a phi_i d_b phi_j, from the scalar basis, in element blocks."""
    nloc, nel, n = len(basis.basis), basis.nelems, basis.N
    grads = np.stack([basis.basis[i][0].grad for i in range(nloc)])  # (i, a, e, q)
    D = np.einsum("iaeq,jbeq,eq->eabij", grads, grads, basis.dx, optimize=True)
    tr = np.einsum("eccij->eij", D)
    Ke = (lam * D.transpose(0, 3, 1, 4, 2) + mu * D.transpose(0, 3, 2, 4, 1)
          + mu * tr[:, :, None, :, None] * np.eye(3)[None, None, :, None, :])
    g = (3 * basis.element_dofs.T[:, :, None] + np.arange(3)).reshape(nel, 3 * nloc)
    rows = np.repeat(g, 3 * nloc, axis=1).ravel()
    cols = np.tile(g, (1, 3 * nloc)).ravel()
    return sp.coo_matrix((Ke.ravel(), (rows, cols)), shape=(3 * n, 3 * n)).tocsr()


def main(size_mm: float) -> None:
    from shaftfem.geometry import build_shape
    from shaftfem.mesh import mesh_shape

    scene = with_mesh(load_scene("paper2018"), size_mm)
    shape = build_shape(scene.shaft, scene.grooves)
    mesh = mesh_shape(shape, scene.shaft, scene.grooves, scene.mesh).to_skfem()
    lam, mu = scene.material.lame

    t0 = time.perf_counter()
    scalar = Basis(mesh, ElementTetP2(), intorder=STIFFNESS_INTORDER[2])
    K_fast = block_stiffness(scalar, lam, mu)
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
    print(f"  scikit-fem vector form (shaftfem) : {t_vec:7.2f} s")
    print(f"  scalar-basis 30x30 blocks         : {t_fast:7.2f} s   (vector form / blocks = "
          f"{t_vec / t_fast:.2f})")
    print(f"  same matrix: |K_fast x - K_vec x| / |K_vec x| = {diff:.1e}")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 8.0)
