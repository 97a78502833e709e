"""Notch stresses you can trust: on notched shafts (shoulder fillets, relief grooves,
keyways, a radial hole) in bending, torsion and tension, `shaftfem strength`'s worst hot
spot, with its bound, against an independent reference on the same geometry, clamped at
one end and loaded by the pure traction at the other, so only the notch's K_t is shared:
- a shaft of revolution: NGSolve at orders 5 and 6 on the half-section, the load's
  variation round the axis exact (benchmarks/axisymmetric_reference.py; converged to
  1e-5 or better);
- any other: NGSolve at orders 3 and 4 on netgen's own curved 3D mesh of the STEP
  (benchmarks/notch_reference.py).
Prints, per shape, K_t as shaftfem gives it (von Mises peak over the nominal von Mises
stress of the notch's section), its bound, the reference's K_t at both orders, the
difference, whether the reference lies inside the bound's interval, and the chart's K_t
(largest principal or largest shear over nominal; a transverse hole in torsion: the
largest principal over tau_nom of the gross section) beside Peterson's where Pilkey's
fits cover the shape.

    .venv/bin/python benchmarks/notch_factors.py [--target 2] [--only "NAME;NAME"]

Needs .venv-ngsolve (see benchmarks/notch_reference.py). About 70 minutes on 2 cores.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _common  # noqa: E402, F401  (one BLAS thread, as the CLI)
from shaftfem.checks.notch_tables import shoulder_fillet  # noqa: E402

HERE = Path(__file__).parent
NGSOLVE = HERE.parent / ".venv-ngsolve" / "bin" / "python"
E, NU = 210e9, 0.3
STEEL = {"name": "42CrMo4", "youngs_modulus_mpa": E / 1e6, "poisson_ratio": NU,
         "density_kg_m3": 7850.0}
L = 300.0         # mm: every shape is 300 mm long, its notch about the middle
F, T, N = 10000.0 / 3, 200.0, 20000.0     # N (M = 100 N m), N m, N


def seats(axial: bool) -> list[dict]:
    """Seats at 10 and 290 mm, stiff enough to hold (1e9 N/mm); the right one locates."""
    right = {"name": "right", "position_mm": L - 10, "width_mm": 16.0, "kind": "springs",
             "radial_stiffness_n_per_mm": 1e9}
    if axial:
        right["axial_stiffness_n_per_mm"] = 1e9
    return [{"name": "left", "position_mm": 10.0, "width_mm": 16.0, "kind": "springs",
             "radial_stiffness_n_per_mm": 1e9}, right]


def duty(load: str) -> dict:
    """Bending by two couples (F up at 40 and 260 mm, down at 70 and 230: M = F 30 mm
    between 70 and 230 mm, whatever the seats do: the loads balance, so the seats carry
    nothing and where their reactions centre does not matter), a torque T from 40 to
    260 mm, or a tension N from 40 mm to the right seat."""
    if load == "bending":
        return {"force": [{"name": "a", "position_mm": 40.0, "fy_n": F},
                          {"name": "b", "position_mm": 70.0, "fy_n": -F},
                          {"name": "c", "position_mm": L - 70, "fy_n": -F},
                          {"name": "d", "position_mm": L - 40, "fy_n": F}]}
    if load == "torsion":
        return {"torque": [{"name": "in", "position_mm": 40.0, "torque_nm": T},
                           {"name": "out", "position_mm": L - 40}]}
    return {"force": [{"name": "pull", "position_mm": 40.0, "fz_n": -N}]}


def nominal_vm(load: str, d: float) -> float:
    """The nominal von Mises stress of the notch's section (diameter d, m), Pa."""
    if load == "bending":
        return F * 0.030 * 32 / (math.pi * d**3)
    if load == "torsion":
        return math.sqrt(3) * T * 16 / (math.pi * d**3)
    return N / (math.pi * d**2 / 4)


def shoulder(D: float, d: float, r: float) -> dict:
    """d on the left half, D on the right, a fillet r in the step's corner (mm)."""
    return {"section": [{"length_mm": L / 2, "diameter_mm": d, "fillet_mm": r},
                        {"length_mm": L / 2, "diameter_mm": D}],
            "mesh": {"element_size_mm": 8.0, "groove_element_size_mm": max(r / 2, 0.4),
                     "edge_element_size_mm": max(r / 2, 0.4)}}


