"""A much finer reference for the notches of a shaft of revolution: NGSolve at high order
on the axial half-section, with the load's variation round the axis taken exactly.

A shaft of revolution (a shoulder fillet, a relief groove) under tension or torsion
holds an axisymmetric field, and under bending one that varies as cos(theta): each is a
2D problem on the half-section (z, r), solved here on netgen's curved 2D mesh with H1
elements of order 4 to 7, elements of `notch_h_mm` on the notch's edges. The
half-section is the one `shaftfem.cad.outline` gives (lines and quarter arcs, in mm):
only the geometry is shared. As benchmarks/notch_reference.py, the left end is clamped,
the right end carries the pure traction that gives a unit nominal stress at the notch's
section (diameter `d_nom_mm`); K_t = sigma_vM,max / sigma_vM,nom read on 4,000 points of
the notch's edges (and 19 angles under bending).

Displacements per load, with the weak form's weight r (2 pi or pi cancels):
- tension: (u_z, u_r)(z, r);
- torsion: u_theta = V(z, r);
- bending: u_r = U cos(theta), u_theta = V sin(theta), u_z = W cos(theta), with
  P = U + V and W zero on the axis (the field's regularity there).

    .venv-ngsolve/bin/python benchmarks/axisymmetric_reference.py '{"pieces": [...],
        "load": "tension", "window_mm": [140, 160], "d_nom_mm": 32, "notch_h_mm": 0.15,
        "orders": [5, 6], "E_pa": 210e9, "nu": 0.3}'

Prints one JSON line per order: {"order", "dofs", "kt_vm", "kt_chart", "where_mm"}.
"""

import json
import math
import sys

import numpy as np
from netgen.geom2d import SplineGeometry
from ngsolve import H1, BilinearForm, GridFunction, LinearForm, Mesh, ds, dx, grad, y
from ngsolve import CoefficientFunction as CF

FAR_H = 6.0        # mm: the element size away from the notch


def section(pieces: list, window: tuple[float, float], notch_h: float) -> SplineGeometry:
    """The half-section in (z, r) mm, x = z and y = r: the axis (r = 0) named axis, the
    end faces fix (z = 0) and load, the edges inside the notch window notch."""
    pts = [tuple(p["a"]) for p in pieces]
    area = sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(pts, pts[1:] + pts[:1])) / 2
    left, right = (1, 0) if area > 0 else (0, 1)
    zmax = max(p[0] for p in pts)
    geo = SplineGeometry()
    ids = [geo.AppendPoint(*p) for p in pts]
    for i, p in enumerate(pieces):
        a, b = tuple(p["a"]), tuple(p["b"])
        j, k = ids[i], ids[(i + 1) % len(ids)]
        if abs(a[1]) < 1e-9 and abs(b[1]) < 1e-9:
            bc, h = "axis", FAR_H
        elif abs(a[0]) < 1e-9 and abs(b[0]) < 1e-9:
            bc, h = "fix", FAR_H
        elif abs(a[0] - zmax) < 1e-9 and abs(b[0] - zmax) < 1e-9:
            bc, h = "load", FAR_H
        elif min(a[0], b[0]) >= window[0] - 1e-9 and max(a[0], b[0]) <= window[1] + 1e-9:
            bc, h = "notch", notch_h
        else:
            bc, h = "mantle", FAR_H
        if p.get("centre") is None:
            geo.Append(["line", j, k], bc=bc, leftdomain=left, rightdomain=right, maxh=h)
        else:
            c = p["centre"]    # a quarter arc: its control point where its tangents meet
            m = geo.AppendPoint(a[0] + b[0] - c[0], a[1] + b[1] - c[1])
            geo.Append(["spline3", j, m, k], bc=bc, leftdomain=left, rightdomain=right,
                       maxh=h)
    return geo


