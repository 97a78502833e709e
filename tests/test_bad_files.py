"""Sweep and calibration files with mistakes: one line naming the key, exit 2, no
traceback, nothing written; two sweeps into one folder; a sweep with nothing usable."""

import pytest

from shaftfem.cli import main

SWEEP_OK = 'base = "plain_cylinder"\nmesh_size_mm = 16.0\n'
CAL_OK = ('base = "plain_cylinder"\nmesh_size_mm = 16.0\n'
          '[unknowns]\n"shaft.length_mm" = {min = 500.0, max = 600.0}\n'
          '[targets]\nfrequencies_hz = [480.0, 480.0]\nuncertainty_percent = 1.0\n')

SWEEPS = [
    (SWEEP_OK + '[axes]\n"shaft.length_mm" = {start = "a", stop = 600, num = 2}\n', "start"),
    (SWEEP_OK + 'points = [{"shaft.length_mm" = "long"}]\n', "points[0].shaft.length_mm"),
    (SWEEP_OK + 'axes = 3\n', "axes"),
    (SWEEP_OK + '[axes]\n', "axes"),
    (SWEEP_OK + '[axes]\n"shaft.length_mm" = []\n', "axes.shaft.length_mm"),
    (SWEEP_OK + '[axes]\n"shaft.length_mm" = [500.0, nan]\n', "axes.shaft.length_mm"),
    (SWEEP_OK + '[axes]\n"shaft.lenght_mm" = [500.0]\n', "shaft.lenght_mm"),
    (SWEEP_OK + '[axes]\n"material.name" = [1.0]\n', "material.name"),
    (SWEEP_OK + '[axes]\n"shaft.length_mm" = {start = 1, stop = 2, num = 0}\n', "num"),
    (SWEEP_OK + 'points = []\n', "points"),
    (SWEEP_OK + 'colour = "red"\n[axes]\n"shaft.length_mm" = [500.0]\n', "colour"),
    ('base = 5\n[axes]\n"shaft.length_mm" = [500.0]\n', "base"),
    ('base = "plain_cylinder"\nmesh_size_mm = nan\n[axes]\n"shaft.length_mm" = [500.0]\n',
     "mesh_size_mm"),
    ('base = "no_such_scene"\n[axes]\n"shaft.length_mm" = [500.0]\n', "no_such_scene"),
]

