"""The turning shaft against an independent rotor model and against itself.

The references are Friswell et al.'s rotors (Dynamics of Rotating Machines, 5.9) as
ross-rotordynamics 2.3 solves them on 48 Timoshenko beam elements
(benchmarks/ross_reference.py wrote tests/data/ross_rotors.json). The 3D solid differs
from the beam in three ways: its bearings act on a 2 mm band at each end, not at the
end point; its disks sit on the mean motion of the section at their centre
(`joint = "distributing"`, ross's point disk); and it has no shear coefficient to
choose. What remains is within a few tenths of a percent.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from shaftfem.errors import SceneError
from shaftfem.scene.load import load_scene
from shaftfem.workflows.campbell import run_campbell

ROSS = json.loads((Path(__file__).parent / "data" / "ross_rotors.json").read_text())
STEEL = {"name": "steel", "youngs_modulus_mpa": 211000.0, "poisson_ratio": 0.29926108,
         "density_kg_m3": 7810.0}
RAD_S = 2 * math.pi      # rad/s per Hz


def disk(position_mm: float, od_m: float, name: str) -> dict:
    """A 70 mm wide steel disk with a 50 mm bore, as ross's DiskElement.from_geometry."""
    m = 7810.0 * math.pi / 4 * (od_m**2 - 0.05**2) * 0.07
    ip = m / 8 * (od_m**2 + 0.05**2)
    return {"name": name, "position_mm": position_mm, "width_mm": 70.0, "mass_kg": m,
            "polar_inertia_kg_m2": ip, "diametral_inertia_kg_m2": ip / 2 + m * 0.07**2 / 12,
            "joint": "distributing"}


def bearing(position_mm: float, name: str, **coefficients) -> dict:
    return {"name": name, "position_mm": position_mm, "width_mm": 2.0, "kind": "bearing",
            **coefficients}


def friswell(supports: list[dict], disks: list[dict], rotor: dict, **tables) -> dict:
    """A 1.5 m x 50 mm steel shaft, P2 at 25 mm (within 0.03 % of 12.5 mm on 5.9.1)."""
    return {"name": "friswell", "shaft": {"length_mm": 1500.0, "diameter_mm": 50.0},
            "material": STEEL, "mesh": {"element_size_mm": 25.0}, "modes": {"count": 8},
            "support": supports, "attachment": disks, "rotor": rotor, **tables}


def ends(**coefficients) -> list[dict]:
    return [bearing(1.0, "left", **coefficients), bearing(1499.0, "right", **coefficients)]


def two_disks() -> list[dict]:
    return [disk(500.0, 0.28, "disk 1"), disk(1000.0, 0.35, "disk 2")]


def lateral(c, rpm: float) -> np.ndarray:
    """The whirl frequencies (rad/s) at one speed of the diagram, torsion left out."""
    return np.array([w.frequency_hz * RAD_S for w in c.whirl
                     if w.speed_rpm == rpm and w.kind != "torsion"])


def ross_lateral(example: str, rpm: int) -> np.ndarray:
    d = ROSS[example][str(rpm)]
    return np.array([w for w, kind in zip(d["wd"], d["whirl"]) if kind != "None"])


@pytest.fixture(scope="module")
def example_591():
    scene = load_scene(friswell(ends(kxx_n_per_mm=1000.0), two_disks(),
                                {"speed_rpm": 4000.0, "max_speed_rpm": 4000.0,
                                 "campbell_points": 2}))
    return run_campbell(scene)


