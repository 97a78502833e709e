"""The undamped critical speed map (shaftfem.workflows.ucs) against ross-rotordynamics
2.3's run_ucs on two of Friswell's rotors (tests/data/ross_rotors.json, written by
benchmarks/ross_reference.py --ucs), against its two limits (bearings far stiffer
than the shaft: the shaft held at its seats; far softer: the free shaft), and as a
user runs it."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from shaftfem.scene.load import load_scene
from shaftfem.workflows.pipeline import run_modes
from shaftfem.workflows.ucs import run_ucs

_REFERENCE = json.loads((Path(__file__).parent / "data" / "ross_rotors.json").read_text())
ROSS, ROSS_SYNCHRONOUS = _REFERENCE["ucs"], _REFERENCE["ucs_synchronous"]


def rotor(name: str) -> dict:
    """Friswell's 5.9.1 (two disks between bearings at the ends) or 5.9.9 (bearings at
    0 and 1 m, the 350 mm disk overhung at the end, on the 2 mm there), as
    tests/test_rotor.py writes them."""
    from test_rotor import bearing, disk, ends, friswell, two_disks

    if name == "5.9.1":
        return friswell(ends(kxx_n_per_mm=1000.0), two_disks(), {"speed_rpm": 3000.0})
    return friswell([bearing(1.0, "left", kxx_n_per_mm=1e4),
                     bearing(1000.0, "right", kxx_n_per_mm=1e4)],
                    [{**disk(1465.0, 0.35, "disk"), "position_mm": 1499.0, "width_mm": 2.0}],
                    {"speed_rpm": 3000.0})


@pytest.mark.parametrize("kind", ["forward", "standstill"])
@pytest.mark.parametrize("name", ["5.9.1", "5.9.9"])
def test_every_branch_against_ross_over_four_decades(name, kind):
    """Four branches at 20 stiffnesses from 1e5 to 1e9 N/m, each within 1 % of ross's
    run_ucs: the synchronous map (synchronous=True; on the overhung 5.9.9 its third
    branch lies up to 2.7 times the standstill one) and the standstill map."""
    ks = np.array(ROSS["stiffness_n_per_m"])
    m = run_ucs(load_scene(rotor(name)), ks, kind=kind)
    ours = m.frequencies * 2 * math.pi
    theirs = np.array((ROSS_SYNCHRONOUS if kind == "forward" else ROSS)[name])
    assert ours.shape == theirs.shape
    np.testing.assert_allclose(ours, theirs, rtol=0.01)
    assert m.change < 1e-3


def test_the_bearings_cross_the_synchronous_map_at_the_campbell_s_critical_speeds():
    """5.9.9 on its 10 MN/m bearings, undamped and constant: where the bearings cross
    the synchronous forward map is where the Campbell diagram's forward whirl meets the
    1x line (found there directly, an eigenproblem in the speed squared), within
    0.5 %; the standstill map's crossing lies lower on this overhung disk."""
    from shaftfem.workflows.campbell import run_campbell

    scene = load_scene(rotor("5.9.9"))
    scene = replace(scene, rotor=replace(scene.rotor, max_speed=30000 * math.pi / 30,
                                         points=61))
    c = run_campbell(scene)
    forward = sorted(cs.speed_rpm for cs in c.critical_speeds
                     if cs.order == 1 and cs.whirl == "forward")
    m = run_ucs(scene, np.logspace(6, 8, 9))
    met = sorted({round(n, 6) for b in m.bearings for i, _, _, n in b.crossings
                  if n <= 30000.0})
    assert len(met) >= 2
    np.testing.assert_allclose(met, forward[:len(met)], rtol=0.005)
    # forward whirl is stiffened by the disk's gyroscopic moments: the standstill map
    # puts each crossing lower, the third by far
    still = run_ucs(scene, np.logspace(6, 8, 9), kind="standstill")
    for i in range(3):
        ours = min(n for b in m.bearings for j, _, _, n in b.crossings if j == i)
        rest = min(n for b in still.bearings for j, _, _, n in b.crossings if j == i)
        assert rest <= ours * (1 + 1e-6)
        if i == 2:
            assert rest < 0.8 * ours