def relief(D: float, d: float, r: float) -> dict:
    """A relief groove: diameter d over 2 r + 2 mm between two D sections, fillets r."""
    return {"section": [{"length_mm": L / 2 - r - 1, "diameter_mm": D, "fillet_mm": r},
                        {"length_mm": 2 * r + 2, "diameter_mm": d, "fillet_mm": r},
                        {"length_mm": L / 2 - r - 1, "diameter_mm": D}],
            "mesh": {"element_size_mm": 8.0, "groove_element_size_mm": max(r / 2, 0.4),
                     "edge_element_size_mm": max(r / 2, 0.4)}}


def keyed(d: float, length: float, width: float, depth: float, corner: float) -> dict:
    """A rounded (end-milled) keyway in a round bar, its centre at the top (+y), where
    bending about x stresses most."""
    return {"shaft": {"length_mm": L, "diameter_mm": d},
            "keyway": [{"position_mm": L / 2, "length_mm": length, "width_mm": width,
                        "depth_mm": depth, "angle_deg": 90.0, "corner_radius_mm": corner}],
            "mesh": {"element_size_mm": 8.0, "groove_element_size_mm": max(corner, 0.5),
                     "edge_element_size_mm": max(corner, 0.5)}}


def hole(D: float, d: float) -> dict:
    """A round bar D with a transverse hole d through its axis at mid-length (along y),
    brought as a STEP (built by `_hole_step`): no profile describes it."""
    return {"hole": {"diameter_mm": D, "hole_mm": d},
            "mesh": {"element_size_mm": 8.0, "groove_element_size_mm": d / 6,
                     "edge_element_size_mm": d / 6}}


def _hole_step(D: float, d: float, path: Path) -> None:
    """The STEP (mm) of `hole`, by gmsh's OpenCASCADE from two cylinders."""
    import gmsh

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        occ = gmsh.model.occ
        bar = occ.addCylinder(0, 0, 0, 0, 0, L, D / 2)
        drill = occ.addCylinder(0, -D, L / 2, 0, 2 * D, 0, d / 2)
        occ.cut([(3, bar)], [(3, drill)])
        occ.synchronize()
        gmsh.option.setString("Geometry.OCCTargetUnit", "MM")
        gmsh.write(str(path))
    finally:
        gmsh.finalize()


def pilkey_hole_torsion(D: float, d: float) -> float:
    """Peterson's transverse hole through a round bar in torsion, by Pilkey's fit (the
    tube's chart at d_i = 0; Pilkey & Pilkey, Peterson's Stress Concentration Factors,
    3rd ed.): the largest principal stress over the gross section's 16 T / (pi D^3)."""
    x = d / D
    return 4.0 - 6.055 * x + 32.764 * x**2 - 38.33 * x**3


def _chart(load: str):
    """Peterson's shoulder-fillet K_t under `load` (shaftfem.checks.notch_tables)."""
    return lambda D, d, r: shoulder_fillet(D, d, r, load)


pilkey_shoulder_bending = _chart("bending")
pilkey_shoulder_tension = _chart("tension")
pilkey_shoulder_torsion = _chart("torsion")


def _shoulder_case(D: float, d: float, r: float, load: str, chart) -> tuple:
    """A shoulder's row of SHAPES: its geometry, load, notch diameter, window, K_t chart."""
    return shoulder(D, d, r), load, d, (140, 160), chart(D, d, r)


