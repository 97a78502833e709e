"""An independent torsion reference for a keyed shaft away from its keyway's ends:
Saint-Venant's torsion of the keyed cross-section, exact in 2D.

Far from a long keyway's ends the shaft is prismatic, and a torque there twists it as
Saint-Venant found: the warping psi solves Laplace's equation on the section with
d psi / d n = y n_x - x n_y on its boundary; the shear stresses are G theta (psi_x - y,
psi_y + x), the torque T = G theta int (x^2 + y^2 + x psi_y - y psi_x) dA. NGSolve at high
order on netgen's curved mesh of the section (a round bar d with a keyway of width b,
depth t from the top, its floor's corners rounded r), the edges of the keyway at h_mm.
K_t = tau_max / tau_nom, tau_nom = 16 T / (pi d^3) of the gross section (von Mises over
von Mises in pure shear: the same ratio, as benchmarks/notch_factors.py reads it).

    .venv-ngsolve/bin/python benchmarks/section_torsion_reference.py '{"d_mm": 32,
        "width_mm": 10, "depth_mm": 5, "corner_mm": 1, "h_mm": 0.1, "orders": [4, 6, 8]}'

Prints one JSON line per order: {"order", "dofs", "kt", "where_mm"}. Seconds.
`'{"ellipse_mm": [16, 8]}'` checks the solver instead on an ellipse of semi-axes a, b,
whose torsion is closed: J = pi a^3 b^3 / (a^2 + b^2), tau_max = 2 T / (pi a b^2).
"""

import json
import math
import sys

import numpy as np
from netgen.occ import Circle, OCCGeometry, WorkPlane
from ngsolve import (
    H1,
    BilinearForm,
    GridFunction,
    Integrate,
    IntegrationRule,
    LinearForm,
    Mesh,
    TaskManager,
    dx,
    grad,
    x,
    y,
)


def section(d: float, b: float, t: float, r: float, h: float):
    """The keyed section (mm): the circle d less the keyway, its two floor corners
    rounded r; the keyway's edges meshed at h."""
    R = d / 2
    floor = R - t
    top = R + 1.0
    wp = WorkPlane().MoveTo(-b / 2, top).Direction(0, -1)
    slot = (wp.Line(top - floor - r).Arc(r, 90).Line(b - 2 * r).Arc(r, 90)
            .Line(top - floor - r).Close().Face())
    face = Circle((0, 0), R).Face() - slot
    for e in face.edges:
        (x0, y0, _), (x1, y1, _) = e.bounding_box
        if min(y0, y1) >= floor - 1e-6 and max(abs(x0), abs(x1)) <= b / 2 + 1e-6:
            e.maxh = h
            e.name = "keyway"
    return OCCGeometry(face, dim=2)


def warping(mesh, p: int):
    """Saint-Venant's warping psi on the section's mesh at order p: its gradient's two
    components, the torque over G theta (the torsion constant J) and the DOFs."""
    fes = H1(mesh, order=p)
    u, v = fes.TnT()
    # the warping is fixed up to a constant: a small mass term pins its mean
    a = BilinearForm(grad(u) * grad(v) * dx + 1e-10 * u * v * dx).Assemble()
    # int (y n_x - x n_y) v ds as the area integral it is by the divergence theorem
    # ((y, -x) has none): no boundary normal (netgen's edges run either way round)
    f = LinearForm((y * grad(v)[0] - x * grad(v)[1]) * dx).Assemble()
    psi = GridFunction(fes)
    with TaskManager():
        psi.vec.data = a.mat.Inverse(fes.FreeDofs(), inverse="sparsecholesky") * f.vec
    gx, gy = grad(psi)[0], grad(psi)[1]
    return gx, gy, Integrate(x * x + y * y + x * gy - y * gx, mesh), fes.ndof


def ellipse(a: float, b: float) -> None:
    """The solver against the ellipse's closed form (mm)."""
    mesh = Mesh(OCCGeometry(WorkPlane().Ellipse(a, b).Face(), dim=2).GenerateMesh(maxh=1.0))
    mesh.Curve(6)
    gx, gy, J, _ = warping(mesh, 6)
    tip = mesh(0.0, b * (1 - 1e-6))
    tau = math.hypot(gx(tip) - b * (1 - 1e-6), gy(tip)) / J
    print(json.dumps({"J": J, "J_exact": math.pi * a**3 * b**3 / (a**2 + b**2),
                      "tau_per_T": tau, "tau_per_T_exact": 2 / (math.pi * a * b**2)}))


def main(cfg: dict) -> None:
    if "ellipse_mm" in cfg:
        ellipse(*cfg["ellipse_mm"])
        return
    d = cfg["d_mm"]
    geo = section(d, cfg["width_mm"], cfg["depth_mm"], cfg["corner_mm"], cfg["h_mm"])
    mesh = Mesh(geo.GenerateMesh(maxh=d / 8))
    for p in cfg["orders"]:
        mesh.Curve(p)
        gx, gy, torque, ndof = warping(mesh, p)
        # the warping lowers the torque below the polar moment's: J = I_p - int |grad psi|^2
        assert torque < math.pi * d**4 / 32, "the warping's sign"
        tau_nom = 16 * torque / (math.pi * d**3)
        # the shear stress on a dense grid along every keyway edge
        m = 200
        ir = IntegrationRule([(i / m,) for i in range(m + 1)], [0.0] * (m + 1))
        mips = mesh.MapToAllElements(ir, mesh.Boundaries("keyway"))
        tx = np.array((gx - y)(mips)).ravel()
        ty = np.array((gy + x)(mips)).ravel()
        tau = np.hypot(tx, ty)
        k = int(np.argmax(tau))
        where = [float(np.array(c(mips)).ravel()[k]) for c in (x, y)]
        print(json.dumps({"order": p, "dofs": ndof, "kt": float(tau[k] / tau_nom),
                          "where_mm": where}), flush=True)


if __name__ == "__main__":
    main(json.loads(sys.argv[1]))
