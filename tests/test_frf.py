"""The running machine's frequency response (shaftfem.workflows.frf): its static limit
against the static solution of the same shaft under a unit force (a separate solver
path: the full mesh, fem.static), its peaks at the whirl frequencies, and the command."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from shaftfem.scene.load import load_scene
from shaftfem.workflows.frf import run_frequency_response


def rotor() -> dict:
    """5.9.1 on 1 MN/m springs at 100 and 1,400 mm (0.5 N s/mm of damping for the whirl),
    weightless, a 1 N force along y at the 280 mm disk."""
    from test_rotor import friswell, two_disks

    def seat(name: str, z: float) -> dict:
        return {"name": name, "position_mm": z, "width_mm": 2.0, "kind": "bearing",
                "kxx_n_per_mm": 1000.0, "cxx_n_s_per_mm": 0.5}
    data = friswell([seat("left", 100.0), seat("right", 1400.0)], two_disks(),
                    {"speed_rpm": 3000.0, "max_speed_rpm": 3000.0, "campbell_points": 2})
    data["static"] = {"gravity_m_s2": 0.0}
    data["force"] = [{"position_mm": 500.0, "fy_n": 1.0}]
    return data


def test_the_static_limit_is_the_static_deflection_and_the_peaks_the_whirl():
    """At standstill and 1 mHz the receptance of the 350 mm disk's section to a force at
    the 280 mm disk's is the static deflection there under 1 N within 1e-4 (the cross
    term x-y vanishes); its first peak lies at the first whirl frequency within 0.5 %."""
    from shaftfem.workflows.campbell import run_campbell
    from shaftfem.workflows.static import run_static

    scene = load_scene(rotor())
    freqs = np.concatenate([[1e-3], np.linspace(5.0, 25.0, 401)])
    r = run_frequency_response(scene, 0.5, 1.0, freqs, np.array([0.0]))
    static = run_static(scene).solution.deflection_at(1.0)[1]
    assert abs(r.H[0, 0, 1, 1]) == pytest.approx(static, rel=1e-4)
    assert abs(r.H[0, 0, 0, 1]) < 1e-6 * abs(r.H[0, 0, 1, 1])
    first = min(w.frequency_hz for w in run_campbell(scene).whirl
                if w.speed_rpm == 0.0 and w.kind == "bending")
    peak = r.frequencies_hz[1:][int(np.argmax(np.abs(r.H[0, 1:, 1, 1])))]
    assert peak == pytest.approx(first, rel=0.005)


def test_frf_as_a_user_runs_it(tmp_path):
    path = tmp_path / "rotor.toml"
    load_scene(rotor()).to_toml(path)
    run = subprocess.run([sys.executable, "-m", "shaftfem", "frf", str(path), "-q",
                          "--at-mm", "1000", "--frequencies-hz", "1:60:60", "--speeds-rpm",
                          "0", "3000", "--out", str(tmp_path / "o"), "--json",
                          str(tmp_path / "f.json")], capture_output=True, text=True,
                         cwd=tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    data = json.loads((tmp_path / "f.json").read_text())
    assert [s["speed_rpm"] for s in data["speeds"]] == [0.0, 3000.0]
    assert len(data["speeds"][1]["hxx_um_per_n"]) == 60
    assert (tmp_path / "o" / "frf.png").stat().st_size > 10_000


@pytest.mark.slow
def test_a_shaft_of_revolution_in_anisotropic_bearings_has_one_receptance_in_either_frame():
    """The same rotor with its bearings half as stiff along y (and damped), solved in the
    stationary frame (constant: one solve a frequency) and in the frame turning with
    the shaft (periodic there: harmonic balance of the force turning backwards, read at
    the housing): across its resonances at 3,000 r/min, every receptance within 1e-6 of
    the largest (measured 1e-8)."""
    out = {}
    for frame in ("stationary", "rotating"):
        data = rotor()
        for s in data["support"]:
            s["kyy_n_per_mm"] = 0.5 * s["kxx_n_per_mm"]
        data["rotor"]["frame"] = frame
        out[frame] = run_frequency_response(load_scene(data), 0.35, 0.28,
                                            np.linspace(5.0, 60.0, 23), np.array([3000.0])).H
    a, b = out["stationary"], out["rotating"]
    assert np.abs(a - b).max() < 1e-6 * np.abs(a).max()