def test_friswell_591_whirl_against_ross(example_591):
    """Three pairs at 0 and 4,000 r/min within 1 %, each pair's split within 5 %."""
    c = example_591
    assert c.frame == "stationary"
    for rpm in (0, 4000):
        ours, ross = lateral(c, rpm)[:6], ross_lateral("5.9.1", rpm)[:6]
        assert np.all(np.abs(ours / ross - 1) < 0.01), (rpm, ours, ross)
    ours, ross = lateral(c, 4000)[:6], ross_lateral("5.9.1", 4000)[:6]
    split, ross_split = ours[1::2] - ours[::2], ross[1::2] - ross[::2]
    assert np.all(np.abs(split / ross_split - 1) < 0.05), (split, ross_split)
    # forward above backward in each pair, and the orbits circular on a shaft of revolution
    at = [w for w in c.whirl if w.speed_rpm == 4000 and w.kind == "bending"][:6]
    assert [w.whirl for w in at] == ["backward", "forward"] * 3
    assert all(abs(abs(w.whirl_index) - 1) < 1e-3 for w in at)
    assert c.truncation.change < 1e-4


def test_friswell_592_anisotropic_bearings():
    """kyy = 0.8 kxx: the stationary frame, within the same tolerances as 5.9.1."""
    scene = load_scene(friswell(ends(kxx_n_per_mm=1000.0, kyy_n_per_mm=800.0), two_disks(),
                                {"speed_rpm": 4000.0, "max_speed_rpm": 4000.0,
                                 "campbell_points": 2}))
    c = run_campbell(scene)
    assert c.frame == "stationary"
    for rpm in (0, 4000):
        ours, ross = lateral(c, rpm)[:6], ross_lateral("5.9.2", rpm)[:6]
        assert np.all(np.abs(ours / ross - 1) < 0.01), (rpm, ours, ross)
        split, ross_split = ours[1::2] - ours[::2], ross[1::2] - ross[::2]
        assert np.all(np.abs(split / ross_split - 1) < 0.05), (rpm, split, ross_split)


def test_friswell_599_overhung_critical_speeds():
    """The overhung rotor's first backward and forward 1x critical speeds within 2 %."""
    scene = load_scene(friswell(
        [bearing(1.0, "left", kxx_n_per_mm=10_000.0),
         bearing(1000.0, "right", kxx_n_per_mm=10_000.0)],
        [{**disk(1465.0, 0.35, "disk"), "position_mm": 1499.0, "width_mm": 2.0}],
        {"speed_rpm": 600.0, "max_speed_rpm": 1500.0, "campbell_points": 16}))
    c = run_campbell(scene)
    ross = ROSS["5.9.9"]["critical_1x"]
    for whirl in ("backward", "forward"):
        first = min((cs for cs in c.critical_speeds if cs.whirl == whirl and cs.order == 1),
                    key=lambda cs: cs.speed_rpm)
        assert first.speed_rpm * math.pi / 30 == pytest.approx(ross[whirl], rel=0.02)
    # crossed from above: a critical speed lies where its curve meets the 1x line
    for cs in c.critical_speeds:
        assert cs.frequency_hz == pytest.approx(cs.order * cs.speed_rpm / 60, rel=1e-12)
    # the crossings, found by root finding on the diagram, against the same critical
    # speeds as one Hermitian eigenproblem in the speed squared (fem.rotor)
    assert c.synchronous_check is not None and c.synchronous_check < 1e-8


