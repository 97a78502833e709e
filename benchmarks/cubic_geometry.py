"""Quadratic against cubic geometry: the paper's shaft on coarse meshes whose elements
are curved to order 2 or to order 3 (shaftfem's mesher at [mesh] geometry_order 2 and 3:
gmsh's 20-node tetrahedra, boundary nodes at their CAD parameters, the boundary's
curving carried inside, elements still folded partly straightened), with hierarchical
elements of orders 3 and 4 (or --orders) on each.

    .venv/bin/python benchmarks/cubic_geometry.py [--geometry 2,3] [--orders 3,4] [SIZES ...]

SIZES is away/grooves/floor edges in mm (default 16/8/8 12/8/8). For each mesh: the
volume the elements hold against the solid's, and the largest and smallest true error
of the ten frequencies (against the NGSolve order-4 reference of docs/verification.md)
at orders 3 and 4. Every row is a fresh process, meshing without the cache.
"""


import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import PAPER_REFERENCE_HZ, in_fresh_process, machine, peak_mb  # noqa: E402, I001  (before NumPy)

import numpy as np  # noqa: E402

REFERENCE_HZ = np.array(PAPER_REFERENCE_HZ)


def _frequencies(mesh, p: int, material) -> tuple[int, np.ndarray, float]:
    """(DOFs, ten elastic frequencies in Hz, smallest det J) at order p on `mesh`."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as sla
    from skfem import Basis, BilinearForm, LinearForm

    from shaftfem.fem.assembly import MASS_INTORDER, STIFFNESS_INTORDER, Pattern, stiffness_and_mass
    from shaftfem.fem.eigen import solve_modes
    from shaftfem.fem.elements import element
    from shaftfem.fem.supports import rigid_body_modes
    from shaftfem.scene.model import ModeRequest

    basis = Basis(mesh, element(p), intorder=STIFFNESS_INTORDER[p])
    K, Ms = stiffness_and_mass(basis, Pattern.of(basis.element_dofs, basis.N), material,
                               MASS_INTORDER[p], 2)
    M = sp.kron(Ms, sp.identity(3, format="csr"), format="csr")
    # the coordinate field lies in the space (order >= 3): its coefficients by an L2
    # projection (mass and load on one quadrature, so a field of the space is kept exactly)
    mb = Basis(mesh, element(p), intorder=MASS_INTORDER[p])
    b = np.column_stack([LinearForm(lambda v, w, c=c: w.x[c] * v).assemble(mb)
                         for c in range(3)])
    x = sla.splu(BilinearForm(lambda u, v, _: u * v).assemble(mb).tocsc()).solve(b)
    one = np.zeros(basis.N)
    one[basis.element_dofs[:4].ravel()] = 1.0
    sol = solve_modes(K.tocsr(), M.tocsr(), ModeRequest(10),
                      rigid=rigid_body_modes(x, constant=one))
    det = float(basis.mapping.detDF(basis.X).min())
    return 3 * basis.N, np.sqrt(sol.eigenvalues[6:16]) / (2 * np.pi), det


def one(sizes_mm: tuple, geometry: int, orders: tuple) -> dict:
    import time
    from dataclasses import replace

    from skfem import Basis

    from shaftfem.fem.elements import element
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows import stages

    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = load_scene("paper2018")
    scene = replace(scene, max_dofs=5_000_000,
                    mesh=replace(scene.mesh, size=s, groove_size=g, edge_size=e, order=3,
                                 geometry_order=geometry))
    shape = stages.solid(scene)[1]
    t = time.perf_counter()
    shaft_mesh = stages.mesh(shape, scene.shaft, scene.grooves, scene.mesh, use_cache=False)
    mesh, straightened = shaft_mesh.to_skfem(), shaft_mesh.straightened
    # the signed volume on a rule exact for det J of a cubic map (degree 6, positive weights)
    b = Basis(mesh, element(3), intorder=7)
    v = mesh.p[:, mesh.t]
    sign = np.sign(np.einsum("de,de->e", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0], axis=0),
                             v[:, 3] - v[:, 0]))
    volume = float((sign[:, None] * b.mapping.detDF(b.X) * b.W).sum() / shape.volume - 1)
    out = {"elements": mesh.t.shape[1], "volume": volume, "rows": [],
           "mesh_seconds": time.perf_counter() - t,
           "straightened": straightened}
    for p in orders:
        dofs, f, det = _frequencies(mesh, p, scene.material)
        err = np.abs(f / REFERENCE_HZ - 1)
        out["rows"].append({"order": p, "dofs": dofs, "max": float(err.max()),
                            "min": float(err.min()), "f": f.tolist(), "min_det": det})
    out["peak"] = peak_mb()
    return out


def main(args: list[str]) -> None:
    print(f"machine: {machine()}; paper2018, hierarchical elements on quadratic and cubic "
          "geometry\n")
    flags = {a: b for a, b in zip(args, args[1:]) if a.startswith("--")}
    geometries = [int(g) for g in flags.get("--geometry", "2,3").split(",")]
    orders = tuple(int(p) for p in flags.get("--orders", "3,4").split(","))
    specs = [a for a in args if not a.startswith("--") and a not in flags.values()]
    print("| sizes (mm) | geometry | elements | volume, mesh / solid - 1 | order | DOFs "
          "| largest true error | smallest true error | straightened elements | meshing (s) |\n"
          "|---|---|---|---|---|---|---|---|---|---|")
    for spec in specs or ["16/8/8", "12/8/8"]:
        mm = tuple(float(x) for x in spec.split("/"))
        for geometry in geometries:
            r = in_fresh_process(one, mm, geometry, orders)
            for row in r["rows"]:
                print(f"| {spec} | {'quadratic' if geometry == 2 else 'cubic'} | "
                      f"{r['elements']} | {r['volume']:+.1e} | {row['order']} | {row['dofs']} | "
                      f"{100 * row['max']:.3f} % | {100 * row['min']:.3f} % | {r['straightened']} | "
                      f"{r['mesh_seconds']:.1f} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
