"""shaftfem's hierarchical elements against NGSolve's on the same curved mesh, and both
against NGSolve on its own mesh of the same STEP, in one run.

    .venv/bin/python benchmarks/ngsolve_same_mesh.py [SIZES:ORDERS ...] [--own S/G:P:SAFETY]

SIZES is away/grooves/floor edges in mm, ORDERS a comma list (default 16/8/8:3,4). For
each, a fresh shaftfem process meshes the paper's shaft (solid cached) and solves each
order (a warm `run_modes` without the bound: assembly, factorisation, eigensolve). The
same quadratic mesh, node for node, then goes to NGSolve in a fresh process of the
NGSolve venv: the straight tetrahedra as a netgen mesh, curved by a quadratic
deformation that puts every edge's midpoint where gmsh put its node, so both codes map
the same reference elements the same way. NGSolve's H1 space of order p on it spans the
same functions as shaftfem's hierarchical order p (different bases), so the frequencies
must agree up to the two codes' quadrature: that checks the elements. The assembly times
compare the two codes' element kernels on the same DOFs. The eigensolves both factorise
with MKL PARDISO, but differ in their Lanczos settings (shaftfem's inertia proof and
refinement; benchmarks/ngsolve_reference.py's pypardiso at tolerance 1e-12), so their
ratio is that of two solver set-ups, not of the discretisations.

`--own` also runs NGSolve on its own curved mesh of the exported STEP (maxh S mm, groove
faces G mm, order P, netgen curvature safety SAFETY; benchmarks/ngsolve_reference.py),
timed from the STEP file to the frequencies, for the time-to-accuracy comparison. True
errors are against the NGSolve order-4 reference of docs/verification.md.

The NGSolve venv (a benchmark tool, never a runtime need; NGSOLVE_PYTHON names another):

    python3 -m venv .venv-ngsolve
    .venv-ngsolve/bin/pip install ngsolve scipy pypardiso
"""

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).parent
NGSOLVE_PYTHON = os.environ.get("NGSOLVE_PYTHON", str(HERE.parent / ".venv-ngsolve/bin/python"))
# VTK's quadratic tetrahedron: the edge of each midside node (cells[:, 4:])
EDGES = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]


# --- the shaftfem side (the project's venv) ---------------------------------------------

def ours(sizes_mm: tuple, orders: list, out: str, bonus: int) -> list:
    """Solve the paper's shaft on one mesh at each order, its quadrature orders raised by
    `bonus`; write the mesh to `out`."""
    from dataclasses import replace

    import numpy as np

    from shaftfem.fem import assembly

    for rule in (assembly.STIFFNESS_INTORDER, assembly.MASS_INTORDER):
        for p in rule:
            rule[p] = min(rule[p] + bonus, 8)   # scikit-fem's tetrahedral rules end at 8
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes

    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = load_scene("paper2018")
    scene = replace(scene, max_dofs=2_000_000,
                    mesh=replace(scene.mesh, size=s, groove_size=g, edge_size=e))
    first = run_modes(replace(scene, mesh=replace(scene.mesh, order=2)))  # solid, mesh cached
    np.savez(out, points=first.mesh.points, cells=first.mesh.cells)
    rows = []
    for p in orders:
        t = time.perf_counter()
        r = run_modes(replace(scene, mesh=replace(scene.mesh, order=p)))
        wall = time.perf_counter() - t
        rows.append({"order": p, "dofs": r.modes.n_dofs, "wall": wall,
                     "assembly": r.timings.assembly,
                     "solve": r.timings.solve, "f": list(map(float, r.modes.frequencies))})
    return rows


def ours_to_accuracy(sizes_mm: tuple, order: int, geometry_order: int = 2) -> dict:
    """A whole `run_modes` of the paper's shaft from its cached solid: mesh (not
    cached; curved to `geometry_order`), assembly, factorisation, eigensolve; no bound,
    and nothing from an earlier solve (no shift, no kept shapes): a repeat starts as cold
    as the first."""
    from dataclasses import replace

    from _common import peak_mb
    from shaftfem.runtime import RunOptions
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows import stages
    from shaftfem.workflows.pipeline import Stopwatch, solve_mesh

    s, g, e = (x * 1e-3 for x in sizes_mm)
    scene = load_scene("paper2018")
    scene = replace(scene, max_dofs=2_000_000, mesh=replace(
        scene.mesh, size=s, groove_size=g, edge_size=e, order=order,
        geometry_order=geometry_order))
    shape = stages.solid(scene)[1]
    t = time.perf_counter()
    mesh = stages.mesh(shape, scene.shaft, scene.grooves, scene.mesh, use_cache=False)
    r = solve_mesh(scene, shape, mesh, RunOptions(use_cache=False), Stopwatch())
    return {"dofs": r.modes.n_dofs, "wall": time.perf_counter() - t,
            "f": list(map(float, r.modes.frequencies)), "peak": peak_mb()}


