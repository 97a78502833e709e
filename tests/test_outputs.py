"""Resonance check, exported files and pictures."""

import re
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest
from scipy.spatial import cKDTree

from references import timoshenko_free_free_hz
from shaftfem.cli import main
from shaftfem.outputs.export import export_modes
from shaftfem.scene.load import GEOMETRY_DIR

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


def test_a_free_free_pass_says_so_in_its_verdict_and_exits_4(tmp_path, capsys):
    """No [[support]]: the verdict line says free-free, a caveat says what that means,
    and the exit status is 4 (docs/cli.md), unless --free or [resonance] free_free says
    free-free is what the check is for (then 0)."""
    import json

    f = _scene_with_engine(tmp_path, _first_bending_hz() / 1.2)
    f.write_text(re.sub(r"free_free = true.*\n", "", f.read_text()))   # not declared
    assert main(["check", str(f), "-q", "--json", str(tmp_path / "c.json")]) == 4
    out = capsys.readouterr().out
    verdict = next(line for line in out.splitlines() if line.startswith("VERDICT"))
    assert verdict.startswith("VERDICT: PASS (free-free)")
    assert "hanging free" in out and "[[support]]" in out and "free_free = true" in out
    record = json.loads((tmp_path / "c.json").read_text())
    assert record["free_free"] and record["exit_status"] == 4
    assert main(["check", str(f), "-q", "--free"]) == 0
    assert "PASS (free-free)" in capsys.readouterr().out
    g = tmp_path / "meant.toml"
    g.write_text(f.read_text().replace("[resonance]", "[resonance]\nfree_free = true", 1))
    assert main(["check", str(g), "-q"]) == 0
    assert "PASS (free-free)" in capsys.readouterr().out
    # the design run says it too, in its verdict and in both reports, with the same status
    out = tmp_path / "design"
    assert main(["design", str(f), "--out", str(out), "--mesh-size", "16", "--modes", "3",
                 "--no-estimate", "--no-html", "-q"]) == 4
    assert "VERDICT: PASS (free-free)" in capsys.readouterr().out
    report = (out / "report.md").read_text()
    assert "**VERDICT: PASS (free-free)**" in report and "[[support]]" in report


def test_check_bad_input_exits_2(tmp_path, capsys):
    f = tmp_path / "bad.toml"
    f.write_text(CYL.replace("orders = [1, 2]", "orders = [0]"))
    assert main(["check", str(f), "-q"]) == 2
    assert "excitation 1" in capsys.readouterr().err


@pytest.fixture(scope="module")
def exported(cylinder, tmp_path_factory):
    out = tmp_path_factory.mktemp("export")
    export_modes(cylinder, out)
    return out


def test_vtu_shapes_read_back_exactly_and_are_mass_orthonormal(cylinder, exported):
    import pyvista as pv

    from shaftfem.outputs.export import KIND_FIELD, KINDS

    nodes, M, X = cylinder.system.nodes, cylinder.system.M, cylinder.modes.shapes
    Y, Z = np.zeros_like(X), np.zeros_like(X)
    every = meshio.read(exported / "modes_all.vtu")
    for k in range(X.shape[1]):
        m = meshio.read(exported / f"mode_{k + 1:02d}.vtu")
        assert m.cells[0].type == "tetra10"
        assert set(m.point_data) == {"displacement", "displacement_magnitude"}
        assert m.field_data["mode"][0] == k + 1
        assert m.field_data["frequency_hz"][0] == cylinder.modes.frequencies[k]
        assert KINDS[m.field_data[KIND_FIELD][0]] == cylinder.modes.kinds[k]
        u = m.point_data["displacement"]
        assert np.allclose(m.point_data["displacement_magnitude"], np.linalg.norm(u, axis=1))
        dist, idx = cKDTree(m.points).query(nodes)
        assert dist.max() < 1e-12
        Y[:, k] = u[idx].ravel()
        Z[:, k] = every.point_data[f"mode_{k + 1:02d}"][idx].ravel()
        # pyvista (VTK's reader) sees the same vectors
        g = pv.read(exported / f"mode_{k + 1:02d}.vtu")
        assert np.array_equal(np.asarray(g.point_data["displacement"]), u)
    assert np.max(np.abs(Y - X)) < 1e-12 * np.max(np.abs(X))
    assert np.array_equal(Y, Z)
    assert np.max(np.abs(Y.T @ (M @ Y) - np.eye(Y.shape[1]))) < 1e-8


