"""The verification matrix's references: NGSolve at high order on a graded netgen mesh of
each case's STEP, free-free or held in its seats (the cases' inputs are
tests/data/verification/cases/CASE.json; this script runs in NGSolve's own venv, never
shaftfem's; benchmarks/verification.py --steps exports the profiles' STEP files).

    .venv-ngsolve/bin/python benchmarks/verification_reference.py \
        tests/data/verification/cases/CASE.json

A different discretisation of the same solid: netgen's own mesh, curved to the order, with
the faces inside the case's `feature_boxes_mm` (fillets, keyways, grooves, holes) meshed
at `feature_mm`, and geometric refinement (`hp_levels` layers, each HP_FACTOR times
the last) towards the case's sharp concave edges, where the stress is singular and raising
the order alone converges slowly. A seat holds the means of the displacement over its band
of surface (x and y; z too for a "rigid" seat), as exact constraints through Lagrange
multipliers: the mean of a continuous field, where shaftfem's seat reads the band's nodes
with lumped weights (that difference is discretisation, and shaftfem's bound must cover
it). The pencil is solved by shift-invert Lanczos through PARDISO; a seat's multipliers
make K indefinite and M singular on them, which shift-invert takes.

Writes tests/data/verification/CASE.json: the orders' DOFs, times and frequencies, the
highest order being the reference and the change from the order below it its own
convergence.
"""

import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from netgen.occ import Box, Glue, OCCGeometry, Pnt
from ngsolve import BilinearForm, Grad, InnerProduct, Mesh, NumberSpace, Sym, VectorH1, div, ds, dx

sys.path.insert(0, str(Path(__file__).parent))
from ngsolve_reference import csr, frequencies  # noqa: E402

HP_FACTOR = 0.2
ROOT = Path(__file__).resolve().parents[1]


def solid(case: dict):
    """The STEP's solid in m, cut at the seats' ends so that each band is a set of faces
    (its name "seat<i>"), small faces meshed at feature_mm."""
    shape = Glue(list(OCCGeometry(str(ROOT / case["step"])).shape.solids)).Scale(Pnt(0, 0, 0),
                                                                                   1e-3)
    radius = case["radius_mm"] * 1e-3
    cuts = sorted({z * 1e-3 for s in case["seats"] for z in (s["z0_mm"], s["z1_mm"])})
    if cuts:
        big = 4 * radius
        length = case["length_mm"] * 1e-3
        edges = [-big] + cuts + [length + big]
        shape = Glue([shape * Box(Pnt(-big, -big, a), Pnt(big, big, b))
                      for a, b in zip(edges, edges[1:])])
    feature = case["feature_mm"] * 1e-3
    for face in shape.faces:
        lo, hi = face.bounding_box
        # the face's reach from the axis, from its box (a ring's centre of mass is on it)
        reach = max(hi[0], hi[1], -lo[0], -lo[1])
        for z0, z1, r1 in case.get("feature_boxes_mm", []):
            if (z0 * 1e-3 - 1e-6 <= lo[2] and hi[2] <= z1 * 1e-3 + 1e-6
                    and reach <= r1 * 1e-3 + 1e-6):
                face.maxh = feature
        for i, s in enumerate(case["seats"]):
            r = s["radius_mm"] * 1e-3
            # a band of the cylinder r = R (its centre of mass lies on the axis)
            if (s["z0_mm"] * 1e-3 - 1e-6 <= lo[2] and hi[2] <= s["z1_mm"] * 1e-3 + 1e-6
                    and hi[2] - lo[2] > 1e-5 and abs(hi[0] - r) < 1e-5 and abs(lo[0] + r) < 1e-5
                    and abs(hi[1] - r) < 1e-5 and abs(lo[1] + r) < 1e-5):
                face.name = f"seat{i}"
    for edge in shape.edges:
        for z0, z1, rmax in case.get("sharp_edges", []):
            c = edge.center
            if z0 * 1e-3 <= c.z <= z1 * 1e-3 and math.hypot(c.x, c.y) < rmax * 1e-3:
                edge.hpref = 1
    return shape


def main() -> None:
    case = json.loads(Path(sys.argv[1]).read_text())
    E, nu, rho = case["youngs_modulus_mpa"] * 1e6, case["poisson_ratio"], case["density_kg_m3"]
    mu, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))
    t0 = time.perf_counter()
    geometry = solid(case)
    named = {f.name for f in geometry.faces}
    missing = [i for i in range(len(case["seats"])) if f"seat{i}" not in named]
    if missing:
        raise SystemExit(f"{case['name']}: no faces found for seat(s) {missing}")
    # curved high-order elements carry the fillets: little curvature-driven refinement
    mesh = Mesh(OCCGeometry(geometry).GenerateMesh(
        maxh=case["size_mm"] * 1e-3, curvaturesafety=0.7, segmentsperedge=0.3, grading=0.5))
    if case.get("hp_levels"):
        mesh.RefineHP(case["hp_levels"], factor=HP_FACTOR)
    print(f"{case['name']}: netgen {mesh.ne} elements in {time.perf_counter() - t0:.1f} s",
          flush=True)
    seats = case["seats"]
    rigid = 0 if seats else 6
    n = case["modes"]
    orders = []
    for p in case["orders"]:
        t = time.perf_counter()
        mesh.Curve(max(p, 2))
        V = VectorH1(mesh, order=p)
        held = [(i, c) for i, s in enumerate(seats) for c in range(3 if s["kind"] == "rigid" else 2)]
        fes = V
        for _ in held:
            fes = fes * NumberSpace(mesh)
        trial, test = fes.TnT()
        u, v = (trial[0], test[0]) if held else (trial, test)
        a = BilinearForm(fes)
        a += 2 * mu * InnerProduct(Sym(Grad(u)), Sym(Grad(v))) * dx + lam * div(u) * div(v) * dx
        for j, (i, c) in enumerate(held):
            band = mesh.Boundaries(f"seat{i}")
            a += (trial[1 + j] * v[c] + u[c] * test[1 + j]) * ds(definedon=band)
        m = BilinearForm(fes)
        m += rho * u * v * dx
        a.Assemble()
        m.Assemble()
        K, M = csr(a.mat), csr(m.mat)
        used = np.flatnonzero(abs(K).sum(axis=1).A1 != 0)   # hp leaves unused DOFs
        f = frequencies(K[used][:, used], M[used][:, used], n + rigid, case["shift_hz"],
                        definite=not held)
        if rigid and (np.max(f[:rigid]) > 1.0 or np.min(f[rigid:]) < 1.0):
            raise SystemExit(f"order {p}: expected {rigid} rigid-body modes, got {f[:8]}")
        orders.append({"order": p, "dofs": int(fes.ndof), "seconds": round(time.perf_counter() - t, 1),
                       "frequencies_hz": [float(v) for v in f[rigid:]]})
        print(f"order {p}: {fes.ndof} DOFs, {time.perf_counter() - t:.0f} s: "
              + " ".join(f"{v:.3f}" for v in f[rigid:]), flush=True)
        write(case, mesh, orders)


def write(case: dict, mesh, orders: list[dict]) -> None:
    """The orders so far (an order that does not fit in memory kills the process)."""
    out = ROOT / "tests" / "data" / "verification" / f"{case['name']}.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"case": case["name"], "program": "NGSolve "
                               + __import__("ngsolve").__version__, "elements": mesh.ne,
                               "feature_mm": case["feature_mm"], "size_mm": case["size_mm"],
                               "hp_levels": case.get("hp_levels", 0), "orders": orders},
                              indent=1) + "\n")


if __name__ == "__main__":
    main()
