"""Resonance check, exported files and pictures."""

import re
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest
from references import timoshenko_free_free_hz
from scipy.spatial import cKDTree

from shaftfem.cli import main
from shaftfem.export import export_modes
from shaftfem.scene import GEOMETRY_DIR

CYL = (GEOMETRY_DIR / "plain_cylinder.toml").read_text()


def _first_bending_hz():
    return timoshenko_free_free_hz(1, 0.55, 0.016, 2.11e11, 0.277, 7870)[0]


def _scene_with_engine(tmp_path, hz):
    text = re.sub(r"speed_rpm = .*", f"speed_rpm = {hz * 60:.6f}", CYL)
    text = text.replace("orders = [1, 2]", "orders = [1]")
    f = tmp_path / "exc.toml"
    f.write_text(text)
    return f


def test_check_fails_with_an_excitation_on_a_mode(tmp_path, capsys):
    # the Timoshenko beam's first bending frequency: 483.3 Hz, within 0.02 % of the FE mode
    f = _scene_with_engine(tmp_path, _first_bending_hz())
    assert main(["check", str(f), "-q"]) == 1
    assert "FAIL" in capsys.readouterr().out


def test_check_passes_twenty_percent_away(tmp_path, capsys):
    f = _scene_with_engine(tmp_path, _first_bending_hz() / 1.2)
    assert main(["check", str(f), "-q", "--json", str(tmp_path / "c.json")]) == 0
    assert "PASS" in capsys.readouterr().out
    assert (tmp_path / "c.json").exists()


def test_check_bad_input_exits_2(tmp_path, capsys):
    f = tmp_path / "bad.toml"
    f.write_text(CYL.replace("orders = [1, 2]", "orders = [0]"))
    assert main(["check", str(f), "-q"]) == 2
    assert "excitation[0].orders" in capsys.readouterr().err


@pytest.fixture(scope="module")
def exported(cylinder, tmp_path_factory):
    out = tmp_path_factory.mktemp("export")
    export_modes(cylinder, out)
    return out


def test_vtu_shapes_read_back_exactly_and_are_mass_orthonormal(cylinder, exported):
    nodes, M, X = cylinder.system.nodes, cylinder.system.M, cylinder.modes.shapes
    Y = np.zeros_like(X)
    for k in range(X.shape[1]):
        m = meshio.read(exported / f"mode_{k + 1:02d}.vtu")
        assert m.cells[0].type == "tetra10"
        (name, u), = m.point_data.items()
        assert name.endswith(f"{cylinder.modes.frequencies[k]:.2f}Hz")
        dist, idx = cKDTree(m.points).query(nodes)
        assert dist.max() < 1e-12
        Y[:, k] = u[idx].ravel()
    assert np.max(np.abs(Y - X)) < 1e-12 * np.max(np.abs(X))
    assert np.max(np.abs(Y.T @ (M @ Y) - np.eye(Y.shape[1]))) < 1e-8


def test_pvd_lists_every_mode(exported):
    sets = ET.parse(exported / "modes.pvd").getroot().findall("./Collection/DataSet")
    assert [int(d.get("timestep")) for d in sets] == list(range(1, 11))
    assert all((exported / d.get("file")).exists() for d in sets)


def test_tables_solid_and_mesh_are_written(cylinder, exported):
    import csv

    rows = list(csv.DictReader(open(exported / "modes.csv")))
    assert len(rows) == 10
    f = float(rows[0]["frequency_hz"])
    assert float(rows[0]["period_s"]) == pytest.approx(1 / f)
    assert float(rows[0]["omega_rad_s"]) == pytest.approx(2 * np.pi * f)
    assert (exported / "shaft.step").read_text()[:13] == "ISO-10303-21;"
    m = meshio.read(exported / "mesh.msh")
    assert m.cells_dict["tetra10"].shape[0] == cylinder.mesh.n_elements


def test_failure_mid_export_leaves_no_file(cylinder, tmp_path, monkeypatch):
    calls = {"n": 0}
    real = meshio.write

    def flaky(*a, **k):
        calls["n"] += 1
        if calls["n"] == 3:
            raise OSError("disk full (injected)")
        return real(*a, **k)

    monkeypatch.setattr(meshio, "write", flaky)
    out = tmp_path / "out"
    with pytest.raises(OSError, match="injected"):
        export_modes(cylinder, out)
    assert list(out.iterdir()) == []


def test_render_writes_non_blank_pngs(cylinder, tmp_path):
    from PIL import Image

    from shaftfem.render import GEOMETRY_SIZE, MODES_SIZE, render_geometry, render_modes

    for fn, size in ((render_geometry, GEOMETRY_SIZE), (render_modes, MODES_SIZE)):
        path = fn(cylinder, tmp_path / f"{fn.__name__}.png")
        img = np.asarray(Image.open(path).convert("RGB"))
        assert img.shape[:2] == (size[1], size[0])
        background = np.all(img == 255, axis=2)
        assert 0.02 < 1 - background.mean() < 0.9  # something drawn, not everything
        assert len(np.unique(img.reshape(-1, 3), axis=0)) > 50  # shaded, not a flat fill
