"""What a careless user or CI does: output paths nobody meant, a broken cache setting, a
folder reused by a smaller run, a BOM, an interrupted run. Each is refused before any
work with exit 2 and one line naming what is wrong, or handled without a trace."""

import json

import pytest

from shaftfem.cli import main

QUICK = ["--mesh-size", "16", "-q"]


def _one_line_exit_2(capsys, argv, named):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and named in err and "Traceback" not in err, err


@pytest.fixture()
def no_solve(monkeypatch):
    """Any solve is an error: a refusal must come before the work."""
    from shaftfem.workflows import bounded, pipeline

    def never(*_a, **_k):
        raise AssertionError("the solve ran")

    monkeypatch.setattr(pipeline, "run_modes", never)
    monkeypatch.setattr(bounded, "run_bounded", never)


@pytest.mark.parametrize("name", ["../x", "/tmp/shaftfem-abs", ".", "..", "a/b", ""])
def test_a_scene_name_is_a_folder_name_not_a_path(tmp_path, capsys, monkeypatch, no_solve,
                                                  name):
    from shaftfem.scene.load import GEOMETRY_DIR

    monkeypatch.chdir(tmp_path)
    f = tmp_path / "named.toml"
    f.write_text(f'name = "{name}"\n' + (GEOMETRY_DIR / "plain_cylinder.toml").read_text()
                 .replace('name = "plain_cylinder"', ""))
    _one_line_exit_2(capsys, ["design", str(f), *QUICK], "name")
    assert not any(tmp_path.parent.glob("x")) and list(tmp_path.iterdir()) == [f]


@pytest.mark.parametrize("argv,named", [
    (["export", "plain_cylinder", "--out", ""], "--out ''"),
    (["modes", "plain_cylinder", "--json", ""], "--json ''"),
    (["export", "plain_cylinder", "--out", "/proc/shaftfem-out"], "cannot write there"),
    (["modes", "plain_cylinder", "--json", "/proc/shaftfem.json"], "cannot write there"),
    (["design", "plain_cylinder", "--out", "/proc/self/shaftfem"], "cannot write there"),
])
def test_outputs_that_cannot_be_written_are_refused_before_the_run(tmp_path, capsys,
                                                                   monkeypatch, no_solve,
                                                                   argv, named):
    monkeypatch.chdir(tmp_path)
    _one_line_exit_2(capsys, argv + QUICK, named)
    assert list(tmp_path.iterdir()) == []         # nothing written into the folder either


def test_an_out_folder_under_a_file_is_refused_and_nothing_is_left(tmp_path, capsys,
                                                                   no_solve):
    a_file = tmp_path / "a_file"
    a_file.write_text("x")
    _one_line_exit_2(capsys, ["export", "plain_cylinder", "--out", str(a_file / "sub"),
                              *QUICK], "cannot write there")
    deep = tmp_path / "new" / "deeper"
    assert main(["export", "plain_cylinder", "--out", str(deep), *QUICK]) != 0  # the no_solve
    assert not (tmp_path / "new").exists()       # the probe leaves no folder behind


@pytest.mark.parametrize("cache", ["file", "proc"])
def test_a_cache_that_is_no_writable_folder_is_named(tmp_path, capsys, monkeypatch, no_solve,
                                                     cache):
    path = tmp_path / "cache-file" if cache == "file" else "/proc/shaftfem-cache"
    if cache == "file":
        path.write_text("x")
    monkeypatch.setenv("SHAFTFEM_CACHE", str(path))
    _one_line_exit_2(capsys, ["modes", "plain_cylinder", *QUICK],
                     f"the cache SHAFTFEM_CACHE={path}")


@pytest.mark.parametrize("command", ["modes", "design"])
def test_no_cache_reaches_every_solve(tmp_path, monkeypatch, command):
    """--no-cache neither reads nor writes the cache in any solve, the bound's coarser
    mesh and a design's free-free comparison included: a cache setting that is a file
    is never touched, and an empty cache folder stays empty."""
    bad = tmp_path / "cache-file"
    bad.write_text("x")
    monkeypatch.setenv("SHAFTFEM_CACHE", str(bad))
    scene, out = "plain_cylinder", []
    if command == "design":  # an installed shaft: the design solves it free-free too
        from test_installed import INSTALLED_TOML

        scene = tmp_path / "installed.toml"
        scene.write_text(INSTALLED_TOML)
        out = ["--out", str(tmp_path / "out")]
        monkeypatch.setattr("shaftfem.outputs.render.render_into", lambda *a, **k: [])
    extra = ["--mesh-size", "16", "-q"]
    assert main([command, str(scene), "--no-cache", *out, *extra]) == 0
    assert bad.read_text() == "x"
    empty = tmp_path / "empty-cache"
    empty.mkdir()
    monkeypatch.setenv("SHAFTFEM_CACHE", str(empty))
    assert main([command, str(scene), "--no-cache", *out, *extra]) == 0
    assert list(empty.iterdir()) == []


