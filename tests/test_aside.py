"""Work put aside (shaftfem.aside): the same answer as done in line, its errors raised
in the run, and stopped with the run."""

import os
import time

import numpy as np
import pytest

from shaftfem.aside import Aside, aside_allowed
from shaftfem.errors import SceneError
from shaftfem.scene.load import load_scene


@pytest.fixture(autouse=True)
def _beside(monkeypatch):
    """Work beside the run on, as a user's run has it (tests/conftest.py turns it off in
    the suite's workers)."""
    monkeypatch.setenv("SHAFTFEM_ASIDE", "1")


def test_work_aside_gives_what_it_would_give_in_line():
    a = np.random.default_rng(1).normal(size=(60, 60))
    a = a @ a.T
    assert aside_allowed()   # not a daemon: the job goes to another process
    assert Aside(os.getpid).result() != os.getpid()
    assert np.array_equal(Aside(np.linalg.eigvalsh, a).result(), np.linalg.eigvalsh(a))


def test_work_aside_raises_its_error_in_the_run():
    job = Aside(load_scene, "no_such_scene_here")
    with pytest.raises(SceneError, match="no_such_scene_here"):
        job.result()


def test_work_aside_is_done_in_line_when_turned_off(monkeypatch):
    monkeypatch.setenv("SHAFTFEM_ASIDE", "0")
    assert not aside_allowed()
    assert Aside(os.getpid).result() == os.getpid()
    with pytest.raises(SceneError, match="no_such_scene_here"):
        Aside(load_scene, "no_such_scene_here").result()


def test_work_aside_stops_with_the_run():
    t = time.perf_counter()
    job = Aside(time.sleep, 30.0)
    process = job._process
    job.close()
    assert process.returncode is not None and time.perf_counter() - t < 10


def test_work_aside_past_its_time_is_stopped():
    t = time.perf_counter()
    job = Aside(time.sleep, 30.0)
    process = job._process
    with pytest.raises(TimeoutError, match="more than 1 s"):
        job.result(timeout=1.0)
    assert process.returncode is not None and time.perf_counter() - t < 10


def test_a_run_outlives_work_aside_stopped_while_handed_over():
    """gmsh sets SIGPIPE back to its default: a job of 32 MB stopped before the other
    process read it must not end the run that gave it (it used to, silently, exit 141)."""
    import subprocess
    import sys

    script = ("import gmsh, numpy as np\n"
              "from shaftfem.aside import Aside\n"
              "gmsh.initialize(readConfigFiles=False, interruptible=False)\n"
              "try:\n"
              "    Aside(np.sum, np.ones(4_000_000)).result(timeout=0.0)\n"
              "except TimeoutError:\n"
              "    print('stopped, and the run goes on')\n")
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    assert "the run goes on" in run.stdout


def test_a_waiting_process_takes_its_job_when_it_comes_and_ends_without_one():
    job = Aside.waiting("numpy", "no_such_module_at_all")   # a missing one is no matter
    assert job._process is not None and job._process.poll() is None
    a = np.arange(12.0).reshape(3, 4)
    job.start(np.linalg.norm, a)
    assert job.result() == np.linalg.norm(a)
    idle = Aside.waiting("numpy")
    process = idle._process
    idle.close()   # the run ended before its job came
    assert process.returncode is not None