def test_friswell_591_unbalance_response(tmp_path):
    """0.5 N s/mm in each bearing, 100 g mm at the 350 mm disk: the first peak's speed
    within 1 % and its amplitude within 5 % of ross's, read at that disk; the run from
    code (shaftfem.campbell) draws its diagram and its Bode plot."""
    import shaftfem

    ref = ROSS["5.9.1 unbalance"]
    scene = load_scene(friswell(
        ends(kxx_n_per_mm=1000.0, cxx_n_s_per_mm=ref["bearing_damping_n_s_per_m"] / 1e3),
        two_disks(), {"speed_rpm": 1200.0, "max_speed_rpm": 1500.0, "campbell_points": 2,
                      "probes_mm": [750.0]},
        unbalance=[{"part": "disk 2", "amount_g_mm": ref["unbalance_kg_m"] * 1e6}]))
    assert scene.unbalances[0].position == pytest.approx(1.0)
    turning = shaftfem.campbell(scene)
    c = turning.campbell
    assert c.unbalance is not None and turning.critical_speeds == c.critical_speeds
    peak = min((p for p in c.unbalance.peaks if p.probe == "disk 2"), key=lambda p: p.speed_rpm)
    # a probe of one's own choice sees the same resonance
    mid = min((p for p in c.unbalance.peaks if p.probe == "probe at 750 mm"),
              key=lambda p: p.speed_rpm)
    assert mid.speed_rpm == pytest.approx(peak.speed_rpm, rel=1e-3)
    assert peak.speed_rpm * math.pi / 30 == pytest.approx(ref["peak_speed"], rel=0.01)
    assert peak.amplitude == pytest.approx(ref["peak_amplitude_m"], rel=0.05)
    assert peak.amplification is not None and peak.amplification > 2.5
    # the margin is measured from the operating speed, and API 684 asks for a margin
    assert peak.margin == pytest.approx(abs(peak.speed_rpm - 1200.0) / 1200.0)
    assert peak.required_margin is not None and peak.ok
    from PIL import Image

    for picture in (turning.plot(tmp_path / "campbell.png"), turning.plot_bode(tmp_path / "bode.png")):
        assert np.asarray(Image.open(picture)).std() > 10


@pytest.mark.slow
def test_cross_coupled_bearings_go_unstable():
    """kxy = -kyx growing as 150 N s/m times the speed, 0.5 N s/mm of damping: the first
    forward mode's log decrement falls through zero within 2 % of ross's onset."""
    ref = ROSS["5.9.1 cross-coupled"]
    table = np.linspace(0.0, 2000.0, 21)                  # rad/s, as in the reference
    slope = ref["kxy_per_speed"]
    coefficients = {"kxx_n_per_mm": 1000.0,
                    "cxx_n_s_per_mm": ref["bearing_damping_n_s_per_m"] / 1e3,
                    "speeds_rpm": list(table * 30 / math.pi),
                    "kxy_n_per_mm": list(slope * table / 1e3),
                    "kyx_n_per_mm": list(-slope * table / 1e3)}
    scene = load_scene(friswell(ends(**coefficients), two_disks(),
                                {"speed_rpm": 2000.0, "max_speed_rpm": 5000.0,
                                 "campbell_points": 11}))
    c = run_campbell(scene)
    first = c.onsets[0]
    assert first.whirl == "forward"
    assert first.speed_rpm * math.pi / 30 == pytest.approx(ref["onset_speed"], rel=0.02)


def test_a_keyed_shaft_in_anisotropic_bearings_is_solved_and_a_frame_that_cannot_refused(
        tmp_path):
    """A keyed shaft in anisotropic bearings is periodic in time in either frame: solved
    in the turning frame by Floquet theory, its two routes agreeing at the running
    speed; the stationary frame refuses a shaft that is not a solid of revolution."""
    from shaftfem.fem.floquet import routes_apart
    from shaftfem.workflows.campbell import turning

    keyed = {"name": "keyed", "material": STEEL, "mesh": {"element_size_mm": 8.0},
             "section": [{"length_mm": 300.0, "diameter_mm": 30.0}],
             "keyway": [{"position_mm": 150.0, "length_mm": 40.0}],
             "support": [bearing(30.0, "a", kxx_n_per_mm=1e5, kyy_n_per_mm=5e4),
                         bearing(270.0, "b", kxx_n_per_mm=1e5)],
             "modes": {"count": 4},
             "rotor": {"speed_rpm": 3000.0}}
    _, model, why = turning(load_scene(keyed))
    assert model.frame == "rotating" and "Floquet" in why
    assert model.periodic(3000 * math.pi / 30)
    assert routes_apart(model, 3000 * math.pi / 30) < 1e-8
    keyed["support"][0]["kyy_n_per_mm"] = 1e5
    keyed["rotor"]["frame"] = "stationary"
    with pytest.raises(SceneError, match="shafts of revolution only"):
        run_campbell(load_scene(keyed))
    with pytest.raises(SceneError, match="speeds_rpm"):
        load_scene({**keyed, "support": [bearing(30.0, "a", kxx_n_per_mm=[1.0, 2.0])]})
    with pytest.raises(SceneError, match=r"rotor\.max_speed_rpm"):
        load_scene({**keyed, "rotor": {"speed_rpm": 3000.0, "max_speed_rpm": 1000.0}})
    with pytest.raises(SceneError, match=r"part = 'wheel': no \[\[attachment\]\]"):
        load_scene({**keyed, "unbalance": [{"part": "wheel", "amount_g_mm": 10.0}]})
    with pytest.raises(SceneError, match="either position_mm or part"):
        load_scene({**keyed, "unbalance": [{"amount_g_mm": 10.0}]})
    with pytest.raises(SceneError, match="off the shaft"):
        load_scene({**keyed, "rotor": {"speed_rpm": 3000.0, "probes_mm": [400.0]}})


