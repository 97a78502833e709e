"""A run-up through the critical speeds (shaftfem.workflows.runup): against
ross-rotordynamics 2.3's Newmark run of the same rotor at the same acceleration
(tests/data/ross_rotors.json, benchmarks/ross_reference.py --runup), against the steady
response when slow, and Lewis's finding that a fast passage peaks lower and later."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from shaftfem.scene.load import load_scene
from shaftfem.workflows.runup import run_run_up

ROSS = json.loads((Path(__file__).parent / "data" / "ross_rotors.json").read_text())["runup"]


def rotor() -> dict:
    """Friswell's 5.9.1 with 2 N s/mm in each bearing, 100 g mm at the 350 mm disk."""
    from test_rotor import ends, friswell, two_disks

    data = friswell(ends(kxx_n_per_mm=1000.0,
                         cxx_n_s_per_mm=ROSS["bearing_damping_n_s_per_m"] / 1e3), two_disks(),
                    {"speed_rpm": 1000.0, "max_speed_rpm": 1400.0, "campbell_points": 2})
    data["unbalance"] = [{"name": "disk 2", "position_mm": 1000.0,
                          "amount_g_mm": ROSS["unbalance_kg_m"] * 1e6}]
    return data


def test_a_run_up_against_ross_peaks_lower_and_later_than_steady():
    """500 to 1,300 r/min at 100 r/min per s: the peak's radius and speed within 2 % of
    ross's run of the same rotor; both lower than the steady peak and past its speed."""
    r = run_run_up(load_scene(rotor()), ROSS["start_rpm"], ROSS["stop_rpm"],
                   ROSS["accel_rpm_per_s"])
    speed, radius = r.peaks[0]
    assert radius == pytest.approx(ROSS["peak_radius_m"], rel=0.02)
    assert speed == pytest.approx(ROSS["peak_speed_rpm"], rel=0.02)
    steady = r.steady[0]
    assert radius < 0.95 * steady.max()
    assert speed > r.speeds_rpm[int(np.argmax(steady))]


def test_a_slow_run_up_is_the_steady_response_and_a_coast_down_peaks_early():
    """At 2 r/min per s the peak is the steady one within 1 % (radius and speed); coasting
    down fast, it comes below the steady peak's speed."""
    scene = load_scene(rotor())
    slow = run_run_up(scene, 760.0, 920.0, 2.0, steps_per_turn=50)
    steady = slow.steady[0]
    i = int(np.argmax(steady))
    assert slow.peaks[0][1] == pytest.approx(steady[i], rel=0.01)
    assert slow.peaks[0][0] == pytest.approx(slow.speeds_rpm[i], rel=0.01)
    down = run_run_up(scene, 1100.0, 600.0, -100.0, steps_per_turn=50)
    assert down.peaks[0][0] < slow.speeds_rpm[i]
    assert down.peaks[0][1] < steady[i]


@pytest.mark.slow
def test_a_run_up_in_the_turning_frame_is_the_stationary_frame_s():
    """The same rotor of revolution with its bearings half as stiff along y as along x
    (so periodic in the turning frame), run up in the frame turning with the shaft
    (the bearings turned at twice its angle, the unbalance standing still, the Euler
    force of the acceleration) and in the stationary frame: two frames, one answer. The
    peaks' radii and speeds, and the steady responses' largest, agree within 0.5 %
    (the mesh is never exactly round)."""
    runs = {}
    for frame in ("stationary", "rotating"):
        data = rotor()
        for s in data["support"]:
            s["kyy_n_per_mm"] = 0.5 * s["kxx_n_per_mm"]
        data["rotor"]["frame"] = frame
        runs[frame] = run_run_up(load_scene(data), ROSS["start_rpm"], ROSS["stop_rpm"],
                                 ROSS["accel_rpm_per_s"])
    a, b = runs["stationary"], runs["rotating"]
    (sa, ra), (sb, rb) = a.peaks[0], b.peaks[0]
    assert rb == pytest.approx(ra, rel=0.005)
    assert sb == pytest.approx(sa, rel=0.005)
    assert b.steady[0].max() == pytest.approx(a.steady[0].max(), rel=0.005)