def ngsolve_own_mesh(step: str, spec: str) -> dict:
    """NGSolve on its own mesh of `step` (benchmarks/ngsolve_reference.py), timed from
    the file to the frequencies in a fresh process of the NGSolve venv."""
    from _common import run_measured

    sizes, order, safety = spec.split(":")
    away, groove = sizes.split("/")
    done = run_measured([NGSOLVE_PYTHON, str(HERE / "ngsolve_reference.py"), step, away,
                         groove, order], env={**os.environ, "NETGEN_CURVATURESAFETY": safety})
    if done["returncode"]:
        raise SystemExit(done["stderr"][-3000:])
    row = [x.strip() for x in done["stdout"].strip().splitlines()[-1].strip("|").split("|")]
    tets = done["stdout"].split("netgen: ")[1].split(" elements")[0]
    return {"dofs": int(row[1]), "wall": done["wall"], "f": [float(x) for x in row[3:]],
            "tets": int(tets), "peak": done["peak"]}


# --- the NGSolve side (the NGSolve venv) ------------------------------------------------

def ngsolve_same_mesh(mesh_file: str, orders: list, bonus: int) -> list:
    import numpy as np
    import scipy.sparse as sp
    from netgen.meshing import Element3D, MeshPoint, Pnt
    from netgen.meshing import Mesh as NetgenMesh
    from ngsolve import (
        EDGE,
        H1,
        BilinearForm,
        Grad,
        GridFunction,
        InnerProduct,
        Mesh,
        NodeId,
        Sym,
        VectorH1,
        div,
        dx,
    )

    sys.path.insert(0, str(HERE))
    from ngsolve_reference import NU, RHO, E, frequencies

    z = np.load(mesh_file)
    points, cells = z["points"], z["cells"]
    t0 = time.perf_counter()
    used = np.unique(cells[:, :4])
    number = np.full(points.shape[0], -1)
    number[used] = np.arange(used.size)
    ngm = NetgenMesh(dim=3)
    ids = [ngm.Add(MeshPoint(Pnt(*map(float, points[v])))) for v in used]
    ngm.SetMaterial(1, "shaft")
    for c in number[cells[:, :4]]:
        ngm.Add(Element3D(1, [ids[i] for i in c]))
    mesh = Mesh(ngm)
    # the quadratic map: on each edge, the offset of gmsh's midside node from the
    # straight edge's midpoint, through the order-2 edge function (scaled by its value
    # at the midpoint, measured on one edge)
    offset = {}
    for c in cells:
        for k, (a, b) in enumerate(EDGES):
            key = (min(number[c[a]], number[c[b]]), max(number[c[a]], number[c[b]]))
            offset[key] = points[c[4 + k]] - 0.5 * (points[c[a]] + points[c[b]])
    scalar = H1(mesh, order=2)
    probe = GridFunction(scalar)
    edge0 = next(iter(mesh.edges))
    probe.vec[:] = 0
    probe.vec[scalar.GetDofNrs(NodeId(EDGE, edge0.nr))[0]] = 1.0
    va, vb = (np.array(mesh.vertices[v.nr].point) for v in edge0.vertices)
    mid = 0.5 * (va + vb)
    scale = probe(mesh(*mid))
    shift = H1(mesh, order=2, dim=3)
    deform = GridFunction(shift)
    values = np.zeros((shift.ndof, 3))
    for edge in mesh.edges:
        a, b = (v.nr for v in edge.vertices)
        d = shift.GetDofNrs(NodeId(EDGE, edge.nr))[0]
        values[d] = offset[(min(a, b), max(a, b))] / scale
    deform.vec.FV().NumPy()[:] = values.ravel()
    mesh.SetDeformation(deform)
    build = time.perf_counter() - t0
    mu, lam = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
    rows = []
    for p in orders:
        t = time.perf_counter()
        fes = VectorH1(mesh, order=p)
        u, v = fes.TnT()
        rule = dx(bonus_intorder=bonus)
        a = BilinearForm(2 * mu * InnerProduct(Sym(Grad(u)), Sym(Grad(v))) * rule
                         + lam * div(u) * div(v) * rule)
        m = BilinearForm(RHO * u * v * rule)
        a.Assemble()
        m.Assemble()
        assembly = time.perf_counter() - t
        # the hand-over to SciPy (CSR arrays, no copy of the pattern) is not timed
        K, M = (sp.csr_matrix(tuple(map(np.asarray, x.mat.CSR())), shape=(fes.ndof, fes.ndof))
                for x in (a, m))
        t_solve = time.perf_counter()
        f = frequencies(K, M)
        solve = time.perf_counter() - t_solve
        rows.append({"order": p, "dofs": fes.ndof, "wall": assembly + solve, "build": build,
                     "assembly": assembly, "solve": solve, "f": list(map(float, f[6:])),
                     "rigid": float(np.max(f[:6])), "midpoint": float(scale)})
    return rows