def stepped_rotor(frame: str) -> dict:
    """A stepped shaft of revolution (30/45/30 mm, 1 mm fillets) with a wheel between
    two damped isotropic bearings, its whirl on 16 standstill modes."""
    brg = {"kind": "bearing", "width_mm": 16.0, "kxx_n_per_mm": 1e5, "cxx_n_s_per_mm": 0.2}
    return {"name": "stepped_rotor", "material": STEEL, "mesh": {"element_size_mm": 8.0},
            "section": [{"length_mm": 60.0, "diameter_mm": 30.0, "fillet_mm": 1.0},
                        {"length_mm": 300.0, "diameter_mm": 45.0, "fillet_mm": 1.0},
                        {"length_mm": 60.0, "diameter_mm": 30.0}],
            "support": [{**brg, "name": "left", "position_mm": 30.0},
                        {**brg, "name": "right", "position_mm": 390.0}],
            "attachment": [{"name": "wheel", "position_mm": 260.0, "width_mm": 40.0,
                            "mass_kg": 12.0, "polar_inertia_kg_m2": 0.06,
                            "diametral_inertia_kg_m2": 0.032, "joint": "distributing"}],
            "modes": {"count": 6},
            "rotor": {"speed_rpm": 3000.0, "max_speed_rpm": 20000.0, "frame": frame,
                      "basis_modes": 16}}


@pytest.mark.parametrize("size_mm,agree", [
    pytest.param(12.0, 1e-4, marks=pytest.mark.slow),
    pytest.param(8.0, 1e-6, marks=pytest.mark.slow)])
def test_the_two_frames_agree(size_mm, agree):
    """A shaft of revolution in isotropic bearings solved in the stationary frame (its
    material flowing through the mesh) and in the frame turning with it (Coriolis, spin
    softening, the spin's own stress) whirls alike, seen from the housing: three pairs
    at three speeds to 1e-6 on an 8 mm mesh (slow), 1e-4 on a 12 mm one, log decrements
    to 100 times that. What differs is the mesh: no tetrahedral
    mesh is a solid of revolution, and its own small asymmetry (a standstill pair split by
    1.8e-4 at 8 mm, 1.2e-3 at 12 mm) acts as a stiffness fixed in space in one frame and
    turning in the other; the frames differ by its square (6.7e-7 at 8 mm, 3.3e-5 at 12)."""
    from shaftfem.fem.rotor import rotor_model
    from shaftfem.workflows.campbell import campbell_of, turning

    speeds = np.array([3000.0, 10000.0, 15000.0])
    scene = load_scene({**stepped_rotor("stationary"), "mesh": {"element_size_mm": size_mm}})
    result, _, why = turning(scene)        # one standstill basis, two frames on it
    c = {frame: campbell_of(scene, result, rotor_model(result, frame), why, speeds)
         for frame in ("stationary", "rotating")}
    assert c["stationary"].frame == "stationary" and c["rotating"].frame == "rotating"
    for a, b in zip(c["stationary"].whirl, c["rotating"].whirl):
        assert a.speed_rpm == b.speed_rpm and a.whirl == b.whirl
        assert b.frequency_hz == pytest.approx(a.frequency_hz, rel=agree)
        assert b.log_dec == pytest.approx(a.log_dec, rel=100 * agree)
    # the critical speeds, found in each frame on its own curves, are the same
    full = {frame: campbell_of(scene, result, rotor_model(result, frame), why)
            for frame in ("stationary", "rotating")}
    crit = {frame: sorted((cs.order, cs.whirl, cs.speed_rpm) for cs in full[frame].critical_speeds)
            for frame in full}
    assert len(crit["stationary"]) == len(crit["rotating"]) >= 2
    for (oa, wa, na), (ob, wb, nb) in zip(crit["stationary"], crit["rotating"]):
        assert (oa, wa) == (ob, wb) and nb == pytest.approx(na, rel=agree)
    # in the rotating frame the same modes stand at f -+ n
    for b in c["rotating"].whirl:
        n = b.speed_rpm / 60
        seen = b.rotating_frame_hz + (n if b.whirl == "forward" else -n)
        assert abs(seen) == pytest.approx(b.frequency_hz, rel=1e-12)


