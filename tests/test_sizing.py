"""Equations (1)-(9) and Table 1 of the paper."""

import math
import subprocess
import sys

import pytest

from shaftfem.checks.sizing import axial_load_n, keyway_increase_percent, min_mean_diameter_mm, size_screw
from shaftfem.cli import main
from shaftfem.scene.load import load_scene

INPUTS = dict(load_scene("paper2018").sizing)


def test_d2_satisfies_the_wear_condition_with_equality():
    r = size_screw(INPUTS)
    d2 = r["d2"]
    F = axial_load_n(r["T"], d2, INPUTS["lead_angle_deg"], r["rho'"])
    rhs = 0.8 * math.sqrt(F / (INPUTS["psi"] * INPUTS["allowable_pressure_mpa"]))
    assert abs(d2 - rhs) / d2 < 1e-9


def test_d2_grows_with_power_and_falls_with_speed():
    base = size_screw(INPUTS)["d2"]
    assert size_screw({**INPUTS, "power_kw": 1.0})["d2"] > base
    assert size_screw({**INPUTS, "speed_rpm": 160.0})["d2"] < base


@pytest.mark.parametrize("d,one,two", [(29.9, 7, 15), (30.0, 5, 10), (100.0, 5, 10),
                                       (100.1, 3, 7)])
def test_table_1_band_edges(d, one, two):
    assert keyway_increase_percent(d, 1) == one
    assert keyway_increase_percent(d, 2) == two
    assert keyway_increase_percent(d, 0) == 0


def test_papers_pitch_travel_and_box_width():
    r = size_screw(INPUTS)
    assert r["P"] == pytest.approx(80.0)   # b = 40 mm at 1:2 -> P = 80 mm, eq. (1)
    assert r["L"] == pytest.approx(320.0)  # 40 (9 - 1), eq. (8)
    assert r["B"] == pytest.approx(360.0)  # 320 + 40, eq. (9)


def test_torque_equation_5():
    assert size_screw(INPUTS)["T"] == pytest.approx(9_549_000 * 0.5 / 80)


def test_rounding_and_major_diameter():
    r = size_screw(INPUTS)
    assert r["D"] >= r["d_k"] and r["D"] - r["d_k"] < INPUTS["rounding_step_mm"]
    assert r["D0"] == pytest.approx(r["D"] + 2 * INPUTS["crest_clearance_mm"])


def test_closed_form_is_the_fixed_point():
    d2 = min_mean_diameter_mm(1e5, 5.0, 9.0, 3.0, 10.0)
    F = axial_load_n(1e5, d2, 5.0, 9.0)
    assert d2 == pytest.approx(0.8 * math.sqrt(F / 30.0), rel=1e-12)


def test_self_locking_limit_is_reported(capsys, tmp_path):
    r = size_screw({**INPUTS, "pressure_angle_deg": 40.0})
    assert not r.ok and "self-lock" in r.violations[0]


@pytest.mark.parametrize("key,value", [
    ("power_kw", "0"), ("power_kw", "-1"), ("speed_rpm", "0"), ("friction_coefficient", "1.0"),
    ("pressure_angle_deg", "90"), ("picks_per_row", "1"), ("psi", '"three"'),
])
def test_bad_sizing_input_names_the_key(tmp_path, capsys, key, value):
    import re

    from shaftfem.scene.load import GEOMETRY_DIR

    head, tail = (GEOMETRY_DIR / "paper2018.toml").read_text().split("[sizing]")
    tail, n = re.subn(rf"(?m)^{key}\s*=.*$", f"{key} = {value}", tail)
    assert n == 1
    text = head + "[sizing]" + tail
    f = tmp_path / "bad.toml"
    f.write_text(text)
    assert main(["size", str(f)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and f"sizing.{key}" in err


def test_size_json(tmp_path):
    out = tmp_path / "size.json"
    assert main(["size", "--json", str(out)]) == 0
    import json

    data = json.loads(out.read_text())
    assert {q["symbol"] for q in data["quantities"]} >= {"P", "T", "F", "d2", "D", "D0", "L", "B"}


def test_import_and_size_load_no_mesher_or_fem():
    code = (
        "import sys, shaftfem; from shaftfem.cli import main; rc = main(['size']);"
        "heavy = [m for m in ('gmsh', 'skfem', 'pyvista', 'meshio', 'scipy') if m in sys.modules];"
        "assert not heavy, heavy; sys.exit(rc)"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr


def test_the_public_api_is_lazy_and_complete():
    """`import shaftfem` and the names a library user calls load no mesher, FE or solver
    library until a step runs; every name it lists resolves."""
    code = (
        "import sys, shaftfem;"
        "heavy = lambda: [m for m in ('gmsh', 'skfem', 'scipy', 'pyvista', 'meshio') "
        "if m in sys.modules];"
        "assert not heavy(), heavy();"
        "s = shaftfem.load_scene('paper2018'); o = shaftfem.RunOptions(use_cache=False);"
        "f = (shaftfem.run_modes, shaftfem.run_bounded, shaftfem.run_design);"
        "assert not heavy(), heavy();"
        "[getattr(shaftfem, n) for n in shaftfem.__all__];"
        "assert 'scipy' in sys.modules and isinstance(s, shaftfem.Scene)"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr


def test_the_scene_shaft_and_grooves_are_checked_against_the_sizing(tmp_path, capsys):
    """Across tables: a [shaft] thinner than the duty's D, and a [grooves] pitch that the
    feed step and gears (equation 1) do not give, are broken limits (exit 1), said."""
    from shaftfem.scene.load import GEOMETRY_DIR

    paper = (GEOMETRY_DIR / "paper2018.toml").read_text()
    f = tmp_path / "thin.toml"
    f.write_text(paper.replace("diameter_mm = 32.0", "diameter_mm = 20.0"))
    assert main(["size", str(f)]) == 1
    assert "diameter 20 mm (the grooved or smallest section's) is below the D = 24 mm" in (
        capsys.readouterr().out)
    f.write_text(paper.replace("driven_teeth = 40", "driven_teeth = 30"))
    assert main(["size", str(f)]) == 1
    assert "[grooves] pitch_mm = 80 differs from P" in capsys.readouterr().out