# name: (the scene's geometry, load, the notch's section diameter (mm), the notch window
# (mm), Peterson's K_t by Pilkey's fit or None)
SHAPES = {
    "shoulder 48/32 r3, bending": _shoulder_case(48, 32, 3, "bending", pilkey_shoulder_bending),
    "shoulder 48/32 r3, tension": _shoulder_case(48, 32, 3, "tension", pilkey_shoulder_tension),
    "shoulder 48/32 r3, torsion": _shoulder_case(48, 32, 3, "torsion", pilkey_shoulder_torsion),
    "shoulder 40/32 r1.6, bending": _shoulder_case(40, 32, 1.6, "bending",
                                                   pilkey_shoulder_bending),
    "shoulder 40/32 r1.6, torsion": _shoulder_case(40, 32, 1.6, "torsion",
                                                   pilkey_shoulder_torsion),
    "shoulder 64/32 r5, bending": _shoulder_case(64, 32, 5, "bending", pilkey_shoulder_bending),
    "shoulder 64/32 r5, tension": _shoulder_case(64, 32, 5, "tension", pilkey_shoulder_tension),
    "shoulder 40/32 r3, bending": _shoulder_case(40, 32, 3, "bending", pilkey_shoulder_bending),
    "shoulder 40/32 r3, tension": _shoulder_case(40, 32, 3, "tension", pilkey_shoulder_tension),
    "shoulder 56/32 r2, bending": _shoulder_case(56, 32, 2, "bending", pilkey_shoulder_bending),
    "shoulder 56/32 r2, torsion": _shoulder_case(56, 32, 2, "torsion", pilkey_shoulder_torsion),
    "shoulder 56/32 r2, tension": _shoulder_case(56, 32, 2, "tension", pilkey_shoulder_tension),
    "shoulder 40/32 r3, torsion": _shoulder_case(40, 32, 3, "torsion", pilkey_shoulder_torsion),
    "shoulder 64/32 r5, torsion": _shoulder_case(64, 32, 5, "torsion", pilkey_shoulder_torsion),
    "relief groove 40/32 r4, bending": (relief(40, 32, 4), "bending", 32, (140, 160), None),
    "relief groove 40/32 r4, tension": (relief(40, 32, 4), "tension", 32, (140, 160), None),
    "relief groove 40/32 r2, torsion": (relief(40, 32, 2), "torsion", 32, (140, 160), None),
    # held out: shapes never used to set the bound's constants (run after they were set)
    "shoulder 44/36 r2.5, bending": _shoulder_case(44, 36, 2.5, "bending",
                                                   pilkey_shoulder_bending),
    "shoulder 44/36 r2.5, tension": _shoulder_case(44, 36, 2.5, "tension",
                                                   pilkey_shoulder_tension),
    "shoulder 50/40 r1.2, torsion": _shoulder_case(50, 40, 1.2, "torsion",
                                                   pilkey_shoulder_torsion),
    "shoulder 40/30 r4, tension": _shoulder_case(40, 30, 4, "tension", pilkey_shoulder_tension),
    "shoulder 60/40 r6, bending": _shoulder_case(60, 40, 6, "bending", pilkey_shoulder_bending),
    "relief groove 48/36 r3, bending": (relief(48, 36, 3), "bending", 36, (140, 160), None),
    "transverse hole 32/6, torsion": (hole(32, 6), "torsion", 32, (140, 160),
                                      pilkey_hole_torsion(32, 6)),
    "transverse hole 32/3.2, torsion": (hole(32, 3.2), "torsion", 32, (140, 160),
                                        pilkey_hole_torsion(32, 3.2)),
    "transverse hole 40/10, torsion": (hole(40, 10), "torsion", 40, (140, 160),
                                       pilkey_hole_torsion(40, 10)),
    "keyway 10x5 r1, bending": (keyed(32, 40, 10, 5, 1.0), "bending", 32, (125, 175), None),
    "keyway 10x5 r1, torsion": (keyed(32, 40, 10, 5, 1.0), "torsion", 32, (125, 175), None),
    "radial hole 8 deep 8 r1, torsion": (keyed(32, 8, 8, 8, 1.0), "torsion", 32, (140, 160),
                                         None),
}


def ours(name: str, target: float, folder: Path) -> dict:
    """shaftfem strength on the shape: its hot spot inside the notch window with the
    largest peak, as K_t with its bound; and the solid as a BREP (m) for the reference."""
    from shaftfem.cad.build import build_solid, write_solid
    from shaftfem.runtime import RunOptions
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.strength import run_strength

    geometry, load, d, window, _ = SHAPES[name]
    if "hole" in geometry:
        given = folder / "solid.step"
        _hole_step(geometry["hole"]["diameter_mm"], geometry["hole"]["hole_mm"], given)
        geometry = {"shaft": {"step_file": str(given)}, "mesh": geometry["mesh"]}
    scene = load_scene({"name": "notch", "material": STEEL, "static": {"gravity_m_s2": 0.0},
                        "support": seats(load == "tension"), **geometry, **duty(load),
                        "strength": {"target_error_percent": target}})
    from shaftfem.cad.outline import outline

    pieces = [{"a": list(p.a), "b": list(p.b),
               "centre": None if p.centre is None else list(p.centre)}
              for p in outline(scene.shaft)] if "section" in geometry else None
    step = folder / "solid.step"
    if "shaft" not in geometry or "step_file" not in geometry["shaft"]:
        brep = folder / "solid.brep"
        build_solid(scene.shaft, scene.grooves, brep)
        write_solid(brep, scene.shaft, [step])
    t = time.perf_counter()
    result = run_strength(scene, RunOptions())
    wall = time.perf_counter() - t
    inside = [s for s in result.spots if window[0] <= s.z * 1e3 <= window[1]]
    if not inside:
        return {"error": "no hot spot in the notch window", "wall": wall}
    s = max(inside, key=lambda s: s.peak)
    return {"kt": s.peak / nominal_vm(load, d * 1e-3), "bound": s.bound,
            "converging": s.converging, "feature": s.feature, "z_mm": s.z * 1e3,
            "dofs": list(result.dofs), "wall": wall, "step": str(step), "pieces": pieces}