@pytest.mark.slow
def test_paper_shaft_turning_in_its_own_frame():
    """The grooved shaft is no solid of revolution: it turns in the rotating frame. At the
    paper's 80 r/min its pair's Coriolis coupling moves each mode by 2 W^2 / (w2^2 - w1^2)
    (two modes, W the spin): 3.7e-4, not the 1e-4 a glance would give; its stationary-frame
    components stand at f -+ 1.33 Hz. Between its pair's frequencies a shaft stiffer across
    one diameter diverges (an asymmetric Jeffcott rotor: w1 < W < w2)."""
    scene = load_scene("paper2018", overrides={"rotor.speed_rpm": 80.0,
                                               "rotor.max_speed_rpm": 30000.0})
    c = run_campbell(scene, speeds_rpm=np.array([0.0, 80.0, 10000.0, 25000.0, 26400.0,
                                                 28000.0]))
    assert c.frame == "rotating" and "grooves" in c.why
    f = c.result.modes.frequencies
    w1, w2, spin = 2 * math.pi * f[0], 2 * math.pi * f[1], 80 * math.pi / 30
    two_modes = 2 * spin**2 / (w2**2 - w1**2)
    at80 = [w for w in c.whirl if w.speed_rpm == 80.0]
    assert at80[0].rotating_frame_hz / f[0] - 1 == pytest.approx(-two_modes, rel=0.1)
    assert at80[1].rotating_frame_hz / f[1] - 1 == pytest.approx(two_modes, rel=0.1)
    for w in at80[:2]:
        assert {round(w.frequency_hz, 9), round(w.companion_hz, 9)} == {
            round(w.rotating_frame_hz + 80 / 60, 9), round(w.rotating_frame_hz - 80 / 60, 9)}
    (lo, hi), = c.divergent
    assert lo == pytest.approx(60 * f[0], rel=0.02) and hi == pytest.approx(60 * f[1], rel=0.02)
    assert hi - lo == pytest.approx(60 * (f[1] - f[0]), rel=0.05)
    # the resonance check at 80 r/min is the standstill one: nothing moved by 0.1 %
    assert np.allclose([w.rotating_frame_hz for w in at80], f[:len(at80)], rtol=1e-3)
    # at 10,000 r/min (167 Hz, far above the pair's 10.8 Hz split) Coriolis coupling makes
    # the pair's orbits circular, seen near the two stiffnesses' root mean square
    fast = [w for w in c.whirl if w.speed_rpm == 10000.0][:2]
    assert [w.whirl for w in fast] == ["backward", "forward"]
    assert all(abs(w.whirl_index) > 0.95 for w in fast)
    rms = math.sqrt((f[0] ** 2 + f[1] ** 2) / 2)
    assert all(w.frequency_hz == pytest.approx(rms, rel=0.005) for w in fast)


