"""An independent reference for the paper's shaft: NGSolve, p-refinement on the same solid.

A different discretisation of the exported BREP/STEP: netgen's own curved mesh and
NGSolve's H1 elements of order 2, 3, 4, ... on it (shaftfem has P2 only). The
eigenproblem is the same free-free pencil, solved as shaftfem does (shift-invert
Lanczos through MKL PARDISO) so that only the discretisation differs. NGSolve is a
benchmark tool, never a runtime need; it lives in a venv of its own:

    python3 -m venv .venv-ngsolve
    .venv-ngsolve/bin/pip install ngsolve scipy pypardiso
    .venv/bin/shaftfem export --out out/solid                 # writes out/solid/shaft.step
    .venv-ngsolve/bin/python benchmarks/ngsolve_reference.py out/solid/shaft.step 16 8 2,3,4

Arguments: STEP file, element size away from the grooves (mm), on the groove faces
(mm), orders, and optionally HP_LEVELS: layers of geometric refinement (each
HP_FACTOR times the last) towards every edge inside the outer surface, for grooves
with sharp corners (`root_radius_mm = 0`), whose re-entrant edges make the field
singular and p-refinement alone slow. Prints the ten elastic frequencies per order.
Material: the paper's 40Cr. NETGEN_CURVATURESAFETY (default 0.7) sets netgen's curvature
refinement: 0.2 meshes the paper's shaft coarsely enough for order 4 within 24 GB.

    .venv/bin/shaftfem export sharp.toml --out out/sharp    # root_radius_mm = 0
    .venv-ngsolve/bin/python benchmarks/ngsolve_reference.py out/sharp/shaft.step 16 8 2,3 1
"""

import math
import os
import sys
import time

import numpy as np
import scipy.sparse as sp
from netgen.occ import Glue, OCCGeometry, Pnt
from ngsolve import BilinearForm, Grad, InnerProduct, Mesh, Sym, VectorH1, div, dx
from scipy.sparse.linalg import LinearOperator, eigsh

E, NU, RHO = 2.11e11, 0.277, 7870.0   # 40Cr, as geometry/paper2018.toml
RADIUS = 0.016                         # m: faces inside it are groove faces
N_ELASTIC = 10
HP_FACTOR = 0.2                        # size ratio of successive layers at a sharp edge
# netgen's curvature refinement: 0.7 gives 69k tetrahedra on the paper's shaft at 16/8 mm,
# 0.2 gives 11.7k (for order 4 within 24 GB)
CURVATURE_SAFETY = float(os.environ.get("NETGEN_CURVATURESAFETY", "0.7"))


def csr(mat) -> sp.csr_matrix:
    r, c, v = mat.COO()
    return sp.csr_matrix((np.array(v), (np.array(r), np.array(c))), shape=(mat.height, mat.width))


def frequencies(K: sp.csr_matrix, M: sp.csr_matrix, k: int = N_ELASTIC + 6,
                shift_hz: float = 100.0, definite: bool = True) -> np.ndarray:
    """Lowest k eigenfrequencies (Hz) of the free body, shift-invert about a negative shift
    (`definite` False: K - sigma M is symmetric indefinite, as with Lagrange multipliers)."""
    import pypardiso

    sigma = -(2 * math.pi * shift_hz) ** 2
    # indefinite: PARDISO's symmetric indefinite factorisation perturbs small pivots, which
    # split the pairs of an axisymmetric shaft at order 4; the full LU pivots properly
    A = (K - sigma * M).tocsr()
    if definite:
        A = sp.triu(A, format="csr")   # PARDISO reads a symmetric matrix's upper triangle
    A.sort_indices()
    solver = pypardiso.PyPardisoSolver(mtype=2 if definite else 11)
    solver.factorize(A)
    op = LinearOperator(K.shape, matvec=lambda b: solver.solve(A, np.asarray(b, float)),
                        dtype=float)
    lam = eigsh(K, k=k, M=M, sigma=sigma, OPinv=op, which="LM", tol=1e-12,
                return_eigenvectors=False)
    return np.sqrt(np.abs(np.sort(lam))) / (2 * math.pi)


def main() -> None:
    path, size, groove = sys.argv[1], float(sys.argv[2]) * 1e-3, float(sys.argv[3]) * 1e-3
    orders = [int(p) for p in sys.argv[4].split(",")]
    hp_levels = int(sys.argv[5]) if len(sys.argv) > 5 else 0
    mu, lam = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
    t0 = time.perf_counter()
    # one conforming body; OpenCASCADE reads STEP in mm, the material is in SI
    shape = Glue(list(OCCGeometry(path).shape.solids)).Scale(Pnt(0, 0, 0), 1e-3)
    for face in shape.faces:
        if math.hypot(face.center.x, face.center.y) < RADIUS - 1e-5:
            face.maxh = groove
    if hp_levels:
        # sharp grooves: every edge inside the outer surface may be re-entrant; a
        # geometric refinement towards them (factor HP_FACTOR per level) restores
        # exponential convergence in the order
        for edge in shape.edges:
            if math.hypot(edge.center.x, edge.center.y) < RADIUS - 1e-5:
                edge.hpref = 1
    # curved high-order elements carry the fillets: no curvature-driven refinement
    mesh = Mesh(OCCGeometry(shape).GenerateMesh(maxh=size, curvaturesafety=CURVATURE_SAFETY,
                                                segmentsperedge=0.3, grading=0.5))
    if hp_levels:
        mesh.RefineHP(hp_levels, factor=HP_FACTOR)
    print(f"netgen: {mesh.ne} elements in {time.perf_counter() - t0:.1f} s", flush=True)
    print("| order | DOFs | s | " + " | ".join(f"f{i + 1} (Hz)" for i in range(N_ELASTIC)) + " |")
    print("|---|---|---|" + "---|" * N_ELASTIC)
    for p in orders:
        t = time.perf_counter()
        mesh.Curve(max(p, 2))
        fes = VectorH1(mesh, order=p)
        u, v = fes.TnT()
        a = BilinearForm(2 * mu * InnerProduct(Sym(Grad(u)), Sym(Grad(v))) * dx
                         + lam * div(u) * div(v) * dx)
        m = BilinearForm(RHO * u * v * dx)
        a.Assemble()
        m.Assemble()
        K, M = csr(a.mat), csr(m.mat)
        used = np.flatnonzero(K.diagonal() != 0)  # hp-refinement leaves unused DOFs
        f = frequencies(K[used][:, used], M[used][:, used])
        rigid, elastic = f[:6], f[6:]
        if np.max(rigid) > 1.0 or np.min(elastic) < 1.0:
            raise SystemExit(f"order {p}: expected 6 rigid-body modes, got {f[:8]}")
        print(f"| {p} | {fes.ndof} | {time.perf_counter() - t:.0f} | "
              + " | ".join(f"{x:.3f}" for x in elastic) + " |", flush=True)


if __name__ == "__main__":
    main()
