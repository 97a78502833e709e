"""Quadratic against cubic geometry: the paper's shaft on coarse meshes whose elements
are curved to order 2 (as shaftfem meshes) or to order 3 (gmsh's 20-node tetrahedra, the
boundary's curving carried inside, elements that stay folded straightened), with
hierarchical elements of order 3 and 4 on each.

    .venv/bin/python benchmarks/cubic_geometry.py [--optimize METHODS] [--geometry 2,3] [SIZES ...]

SIZES is away/grooves/floor edges in mm (default 16/8/8 12/6/3). `--optimize` runs
gmsh's high-order optimisers on the cubic mesh, in order, after curving it (e.g.
HighOrderElastic,HighOrder: gmsh.model.mesh.optimize). For each mesh:
the volume the elements hold against the solid's, and the largest and smallest true error
of the ten frequencies (against the NGSolve order-3 reference of docs/verification.md)
at orders 3 and 4, on both geometries. Every row is a fresh process.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import in_fresh_process, machine, peak_mb  # noqa: E402, I001  (before NumPy)

import numpy as np  # noqa: E402

REFERENCE_HZ = np.array([432.02, 443.35, 1193.91, 1222.42, 2333.47, 2381.62, 2731.30,
                         3814.81, 3883.84, 4448.27])


def _cubic_mesh(scene, shape, optimize: tuple = ()):
    """gmsh's mesh of the solid with the scene's size fields, curved to order 3, as a
    scikit-fem mesh whose geometry is the Lagrange cubic on ascending-vertex cells, and
    how many elements were straightened."""
    from dataclasses import dataclass

    from skfem import MeshTet1

    from shaftfem.cad import mesher
    from shaftfem.cad.session import session
    from shaftfem.fem.elements import lagrange_cubic

    cubic = lagrange_cubic()

    @dataclass(repr=False)
    class MeshTet3(MeshTet1):
        elem: type = cubic
        affine: bool = False
        sort_t: bool = False

    s_ = scene.mesh
    with session("mesh") as s:
        gmsh = s.gmsh
        gmsh.model.occ.importShapes(str(shape.brep))
        gmsh.model.occ.synchronize()
        mesher._background(gmsh, mesher._groove_fields(gmsh, scene.shaft, scene.grooves, s_))
        s.option("Mesh.MeshSizeMax", s_.size)
        s.option("Mesh.MeshSizeMin", min(s_.edge_size, s_.size) * 0.5)
        s.option("Mesh.MeshSizeFromPoints", 0)
        s.option("Mesh.MeshSizeFromCurvature", 0)
        s.option("Mesh.MeshSizeExtendFromBoundary", 0)
        s.option("Mesh.Optimize", 1)
        gmsh.model.mesh.generate(3)
        gmsh.model.mesh.setOrder(3)
        for method in optimize:
            gmsh.model.mesh.optimize(method)
        etype = gmsh.model.mesh.getElementType("tetrahedron", 3)
        local = np.array(gmsh.model.mesh.getElementProperties(etype)[4]).reshape(-1, 3)
        _, enodes = gmsh.model.mesh.getElementsByType(etype)
        ntags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.full(int(ntags.max()) + 1, -1)
    index[ntags.astype(np.int64)] = np.arange(ntags.size)
    cells = index[np.asarray(enodes, dtype=np.int64)].reshape(-1, 20)
    points = coords.reshape(-1, 3)
    # gmsh's local nodes by barycentric coordinates; ours likewise, for each vertex order
    bary = lambda X: np.column_stack([1 - X.sum(axis=1), X])  # noqa: E731
    theirs, ours = bary(local), bary(cubic.doflocs)
    perm = np.argsort(cells[:, :4], axis=1)
    t = np.empty_like(cells)
    for key in {tuple(p) for p in perm}:
        rows = np.all(perm == key, axis=1)
        # our node k of the sorted cell has barycentrics ours[k] over the sorted vertices,
        # that is ours[k][inverse] over gmsh's vertex order
        inverse = np.argsort(key)
        mapped = ours[:, inverse]
        pick = [int(np.argmin(np.abs(theirs - m).sum(axis=1))) for m in mapped]
        assert len(set(pick)) == 20
        t[rows] = cells[rows][:, pick]
    # gmsh curves only the boundary; a curved face spanning a fillet can fold over an inner
    # vertex. The inner nodes follow the boundary's curving (harmonic, 1 / det J weighted);
    # elements that stay folded anywhere (vertices, edge thirds, face centres or inside:
    # min / max det J <= MIN_JACOBIAN_RATIO) are straightened, shared nodes too.
    from shaftfem.cad.mesh import MIN_JACOBIAN_RATIO

    def make(p):
        return MeshTet3(np.ascontiguousarray(p.T), np.ascontiguousarray(t.T))

    points = _curve_inside(make, points, t, lam=bary(cubic.doflocs), cubic=cubic)
    straightened = np.zeros(len(t), dtype=bool)
    for _ in range(10):
        bad = _jacobian_ratios(make(points), points, t, cubic) <= MIN_JACOBIAN_RATIO
        if not bad.any():
            return make(points), int(straightened.sum())
        points[t[bad, 4:]] = np.einsum("nk,ekd->end", bary(cubic.doflocs)[4:], points[t[bad, :4]])
        straightened |= bad
    raise RuntimeError("curved elements stay folded")


def _boundary_nodes(t: np.ndarray) -> np.ndarray:
    """The nodes on the faces of one cell only (cells (E, 20) in the cubic element's order)."""
    from shaftfem.cad.mesh import EDGES, FACES

    faces = np.concatenate([t[:, list(f)] for f in FACES])
    _, inverse, counts = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True,
                                   return_counts=True)
    local = [list(f) + [4 + 2 * k + j for k, e in enumerate(EDGES) if set(e) <= set(f)
                        for j in (0, 1)] + [16 + n] for n, f in enumerate(FACES)]
    nodes = np.concatenate([t[:, n] for n in local])
    return np.unique(nodes[counts[inverse.ravel()] == 1])