@pytest.mark.slow
def test_keyed_shaft_whirls_at_its_mean_stiffness():
    """A keyed stepped shaft turns in the rotating frame. At rest its keyway splits the
    first pair by 3 %; turning fast, Coriolis coupling averages the two stiffnesses and
    the stationary frame sees the pair near their root mean square (asymmetric Jeffcott
    rotor, n >> the split)."""
    import tomllib

    data = tomllib.loads((Path(__file__).parents[1] / "examples" / "stepped_shaft.toml")
                         .read_text())
    data["mesh"]["element_size_mm"] = 12.0
    data["modes"] = {"count": 4}
    data["rotor"] = {"speed_rpm": 10000.0}
    c = run_campbell(load_scene(data), speeds_rpm=np.array([0.0, 10000.0]))
    assert c.frame == "rotating" and "keyways" in c.why
    f = c.result.modes.frequencies
    rest = [w.frequency_hz for w in c.whirl if w.speed_rpm == 0.0]
    assert np.allclose(rest, f[:len(rest)], rtol=1e-12)
    assert f[1] / f[0] - 1 > 0.02
    fast = [w for w in c.whirl if w.speed_rpm == 10000.0][:2]
    assert {w.whirl for w in fast} == {"forward", "backward"}
    rms = math.sqrt((f[0] ** 2 + f[1] ** 2) / 2)
    for w in fast:
        assert w.frequency_hz == pytest.approx(rms, rel=0.005)


def test_an_interval_says_what_it_covers():
    """Printed under every bounded table (terminal, report.md, report.html) and in the
    JSON: the discretisation and the mesh's geometry, for the model as given; not this
    scene's bearings, joints, material, nor, standing still, its rotation."""
    from shaftfem.outputs.tables import bound_coverage

    free = load_scene("paper2018")
    said = bound_coverage(free)
    assert said.startswith("the interval covers the discretisation and the mesh's geometry")
    assert "bearings" not in said and "material" in said and "[rotor]" in said
    turning = load_scene(friswell(ends(kxx_n_per_mm=1000.0), two_disks(), {"speed_rpm": 4000.0}))
    said = bound_coverage(turning)
    assert "bearings' stiffness" in said and "parts' joints" in said
    assert "`shaftfem campbell` turns them" in said


def test_anisotropic_damped_bearings_crossings_and_both_peaks_against_ross():
    """Friswell's 5.9.1 rotor in bearings twice as stiff along x as along y, damped: both
    1x crossings (elliptical whirl) and both unbalance peaks of the 350 mm disk (the
    orbit's major semi-axis) within 1 % of ross's, the same count."""
    ref = ROSS["anisotropic damped"]
    scene = load_scene(friswell(
        ends(kxx_n_per_mm=ref["kxx"] / 1e3, kyy_n_per_mm=ref["kyy"] / 1e3,
             cxx_n_s_per_mm=ref["c"] / 1e3),
        two_disks(), {"speed_rpm": 1200.0, "max_speed_rpm": 1500.0},
        unbalance=[{"name": "disk 2", "position_mm": 1000.0,
                    "amount_g_mm": ref["unbalance_kg_m"] * 1e6}]))
    c = run_campbell(scene)
    ours = sorted(cs.speed_rpm * math.pi / 30 for cs in c.critical_speeds if cs.order == 1)
    assert ours == pytest.approx([x["speed"] for x in ref["crossings"]], rel=0.01)
    assert c.unbalance is not None
    peaks = sorted((p for p in c.unbalance.peaks if p.probe == "disk 2"),
                   key=lambda p: p.speed_rpm)
    assert len(peaks) == len(ref["peaks"]) == 2
    for p, x in zip(peaks, ref["peaks"]):
        assert p.speed_rpm * math.pi / 30 == pytest.approx(x["speed"], rel=0.01)
        assert p.amplitude == pytest.approx(x["major_m"], rel=0.01)


