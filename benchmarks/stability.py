"""The stability cases as a table: rigid-body count, residuals, orthonormality, scaling laws.

    .venv/bin/python benchmarks/stability.py

The same cases are asserted in tests/test_stability.py; this prints the numbers.
"""

from dataclasses import replace

import numpy as np

from shaftfem.fem.assembly import assemble
from shaftfem.fem.modes import modal_analysis
from shaftfem.scene.load import scene_from_dict
from shaftfem.scene.model import Material
from shaftfem.workflows.pipeline import run_modes


def scene(length, diameter, size, nu=0.277, order=2, grooves=None):
    d = {"shaft": {"length_mm": length, "diameter_mm": diameter},
         "material": {"youngs_modulus_mpa": 211000.0, "poisson_ratio": nu, "density_kg_m3": 7870.0},
         "mesh": {"element_size_mm": size, "order": order, "max_dofs": 20_000_000}}
    if grooves:
        d["grooves"] = grooves
    return scene_from_dict(d, "stability")


def row(name, modes, law="", warn=""):
    print(f"| {name} | {modes.n_dofs} | {modes.n_rigid} | {modes.frequencies[0]:.2f} | "
          f"{modes.residuals.max():.1e} | {modes.backward_errors.max():.1e} | "
          f"{modes.orthonormality_error:.1e} | {law} | {warn} |", flush=True)


def main():
    print("| case | DOFs | rigid modes | f1 (Hz) | max residual | max backward error | "
          "max abs(X^T M X - I) | exact law, error | warning |")
    print("|---|---|---|---|---|---|---|---|---|")
    base = run_modes(scene(550, 32, 8))
    row("cylinder 32 x 550, P2 8 mm", base.modes)
    sk, m = base.mesh, base.scene.material
    for k in (1e6, 1e-6):
        s = assemble(sk, replace(m, youngs_modulus=m.youngs_modulus * k))
        md = modal_analysis(s)
        err = np.max(np.abs(md.frequencies / base.modes.frequencies / np.sqrt(k) - 1))
        row(f"E x {k:g}", md, f"f ~ sqrt(E): {err:.1e}")
    s = assemble(sk, replace(m, density=m.density * 1e3))
    md = modal_analysis(s)
    row("density x 1000", md, f"f ~ 1/sqrt(rho): "
        f"{np.max(np.abs(md.frequencies * np.sqrt(1e3) / base.modes.frequencies - 1)):.1e}")
    from shaftfem.cad.mesh import ShaftMesh

    mm = ShaftMesh(base.mesh.points * 1e3, base.mesh.cells, 2, 1.0, 0, 0.0)
    s = assemble(mm, Material("mm", m.youngs_modulus * 1e-6, m.poisson_ratio, m.density * 1e-12))
    md = modal_analysis(s)
    row("same shaft in mm, MPa, t/mm^3", md,
        f"same Hz: {np.max(np.abs(md.frequencies / base.modes.frequencies - 1)):.1e}")
    from tests_references import timoshenko_free_free_hz

    for nu in (0.0, 0.3, 0.45, 0.49, 0.499):
        ref = timoshenko_free_free_hz(1, 0.55, 0.016, 2.11e11, nu, 7870)[0]
        for order in (1, 2):
            r = run_modes(scene(550, 32, 8, nu=nu, order=order))
            row(f"nu = {nu:g}, P{order}", r.modes,
                f"bending 1 vs Timoshenko: {100 * (r.modes.frequencies[0] / ref - 1):+.2f} %",
                "; ".join(r.warnings))
    r = run_modes(scene(1000, 10, 5))
    slender = timoshenko_free_free_hz(1, 1.0, 0.005, 2.11e11, 0.277, 7870)[0]
    row("slender L/D = 100 (10 x 1000, 5 mm)", r.modes,
        f"vs Timoshenko: {100 * (r.modes.frequencies[0] / slender - 1):+.2f} %")
    r = run_modes(scene(32, 32, 4))
    row("stubby L/D = 1 (32 x 32, 4 mm)", r.modes)
    g = {"hands": ["right", "left"], "pitch_mm": 80.0, "width_mm": 8.0, "depth_mm": 6.4,
         "root_radius_mm": 1.0, "grooved_length_mm": 160.0}
    r = run_modes(scene(300, 32, 8, grooves=g))
    row("grooves 40 % of R deep", r.modes, f"groove volume: {r.shape.groove_volume_error:+.1e}")
    r = run_modes(scene(550, 32, 24))
    row("very coarse, 24 mm elements", r.modes, "", "; ".join(r.warnings))
    r = run_modes(scene(550, 32, 3))
    row("very fine, 3 mm elements", r.modes)


if __name__ == "__main__":
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    import references as tests_references

    sys.modules["tests_references"] = tests_references
    main()