def test_a_smaller_run_removes_the_files_of_the_larger_one_before(tmp_path):
    """A 12-mode export, then a 10-mode one into the same folder: mode_11 and mode_12
    are gone, and the manifest vouches for exactly what is there."""
    from shaftfem.outputs.export import MANIFEST
    from shaftfem.store import manifest_complete

    out = tmp_path / "out"
    assert main(["export", "plain_cylinder", "--out", str(out), "--modes", "12", *QUICK]) == 0
    assert (out / "mode_12.vtu").exists()
    (out / "mine.txt").write_text("a file of the user's")
    assert main(["export", "plain_cylinder", "--out", str(out), "--modes", "10", *QUICK]) == 0
    assert not (out / "mode_11.vtu").exists() and not (out / "mode_12.vtu").exists()
    assert (out / "mode_10.vtu").exists() and (out / "mine.txt").exists()
    listed = json.loads((out / MANIFEST).read_text())["files"]
    assert "mode_11.vtu" not in listed and manifest_complete(out, MANIFEST)


def test_a_run_interrupted_before_publishing_leaves_no_folder(tmp_path, capsys, monkeypatch):
    from shaftfem.outputs import export

    def interrupted(*_a, **_k):
        raise KeyboardInterrupt

    monkeypatch.setattr(export, "write_mode_files", interrupted)
    out = tmp_path / "out"
    assert main(["export", "plain_cylinder", "--out", str(out), *QUICK]) == 130
    assert not out.exists()


def test_a_scene_with_a_byte_order_mark_is_read(tmp_path):
    from shaftfem.scene.load import GEOMETRY_DIR, load_scene, read_scene_text

    f = tmp_path / "bom.toml"
    f.write_bytes(b"\xef\xbb\xbf" + (GEOMETRY_DIR / "plain_cylinder.toml").read_bytes())
    assert load_scene(f).shaft.length == load_scene("plain_cylinder").shaft.length
    assert not read_scene_text(f).text.startswith("\ufeff")


def test_a_sweep_whose_scheduler_never_answers_leaves_nothing(tmp_path, capsys, monkeypatch):
    from shaftfem.workflows import sweep as sweeping

    monkeypatch.setattr(sweeping, "CONNECT_TIMEOUT", "1s")   # the port refuses at once
    f = tmp_path / "sweep.toml"
    f.write_text('base = "plain_cylinder"\nmesh_size_mm = 16.0\n[axes]\n'
                 '"shaft.length_mm" = [500.0]\n')
    out = tmp_path / "out"
    assert main(["sweep", str(f), "--out", str(out), "--scheduler", "tcp://127.0.0.1:9",
                 "-q"]) == 3
    assert "no Dask scheduler answers" in capsys.readouterr().err
    assert not out.exists()                       # no lock file, key or empty folder


METRES = """name = "in_metres"
[shaft]
length_mm = 0.6
diameter_mm = 0.04
[material]
name = "steel"
youngs_modulus_mpa = 210000.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0
[mesh]
element_size_mm = 0.01
"""


def test_a_shaft_given_in_metres_is_solved_with_warnings_naming_the_unit(tmp_path, capsys):
    """0.6 m x 40 mm typed into the mm keys as metres: it solves (nothing in it is
    invalid), and stderr says twice that lengths are in mm: for the 0.6 mm length, and
    for the first frequency of some 500 kHz that follows from it."""
    f = tmp_path / "in_metres.toml"
    f.write_text(METRES)
    assert main(["modes", str(f), "--no-estimate", "--modes", "2", "-q"]) == 0
    err = capsys.readouterr().err
    warnings = [line for line in err.splitlines() if line.startswith("shaftfem: warning:")]
    assert len(warnings) == 2, err
    assert "0.6 mm long: lengths are in mm" in warnings[0] and "metres" in warnings[0]
    assert "kHz" in warnings[1] and "lengths are in mm" in warnings[1]


def test_a_shaft_in_mm_gives_no_plausibility_warning(capsys):
    assert main(["modes", "plain_cylinder", "--mesh-size", "16", "--no-estimate", "-q"]) == 0
    assert "warning" not in capsys.readouterr().err
