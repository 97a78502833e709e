"""Design sweeps on Dask: same results as one by one, resumable, failures recorded."""

import os
import signal
import subprocess
import sys
import time

import pytest

from shaftfem.plots import sweep_plots
from shaftfem.sweep import load_sweep, read_results, run_sweep, run_variant, variant_id

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


@pytest.mark.parametrize("kill_after_rows", [0, 2])
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
    os.killpg(p.pid, signal.SIGKILL)  # the sweep and its Dask workers, mid-run
    p.wait()
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


def test_an_impossible_variant_is_recorded_and_the_rest_finish(tmp_path):
    f = tmp_path / "sweep.toml"
    # 16.0 mm deep grooves in a 32 mm shaft: deeper than the radius allows (a short shaft
    # with one grooved cell keeps the good variant's CAD build to seconds)
    short = '"shaft.length_mm" = 120.0, "grooves.grooved_length_mm" = 40.0'
    f.write_text('base = "paper2018"\nmesh_size_mm = 16.0\n'
                 f'points = [{{"grooves.depth_mm" = 2.0, {short}}}, '
                 f'{{"grooves.depth_mm" = 16.0, {short}}}]\n')
    rows = run_sweep(load_sweep(f), tmp_path / "results.csv", workers=2)
    status = {float(r["grooves.depth_mm"]): r for r in rows}
    assert status[2.0]["status"] == "ok"
    assert status[16.0]["status"] == "failed"
    assert "grooves.depth_mm" in status[16.0]["error"]
