"""The library's workflows as a user meets them: design without excitations, any
number of modes, a non-editable install, gmsh inside a caller's own session."""

import csv
import json
import os
import re
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import numpy as np
import pytest

from references import torsion_hz
from shaftfem.cli import main
from shaftfem.scene.load import GEOMETRY_DIR

REPO = Path(__file__).resolve().parents[1]
CYL = (GEOMETRY_DIR / "plain_cylinder.toml").read_text()


def test_design_without_excitations_reports_not_checked(tmp_path, capsys):
    import time

    scene = tmp_path / "quiet.toml"
    scene.write_text(re.sub(r"(?s)\[\[excitation\]\].*", "", CYL))
    out = tmp_path / "out"
    started = time.perf_counter()
    assert main(["design", str(scene), "--out", str(out), "--mesh-size", "16", "--modes", "3",
                 "--no-estimate", "-q"]) == 0
    took = time.perf_counter() - started
    assert "NOT CHECKED" in capsys.readouterr().out
    report = (out / "report.md").read_text()
    assert "NOT CHECKED" in report and "nothing to check against" in report
    # the run time is the whole run's, until the report: within what the call took
    said = float(re.search(r"## Run time\n\n([0-9.]+) s in all", report).group(1))
    assert 0.3 * took < said <= took + 0.1
    assert len(list(csv.DictReader((out / "modes.csv").read_text().splitlines()))) == 3
    assert sorted(p.name for p in out.glob("*.gif")) == ["mode_01.gif", "mode_02.gif",
                                                          "mode_03.gif"]
    # `check` still refuses: there is nothing to check
    assert main(["check", str(scene), "--mesh-size", "16", "-q"]) == 2


def test_twenty_modes_and_a_frequency_limit(cylinder, tmp_path):
    """--modes 20 on the 32 x 550 mm cylinder: the first two torsion modes are n c_t / 2L."""
    out = tmp_path / "modes.json"
    assert main(["modes", "plain_cylinder", "--modes", "20", "--no-estimate", "-q",
                 "--json", str(out)]) == 0
    rows = json.loads(out.read_text())["modes"]
    f = np.array([r["frequency_hz"] for r in rows])
    assert len(f) == 20 and np.all(np.diff(f) >= 0)
    s, m = cylinder.scene.shaft, cylinder.scene.material
    torsion = f[[r["kind"] == "torsion" for r in rows]]
    for n in (1, 2):
        exact = torsion_hz(n, s.length, m.youngs_modulus, m.poisson_ratio, m.density)
        assert np.min(np.abs(torsion / exact - 1)) < 1e-3, (n, torsion, exact)
    # the ten-mode run is the start of the twenty
    assert np.max(np.abs(f[:10] / cylinder.modes.frequencies - 1)) < 1e-8
    # every mode below 3000 Hz, and only those
    limit = tmp_path / "limit.json"
    assert main(["modes", "plain_cylinder", "--max-frequency", "3000", "--no-estimate", "-q",
                 "--json", str(limit)]) == 0
    g = np.array([r["frequency_hz"] for r in json.loads(limit.read_text())["modes"]])
    assert len(g) == np.sum(f < 3000) and np.max(np.abs(g / f[:len(g)] - 1)) < 1e-8


def test_gmsh_leaves_a_callers_session_as_it_was(tmp_path):
    import gmsh

    from shaftfem.cad.build import write_solid
    from shaftfem.scene.load import load_scene

    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.model.add("mine")
        gmsh.option.setNumber("General.Terminal", 1)
        write_solid(None, load_scene("plain_cylinder").shaft, [tmp_path / "shaft.step"])
        assert gmsh.isInitialized()
        assert gmsh.model.getCurrent() == "mine"
        assert gmsh.option.getNumber("General.Terminal") == 1
    finally:
        gmsh.finalize()
    assert (tmp_path / "shaft.step").read_text()[:13] == "ISO-10303-21;"


@pytest.mark.slow
def test_installed_package_finds_its_scenes_from_any_folder(tmp_path):
    """A non-editable install into a fresh virtual environment (the dependencies are
    taken from the test's own environment through a .pth line), run elsewhere."""
    env_dir = tmp_path / "venv"
    venv.create(env_dir)     # without pip of its own: this one's installs into it
    py = env_dir / "bin" / "python"
    wheels, source = tmp_path / "wheels", tmp_path / "source"
    # built from a copy: an in-tree build would leave build/ in the checkout
    # (every .venv* and tool cache: a developer's checkout holds ross's benchmark venv,
    # 1.4 GB, beside .venv)
    shutil.copytree(REPO, source, ignore=shutil.ignore_patterns(
        ".venv*", ".*_cache", ".hypothesis", ".git", "build", "out", "*.egg-info",
        "__pycache__"))
    quiet = dict(capture_output=True, text=True, check=True)
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(wheels),
                    str(source)], **quiet)
    subprocess.run([sys.executable, "-m", "pip", "--python", str(py), "install", "--no-deps",
                    "-q", *map(str, wheels.glob("*.whl"))], **quiet)
    site = subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                          **quiet).stdout.strip()
    deps = [p for p in sys.path if p.endswith("site-packages")]
    Path(site, "deps.pth").write_text("\n".join(deps) + "\n")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    run = dict(cwd=elsewhere, capture_output=True, text=True, env=os.environ.copy())
    where = subprocess.run([str(py), "-c", "import shaftfem; print(shaftfem.__file__)"], **run)
    assert where.stdout.startswith(str(env_dir)), where  # the installed copy, not the repo's
    exe = str(env_dir / "bin" / "shaftfem")
    size = subprocess.run([exe, "size"], **run)
    assert size.returncode == 0 and "d2" in size.stdout, size.stderr
    modes = subprocess.run([exe, "modes", "--mesh-size", "16", "--no-estimate", "-q"], **run)
    assert modes.returncode == 0, modes.stderr
    assert "scene paper2018" in modes.stdout and "rigid-body modes: 6" in modes.stdout


@pytest.mark.parametrize("raised,code", [
    ("MeshError", 3), ("SolverError", 3), ("ClusterError", 3), ("SceneError", 2),
    ("OSError", 3), ("RuntimeError", 3)])
def test_exit_status_says_what_failed(monkeypatch, capsys, raised, code):
    """A resonance is 1, bad input 2, anything failing inside the computation 3: one line,
    no traceback, whatever raised it (ours, the disk, or an untranslated library error)."""
    import builtins

    from shaftfem import errors
    from shaftfem.workflows import pipeline

    exc = getattr(errors, raised, None) or getattr(builtins, raised)

    def broken(*_a, **_k):
        raise exc("injected failure\nsecond line")

    monkeypatch.setattr(pipeline, "solve_mesh", broken)   # every modal run's solve
    assert main(["check", "plain_cylinder", "-q"]) == code
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "injected failure second line" in err
    assert "Traceback" not in err


def test_the_run_time_counts_the_bound(tmp_path, capsys):
    """The time line and the record's timings give the bound's own wall time, and a
    total that holds it: the steps add up to no more than the total."""
    out = tmp_path / "modes.json"
    assert main(["modes", "plain_cylinder", "--mesh-size", "16", "-q", "--json", str(out)]) == 0
    t = json.loads(out.read_text())["timings_s"]
    assert list(t) == ["cad", "mesh", "assembly", "solve", "bound", "total"]
    assert t["bound"] > 0 and sum(v for k, v in t.items() if k != "total") <= t["total"] + 1e-9
    line = [s for s in capsys.readouterr().out.splitlines() if s.startswith("time: ")]
    assert len(line) == 1 and f"bound {t['bound']:.1f} s" in line[0]