@pytest.mark.slow
def test_the_map_ends_at_the_held_and_at_the_free_shaft():
    """With bearings 10^4 times stiffer than the shaft's first bending (1e11 N/m) the
    branches are the modes of the shaft held at its seats, within 1 %; with bearings
    10^4 times softer (1e3 N/m) the first two branches are the rigid shaft with its disks
    bouncing and rocking on them (the two-degree-of-freedom closed form) and the third
    is the free shaft's first bending, each within 1 %."""
    scene = load_scene(rotor("5.9.1"))
    m = run_ucs(scene, np.logspace(3, 11, 17), kind="standstill")
    held = replace(scene, supports=tuple(replace(s, kind="rigid-radial", bearing=None)
                                         for s in scene.supports), rotor=None)
    modes = run_modes(held).modes
    bending = [f for f, k in zip(modes.frequencies, modes.kinds) if k == "bending"][::2]
    np.testing.assert_allclose(m.frequencies[:, -1], bending[:4], rtol=0.01)
    free = run_modes(replace(scene.free(), rotor=None)).modes
    first = [f for f, k in zip(free.frequencies, free.kinds) if k == "bending"][0]
    assert m.frequencies[2, 0] == pytest.approx(first, rel=0.01)
    # the rigid shaft with its disks bouncing and rocking on the two springs
    rho, r, length = 7810.0, 0.025, 1.5
    parts = [(rho * math.pi * r**2 * length, 0.75,
              rho * math.pi * r**2 * length * (length**2 / 12 + r**2 / 4))]
    for a in scene.attachments:
        parts.append((a.mass, a.position, a.diametral_inertia))
    mass = sum(p[0] for p in parts)
    zc = sum(p[0] * p[1] for p in parts) / mass
    inertia = sum(i + mp * (z - zc) ** 2 for mp, z, i in parts)
    k = m.stiffness[0]
    d = [s.position - zc for s in scene.supports]
    K = k * np.array([[len(d), sum(d)], [sum(d), sum(x * x for x in d)]])
    rigid = np.sqrt(np.linalg.eigvals(np.linalg.solve(np.diag([mass, inertia]), K)).real)
    np.testing.assert_allclose(m.frequencies[:2, 0], np.sort(rigid) / (2 * math.pi), rtol=0.01)


def test_ucs_as_a_user_runs_it(tmp_path):
    """`shaftfem ucs --out` writes the picture, a CSV of N rows and the JSON; the
    pump's journals meet the first branch below the first critical speed of its
    stiffest bearings; a wrong range is refused (exit 2)."""
    import subprocess
    import sys

    pump = str(Path(__file__).parents[1] / "examples" / "pump_on_journals.toml")
    cmd = [sys.executable, "-m", "shaftfem", "ucs", pump, "--mesh-size", "30", "-q",
           "--stiffness-n-per-mm", "100:1e6:24", "--out", str(tmp_path / "u")]
    run = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    rows = (tmp_path / "u" / "ucs.csv").read_text().splitlines()
    assert len(rows) == 25 and rows[0].startswith("stiffness_n_per_mm,branch_1_rpm")
    data = json.loads((tmp_path / "u" / "ucs.json").read_text())
    first = np.array(data["branches"][0]["critical_speed_rpm"])
    assert np.all(np.diff(first) > 0)            # stiffer bearings, higher criticals
    crossings = [c for b in data["bearings"] for c in b["crossings"] if c["branch"] == 1]
    assert crossings and all(c["speed_rpm"] < first[-1] for c in crossings)
    assert (tmp_path / "u" / "ucs.png").stat().st_size > 10_000
    bad = subprocess.run([*cmd[:5], "--stiffness-n-per-mm", "1e6:100:24"], capture_output=True,
                         text=True, cwd=tmp_path)
    assert bad.returncode == 2 and "need 0 < A < B <= 1e12 N/mm" in bad.stderr


