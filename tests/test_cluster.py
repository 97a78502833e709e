"""A sweep on a real Dask cluster: a scheduler and two workers started as separate
processes (`dask scheduler`, `dask worker`), which cannot see the user's files."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from shaftfem.errors import ClusterError
from shaftfem.scene.load import GEOMETRY_DIR
from shaftfem.workflows.sweep import run_sweep, run_variant, variant_id
from shaftfem.workflows.sweep_file import load_sweep

DASK = str(Path(sys.executable).with_name("dask"))


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """The scheduler's address; the workers run in a folder of their own."""
    home = tmp_path_factory.mktemp("cluster")
    info = home / "scheduler.json"
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    procs = [subprocess.Popen([DASK, "scheduler", "--scheduler-file", str(info), "--port", "0",
                               "--no-dashboard"], cwd=home, env=env, start_new_session=True,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    deadline = time.time() + 60
    while not info.exists() and time.time() < deadline:
        time.sleep(0.2)
    for _ in range(2):
        procs.append(subprocess.Popen(
            [DASK, "worker", "--scheduler-file", str(info), "--nthreads", "1",
             "--no-dashboard"], cwd=home, env=env, start_new_session=True,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    import json

    yield json.loads(info.read_text())["address"]
    for p in procs:
        os.killpg(p.pid, signal.SIGTERM)
    for p in procs:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)


def _user_sweep(folder: Path) -> Path:
    """The user's own scene (not a shipped one) and a sweep of it, in the user's folder."""
    folder.mkdir()
    (folder / "my_shaft.toml").write_text(
        (GEOMETRY_DIR / "plain_cylinder.toml").read_text().replace('name = "plain_cylinder"',
                                                                   'name = "my_shaft"'))
    (folder / "sweep.toml").write_text('base = "my_shaft.toml"\nmesh_size_mm = 16.0\n'
                                       '[axes]\n"shaft.length_mm" = [500.0, 560.0]\n'
                                       '"shaft.diameter_mm" = [30.0, 34.0]\n')
    return folder / "sweep.toml"


def test_a_sweep_runs_where_the_scene_file_is_not(cluster, tmp_path):
    import shutil

    sweep = load_sweep(_user_sweep(tmp_path / "user"))
    local = {variant_id(v): run_variant(sweep.base, v, sweep.mesh_size_mm)
             for v in sweep.variants}
    shutil.rmtree(tmp_path / "user")  # nobody can read the scene file now
    rows = run_sweep(sweep, tmp_path / "out" / "results.csv", scheduler=cluster)
    assert len(rows) == 4 and all(r["status"] == "ok" for r in rows), rows
    assert len({r["worker_pid"] for r in rows} - {str(os.getpid())}) >= 1  # not done here
    for r in rows:
        for i in range(1, sweep.n_modes + 1):
            assert abs(float(r[f"f{i}_hz"]) / local[r["id"]][f"f{i}_hz"] - 1) < 1e-10


def test_workers_of_another_version_are_refused(cluster, tmp_path, monkeypatch):
    import shaftfem

    sweep = load_sweep(_user_sweep(tmp_path / "user"))
    monkeypatch.setattr(shaftfem, "__version__", "0.0.0-other")
    with pytest.raises(ClusterError, match="another shaftfem than this one"):
        run_sweep(sweep, tmp_path / "out" / "results.csv", scheduler=cluster)


def test_no_scheduler_is_a_clear_error(tmp_path, monkeypatch):
    from shaftfem.workflows import sweep as sweeping

    monkeypatch.setattr(sweeping, "CONNECT_TIMEOUT", "1s")   # the port refuses at once
    sweep = load_sweep(_user_sweep(tmp_path / "user"))
    with pytest.raises(ClusterError, match="no Dask scheduler answers"):
        run_sweep(sweep, tmp_path / "out" / "results.csv", scheduler="tcp://127.0.0.1:9")


@pytest.mark.slow
def test_a_calibration_grid_runs_on_the_cluster_without_the_scene_file(cluster, tmp_path):
    import shutil

    import numpy as np

    from shaftfem.workflows.calibrate import calibrate, load_calibration
    from shaftfem.workflows.sweep import read_results

    folder = tmp_path / "user"
    _user_sweep(folder)
    hidden = run_variant(str(folder / "my_shaft.toml"), {"shaft.length_mm": 537.0}, 16.0)
    # targets are the first modes in order (the cylinder's modes 1-2 are one bending pair)
    targets = ", ".join(f"{hidden[f'f{i}_hz']:.6f}" for i in (1, 2, 3, 4))
    (folder / "cal.toml").write_text(
        'base = "my_shaft.toml"\nmesh_size_mm = 16.0\ngrid = 2\n'
        '[unknowns]\n"shaft.length_mm" = {min = 500.0, max = 600.0}\n'
        f'[targets]\nfrequencies_hz = [{targets}]\nuncertainty_percent = 0.1\n')
    cal = load_calibration(folder / "cal.toml")  # reads the scene's content now
    shutil.rmtree(folder)
    res = calibrate(cal, tmp_path / "out", scheduler=cluster)
    assert abs(res.parameters["shaft.length_mm"] / 537.0 - 1) < 0.01
    grid = read_results(tmp_path / "out" / "grid.csv")
    assert len(grid) == 2 and all(r["status"] == "ok" for r in grid)
    assert str(os.getpid()) not in {r["worker_pid"] for r in grid}
    assert np.isfinite(res.chi2)
