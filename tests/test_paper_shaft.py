"""The paper's grooved double-helix shaft (geometry/paper2018.toml)."""

import json

import numpy as np

from shaftfem.cad.profile import groove_volume
from shaftfem.cli import main


def test_exactly_six_rigid_body_modes(paper):
    assert paper.modes.n_rigid == 6


def test_mass_orthonormal_shapes_and_small_residuals(paper):
    X, M, K = paper.modes.shapes, paper.system.M, paper.system.K
    assert np.max(np.abs(X.T @ (M @ X) - np.eye(10))) < 1e-8
    w2 = (2 * np.pi * paper.modes.frequencies) ** 2
    res = np.linalg.norm(K @ X - (M @ X) * w2, axis=0) / np.linalg.norm(K @ X, axis=0)
    assert np.all(res < 1e-8)


def test_groove_volume_within_one_percent_of_analytic(paper):
    shape, scene = paper.shape, paper.scene
    R, L = scene.shaft.radius, scene.shaft.length
    removed = np.pi * R**2 * L - shape.volume
    assert abs(removed / groove_volume(scene.grooves, R) - 1) < 0.01


def test_groove_volume_integral_against_hand_formula():
    """Rectangular grooves: one groove removes L_g * (phi/2) (R^2 - (R-d)^2)."""
    from shaftfem.scene.model import Grooves

    g = Grooves(hands=(1,), pitch=0.08, width=0.008, depth=0.003, root_radius=0.0,
                length=0.36, start=0.0)
    R = 0.016
    phi = 2 * np.pi * g.width / g.pitch
    exact = g.length * phi / 2 * (R**2 - (R - g.depth) ** 2)
    assert abs(groove_volume(g, R) / exact - 1) < 1e-5


def test_mode_one_near_the_papers_432_hz(paper):
    assert abs(paper.modes.frequencies[0] / 432.16 - 1) < 0.02


def test_grooves_split_the_bending_pairs(paper):
    """The paper's reading: modes 1-2 are the two planes of bending, slightly split."""
    f = paper.modes.frequencies
    assert paper.modes.kinds[:2] == ["bending", "bending"]
    assert 1e-3 < f[1] / f[0] - 1 < 0.1


def test_cli_json_has_the_promised_fields(tmp_path, capsys):
    out = tmp_path / "modes.json"
    assert main(["modes", "plain_cylinder", "--json", str(out), "-q"]) == 0
    data = json.loads(out.read_text())
    assert data["rigid_body_modes"] == 6
    assert data["element"] == "P2"
    assert data["dofs"] > 0
    assert len(data["modes"]) == 10
    assert {"frequency_hz", "kind"} <= set(data["modes"][0])
    assert "Hz" in capsys.readouterr().out


def test_a_runouts_volume_against_the_sector_formula():
    """A rectangular groove running out: its tool reaches 0.5 mm below the floor, and in
    the runout its floor rises from there to the lift's top, d + 0.5 mm above the floor:
    at each height the floor stands e = max(0, h (H + 0.5) / H - 0.5) mm above the
    groove's, so the groove removes (phi/2) (R^2 - (R - d + e)^2) of the section while
    e < d. Integrated here by quadrature, apart from groove_volume's grid of widths."""
    from dataclasses import replace

    from scipy.integrate import quad

    from shaftfem.cad.profile import runout_lift
    from shaftfem.scene.model import Grooves

    R = 0.016
    g = Grooves(hands=(1,), pitch=0.08, width=0.008, depth=0.003, root_radius=0.0,
                length=0.12, start=0.05, runout=0.01)
    phi = 2 * np.pi * g.width / g.pitch

    dip, top = 0.5e-3, g.depth + 0.5e-3

    def area(z: float) -> float:
        h = float(runout_lift(g, R, np.array(z)))
        floor = R - g.depth + max(0.0, h * (top + dip) / top - dip)
        return phi / 2 * max(0.0, R**2 - floor**2)

    run, _ = quad(area, 0.0, g.runout, limit=200)
    plain = groove_volume(replace(g, runout=0.0), R)
    assert abs((groove_volume(g, R) - plain) / (2 * run) - 1) < 1e-3   # its r grid: 2.5e-4
    lift = runout_lift(g, R, np.array([0.0, g.runout]))
    assert lift[0] == 0.0 and lift[1] > g.depth     # it leaves the floor and the surface
