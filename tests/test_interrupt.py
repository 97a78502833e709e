"""Ctrl-C stops `shaftfem design` within a second at any step, publishes nothing, and
the next run is correct. Ctrl-C is sent as a terminal sends it: SIGINT to the
command's process group."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from shaftfem.scene.load import GEOMETRY_DIR

# (progress line that starts the step, seconds into it): CAD, meshing, the solve, the
# bound's coarser mesh, the pictures being made in another process, export
ASIDE = "pictures, beside the run"
QUICK_POINTS = [("building the shaft's solid", 1.0), ("DOFs; factorising", 0.1),
                (ASIDE, 1.0)]
ALL_POINTS = [("building the shaft's solid", 0.2), ("building the shaft's solid", 2.0),
              ("CAD done", 0.05), ("DOFs; factorising", 0.05), ("DOFs; factorising", 0.4),
              ("error estimate", 0.1), ("error estimate", 0.6),
              ("the mode table and the solid", 0.05), (ASIDE, 0.3), (ASIDE, 3.0)]


@pytest.fixture(scope="module")
def short_scene(tmp_path_factory):
    """The paper's shaft, 200 mm long with one pitch of grooves: its CAD takes seconds."""
    text = (GEOMETRY_DIR / "paper2018.toml").read_text()
    text = text.replace("length_mm = 545.0", "length_mm = 200.0").replace(
        "grooved_length_mm = 360.0", "grooved_length_mm = 80.0").replace(
        'name = "paper2018"', 'name = "short"')
    f = tmp_path_factory.mktemp("scene") / "short.toml"
    f.write_text(text)
    return f