def _curve_inside(make, points, t, lam, cubic):
    """Inner edge and face nodes displaced from their straight positions by the harmonic
    extension of the boundary's displacement (fixed on the boundary and at the vertices)."""
    import scipy.sparse.linalg as sla
    from skfem import Basis, BilinearForm
    from skfem.helpers import dot, grad

    straight = points.copy()
    straight[t[:, 4:]] = np.einsum("nk,ekd->end", lam[4:], points[t[:, :4]])
    basis = Basis(make(straight), cubic(), intorder=4)
    dof = np.empty(points.shape[0], dtype=np.int64)
    dof[t.T] = basis.element_dofs
    w = 1.0 / np.abs(basis.mapping.detDF(basis.X))
    L = BilinearForm(lambda u, v, p: dot(grad(u), grad(v)) * p.w).assemble(basis, w=w)
    fixed = np.union1d(dof[_boundary_nodes(t)], basis.element_dofs[:4].ravel())
    free = np.setdiff1d(np.arange(basis.N), fixed)
    d = np.zeros((basis.N, 3))
    d[dof] = points - straight
    d[free] = sla.splu(L[free][:, free].tocsc()).solve(-(L[free][:, fixed] @ d[fixed]))
    return straight + d[dof]


def _jacobian_ratios(mesh, points, t, cubic) -> np.ndarray:
    """Per element min / max det J at its nodes, edge midpoints and centre, each element
    against its straight-sided self (ascending-vertex cells mix orientations)."""
    from shaftfem.cad.mesh import VERTICES

    X = np.vstack([cubic.doflocs, [(VERTICES[a] + VERTICES[b]) / 2 for a in range(4)
                                   for b in range(a + 1, 4)], VERTICES.mean(axis=0)])
    det = mesh._mapping().detDF(np.ascontiguousarray(X.T))
    v = points[t[:, :4]]
    sign = np.sign(np.einsum("ed,ed->e", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]),
                             v[:, 3] - v[:, 0]))
    det = sign[:, None] * det
    return det.min(axis=1) / np.abs(det).max(axis=1)


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


def one(sizes_mm: tuple, geometry: int, orders: tuple, optimize: tuple = ()) -> dict:
    import time
    from dataclasses import replace

    from skfem import Basis

    from shaftfem.cad.mesh import mesh_shape
    from shaftfem.cad.solid import build_shape
    from shaftfem.fem.elements import element
    from shaftfem.scene.load import load_scene

    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = load_scene("paper2018")
    scene = replace(scene, max_dofs=5_000_000,
                    mesh=replace(scene.mesh, size=s, groove_size=g, edge_size=e, order=3))
    shape = build_shape(scene.shaft, scene.grooves)
    t = time.perf_counter()
    if geometry == 3:
        mesh, straightened = _cubic_mesh(scene, shape, optimize)
    else:
        shaft_mesh = mesh_shape(shape, scene.shaft, scene.grooves, scene.mesh)
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
    optimize = tuple(m for m in flags.get("--optimize", "").split(",") if m)
    geometries = [int(g) for g in flags.get("--geometry", "2,3").split(",")]
    specs = [a for a in args if not a.startswith("--") and a not in flags.values()]
    print(f"gmsh's optimisers on the cubic mesh: {', '.join(optimize) or 'none'}\n")
    print("| sizes (mm) | geometry | elements | volume, mesh / solid - 1 | order | DOFs "
          "| largest true error | smallest true error | straightened elements | meshing (s) |\n"
          "|---|---|---|---|---|---|---|---|---|---|")
    for spec in specs or ["16/8/8", "12/6/3"]:
        mm = tuple(float(x) for x in spec.split("/"))
        for geometry in geometries:
            r = in_fresh_process(one, mm, geometry, (3, 4), optimize)
            for row in r["rows"]:
                print(f"| {spec} | {'quadratic' if geometry == 2 else 'cubic'} | "
                      f"{r['elements']} | {r['volume']:+.1e} | {row['order']} | {row['dofs']} | "
                      f"{100 * row['max']:.3f} % | {100 * row['min']:.3f} % | {r['straightened']} | "
                      f"{r['mesh_seconds']:.1f} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
