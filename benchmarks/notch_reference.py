"""An independent stress concentration factor: NGSolve at high order on the same solid.

The solid (a STEP in mm, as shaftfem writes it) is clamped at its left end face (z = 0)
and loaded on its right end face by the traction of pure bending about x (t_z
proportional to y), of torsion (t tangential, proportional to r) or of tension (t_z
uniform). Far from both ends that is the beam's state, so the notch's stress over the
nominal stress of its section (diameter D_NOM) is K_t, whatever the supports: the
number shaftfem's own run (bands, seats) must give too. netgen meshes the solid (its
own mesher, curved elements of the order solved) with the faces inside the notch window
at NOTCH_H; NGSolve's H1 elements of order 2, 3, 4 ... on it; MKL PARDISO solves.
K_t is read on a dense grid of points on every notch face (60 a triangle), as von Mises
(sigma_vM,max / sigma_vM,nom) and as the chart's: the largest principal stress over
sigma_nom (bending, tension), the largest shear (sigma_1 - sigma_3) / 2 over tau_nom
(torsion).

NGSolve is a benchmark tool, never a runtime need; it lives in a venv of its own:

    python3 -m venv .venv-ngsolve
    .venv-ngsolve/bin/pip install ngsolve scipy pypardiso
    .venv-ngsolve/bin/python benchmarks/notch_reference.py '{"step": "solid.step",
        "load": "bending", "window_mm": [140, 160], "d_nom_mm": 32, "h_mm": 8,
        "notch_h_mm": 0.6, "orders": [3, 4], "E_pa": 210e9, "nu": 0.3}'

Prints one JSON line per order: {"order", "dofs", "kt_vm", "kt_chart", "kt_principal",
"where_mm"} (kt_principal: the largest principal stress over the nominal stress, in
torsion over tau_nom: a transverse hole's chart).
benchmarks/notch_factors.py runs it for each of its shapes.
"""

import json
import math
import sys

import numpy as np
from netgen.occ import OCCGeometry
from ngsolve import (
    CF,
    BilinearForm,
    BoundaryFromVolumeCF,
    CGSolver,
    GridFunction,
    Id,
    InnerProduct,
    IntegrationRule,
    LinearForm,
    Mesh,
    Preconditioner,
    Sym,
    Trace,
    VectorH1,
    ds,
    dx,
    x,
    y,
    z,
)
from ngsolve import Grad as grad

from ngsolve_reference import csr  # NGSolve's matrix as SciPy's

POINTS_PER_SIDE = 10   # a triangle's sample grid: (n + 1)(n + 2) / 2 points


def solid(step: str, window: tuple[float, float], notch_h: float, h: float,
          fine: dict | None = None):
    """The solid with its end faces named fix (z = 0) and load (the other end), the faces
    inside the notch window named notch and meshed at notch_h, and so are the edges inside
    it (a hole's mouth, whose mantle face reaches beyond the window); the faces and edges
    inside any of fine's boxes_mm (each [[x, y, z], [x, y, z]]) at its h_mm (where a
    notch's peak lies on a small face: a keyway end's floor fillet)."""
    geo = OCCGeometry(step)
    shape = geo.shape
    zs = [f.bounding_box for f in shape.faces]
    zmax = max(b[1][2] for b in zs)
    for f, (lo, hi) in zip(shape.faces, zs):
        if hi[2] < 1e-6:
            f.name = "fix"
        elif lo[2] > zmax - 1e-6:
            f.name = "load"
        elif lo[2] >= window[0] - 1e-6 and hi[2] <= window[1] + 1e-6:
            f.name = "notch"
            f.maxh = notch_h
        else:
            f.name = "mantle"
    for e in shape.edges:
        lo, hi = e.bounding_box
        if lo[2] >= window[0] - 1e-6 and hi[2] <= window[1] + 1e-6:
            e.maxh = notch_h
    for box in (np.array(b) for b in (fine or {}).get("boxes_mm", [])):
        for item in list(shape.faces) + list(shape.edges):
            lo, hi = (np.array([c[0], c[1], c[2]]) for c in item.bounding_box)
            if np.all(lo >= box[0] - 1e-6) and np.all(hi <= box[1] + 1e-6):
                item.maxh = fine["h_mm"]
    return OCCGeometry(shape), zmax


def end_radius(mesh, region: str) -> float:
    """The end face's outer radius (m), from its mesh's vertices."""
    pts = np.array([v.point for e in mesh.Boundaries(region).Elements() for v in
                    (mesh[vv] for vv in e.vertices)])
    return float(np.hypot(pts[:, 0], pts[:, 1]).max())