def reference(name: str, step: str, notch_h: float, pieces: list | None) -> list[dict]:
    """The reference's K_t at two orders: on the half-section of a shaft of revolution
    (elements of a twentieth of the notch's size at orders 5 and 6), else on the 3D
    solid (orders 3 and 4)."""
    geometry, load, d, window, _ = SHAPES[name]
    if pieces is not None:
        cfg = {"pieces": pieces, "load": load, "window_mm": list(window), "d_nom_mm": d,
               "notch_h_mm": notch_h / 10, "orders": [5, 6], "E_pa": E, "nu": NU}
        script = "axisymmetric_reference.py"
    else:
        cfg = {"step": step, "load": load, "window_mm": list(window), "d_nom_mm": d,
               "h_mm": 16.0, "notch_h_mm": notch_h, "orders": [3, 4], "E_pa": E, "nu": NU,
               # netgen refines curved faces by their curvature: less so where the notch's
               # own size is already small (a keyway's 1 mm corners: order 4 within 24 GB)
               "curvature_safety": 2.0 if notch_h >= 1.5 else 1.0}
        if "keyway" in geometry:
            # a keyway's corners at half their radius, its ends' floor fillets (where
            # bending peaks) at a quarter, solved by CG (order 4: about 2 million DOFs,
            # 20 GB; torsion's peak along the sides reads the same at order 4 on 0.5 and
            # 0.35 mm to 0.01 %)
            k = geometry["keyway"][0]
            r, b, floor = k["corner_radius_mm"], k["width_mm"], d / 2 - k["depth_mm"]
            ends = (k["position_mm"] - k["length_mm"] / 2, k["position_mm"] + k["length_mm"] / 2)
            boxes = [[[-b / 2 - 1, floor - 0.1, lo], [b / 2 + 1, floor + r + 0.8, hi]]
                     for lo, hi in ((ends[0] - 1, ends[0] + b / 2 + 0.1),
                                    (ends[1] - b / 2 - 0.1, ends[1] + 1))]
            cfg.update(notch_h_mm=r / 2, iterative=True, fine={"h_mm": r / 4, "boxes_mm": boxes})
        script = "notch_reference.py"
    run = subprocess.run([str(NGSOLVE), str(HERE / script), json.dumps(cfg)],
                         capture_output=True, text=True, timeout=3600)
    if run.returncode != 0:
        raise RuntimeError(run.stderr[-2000:])
    return [json.loads(line) for line in run.stdout.splitlines() if line.startswith("{")]


def main(argv: list[str]) -> int:
    from _common import options

    opts, _ = options(argv, {"--target": "2", "--only": ""})
    names = [n for n in SHAPES if not opts["--only"] or n in opts["--only"].split(";")]
    if not NGSOLVE.exists():
        print(f"notch_factors.py: {NGSOLVE} is missing (see benchmarks/notch_reference.py)",
              file=sys.stderr)
        return 2
    print(f"target {opts['--target']} %; K_t = sigma_vM,max / sigma_vM,nom; reference: "
          "NGSolve, orders 5 / 6 on the half-section (a shaft of revolution), else orders "
          "3 / 4 on netgen's curved 3D mesh\n")
    print("| shape | shaftfem K_t | its bound | reference, lower order | higher order | "
          "shaftfem - higher "
          "| inside the bound | chart K_t | Peterson (Pilkey) | DOFs | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    held = 0
    for name in names:
        with tempfile.TemporaryDirectory() as d:
            o = ours(name, float(opts["--target"]), Path(d))
            if "error" in o:
                print(f"| {name} | {o['error']} |")
                continue
            ref = reference(name, o["step"], SHAPES[name][0]["mesh"]["groove_element_size_mm"],
                            o["pieces"])
        p3, p4 = ref[0], ref[-1]
        diff = o["kt"] / p4["kt_vm"] - 1
        ok = o["bound"] is not None and o["converging"] and abs(diff) <= o["bound"]
        held += ok
        peterson = SHAPES[name][4]
        chart = p4["kt_principal"] if "hole" in SHAPES[name][0] else p4["kt_chart"]
        bound = "unknown" if o["bound"] is None else f"{o['bound']:.2%}"
        print(f"| {name} | {o['kt']:.4f} | {bound} | {p3['kt_vm']:.4f} | {p4['kt_vm']:.4f} "
              f"| {diff:+.2%} | {'yes' if ok else 'NO'} | {chart:.3f} | "
              f"{'' if peterson is None else f'{peterson:.3f}'} | "
              f"{o['dofs'][-1]:,} | {o['wall']:.0f} |", flush=True)
    print(f"\nthe reference inside shaftfem's bound on {held} of {len(names)} shapes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
