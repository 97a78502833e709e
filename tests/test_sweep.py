"""Design sweeps on Dask: same results as one by one, resumable, failures recorded."""

import os
import signal
import subprocess
import sys
import time

import pytest

from shaftfem.outputs.plots import sweep_plots
from shaftfem.workflows.sweep import read_results, run_sweep, run_variant, variant_id
from shaftfem.workflows.sweep_file import load_sweep

SWEEP = """
base = "plain_cylinder"
mesh_size_mm = 16.0
[axes]
"shaft.length_mm" = [500.0, 550.0, 600.0]
"shaft.diameter_mm" = [30.0, 32.0]
"""


@pytest.fixture()
def sweep_file(tmp_path):
    f = tmp_path / "sweep.toml"
    f.write_text(SWEEP)
    return f


def test_two_workers_give_the_same_results_as_one_by_one(sweep_file, tmp_path):
    sweep = load_sweep(sweep_file)
    assert len(sweep.variants) == 6
    rows = run_sweep(sweep, tmp_path / "results.csv", workers=2)
    assert len(rows) == 6 and all(r["status"] == "ok" for r in rows)
    pics = sweep_plots(rows, sweep.parameters, sweep.n_modes, tmp_path)
    assert len(pics) == 3 and all(p.stat().st_size > 10_000 for p in pics)
    assert len({r["worker_pid"] for r in rows}) == 2  # really two processes
    by_id = {r["id"]: r for r in rows}
    for v in sweep.variants:
        alone = run_variant(sweep.base, v, sweep.mesh_size_mm)
        row = by_id[variant_id(v)]
        for i in range(1, 11):
            a, b = float(row[f"f{i}_hz"]), alone[f"f{i}_hz"]
            assert abs(a / b - 1) < 1e-10


def _released(lock, within=5.0):
    """Wait until no process holds the sweep's lock (the killed command's process group
    ends within 0.1 s of its parent: shaftfem.supervise)."""
    import fcntl

    deadline = time.time() + within
    while lock.exists() and time.time() < deadline:
        with open(lock, "a") as fh:
            try:
                fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
                return
            except BlockingIOError:
                time.sleep(0.05)
    assert not lock.exists() or time.time() < deadline, "the killed sweep still holds its lock"