def test_pvd_lists_every_mode(exported):
    sets = ET.parse(exported / "modes.pvd").getroot().findall("./Collection/DataSet")
    assert [int(d.get("timestep")) for d in sets] == list(range(1, 11))
    assert all((exported / d.get("file")).exists() for d in sets)


def test_tables_solid_and_mesh_are_written(cylinder, exported):
    import csv

    rows = list(csv.DictReader((exported / "modes.csv").read_text().splitlines()))
    assert len(rows) == 10
    f = float(rows[0]["frequency_hz"])
    assert float(rows[0]["period_s"]) == pytest.approx(1 / f)
    assert float(rows[0]["omega_rad_s"]) == pytest.approx(2 * np.pi * f)
    assert (exported / "shaft.step").read_text()[:13] == "ISO-10303-21;"
    m = meshio.read(exported / "mesh.msh")
    assert m.cells_dict["tetra10"].shape[0] == cylinder.mesh.n_elements


def test_failure_mid_export_leaves_no_file(cylinder, tmp_path, monkeypatch):
    from shaftfem.outputs import vtk as vtkio

    calls = {"n": 0}
    real = vtkio.write_vtu

    def flaky(*a, **k):
        calls["n"] += 1
        if calls["n"] == 3:
            raise OSError("disk full (injected)")
        return real(*a, **k)

    monkeypatch.setattr(vtkio, "write_vtu", flaky)
    out = tmp_path / "out"
    with pytest.raises(OSError, match="injected"):
        export_modes(cylinder, out)
    assert not out.exists()  # not a file, not a manifest, not the folder the run made