@pytest.mark.slow
def test_a_keyed_shaft_s_map_has_two_criticals_per_bending_pair_where_its_campbell_has():
    """A keyed shaft (tests/test_floquet.py's, on isotropic bearings) is mapped in the
    frame turning with it: each bending pair splits into two synchronous critical speeds,
    one per principal plane, and the bearings cross the map where the Campbell diagram
    of the rotor the curve stands for (crossing_scene) meets 1x forward, within 0.5 %."""
    from shaftfem.workflows.campbell import run_campbell
    from shaftfem.workflows.ucs import crossing_scene
    from test_floquet import keyed

    scene = load_scene(keyed(1.0))
    assert not scene.axisymmetric
    m = run_ucs(scene)
    from shaftfem.workflows.ucs import BRANCHES

    # twice the branches of a round shaft: the first pairs, plane by plane, side by side
    assert m.frequencies.shape[0] == 2 * BRANCHES
    assert np.all(m.frequencies[1] / m.frequencies[0] - 1 < 0.02)
    top = scene.rotor.max_speed * 30 / math.pi
    met = sorted({round(n, 6) for _, _, _, n in m.bearings[0].crossings if n <= top})
    assert len(met) == 2 and met[1] / met[0] - 1 < 0.01      # the split first pair
    c = run_campbell(crossing_scene(m.scene, m.bearings[0]))
    forward = [x.speed_rpm for x in c.critical_speeds if x.order == 1 and x.whirl == "forward"]
    for n in met:
        assert min(abs(f / n - 1) for f in forward) < 0.005


def test_the_map_is_solved_on_the_rotor_s_own_mesh():
    """The map's scene (every bearing alike, seals, unbalances and probes left out)
    cuts and refines the shaft where the rotor's does: the mesher is given the same
    planes and seats, so the map's basis is built on the rotor's mesh."""
    from shaftfem.workflows.ucs import uniform_bearings

    scene = load_scene(Path(__file__).parents[1] / "examples" / "pump_on_journals.toml")
    assert any(s.kind == "seal" for s in scene.supports) and scene.unbalances
    alike = uniform_bearings(scene, 1e7)
    assert not any(s.kind == "seal" for s in alike.supports) and not alike.unbalances
    assert alike.seat_cuts() == scene.seat_cuts()
    assert alike.hubs() == scene.hubs()


@pytest.mark.slow
def test_a_keyed_shaft_s_branches_are_continuous(tmp_path):
    """examples/keyed_pump_on_journals.toml's map, as a user runs `ucs --json`: a mode of
    one principal plane takes on torsion as the bearings stiffen, and a list by speed
    jumped to the next root there (branch 8 rose 2.4 times in one step, then fell). Each
    branch followed by its shape rises with the bearings' stiffness (Rayleigh: stiffer
    bearings, no lower critical) and by at most the step's square root in one step (a
    branch at most as stiff as the bearings: 10^(4/39/2) = 1.126)."""
    import subprocess
    import sys

    example = Path(__file__).parent.parent / "examples" / "keyed_pump_on_journals.toml"
    run = subprocess.run([sys.executable, "-m", "shaftfem", "ucs", str(example), "--mesh-size",
                          "25", "-q", "--json", str(tmp_path / "u.json"), "--out",
                          str(tmp_path / "out")], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    c = json.loads((tmp_path / "u.json").read_text())
    k = np.array(c["stiffness_n_per_mm"])
    step = math.sqrt(float(np.max(k[1:] / k[:-1])))
    f = np.array([b["critical_speed_rpm"] for b in c["branches"]], dtype=float)
    assert f.shape == (8, k.size) and np.isfinite(f).all()
    rise = f[:, 1:] / f[:, :-1]
    assert rise.min() >= 1 - 1e-6 and rise.max() <= step * (1 + 1e-3), (rise.min(), rise.max())