# killed after two rows: what was made is kept (the default run); killed before any row
# (slow: the same resume from an empty results file)
@pytest.mark.parametrize("kill_after_rows", [pytest.param(0, marks=pytest.mark.slow), 2])
def test_a_killed_sweep_resumes_without_recomputing(sweep_file, tmp_path, kill_after_rows):
    """SIGKILL as soon as the sweep holds its folder (no row yet) and after two rows: the
    resumed sweep has every variant once, one header, and keeps the rows made before."""
    results = tmp_path / "out" / "results.csv"
    cmd = [sys.executable, "-m", "shaftfem", "sweep", str(sweep_file), "--out",
           str(results.parent), "--workers", "1", "-q"]
    p = subprocess.Popen(cmd, start_new_session=True, stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    started = results.parent / ".sweep-tmp"
    while time.time() < deadline and not (
            started.exists() if kill_after_rows == 0
            else len(read_results(results)) >= kill_after_rows):
        time.sleep(0.05)
    os.killpg(p.pid, signal.SIGKILL)  # the command; its sweep and Dask workers follow it
    p.wait()
    _released(results.parent / ".sweep.lock")
    before = read_results(results)
    assert kill_after_rows <= len(before) < 6, len(before)
    text_before = results.read_text() if results.exists() else ""
    rows = run_sweep(load_sweep(sweep_file), results, workers=1)
    assert len(rows) == 6 and len({r["id"] for r in rows}) == 6
    lines = results.read_text().splitlines()
    assert len(lines) == 7 and sum(line.startswith("id,") for line in lines) == 1
    assert not started.exists()  # the workers' temp folder is gone
    # the rows computed before the kill are kept as they were, not recomputed
    complete = text_before[: text_before.rfind("\n") + 1]
    assert results.read_text().startswith(complete)
    assert [r["id"] for r in rows[: len(before)]] == [r["id"] for r in before]


def test_a_variant_that_fails_in_the_run_is_recorded_and_the_rest_finish(tmp_path):
    """A DOF budget of 1000 (an integer key swept as a number) passes the scene checks
    but not the run's budget check: that variant is recorded with its error."""
    f = tmp_path / "sweep.toml"
    # a short shaft with one grooved cell keeps the good variant's CAD build to seconds
    short = '"shaft.length_mm" = 120.0, "grooves.grooved_length_mm" = 40.0'
    f.write_text('base = "paper2018"\nmesh_size_mm = 16.0\n'
                 f'points = [{{"mesh.max_dofs" = 400000, {short}}}, '
                 f'{{"mesh.max_dofs" = 1000, {short}}}]\n')
    rows = run_sweep(load_sweep(f), tmp_path / "results.csv", workers=2)
    status = {float(r["mesh.max_dofs"]): r for r in rows}
    assert status[400000.0]["status"] == "ok"
    assert status[1000.0]["status"] == "failed"
    assert "budget" in status[1000.0]["error"]


@pytest.mark.parametrize("axis", ['"grooves.depth_mm" = [2.0, 16.0]',      # deeper than r
                                  '"grooves.depth_mm" = [3.0, -1.0]',
                                  '"shaft.length_mm" = [500.0, 100.0]'])   # grooves too long
def test_a_bad_axis_value_is_refused_at_load_naming_the_variant(tmp_path, capsys, axis):
    from shaftfem.cli import main
    from shaftfem.errors import SceneError

    f = tmp_path / "bad.toml"
    f.write_text(f'base = "paper2018"\n[axes]\n{axis}\n')
    with pytest.raises(SceneError, match=r"bad.toml: variant 2 \(.*\): paper2018.toml: "):
        load_sweep(f)
    out = tmp_path / "out"
    assert main(["sweep", str(f), "--out", str(out), "-q"]) == 2
    err = capsys.readouterr().err
    assert "variant 2" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()                          # refused before anything is written


def test_an_installed_sweep_with_a_seat_past_the_end_is_refused_at_load(tmp_path):
    from shaftfem.errors import SceneError

    f = tmp_path / "seat.toml"
    f.write_text('base = "paper2018_installed"\n[axes]\n"support[1].position_mm" = [525.0, 600.0]\n')
    with pytest.raises(SceneError, match=r"variant 2 \(support\[1\].position_mm = 600\)"):
        load_sweep(f)


@pytest.mark.parametrize("axes,count", [
    ('"shaft.length_mm" = {start = 500, stop = 600, num = 1000}\n'
     '"shaft.diameter_mm" = {start = 30, stop = 34, num = 1000}\n'
     '"grooves.depth_mm" = {start = 2, stop = 4, num = 1000}', "1,000,000,000"),
    ('"shaft.length_mm" = {start = 500, stop = 600, num = 101}\n'
     '"shaft.diameter_mm" = {start = 30, stop = 34, num = 100}', "10,100"),
])
def test_a_grid_beyond_the_cap_is_refused_with_its_count(tmp_path, axes, count):
    from shaftfem.errors import SceneError

    f = tmp_path / "big.toml"
    f.write_text(f'base = "plain_cylinder"\n[axes]\n{axes}\n')
    with pytest.raises(SceneError, match=f"make {count} variants; at most 10,000"):
        load_sweep(f)


def test_integer_keys_sweep_as_numbers(tmp_path):
    """modes.count and mesh.order given as 4.0 (sweep axes carry floats) are integers."""
    f = tmp_path / "ints.toml"
    f.write_text('base = "plain_cylinder"\nmesh_size_mm = 16.0\n[axes]\n'
                 '"modes.count" = [4, 6]\n"mesh.order" = [1, 2]\n')
    sweep = load_sweep(f)
    assert len(sweep.variants) == 4
    row = run_variant(sweep.base, {"modes.count": 4.0, "mesh.order": 1.0}, 16.0, n_modes=4)
    assert row["status"] == "ok", row["error"]
    assert "f4_hz" in row and "f5_hz" not in row


def test_a_folder_of_another_sweep_is_refused_and_the_same_sweep_resumes(sweep_file, tmp_path,
                                                                          capsys):
    """Rows are keyed by the base scene, mesh size, parameters and mode count: a sweep
    into a folder holding another's rows is refused (exit 2), not served stale rows; the
    same sweep with a value added to an axis runs only the new variants."""
    from shaftfem.cli import main
    from shaftfem.errors import SceneError

    out = tmp_path / "out"
    one = tmp_path / "one.toml"
    one.write_text(SWEEP.replace("[500.0, 550.0, 600.0]", "[500.0]").replace("[30.0, 32.0]",
                                                                           "[32.0]"))
    rows = run_sweep(load_sweep(one), out / "results.csv", workers=1)
    assert len(rows) == 1 and rows[0]["status"] == "ok"
    others = {"mesh": SWEEP.replace("mesh_size_mm = 16.0", "mesh_size_mm = 14.0"),
              "base": SWEEP.replace('base = "plain_cylinder"', 'base = "paper2018"'),
              "axis": 'base = "plain_cylinder"\nmesh_size_mm = 16.0\n[axes]\n'
                      '"shaft.diameter_mm" = [32.0]\n'}
    for what, text in others.items():
        f = tmp_path / f"{what}.toml"
        f.write_text(text.replace("[500.0, 550.0, 600.0]", "[500.0]").replace(
            "[30.0, 32.0]", "[32.0]") if what != "axis" else text)
        with pytest.raises(SceneError, match="holds the rows of another sweep"):
            run_sweep(load_sweep(f), out / "results.csv", workers=1)
        assert main(["sweep", str(f), "--out", str(out), "-q"]) == 2, what
        assert "holds the rows of another sweep" in capsys.readouterr().err
    assert len(read_results(out / "results.csv")) == 1      # untouched
    more = tmp_path / "more.toml"
    more.write_text(SWEEP.replace("[500.0, 550.0, 600.0]", "[500.0, 550.0]").replace(
        "[30.0, 32.0]", "[32.0]"))
    rows = run_sweep(load_sweep(more), out / "results.csv", workers=1)
    assert len(rows) == 2 and rows[0] == read_results(out / "results.csv")[0]


def test_a_variant_keeps_no_mode_shapes_but_a_single_run_does(tmp_path, monkeypatch):
    """A sweep solves each design once: its variants leave no kept solve in the cache
    (7 MB a design at the default mesh), where the same design run alone keeps one."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes

    monkeypatch.setenv("SHAFTFEM_CACHE", str(tmp_path / "cache"))
    row = run_variant("plain_cylinder", {"modes.count": 4.0}, 16.0, n_modes=4)
    assert row["status"] == "ok", row["error"]
    assert not list((tmp_path / "cache" / "solves").glob("*.npz"))
    run_modes(with_modes(with_mesh(load_scene("plain_cylinder"), 16.0), count=4))
    assert len(list((tmp_path / "cache" / "solves").glob("*.npz"))) == 1


@pytest.mark.slow
def test_an_overhang_sweep_of_a_turning_pump_resumes_after_a_kill(tmp_path):
    """examples/overhang_sweep.toml: 12 positions of the overhung impeller on two Dask
    workers, killed after three rows and resumed: each variant once, its critical speeds,
    margin and unbalance peak; the further out the impeller, the lower both critical
    speeds, the smaller the margin from the running speed and the larger the peak (a
    longer, softer overhang); the critical speeds drawn against the overhang."""
    from pathlib import Path

    _overhang_sweep(Path(__file__).resolve().parents[1] / "examples" / "overhang_sweep.toml",
                    tmp_path / "out", 12, 3)


@pytest.mark.slow
def test_a_shorter_overhang_sweep_resumes_after_a_kill(tmp_path):
    """The fast twin of the one above: the example's sweep over 3 of its positions,
    killed after one row."""
    from pathlib import Path

    examples = Path(__file__).resolve().parents[1] / "examples"
    text = (examples / "overhang_sweep.toml").read_text()
    assert "num = 12" in text and 'base = "overhung_pump.toml"' in text
    sweep_file = tmp_path / "overhang_sweep.toml"
    sweep_file.write_text(text.replace("num = 12", "num = 3").replace(
        'base = "overhung_pump.toml"', f'base = "{(examples / "overhung_pump.toml").as_posix()}"'))
    _overhang_sweep(sweep_file, tmp_path / "out", 3, 1)


def _overhang_sweep(sweep_file, out, n: int, killed_after: int) -> None:
    p = subprocess.Popen([sys.executable, "-m", "shaftfem", "sweep", str(sweep_file), "--out",
                          str(out), "--workers", "2", "-q"], start_new_session=True,
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 300
    while time.time() < deadline and len(read_results(out / "results.csv")) < killed_after:
        time.sleep(0.05)
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    _released(out / ".sweep.lock")
    before = read_results(out / "results.csv")
    assert killed_after <= len(before) < n
    sweep = load_sweep(sweep_file)
    rows = run_sweep(sweep, out / "results.csv", workers=2)
    assert len(rows) == n and len({r["id"] for r in rows}) == n
    assert all(r["status"] == "ok" for r in rows), [r["error"] for r in rows]
    rows.sort(key=lambda r: float(r["attachment[0].position_mm"]))
    for key, sign in (("crit1_rpm", -1), ("crit2_rpm", -1), ("critical_margin", -1),
                      ("unbalance_peak_um", 1)):
        values = [float(r[key]) for r in rows]
        assert all(sign * (b - a) > 0 for a, b in zip(values, values[1:])), (key, values)
    pics = sweep_plots(rows, sweep.parameters, sweep.n_modes, out)
    plot = out / "critical_speeds_vs_attachment0_position_mm.png"
    assert plot in pics and plot.stat().st_size > 10_000