def test_pictures_have_a_panel_per_mode_a_colour_bar_and_moving_gifs(cylinder, tmp_path):
    from PIL import Image

    from shaftfem.outputs.render import (
        BAR_HEIGHT,
        GEOMETRY_SIZE,
        GIF_FRAMES,
        GIF_SIZE,
        PANEL_SIZE,
        render_geometry,
        render_mode_gifs,
        render_modes,
    )
    from shaftfem.workflows.pipeline import run_modes, with_modes

    def drawn(img):  # fraction of pixels that are not the white background
        return 1 - np.all(img == 255, axis=2).mean()

    geo = np.asarray(Image.open(render_geometry(cylinder, tmp_path / "g.png")).convert("RGB"))
    assert geo.shape[:2] == (GEOMETRY_SIZE[1], GEOMETRY_SIZE[0]) and 0.02 < drawn(geo) < 0.9

    three = run_modes(with_modes(cylinder.scene, count=3))  # three modes: panels 1-3 of 4
    img = np.asarray(Image.open(render_modes(three, tmp_path / "m.png")).convert("RGB"))
    (w, h), rows = PANEL_SIZE, 2
    assert img.shape[:2] == (rows * h + BAR_HEIGHT, 2 * w)
    panels = [img[r * h + 25:(r + 1) * h - 5, c * w + 5:(c + 1) * w - 5]
              for r in range(rows) for c in range(2)]
    for p in panels[:3]:
        assert 0.05 < drawn(p) < 0.9
        assert len(np.unique(p.reshape(-1, 3), axis=0)) > 50  # shaded and coloured
    assert drawn(panels[3]) < 0.01  # no fourth mode was asked for
    # the colour bar's coloured band: 30-42 % of the strip's height from its bottom
    top = rows * h + BAR_HEIGHT
    bar = img[top - int(0.42 * BAR_HEIGHT):top - int(0.30 * BAR_HEIGHT),
              int(0.32 * 2 * w):int(0.68 * 2 * w)]
    # viridis runs from dark purple to yellow
    assert drawn(bar) > 0.5
    colours = bar.reshape(-1, 3).astype(int)
    assert np.any((colours[:, 0] > 200) & (colours[:, 1] > 200) & (colours[:, 2] < 100))  # yellow
    assert np.any((colours[:, 0] < 100) & (colours[:, 1] < 50) & (colours[:, 2] > 60))   # purple

    gifs = render_mode_gifs(three, tmp_path)
    assert [g.name for g in gifs] == ["mode_01.gif", "mode_02.gif", "mode_03.gif"]
    for g in gifs:
        im = Image.open(g)
        assert im.n_frames == GIF_FRAMES and im.size == GIF_SIZE
        frames = []
        for i in (0, GIF_FRAMES // 4):
            im.seek(i)
            frames.append(np.asarray(im.convert("RGB")))
        assert np.any(frames[0] != frames[1])  # it moves


KILLER = """
import os, signal, sys
from pathlib import Path
import shaftfem.runtime
shaftfem.runtime.configure_threads()
from shaftfem.outputs.export import export_modes
from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes
from shaftfem.scene.load import load_scene

out, kill_at = Path(sys.argv[1]), int(sys.argv[2])
moves, real = [0], os.replace

def replace(src, dst):  # SIGKILL at the kill_at-th move into the visible folder
    if Path(dst).parent == out:
        if moves[0] == kill_at:
            os.kill(os.getpid(), signal.SIGKILL)
        moves[0] += 1
    return real(src, dst)

os.replace = replace
export_modes(run_modes(with_modes(with_mesh(load_scene("plain_cylinder"), 16.0), count=3)), out)
"""


def test_an_export_killed_anywhere_is_complete_or_vouched_for_by_no_manifest(tmp_path):
    """SIGKILL before the first file is published, in the middle, and after the last file
    but before the manifest: no manifest vouches for a mixed set, and the next run removes
    the killed run's staging folder and publishes a complete set."""
    import os
    import subprocess
    import sys

    from shaftfem.outputs.export import MANIFEST
    from shaftfem.store import STAGING, manifest_complete

    out = tmp_path / "out"
    env = {**os.environ, "SHAFTFEM_CACHE": str(tmp_path / "cache")}

    def run(kill_at):
        return subprocess.run([sys.executable, "-c", KILLER, str(out), str(kill_at)], env=env,
                              capture_output=True, text=True, timeout=300).returncode

    assert run(10**6) == 0 and manifest_complete(out, MANIFEST)   # a complete first export
    n_files = len(list(out.iterdir())) - 1
    for kill_at in (0, 3, n_files):
        assert run(kill_at) == -9
        assert not manifest_complete(out, MANIFEST)
        assert not (out / MANIFEST).exists()
        assert [p for p in out.iterdir() if p.name.startswith(STAGING)]  # left by the kill
    assert run(10**6) == 0 and manifest_complete(out, MANIFEST)
    assert not [p for p in out.iterdir() if p.name.startswith(STAGING)]
    assert len(list(out.iterdir())) == n_files + 1


def test_the_resonance_table_stays_aligned_with_a_long_source_name():
    """Columns are as wide as their contents: a source named "chain meshing" and a
    32,497 % margin leave every column starting at one position in every row."""
    from shaftfem.checks.resonance import check_resonance
    from shaftfem.outputs.tables import verdict_text
    from shaftfem.scene.model import Excitation

    v = check_resonance(np.array([434.63, 1200.77]), ["bending", "bending"],
                        [Excitation("chain meshing", 24.1667, (1, 2)),
                         Excitation("shaft", 1.3333, (1,))])
    lines = verdict_text(v).splitlines()
    table = lines[:lines.index("")]
    assert len(table) == 4 and "chain meshing" in table[1]
    for column in ("excitation", "frequency", "margin", "required"):
        end = table[0].index(column) + len(column)   # right-aligned: ends line up
        assert all(row[end - 1] != " " and row[end:end + 1] in ("", " ") for row in table), column
    assert "24.17 Hz" in table[1] or "48.33 Hz" in table[1]