def same_mesh(sizes_mm: tuple, orders: list, bonus: int) -> tuple[list, list]:
    """shaftfem's rows and NGSolve's on one mesh of the paper's shaft at `sizes_mm`, each
    code in a fresh process of its own venv."""
    from _common import in_fresh_process

    with tempfile.TemporaryDirectory() as tmp:
        mesh_file = f"{tmp}/mesh.npz"
        mine = in_fresh_process(ours, sizes_mm, orders, mesh_file, bonus)
        done = subprocess.run([NGSOLVE_PYTHON, __file__, "--ngsolve-side", mesh_file,
                               ",".join(map(str, orders)), str(bonus)],
                              capture_output=True, text=True, check=False)
        if done.returncode:
            raise SystemExit(done.stderr[-3000:])
        return mine, json.loads(done.stdout.strip().splitlines()[-1])


def step_file() -> Path:
    """The paper's shaft as STEP (out/solid/shaft.step), exported if missing."""
    step = HERE.parent / "out" / "solid" / "shaft.step"
    if not step.exists():
        subprocess.run([sys.executable, "-m", "shaftfem", "export", "--out",
                        str(step.parent)], check=True, capture_output=True)
    return step


def main(args: list[str]) -> None:
    if args and args[0] == "--ngsolve-side":
        print(json.dumps(ngsolve_same_mesh(args[1], [int(p) for p in args[2].split(",")],
                                           int(args[3]))))
        return
    sys.path.insert(0, str(HERE))
    from _common import in_fresh_process, machine

    own = [b for a, b in zip(args, args[1:]) if a == "--own"]
    mine = [b for a, b in zip(args, args[1:]) if a == "--ours"]
    flagged = set(own) | set(mine)
    specs = [a for a in args if not a.startswith("--") and a not in flagged]
    if not (specs or own or mine):
        specs = ["16/8/8:3,4"]
    bonus = int(os.environ.get("QUADRATURE_BONUS", "0"))
    print(f"machine: {machine()}; paper2018; quadrature orders raised by {bonus}\n")
    if own or mine:
        print("| code | discretisation | DOFs | wall (s) | largest true error |\n|---|---|---|---|---|")
        for spec in own:
            r = ngsolve_own_mesh(str(step_file()), spec)
            print(f"| NGSolve | its own mesh {spec} ({r['tets']} tetrahedra) | {r['dofs']} | "
                  f"{r['wall']:.1f} | {100 * error(r['f']):.3f} % |", flush=True)
        for spec in mine:
            sizes, order = spec.split(":")
            r = in_fresh_process(ours_to_accuracy, tuple(float(x) for x in sizes.split("/")),
                                 int(order))
            print(f"| shaftfem | {sizes} mm, order {order} | {r['dofs']} | {r['wall']:.1f} | "
                  f"{100 * error(r['f']):.3f} % |", flush=True)
        print()
    if specs:
        print("| sizes (mm) | code | order | DOFs | assembly (s) | eigensolve (s) | wall (s) "
              "| largest true error | largest difference from the other code |\n"
              "|---|---|---|---|---|---|---|---|---|")
    for spec in specs:
        sizes, orders = spec.split(":")
        mine_rows, theirs = same_mesh(tuple(float(x) for x in sizes.split("/")),
                                      [int(p) for p in orders.split(",")], bonus)
        for a, b in zip(mine_rows, theirs):
            diff = max(abs(x / y - 1) for x, y in zip(a["f"], b["f"]))
            for who, r in (("shaftfem", a), ("NGSolve", b)):
                print(f"| {sizes} | {who} | {r['order']} | {r['dofs']} | {r['assembly']:.1f} | "
                      f"{r['solve']:.1f} | {r['wall']:.1f} | {100 * error(r['f']):.3f} % | "
                      f"{diff:.1e} |", flush=True)


def error(f: list) -> float:
    """The largest relative difference from the reference (_common's: imported here, as
    this script's NGSolve side runs without shaftfem)."""
    from _common import PAPER_REFERENCE_HZ

    return max(abs(x / y - 1) for x, y in zip(f, PAPER_REFERENCE_HZ))


if __name__ == "__main__":
    main(sys.argv[1:])