def notch_points(pieces: list, window: tuple[float, float], n: int = 4000) -> np.ndarray:
    """Points on the outer edges inside the notch window, 1e-6 mm inside the solid (z, r
    in mm)."""
    out = []
    inside = [p for p in pieces if min(p["a"][0], p["b"][0]) < window[1]
              and max(p["a"][0], p["b"][0]) > window[0]
              and min(p["a"][1], p["b"][1]) > 1e-9]
    per = max(n // max(len(inside), 1), 50)
    for p in inside:
        a, b = np.array(p["a"]), np.array(p["b"])
        if p.get("centre") is None:
            t = np.linspace(0, 1, per)[:, None]
            q = a + t * (b - a)
            normal = np.array([b[1] - a[1], a[0] - b[0]]) / np.linalg.norm(b - a)
        else:
            c = np.array(p["centre"])
            t0, t1 = (math.atan2(*(v - c)[::-1]) for v in (a, b))
            if t1 - t0 > math.pi:
                t1 -= 2 * math.pi
            if t0 - t1 > math.pi:
                t1 += 2 * math.pi
            t = np.linspace(t0, t1, per)
            rho = np.linalg.norm(a - c)
            q = c + rho * np.column_stack([np.cos(t), np.sin(t)])
            normal = None
        for pt in q:
            if not window[0] <= pt[0] <= window[1]:
                continue
            nrm = normal if normal is not None else (pt - c) / rho
            for s in (1.0, -1.0):    # whichever side lies in the solid
                out.append(pt + s * 1e-6 * nrm)
    return np.array(out)


def von_mises(s: np.ndarray) -> np.ndarray:
    """s[..., 6] = rr, tt, zz, rt, tz, rz."""
    rr, tt, zz, rt, tz, rz = (s[..., i] for i in range(6))
    return np.sqrt(0.5 * ((rr - tt) ** 2 + (tt - zz) ** 2 + (zz - rr) ** 2)
                   + 3 * (rt ** 2 + tz ** 2 + rz ** 2))


def largest(s: np.ndarray, load: str) -> np.ndarray:
    """The chart's stress: the largest principal stress, or the largest shear (torsion)."""
    rr, tt, zz, rt, tz, rz = (s[..., i] for i in range(6))
    T = np.stack([np.stack([rr, rt, rz], -1), np.stack([rt, tt, tz], -1),
                  np.stack([rz, tz, zz], -1)], -2)
    w = np.linalg.eigvalsh(T)
    return (w[..., 2] - w[..., 0]) / 2 if load == "torsion" else w[..., 2]


def solve(mesh, load: str, p: int, d: float, R: float, mu: float, lam: float):
    """The number of DOFs, and the stress amplitudes (rr, tt, zz, rt, tz, rz) as a
    coefficient function: under bending the rr, tt, zz, rz ones are cos(theta)'s, rt and
    tz sin(theta)'s."""
    r = y
    c = (d / 2) ** 3 / R ** 4        # bending and torsion: a unit nominal stress at d
    # each load's space, strains of its components, and end traction times a test function
    if load == "tension":
        fes = H1(mesh, order=p, dirichlet="fix") * H1(mesh, order=p, dirichlet="fix|axis")

        def strain(w_z, w_r):
            return [grad(w_r)[1], w_r / r, grad(w_z)[0], 0, 0, grad(w_r)[0] + grad(w_z)[1]]

        def traction(w_z, w_r):
            return (d / 2 / R) ** 2 * w_z
    elif load == "torsion":
        fes = H1(mesh, order=p, dirichlet="fix|axis")

        def strain(v):
            return [0, 0, 0, grad(v)[1] - v / r, grad(v)[0], 0]

        def traction(v):
            return c * r * v
    else:
        P_ = H1(mesh, order=p, dirichlet="fix|axis")
        fes = P_ * H1(mesh, order=p, dirichlet="fix") * P_

        def strain(P, Q, W):
            gU, gV = (grad(P) + grad(Q)) / 2, (grad(P) - grad(Q)) / 2
            return [gU[1], P / r, grad(W)[0],
                    gV[1] - P / r, gV[0] - W / r, gU[0] + grad(W)[1]]

        def traction(P, Q, W):
            return c * r * W

    def stress(e):
        tr = e[0] + e[1] + e[2]
        return [2 * mu * e[0] + lam * tr, 2 * mu * e[1] + lam * tr,
                2 * mu * e[2] + lam * tr, mu * e[3], mu * e[4], mu * e[5]]

    def parts(w):
        return [w] if load == "torsion" else list(w)

    u, v = fes.TnT()
    ev = strain(*parts(v))
    a = BilinearForm(sum(si * fi for si, fi in zip(stress(strain(*parts(u))), ev)) * r
                     * dx).Assemble()
    f = LinearForm(traction(*parts(v)) * r * ds("load")).Assemble()
    g = GridFunction(fes)
    g.vec.data = a.mat.Inverse(fes.FreeDofs(), inverse="sparsecholesky") * f.vec
    return fes.ndof, CF(tuple(stress(strain(*([g] if load == "torsion" else g.components)))))


def main(cfg: dict) -> None:
    E, nu = cfg["E_pa"], cfg["nu"]
    mu, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))
    pieces = [{"a": [v * 1e3 for v in p["a"]], "b": [v * 1e3 for v in p["b"]],
               "centre": None if p.get("centre") is None else [v * 1e3 for v in p["centre"]]}
              for p in cfg["pieces"]]
    window = tuple(cfg["window_mm"])
    load, d = cfg["load"], cfg["d_nom_mm"]
    zmax = max(p["a"][0] for p in pieces)
    R = max(p["a"][1] for p in pieces if abs(p["a"][0] - zmax) < 1e-9)
    geo = section(pieces, window, cfg["notch_h_mm"])
    mesh = Mesh(geo.GenerateMesh(maxh=FAR_H))
    pts = notch_points(pieces, window)
    nominal = math.sqrt(3) if load == "torsion" else 1.0
    for p in cfg["orders"]:
        mesh.Curve(p)
        ndof, S = solve(mesh, load, p, d, R, mu, lam)
        vals, where = [], []
        for q in pts:
            try:
                mp = mesh(float(q[0]), float(q[1]))
                if mp.nr < 0:
                    continue
                vals.append(S(mp))
                where.append(q)
            except Exception:
                continue
        s = np.array(vals)
        if load == "bending":      # the stress at angle theta: cos parts and sin parts
            th = np.linspace(0, math.pi / 2, 19)[:, None, None]
            cs = np.array([1, 1, 1, 0, 0, 1.0])
            s = s[None] * (np.cos(th) * cs + np.sin(th) * (1 - cs))
        vm = von_mises(s)
        chart = largest(s, load)
        k = np.unravel_index(int(np.argmax(vm)), vm.shape)
        w = where[k[-1]]
        print(json.dumps({"order": p, "dofs": int(ndof), "points": len(where),
                          "kt_vm": float(vm.max() / nominal), "kt_chart": float(chart.max()),
                          "where_mm": [float(w[0]), float(w[1])]}), flush=True)


if __name__ == "__main__":
    main(json.loads(sys.argv[1]))