CALS = [
    (CAL_OK.replace('"shaft.length_mm" = {min = 500.0, max = 600.0}\n', ''), "unknowns"),
    (CAL_OK.replace("min = 500.0", 'min = "low"'), "unknowns.shaft.length_mm.min"),
    (CAL_OK.replace("max = 600.0", "max = 400.0"), "unknowns.shaft.length_mm"),
    (CAL_OK.replace("[480.0, 480.0]", '[480.0, "x"]'), "targets.frequencies_hz[1]"),
    (CAL_OK.replace("[480.0, 480.0]", "[480.0, nan]"), "targets.frequencies_hz[1]"),
    (CAL_OK.replace("uncertainty_percent = 1.0", "uncertainty_percent = [1.0, 2.0, 3.0]"),
     "targets.uncertainty_percent"),
    (CAL_OK.replace('[unknowns]\n"shaft.length_mm" = {min = 500.0, max = 600.0}\n', '')
     .replace('mesh_size_mm = 16.0\n', 'mesh_size_mm = 16.0\nunknowns = 5\n'), "unknowns"),
    (CAL_OK.replace('base = "plain_cylinder"', 'base = 5'), "base"),
    (CAL_OK + 'colour = "red"\n', "colour"),
    (CAL_OK.replace("uncertainty_percent = 1.0", "uncertainty_percent = 1.0\nsigma = 2"),
     "targets.sigma"),
    (CAL_OK.replace("mesh_size_mm = 16.0", "mesh_size_mm = 0"), "mesh_size_mm"),
    (CAL_OK.replace("mesh_size_mm = 16.0", "mesh_size_mm = 16.0\ngrid = 1"), "grid"),
    (CAL_OK.replace('"shaft.length_mm" = {', '"length" = {'), "length"),
    # a size longer than the base shaft (once a model at +1000 % with exit 0), and one
    # beyond the DOF budget: refused at load, naming the key
    (CAL_OK.replace("mesh_size_mm = 16.0", "mesh_size_mm = 5000.0"), "mesh_size_mm = 5000"),
    (CAL_OK.replace("mesh_size_mm = 16.0", "mesh_size_mm = 0.5"), "above the budget"),
    # an integer key cannot be fitted; a grid beyond the cap; a grid point that is no
    # valid scene (the diameter reaches 0): refused at load
    (CAL_OK.replace('"shaft.length_mm" = {min = 500.0, max = 600.0}',
                    '"modes.count" = {min = 4, max = 8}'), "an integer key cannot be an unknown"),
    (CAL_OK.replace('"shaft.length_mm" = {min = 500.0, max = 600.0}',
                    '"shaft.length_mm" = {min = 500.0, max = 600.0}\n'
                    '"shaft.diameter_mm" = {min = 30.0, max = 34.0}\n'
                    '"material.density_kg_m3" = {min = 7000.0, max = 8000.0}\n'
                    '"material.youngs_modulus_mpa" = {min = 2e5, max = 2.2e5}\n'
                    '"material.poisson_ratio" = {min = 0.25, max = 0.3}')
     .replace("mesh_size_mm = 16.0", "mesh_size_mm = 16.0\ngrid = 20"),
     "make 3,200,000 variants; at most 10,000"),
    (CAL_OK.replace('"shaft.length_mm" = {min = 500.0, max = 600.0}',
                    '"shaft.diameter_mm" = {min = -2.0, max = 34.0}'),
     "variant 1 (shaft.diameter_mm = -2)"),
]
SWEEPS += [
    (SWEEP_OK.replace("mesh_size_mm = 16.0", "mesh_size_mm = 5000.0")
     + '[axes]\n"shaft.length_mm" = [500.0]\n', "mesh_size_mm = 5000"),
    (SWEEP_OK.replace("mesh_size_mm = 16.0", "mesh_size_mm = 0.5")
     + '[axes]\n"shaft.length_mm" = [500.0]\n', "above the budget"),
]


def _refused(capsys, argv, named, out):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and named in err and "Traceback" not in err, err
    assert not out.exists() or not any(p for p in out.rglob("*") if p.is_file())


@pytest.mark.parametrize("command,text,named", [("sweep", t, n) for t, n in SWEEPS]
                         + [("calibrate", t, n) for t, n in CALS])
def test_bad_sweep_or_calibration_file(tmp_path, capsys, command, text, named):
    f = tmp_path / f"{command}.toml"
    f.write_text(text)
    out = tmp_path / "out"
    _refused(capsys, [command, str(f), "--out", str(out), "-q"], named, out)


def test_a_second_sweep_into_the_same_folder_is_refused(tmp_path, capsys):
    from shaftfem.workflows.sweep import _owned

    f = tmp_path / "sweep.toml"
    f.write_text(SWEEP_OK + '[axes]\n"shaft.length_mm" = [500.0]\n')
    out = tmp_path / "out"
    with _owned(out):  # the first sweep, still running
        assert main(["sweep", str(f), "--out", str(out), "-q"]) == 2
        assert "another sweep is writing into" in capsys.readouterr().err
    assert not (out / "results.csv").exists()


def test_a_sweep_with_nothing_usable_exits_3(tmp_path, capsys):
    f = tmp_path / "sweep.toml"
    # every variant valid as a scene but beyond its own DOF budget, found in the run
    f.write_text('base = "paper2018"\nmesh_size_mm = 16.0\n'
                 'points = [{"mesh.max_dofs" = 1000}, {"mesh.max_dofs" = 2000}]\n')
    out = tmp_path / "out"
    assert main(["sweep", str(f), "--out", str(out), "--workers", "1", "-q"]) == 3
    assert "0 ok, 2 failed" in capsys.readouterr().out
    assert not (out / ".sweep-tmp").exists()  # the workers' temp folder is removed
