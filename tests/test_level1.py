"""API 684's Level I stability screening (shaftfem.workflows.level1) against
ross-rotordynamics 2.3's run_level1 on Friswell's 5.9.1 rotor with damped bearings
(tests/data/ross_rotors.json, benchmarks/ross_reference.py --level1), API 617's
criteria on a stage's Wachel estimate, and the command as a user runs it."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from shaftfem.runtime import RunOptions
from shaftfem.scene.load import load_scene
from shaftfem.workflows.level1 import run_level1

ROSS = json.loads((Path(__file__).parent / "data" / "ross_rotors.json").read_text())["level1"]


def rotor(**rotor_keys) -> dict:
    from test_rotor import ends, friswell, two_disks

    return friswell(ends(kxx_n_per_mm=1000.0,
                         cxx_n_s_per_mm=ROSS["bearing_damping_n_s_per_m"] / 1e3),
                    two_disks(), {"speed_rpm": ROSS["speed_rpm"], "campbell_points": 2,
                                  **rotor_keys})


def test_q0_and_the_log_decrement_against_q_against_ross():
    """Q_0 within 2 % (0.7 % measured), and the log decrement at ross's five Q (0 to
    0.6 Q_0, where it is well off zero) each within 2 %."""
    r = run_level1(load_scene(rotor()), np.array(ROSS["q_n_per_m"]) / 1e3,
                   at_mm=ROSS["at_m"] * 1e3)
    assert r.q0 == pytest.approx(ROSS["q0_n_per_m"], rel=0.02)
    np.testing.assert_allclose(r.log_dec, ROSS["log_dec"], rtol=0.02)
    assert r.qa is None and r.passed is None        # no stage, no Q_A: no verdict


@pytest.mark.slow
def test_a_scene_solved_on_another_s_solve_keeps_its_own_parts(monkeypatch):
    """Two scenes on one pencil (the same shaft, seats and parts; in the first the 350 mm
    disk is a compressor stage): the second takes its standstill modes from the first's
    solve in this process, and its rotor model holds its own parts, not the other's
    stage: its Level I is the one it has solved on its own (with the stage's
    cross-coupling left in, Q_0 came out 10 % lower, and the suite's order decided which)."""
    import weakref

    from shaftfem.workflows import campbell, pipeline
    from test_rotor import ends, friswell, two_disks

    def in_a_new_process():   # nothing solved in this one yet
        monkeypatch.setattr(campbell, "_MODELS", {})
        monkeypatch.setattr(pipeline, "_SOLVED", weakref.WeakValueDictionary())

    q, at = np.array(ROSS["q_n_per_m"]) / 1e3, ROSS["at_m"] * 1e3
    in_a_new_process()
    alone = run_level1(load_scene(rotor()), q, at_mm=at)
    in_a_new_process()
    disks = two_disks()
    disks[1].update(stage_power_kw=1.0, stage_diameter_mm=350.0, stage_width_mm=20.0)
    campbell.turning(load_scene(friswell(ends(kxx_n_per_mm=1000.0, cxx_n_s_per_mm=2.0), disks,
                                         {"speed_rpm": 3000.0, "rated_speed_rpm": 3000.0,
                                          "campbell_points": 2})))
    after = run_level1(load_scene(rotor()), q, at_mm=at)
    assert "(stage)" not in " ".join(b.name for b in campbell._MODELS[
        campbell._model_keys(after.scene, RunOptions())[0]][1].bearings)
    assert after.q0 == pytest.approx(alone.q0, rel=1e-6)
    np.testing.assert_allclose(after.log_dec, alone.log_dec, rtol=1e-6)


@pytest.mark.slow
def test_api617_criteria_on_a_stage(monkeypatch):
    """A compressor stage on the 350 mm disk: Q_A is its Wachel estimate, Q is applied
    there; the screening passes when Q_0 / Q_A >= 2 and the log decrement at Q_A is at
    least 0.1, and fails (exit 1 of the command) otherwise. A stage's power does not make
    K or M: the second screening's standstill modes are refined from the first's solve
    (Lanczos does not run)."""
    from shaftfem.fem import eigen
    from test_rotor import ends, friswell, two_disks

    def scene(power_kw: float):
        disks = two_disks()
        disks[1].update(stage_power_kw=power_kw, stage_diameter_mm=350.0, stage_width_mm=20.0)
        return load_scene(friswell(ends(kxx_n_per_mm=1000.0, cxx_n_s_per_mm=2.0), disks,
                                   {"speed_rpm": 3000.0, "rated_speed_rpm": 3000.0,
                                    "campbell_points": 2}))
    small = run_level1(scene(1.0))
    assert small.plane == pytest.approx(1.0) and small.qa is not None
    assert small.ratio is not None and small.ratio >= 2 and small.log_dec_a >= 0.1
    assert small.passed
    monkeypatch.setattr(eigen, "eigsh", lambda *a, **k: pytest.fail("Lanczos ran"))
    large = run_level1(scene(small.q0 / small.qa * 1.0 / 1.5))   # Q_0 / Q_A = 1.5
    assert large.ratio == pytest.approx(1.5, rel=1e-3)
    assert large.passed is False


def test_level1_as_a_user_runs_it(tmp_path):
    """`shaftfem level1` with a Q_A: the table, Q_0 / Q_A in the JSON, the picture, and
    exit 1 where the criteria fail."""
    import subprocess
    import sys

    path = tmp_path / "rotor.toml"
    load_scene(rotor()).to_toml(path)
    run = subprocess.run([sys.executable, "-m", "shaftfem", "level1", str(path), "-q",
                          "--qa-n-per-mm", "2", "--at-mm", "750", "--out", str(tmp_path / "o"),
                          "--json", str(tmp_path / "l.json")],
                         capture_output=True, text=True, cwd=tmp_path)
    # the rotor's own log decrement, 0.056, is below API 617's 0.1 already: it fails
    assert run.returncode == 1, run.stderr[-2000:]
    assert "FAIL: a Level II analysis is required" in run.stdout
    data = json.loads((tmp_path / "l.json").read_text())
    assert data["q0_over_qa"] == pytest.approx(data["q0_n_per_mm"] / 2, rel=1e-9)
    assert (tmp_path / "o" / "level1.png").exists()
    # Q_A on the curve, and resolved: at least ten steps up to twice Q_A, however far
    # Q_0 lies beyond it
    q = np.array(data["q_n_per_mm"])
    assert np.any(np.isclose(q, 2.0)) and np.count_nonzero(q <= 4.0 + 1e-9) >= 11
    assert data["q0_n_per_mm"] > 4.0


@pytest.mark.slow
def test_check_screens_level1_when_the_scene_asks(tmp_path):
    """[rotor] level1 = true: `check` runs the screening and fails (exit 1) where API 617's
    criteria fail, saying so; without it the same rotor passes its check."""
    import subprocess
    import sys

    asked = tmp_path / "asked.toml"
    # at 1,500 r/min, clear of both critical speeds (826 and 2,760 r/min)
    load_scene(rotor(speed_rpm=1500.0, level1=True, level1_qa_n_per_mm=8.0)).to_toml(asked)
    plain = tmp_path / "plain.toml"
    load_scene(rotor(speed_rpm=1500.0)).to_toml(plain)
    runs = [subprocess.run([sys.executable, "-m", "shaftfem", "check", str(p), "-q"],
                           capture_output=True, text=True, cwd=tmp_path) for p in (asked, plain)]
    assert runs[0].returncode == 1, runs[0].stderr[-2000:]
    assert "Level I screening fails API 617's criteria" in runs[0].stdout
    assert runs[1].returncode == 0, runs[1].stdout[-2000:]


def test_design_leaves_level1_to_its_command_where_hill_spreads_wide():
    """A rotor periodic at its running speed (an asymmetric Jeffcott rotor in supports
    twice as stiff along x as along y): the slower it turns against the supports' split,
    the more harmonics its Floquet forms spread over (2 at 3,000 r/min, past HILL_MAX at
    30); there design leaves Level I, over a hundred more such solves, to `shaftfem level1`
    and says why. A round rotor's equations are constant: screened at any speed."""
    import math

    from shaftfem.fem.floquet import HILL_MAX, floquet_roots, harmonics_taken, widen
    from shaftfem.workflows.level1 import level1_too_slow
    from test_floquet import jeffcott

    taken = {}
    for rpm in (3000.0, 30.0):
        w = rpm * math.pi / 30
        model = widen(jeffcott(4e5, 2e5), (w,), 2)
        floquet_roots(model, w)
        taken[rpm] = harmonics_taken(model, w)
        said = level1_too_slow(model, w)
        assert (said is not None) == (taken[rpm] > HILL_MAX), (rpm, taken[rpm])
    assert taken[3000.0] <= HILL_MAX < taken[30.0]
    assert "`shaftfem level1`" in level1_too_slow(model, w)
    round_ = jeffcott(3e5, 3e5, k1=2e5, k2=2e5)
    assert not round_.periodic(w) and level1_too_slow(round_, w) is None