def main(cfg: dict) -> None:
    import pypardiso

    E, nu = cfg["E_pa"], cfg["nu"]
    mu, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))
    # in mm throughout (netgen's tolerances are made for it); K_t is a ratio
    geo, _ = solid(cfg["step"], tuple(cfg["window_mm"]), cfg["notch_h_mm"], cfg["h_mm"],
                   cfg.get("fine"))
    d = cfg["d_nom_mm"]
    for p in cfg["orders"]:
        mesh = Mesh(geo.GenerateMesh(maxh=cfg["h_mm"],
                                     curvaturesafety=cfg.get("curvature_safety", 2.0)))
        mesh.Curve(p)
        R = end_radius(mesh, "load")
        # tractions with a unit nominal stress at the notch's section (diameter d)
        # (d / 2)^3 / R^4 is M / I_R and T / J_R for a unit nominal stress at d
        c = (d / 2) ** 3 / R ** 4
        if cfg["load"] == "bending":
            t, nominal_vm = CF((0, 0, c * y)), 1.0
        elif cfg["load"] == "torsion":
            t, nominal_vm = CF((-c * y, c * x, 0)), math.sqrt(3)
        else:
            t, nominal_vm = CF((0, 0, (d / 2 / R) ** 2)), 1.0
        fes = VectorH1(mesh, order=p, dirichlet="fix")
        u, v = fes.TnT()

        def stress(w):
            e = Sym(grad(w))
            return 2 * mu * e + lam * Trace(e) * Id(3)

        free = np.array(list(fes.FreeDofs()), dtype=bool)
        gfu = GridFunction(fes)
        if cfg.get("iterative"):
            # CG with NGSolve's BDDC on the statically condensed system: memory grows
            # with the element count, not the factor's fill, so orders 5 and 6 fit
            a = BilinearForm(InnerProduct(stress(u), Sym(grad(v))) * dx, condense=True)
            pre = Preconditioner(a, "bddc")
            a.Assemble()
            f = LinearForm(t * v * ds("load")).Assemble()
            inv = CGSolver(a.mat, pre.mat, tol=1e-11, maxiter=5000)
            f.vec.data += a.harmonic_extension_trans * f.vec
            gfu.vec.data = inv * f.vec
            gfu.vec.data += a.harmonic_extension * gfu.vec
            gfu.vec.data += a.inner_solve * f.vec
            print(f"# order {p}: CG {inv.GetSteps()} steps", file=sys.stderr, flush=True)
        else:
            a = BilinearForm(InnerProduct(stress(u), Sym(grad(v))) * dx).Assemble()
            f = LinearForm(t * v * ds("load")).Assemble()
            K = csr(a.mat)[free][:, free]
            sol = np.zeros(fes.ndof)
            sol[free] = pypardiso.spsolve(K.tocsr(), np.array(f.vec)[free])
            gfu.vec.FV().NumPy()[:] = sol
        S = BoundaryFromVolumeCF(stress(gfu))
        n = POINTS_PER_SIDE
        ir = IntegrationRule([(i / n, j / n) for i in range(n + 1) for j in range(n + 1 - i)],
                             [0.0] * ((n + 1) * (n + 2) // 2))
        mips = mesh.MapToAllElements(ir, mesh.Boundaries("notch"))
        tensors = np.array(S(mips)).reshape(-1, 3, 3)
        where = np.column_stack([np.array(c(mips)).ravel() for c in (x, y, z)])
        w = np.linalg.eigvalsh(tensors)
        vm = np.sqrt(0.5 * ((w[:, 0] - w[:, 1]) ** 2 + (w[:, 1] - w[:, 2]) ** 2
                            + (w[:, 2] - w[:, 0]) ** 2))
        chart = (w[:, 2] - w[:, 0]) / 2 if cfg["load"] == "torsion" else w[:, 2]
        k = int(np.argmax(vm))
        print(json.dumps({"order": p, "dofs": int(free.sum()),
                          "kt_vm": float(vm[k] / nominal_vm), "kt_chart": float(chart.max()),
                          # a hole's chart in torsion: the largest principal over tau_nom
                          "kt_principal": float(w[:, 2].max()),
                          "where_mm": [float(c) for c in where[k]]}), flush=True)


if __name__ == "__main__":
    main(json.loads(sys.argv[1]))