def _design(scene: Path, out: Path, cache: Path) -> subprocess.Popen:
    # work beside the run on, as a user's run has it (one of the points is in it)
    env = dict(os.environ, SHAFTFEM_CACHE=str(cache), SHAFTFEM_ASIDE="1")
    env.pop("SHAFTFEM_NO_SUPERVISOR", None)
    return subprocess.Popen([sys.executable, "-m", "shaftfem", "design", str(scene),
                             "--mesh-size", "16", "--out", str(out)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, env=env)


def _interrupt_at(scene, out, cache, marker, delay):
    """Run design, send Ctrl-C `delay` s after `marker` shows: (exit code, seconds from
    Ctrl-C to exit, stderr)."""
    p = _design(scene, out, cache)
    seen = []
    for line in p.stderr:
        seen.append(line)
        if marker in line:
            time.sleep(delay)
            break
    else:
        p.wait()
        raise AssertionError(f"{marker!r} never showed: {''.join(seen)}")
    t = time.perf_counter()
    os.killpg(p.pid, signal.SIGINT)
    code = p.wait(timeout=30)
    elapsed = time.perf_counter() - t
    while time.perf_counter() - t < 5:   # every process of the run ends with it
        try:
            os.killpg(p.pid, 0)
        except ProcessLookupError:
            break
        time.sleep(0.05)
    else:
        raise AssertionError(f"a process of the run outlived it, Ctrl-C {delay} s after "
                             f"{marker!r}: {_group(p.pid)}")
    return code, elapsed, "".join(seen) + p.stderr.read()


def _group(pgid: int) -> list[str]:
    """The processes still in the process group: pid, state and command line (what a
    failure should name)."""
    import psutil

    out = []
    for proc in psutil.process_iter(["pid", "status", "cmdline"]):
        try:
            if os.getpgid(proc.info["pid"]) == pgid:
                out.append(f"{proc.info['pid']} {proc.info['status']} "
                           f"{' '.join(proc.info['cmdline'] or [])[:200]}")
        except (ProcessLookupError, psutil.Error):
            pass
    return out


def _check(scene, tmp_path, points):
    cache = tmp_path / "cache"
    for i, (marker, delay) in enumerate(points):
        out = tmp_path / f"out{i}"
        code, elapsed, err = _interrupt_at(scene, out, cache, marker, delay)
        print(f"  Ctrl-C {delay:g} s after {marker!r}: exit {code} in {elapsed:.2f} s")
        assert code == 130, err
        assert elapsed < 2.0, (marker, delay, elapsed)
        assert err.strip().splitlines()[-1] == "shaftfem: interrupted; nothing was published"
        assert "Traceback" not in err
        assert not out.exists(), (marker, list(out.rglob("*")))   # nothing published
    # the next run, on the cache the interrupted ones left, is complete and right
    out = tmp_path / "done"
    p = _design(scene, out, cache)
    err = p.stderr.read()
    assert p.wait() == 0, err
    from shaftfem.store import manifest_complete
    from shaftfem.workflows.design import MANIFEST

    assert manifest_complete(out, MANIFEST)
    fresh = subprocess.run([sys.executable, "-m", "shaftfem", "modes", str(scene),
                            "--mesh-size", "16", "--no-cache", "--no-estimate", "-q",
                            "--json", str(tmp_path / "fresh.json")], capture_output=True,
                           text=True, env=dict(os.environ, SHAFTFEM_CACHE=str(cache)))
    assert fresh.returncode == 0, fresh.stderr
    a = json.loads((out / "modes.json").read_text())["modes"]
    b = json.loads((tmp_path / "fresh.json").read_text())["modes"]
    assert [m["frequency_hz"] for m in a] == pytest.approx([m["frequency_hz"] for m in b],
                                                           rel=1e-9)


@pytest.mark.slow
def test_ctrl_c_stops_design_at_once_and_publishes_nothing(short_scene, tmp_path):
    _check(short_scene, tmp_path, QUICK_POINTS)


@pytest.mark.slow
def test_ctrl_c_at_ten_points_of_design(short_scene, tmp_path):
    _check(short_scene, tmp_path, ALL_POINTS)


@pytest.mark.parametrize("argv,code,stream,text", [
    (["--help"], 0, "stdout", "usage: shaftfem"),
    (["modes", "--bogus"], 2, "stderr", "unrecognized arguments: --bogus"),
    (["size", "no_such_scene"], 2, "stderr", "no_such_scene"),
])
def test_the_command_says_things_once(argv, code, stream, text):
    """The command's parent parses the command line only to know its output folders:
    help and errors are printed once, by the command itself."""
    p = subprocess.run([sys.executable, "-m", "shaftfem", *argv], capture_output=True,
                       text=True, timeout=120)
    assert p.returncode == code, p.stderr
    out = getattr(p, stream)
    assert out.count(text) == 1, out


def test_ctrl_c_stops_a_sweep_and_its_workers(tmp_path):
    """Ctrl-C during a sweep: exit 130 at once, no worker left running, the lock and
    the workers' temp folder gone; the rows written so far stay (a sweep resumes)."""
    import psutil

    f = tmp_path / "sweep.toml"
    f.write_text('base = "plain_cylinder"\nmesh_size_mm = 16.0\n[axes]\n'
                 '"shaft.length_mm" = [500.0, 520.0, 540.0, 560.0, 580.0, 600.0]\n')
    out = tmp_path / "out"
    p = subprocess.Popen([sys.executable, "-m", "shaftfem", "sweep", str(f), "--out", str(out),
                          "--workers", "2"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         text=True, start_new_session=True)
    for line in p.stderr:
        if "to run" in line:
            break
    time.sleep(1.0)
    family = psutil.Process(p.pid).children(recursive=True)
    assert len(family) >= 3, family       # the command's child and its two workers at least
    t = time.perf_counter()
    os.killpg(p.pid, signal.SIGINT)
    assert p.wait(timeout=30) == 130
    assert time.perf_counter() - t < 2.0
    gone, alive = psutil.wait_procs(family, timeout=2.0)
    assert not alive, alive
    assert not (out / ".sweep.lock").exists() and not (out / ".sweep-tmp").exists()


def test_a_stop_after_publishing_says_what_stands(tmp_path):
    """Ctrl-C after the command has published its files (a manifest-vouched set) and
    while it still works: the one line says what stands, not that nothing was
    published, and the files stay."""
    out = tmp_path / "out"
    script = f"""
import sys, time
from pathlib import Path
from shaftfem.store import staged_directory
from shaftfem.supervise import supervised

def run():
    with staged_directory({str(out)!r}, "manifest.json") as stage:
        (stage / "report.md").write_text("# done")
    print("published", flush=True)
    time.sleep(60)
    return 0

sys.exit(supervised(run, [Path({str(out)!r})]))
"""
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, start_new_session=True)
    assert p.stdout is not None and p.stdout.readline().strip() == "published"
    os.killpg(p.pid, signal.SIGINT)
    assert p.wait(timeout=30) == 130
    last = p.stderr.read().strip().splitlines()[-1]
    assert "nothing was published" not in last
    assert "2 files in" in last and str(out) in last, last
    assert (out / "report.md").read_text() == "# done"