def test_every_crossing_of_1x_2x_and_7x_against_ross():
    """5.9.1 with a pump's orders (1x, 2x and a 7x vane pass) up to 3,000 r/min: every
    crossing ross finds on its first six lateral curves, each within 1 %, matched one to
    one, and the direct route finds none the curves missed."""
    scene = load_scene(friswell(
        ends(kxx_n_per_mm=1000.0), two_disks(), {"speed_rpm": 1500.0, "max_speed_rpm": 3000.0},
        excitation=[{"name": "vane pass", "speed_rpm": 1500.0, "orders": [1, 2, 7]}]))
    c = run_campbell(scene)
    assert c.crossing_check is not None and c.crossing_check.direct_only == 0
    used: set[int] = set()
    for x in ROSS["orders 1 2 7"]["crossings"]:
        near = min((abs(cs.speed_rpm * math.pi / 30 / x["speed"] - 1), k)
                   for k, cs in enumerate(c.critical_speeds)
                   if cs.order == x["order"] and k not in used)
        used.add(near[1])
        assert near[0] < 0.01, x


def test_a_torsional_curve_is_seen_at_its_own_frequency_in_the_turning_frame():
    """Torsion does not whirl: the housing sees a torsional mode solved in the turning
    frame at the frequency it has there (no forward and backward companions at f +- n,
    which only a sideways orbit has), on the diagram's lines and in its rows."""
    from shaftfem.fem.tracking import component_lines
    from shaftfem.fem.whirl import Curve

    speeds = np.array([0.0, 3000.0, 6000.0])
    f = np.array([24.86, 24.86, 24.85])
    c = Curve(1, "rotating", speeds, f, np.zeros(3), np.zeros(3), ("torsion",) * 3,
              np.ones((2, 3)))
    lines = component_lines(c)
    assert len(lines) == 1 and np.allclose(lines[0][1], f)
    assert np.allclose(c.seen_hz, f)
    bending = Curve(2, "rotating", speeds, f, np.zeros(3), np.ones(3), ("bending",) * 3,
                    np.ones((2, 3)))
    assert np.allclose(bending.seen_hz, f + speeds / 60.0)   # a forward orbit: f + n


@pytest.mark.slow
def test_fewer_modes_of_the_whirl_s_pencil_are_the_lowest_of_its_basis(monkeypatch):
    """A design's standstill modes of a rotor, after its whirl's basis (18 or more modes
    of the same pencil on the same mesh) in the same process: the basis' lowest, their
    frequencies and shapes those of the basis bit for bit, K and M not assembled again;
    on another mesh, a solve of its own."""
    from shaftfem.fem import assembly
    from shaftfem.workflows.campbell import turning
    from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes

    scene = load_scene(friswell(ends(kxx_n_per_mm=1000.0, cxx_n_s_per_mm=2.0), two_disks(),
                                {"speed_rpm": 3000.0, "campbell_points": 2}))
    basis, _, _ = turning(scene)
    f = basis.modes.frequencies
    # a count that splits no pair of one frequency (that pair's basis would be any)
    n = next(i for i in range(4, f.size) if f[i] - f[i - 1] > 1e-4 * f[i])
    assemble = assembly.assemble
    monkeypatch.setattr(assembly, "assemble", lambda *a, **k: pytest.fail("assembled again"))
    design = run_modes(with_modes(scene, count=n))
    assert np.array_equal(design.modes.frequencies, basis.modes.frequencies[:n])
    assert np.array_equal(design.modes.shapes, basis.modes.shapes[:, :n])
    assert design.modes.kinds == basis.modes.kinds[:n] and design.modes.count == n
    monkeypatch.setattr(assembly, "assemble", assemble)
    calls = []
    monkeypatch.setattr(assembly, "assemble", lambda *a, **k: calls.append(1) or assemble(*a, **k))
    run_modes(with_mesh(with_modes(scene, count=n), 30.0))
    assert calls
