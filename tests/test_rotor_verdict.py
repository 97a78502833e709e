"""The turning shaft's verdict: every crossing found whatever the grid, by two routes,
in both frames; stability and operating ranges judged; the CLI's exit status.

The closed forms are a rigid rotor's (mass m, moments I_d and I_p, radial stiffness k
and tilting stiffness k_t, isotropic): its translation pair whirls at sqrt(k / m) at
every speed, its tilting pair at the roots of I_d w^2 -+ I_p Omega w = k_t, so the k-th
order line meets them at Omega = sqrt(k/m) / k and Omega^2 (k^2 I_d -+ k I_p) = k_t.
The rotors on the 3D solid are checked against the direct route (an eigenproblem in
the speed squared, independent of the curves) and against themselves on a grid ten
times finer.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from shaftfem.fem.rotor import RotorModel, part_matrices
from shaftfem.fem.tracking import curve_crossings, direct_crossings, reported, track
from shaftfem.fem.whirl import RPM
from shaftfem.scene.load import load_scene

M, ID, IP, K, KT = 10.0, 0.1, 0.05, 1e6, 2e4
STEEL = {"name": "steel", "youngs_modulus_mpa": 211000.0, "poisson_ratio": 0.3,
         "density_kg_m3": 7810.0}


def rigid_rotor(frame: str) -> RotorModel:
    """The rigid rotor on its four lateral modes (x, y, tilt about x, tilt about y),
    mass-normalised, in either frame (fem.rotor.part_matrices)."""
    phi = np.diag([1 / math.sqrt(M)] * 2 + [1 / math.sqrt(ID)] * 2)
    Gp, Kp = part_matrices(M, IP, ID, frame)
    keep = [0, 1, 3, 4]
    G = phi @ Gp[np.ix_(keep, keep)] @ phi
    K2 = phi @ Kp[np.ix_(keep, keep)] @ phi
    # whirl forms: (x, tilt about y) move along x, (y, -tilt about x) along y
    w = np.diag([M, ID])
    X, Y = phi[[0, 3]], np.vstack([phi[1], -phi[2]])
    lateral = X.T @ w @ X + Y.T @ w @ Y
    t = 1j * (X.T @ w @ Y - (X.T @ w @ Y).T)
    return RotorModel(frame, np.array([K / M, K / M, KT / ID, KT / ID]), 0.5 * (G - G.T),
                      0.5 * (K2 + K2.T), (), lateral, 0.5 * (t + t.conj().T), ("bending",) * 4)


def closed_form(order: int) -> list[float]:
    """The rigid rotor's crossings with the order line, r/min, ascending."""
    out = [math.sqrt(K / M) / order] * 2 + [math.sqrt(KT / (order**2 * ID + order * IP))]
    if order**2 * ID > order * IP:
        out.append(math.sqrt(KT / (order**2 * ID - order * IP)))
    return sorted(om / RPM for om in out)


@pytest.mark.parametrize("frame", ["stationary", "rotating"])
@pytest.mark.parametrize("points", [3, 31, 310])
def test_rigid_rotor_crossings_on_any_grid_in_either_frame(frame, points):
    """Every crossing of 1x, 2x and 3x with all four curves, on a grid of 3, 31 or 310
    speeds, in either frame: the closed forms to 1e-8, each curve labelled forward or
    backward from standstill on (its double pair split, not "mixed")."""
    model = rigid_rotor(frame)
    top = 8000 * RPM
    curves = track(model, np.linspace(0.0, top, points), 4)
    assert len(curves) == 4
    assert sorted(c.whirl[0] for c in curves) == ["backward"] * 2 + ["forward"] * 2
    found = curve_crossings(model, curves, (1, 2, 3))
    for order in (1, 2, 3):
        ours = sorted(x.omega / RPM for x in found if x.order == order)
        ref = [n for n in closed_form(order) if n <= 8000]
        assert ours == pytest.approx(ref, rel=1e-8), (order, ours, ref)
    direct = direct_crossings(model, (1, 2, 3), top)
    for order in (1, 2, 3):
        ours = sorted(d.omega / RPM for d in direct if d.order == order)
        assert ours == pytest.approx([n for n in closed_form(order) if n <= 8000], rel=1e-8)


def test_the_curves_cross_and_keep_their_identity():
    """In the stationary frame the tilting pair's backward curve falls through the
    translation pair (a true crossing: the shapes do not mix): each curve stays on its
    own mode family, its frequency continuous, the translation at sqrt(k/m) throughout."""
    model = rigid_rotor("stationary")
    curves = track(model, np.linspace(0.0, 20000 * RPM, 9), 4)
    tilt_back = [c for c in curves if c.whirl[-1] == "backward" and c.seen_hz[0] > 60]
    assert len(tilt_back) == 1
    c = tilt_back[0]
    assert c.seen_hz[-1] < math.sqrt(K / M) / (2 * math.pi)   # it passed below the pair
    assert np.all(np.diff(c.seen_hz) < 0)
    flat = [c for c in curves if np.allclose(c.seen_hz, math.sqrt(K / M) / (2 * math.pi))]
    assert len(flat) == 2


def test_reported_curves_are_those_among_the_modes_asked():
    model = rigid_rotor("stationary")
    curves = track(model, np.linspace(0.0, 8000 * RPM, 11), 4)
    assert len(reported(curves, 2)) >= 2
    assert len(reported(curves, 4)) == 4


# --------------------------------------------------------------------------------------
# On the 3D solid


def pulley_rotor(**bearing) -> dict:
    """A stepped shaft (35/50/35 mm) with a disk between two bearings and an overhung
    pulley, P2 at 14 mm."""
    brg = {"kind": "bearing", "width_mm": 20.0, "kxx_n_per_mm": 5e4, **bearing}
    return {"name": "pulley_rotor", "material": STEEL, "mesh": {"element_size_mm": 14.0},
            "section": [{"length_mm": 80.0, "diameter_mm": 35.0, "fillet_mm": 1.0},
                        {"length_mm": 420.0, "diameter_mm": 50.0, "fillet_mm": 1.0},
                        {"length_mm": 160.0, "diameter_mm": 35.0}],
            "support": [{**brg, "name": "drive end", "position_mm": 50.0},
                        {**brg, "name": "free end", "position_mm": 520.0}],
            "attachment": [{"name": "disk", "position_mm": 300.0, "width_mm": 40.0,
                            "mass_kg": 18.0, "polar_inertia_kg_m2": 0.12,
                            "diametral_inertia_kg_m2": 0.065, "joint": "distributing"},
                           {"name": "pulley", "position_mm": 620.0, "width_mm": 50.0,
                            "mass_kg": 6.0, "polar_inertia_kg_m2": 0.03,
                            "diametral_inertia_kg_m2": 0.017, "joint": "distributing"}],
            "modes": {"count": 6},
            "rotor": {"speed_rpm": 3000.0, "max_speed_rpm": 12000.0}}


@pytest.fixture(scope="module")
def pulley():
    """The rotor's standstill basis and its turning model, solved once."""
    from shaftfem.workflows.campbell import turning

    scene = load_scene(pulley_rotor())
    result, model, why = turning(scene)
    return scene, result, model, why


def at_speed(scene, rpm: float | None = None, **rotor):
    """The scene with its [rotor] changed (speeds in r/min)."""
    r = scene.rotor
    if rpm is not None:
        r = replace(r, speeds=(rpm * RPM,))
    if "range_rpm" in rotor:
        lo, hi = rotor.pop("range_rpm")
        r = replace(r, ranges=((lo * RPM, hi * RPM),), speeds=(lo * RPM, hi * RPM))
    return replace(scene, rotor=replace(r, **rotor))


def test_stepped_rotor_every_crossing_by_two_routes_on_any_grid(pulley):
    """Isotropic undamped bearings, 0-12,000 r/min: the curves' crossings equal the
    direct route's (none added, none extra, to 1e-6), the same set on the default grid
    and on one ten times finer (to 1e-4), the forward and backward 1x crossings of the
    first pairs among them, and at standstill no bending row "mixed"."""
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    c = campbell_of(scene, result, model, why)
    x = c.crossing_check
    assert x is not None and x.applies
    assert x.direct_only == 0 and x.curves_only == 0 and x.largest_difference < 1e-6
    ones = [cs for cs in c.critical_speeds if cs.order == 1]
    assert {cs.whirl for cs in ones} == {"forward", "backward"} and len(ones) >= 2
    still = [w for w in c.whirl if w.speed_rpm == 0.0 and w.kind == "bending"]
    assert still and all(w.whirl != "mixed" for w in still)
    fine = campbell_of(scene, result, model, why, np.linspace(0.0, 12000.0, 310))
    a = sorted((cs.order, cs.speed_rpm) for cs in c.critical_speeds)
    b = sorted((cs.order, cs.speed_rpm) for cs in fine.critical_speeds)
    assert len(a) == len(b)
    for (oa, na), (ob, nb) in zip(a, b):
        assert oa == ob and na == pytest.approx(nb, rel=1e-4)


def test_a_high_order_crossing_near_the_running_range_fails(pulley):
    """A pump's vane pass, 7x: put its first crossing (found directly, independently of
    the curves) 12 % above one of two operating speeds; the verdict fails on it, with a
    15 % margin, and passes with 10 %."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.fem.tracking import direct_crossings
    from shaftfem.scene.model import Excitation
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    seven = min(d.omega for d in direct_crossings(model, (7,), 12000 * RPM))
    run = seven / RPM / 1.12
    vane = Excitation(name="vane pass", frequency=run / 60, orders=(1, 2, 7))
    pump = replace(at_speed(scene, None), rotor=replace(
        scene.rotor, speeds=(0.66 * run * RPM, run * RPM)), excitations=(vane,))
    c = campbell_of(pump, result, model, why)
    v = check_whirl(c, 0.15)
    assert not v.ok and v.exit_status == 1
    assert any(a.order == 7 and a.margin == pytest.approx(0.12, rel=1e-3) for a in v.violations)
    assert check_whirl(c, 0.10).ok or all(a.order != 7 for a in check_whirl(c, 0.10).violations)


def test_a_critical_speed_inside_the_running_range_has_margin_zero(pulley):
    """A variable-speed drive whose range holds the first forward 1x critical speed
    fails with margin 0; outside it the margin is measured to the nearer end."""
    from shaftfem.checks.whirl_check import check_whirl, span_margin
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    c = campbell_of(scene, result, model, why)
    first = min(cs.speed_rpm for cs in c.critical_speeds
                if cs.order == 1 and cs.whirl == "forward")
    inside = campbell_of(at_speed(scene, range_rpm=(0.9 * first, 1.05 * first)), result,
                         model, why)
    v = check_whirl(inside, 0.15)
    assert not v.ok and v.exit_status == 1
    assert any(a.margin == 0.0 and a.order == 1 for a in v.violations)
    assert span_margin(100.0, 110.0, 200.0) == (pytest.approx(10 / 110), False)
    assert span_margin(250.0, 110.0, 200.0) == (pytest.approx(0.25), True)


def test_no_crossing_in_range_gives_a_verdict(pulley):
    """Running below every critical speed, the diagram ending at the running speed: no
    crossing, a verdict all the same (PASS), not a crash."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.outputs.tables import verdict_text
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    low = replace(scene, rotor=replace(scene.rotor, speeds=(500 * RPM,),
                                       max_speed=500 * RPM))
    c = campbell_of(low, result, model, why)
    assert not c.critical_speeds
    v = check_whirl(c, 0.15)
    assert v.ok and v.exit_status == 0
    assert "VERDICT: PASS" in verdict_text(v)


def test_cross_coupled_bearings_fail_for_instability():
    """kxy = -kyx (a constant cross-coupling, as an oil film's) larger than the bearings'
    damping can hold: a forward mode grows from standstill. The verdict fails naming
    it, and the unbalance peak of the growing mode has no amplification factor."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.workflows.campbell import run_campbell

    data = pulley_rotor(cxx_n_s_per_mm=0.2, kxy_n_per_mm=2e4, kyx_n_per_mm=-2e4)
    data["unbalance"] = [{"part": "disk", "amount_g_mm": 50.0}]
    data["rotor"]["campbell_points"] = 13
    c = run_campbell(load_scene(data))
    st = c.stability
    assert st is not None and st.growing and st.log_dec < 0 and st.whirl == "forward"
    v = check_whirl(c, 0.15)
    assert not v.ok and v.exit_status == 1 and v.unstable
    assert "grows" in v.unstable[0]
    assert c.unbalance is not None
    grown = [p for p in c.unbalance.peaks if p.unstable]
    assert all(p.amplification is None for p in grown)


def test_instability_above_the_running_speed_warns_and_inside_fails(pulley):
    """A cross-coupling growing with speed (kxy = -kyx = q n): its onset found on the
    curves; running above it fails, running at half of it passes with a warning that
    gives the margin."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.scene.model import BearingCoefficients
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    table = tuple(np.linspace(0.0, 12000 * RPM, 7))
    q = [4e6 * w / table[-1] for w in table]
    coeffs = BearingCoefficients(speeds=table, kxx=(5e7,) * 7, kxy=tuple(q),
                                 kyx=tuple(-x for x in q), kyy=(5e7,) * 7,
                                 cxx=(200.0,) * 7, cxy=(0.0,) * 7, cyx=(0.0,) * 7,
                                 cyy=(200.0,) * 7)
    coupled = replace(model, bearings=tuple(replace(b, coefficients=coeffs)
                                            for b in model.bearings))
    c = campbell_of(scene, result, coupled, why)
    assert c.onsets, "the cross-coupling should destabilise a forward mode in range"
    onset = c.onsets[0].speed_rpm
    fast = check_whirl(campbell_of(at_speed(scene, 1.2 * onset), result, coupled, why), 0.15)
    assert not fast.ok and fast.exit_status == 1
    assert any("starts to grow" in u or "grows" in u for u in fast.unstable)
    slow = check_whirl(campbell_of(at_speed(scene, 0.5 * onset), result, coupled, why), 0.15)
    assert not slow.unstable
    assert any("above the highest operating speed" in w for w in slow.warnings)


def test_a_required_log_decrement_fails_a_lightly_damped_rotor(pulley):
    """[rotor] min_log_dec = 0.1 on bearings that damp little: FAIL, naming the mode."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.outputs.tables import verdict_lines
    from shaftfem.workflows.campbell import run_campbell

    data = pulley_rotor(cxx_n_s_per_mm=0.05)
    data["rotor"]["min_log_dec"] = 0.1
    data["rotor"]["campbell_points"] = 7
    c = run_campbell(load_scene(data))
    assert c.stability is not None and 0 < c.stability.log_dec <= 0.1
    v = check_whirl(c, 0.15)
    # stable (every log decrement positive), so no instability: the criterion fails
    assert not v.ok and v.exit_status == 1 and not v.unstable
    assert "damped less than required" in v.underdamped[0]
    assert "UNSTABLE" not in "\n".join(verdict_lines(v))


def test_the_required_log_decrement_holds_for_the_modes_log_dec_modes_names():
    """min_log_dec is required of the forward modes by default, of the first forward
    mode alone, or of every whirling mode: set between the least damped backward and
    forward modes where the shaft runs, it fails only the rules that take in the less
    damped one; a backward mode is listed, not judged, under "forward"."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.workflows.campbell import least_damped, run_campbell

    data = pulley_rotor(cxx_n_s_per_mm=0.05)
    data["rotor"]["campbell_points"] = 7
    c = run_campbell(load_scene(data))
    n = c.operating_rpm[0]
    least: dict[str, float] = {}
    first_forward = None
    for cv in c.curves:
        if not cv.whirling:
            continue
        i = int(np.argmin(abs(cv.speeds_rpm - n)))
        word, d = cv.whirl[i], float(cv.log_dec[i])
        least[word] = min(least.get(word, math.inf), d)
        if word == "forward" and (first_forward is None or cv.seen_hz[i] < first_forward[0]):
            first_forward = (float(cv.seen_hz[i]), d)
    assert {"forward", "backward"} <= set(least) and first_forward is not None
    lo, hi = sorted((least["forward"], least["backward"]))
    assert hi > 1.1 * lo > 0
    required = 0.5 * (lo + hi)
    outcome = {}
    for rule in ("forward", "first_forward", "all"):   # the same curves, judged anew
        data["rotor"].update(min_log_dec=required, log_dec_modes=rule)
        scene = load_scene(data)
        judged = replace(c, scene=scene,
                         stability=least_damped(scene, list(c.curves), c.lift_rpm))
        outcome[rule] = check_whirl(judged, 0.15).ok
    assert outcome["all"] is False
    assert outcome["forward"] is (least["forward"] > required)
    assert outcome["first_forward"] is (first_forward[1] > required)


# --------------------------------------------------------------------------------------
# What probing found


@pytest.mark.parametrize("key,value", [("kxy_n_per_mm", float("nan")),
                                       ("kxx_n_per_mm", float("inf")),
                                       ("cxx_n_s_per_mm", float("-inf"))])
def test_a_coefficient_that_is_no_number_is_refused_at_load(key, value):
    from shaftfem.errors import SceneError

    data = pulley_rotor(**{key: value})
    with pytest.raises(SceneError, match=key) as e:
        load_scene(data)
    assert "finite" in str(e.value)


@pytest.mark.parametrize("given", [{"kyy_n_per_mm": 0.0},
                                   {"kxx_n_per_mm": 0.0, "kyy_n_per_mm": 5e4}])
def test_a_bearing_that_holds_one_way_only_is_refused_naming_the_key(given):
    """kyy = 0 beside kxx > 0 (or the other way round) leaves the shaft free to slide
    across its bearing: refused at once, naming the zero, not minutes later by a whirl
    that does not settle."""
    from shaftfem.errors import SceneError

    zero = next(k for k, v in given.items() if v == 0.0)
    with pytest.raises(SceneError, match=rf"{zero} = 0.0: the bearing holds the shaft"):
        load_scene(pulley_rotor(**given))


def test_the_rotor_table_refuses_what_it_cannot_mean():
    """Two operating speeds less than 1 r/min apart (they would name the same files),
    a basis smaller than the modes asked plus two (its check would be empty), and a
    speed range upside down; a one-speed coefficient table is a constant one."""
    from shaftfem.errors import SceneError
    from shaftfem.workflows.campbell import turning

    with pytest.raises(SceneError, match=r"rotor\.speed_rpm.*less than 1 r/min apart"):
        load_scene({**pulley_rotor(), "rotor": {"speed_rpm": [9000.0, 9000.4]}})
    with pytest.raises(SceneError, match="basis_modes = 2"):
        turning(load_scene({**pulley_rotor(), "rotor": {"speed_rpm": 3000.0,
                                                         "basis_modes": 2}}))
    with pytest.raises(SceneError, match="speed_range_rpm"):
        load_scene({**pulley_rotor(), "rotor": {"speed_range_rpm": [4500.0, 2950.0]}})
    one = load_scene(pulley_rotor(speeds_rpm=[3000.0], kxx_n_per_mm=[5e4]))
    assert one.held[0].bearing is not None and one.held[0].bearing.speeds == ()
    ranged = load_scene({**pulley_rotor(), "rotor": {"speed_range_rpm": [2950.0, 4500.0]}})
    assert ranged.rotor is not None
    assert [round(w / RPM) for w in ranged.rotor.speeds] == [2950, 4500]
    assert ranged.rotor.spans == ((2950 * RPM, 4500 * RPM),)


def test_a_bearing_is_summarised_by_its_coefficients_and_units_are_named():
    from shaftfem.outputs.tables import installation_lines
    from shaftfem.scene.reference import unit

    class Result:
        scene = load_scene(pulley_rotor(cxx_n_s_per_mm=0.3))
        installed = None

    line = installation_lines(Result())[0]   # type: ignore[arg-type]
    assert "kxx 5e+04" in line and "cxx 0.3, cyy 0.3 N s/mm" in line and "k_r" not in line
    assert unit("cxx_n_s_per_mm") == "N s/mm" and unit("kxx_n_per_mm") == "N/mm"


def test_json_holds_no_infinity():
    import json

    from shaftfem.store import json_text

    text = json_text({"a": math.inf, "b": [1.0, -math.inf, math.nan], "c": {"d": 2.0}})
    assert json.loads(text) == {"a": None, "b": [1.0, None, None], "c": {"d": 2.0}}


# --------------------------------------------------------------------------------------
# The unbalance response


def free_bar(**support) -> dict:
    """A 500 x 40 mm steel bar turning, an unbalance at its middle; held by damping
    only at both ends (`support` given) or not at all."""
    data = {"name": "free_bar", "material": STEEL, "mesh": {"element_size_mm": 16.0},
            "shaft": {"length_mm": 500.0, "diameter_mm": 40.0}, "modes": {"count": 4},
            "rotor": {"speed_rpm": 2000.0, "max_speed_rpm": 2000.0, "campbell_points": 3},
            "unbalance": [{"position_mm": 250.0, "amount_g_mm": 100.0}]}
    if support:
        brg = {"kind": "bearing", "width_mm": 20.0, **support}
        data["support"] = [{**brg, "name": "a", "position_mm": 20.0},
                           {**brg, "name": "b", "position_mm": 480.0}]
    return data


@pytest.mark.parametrize("support", [{}, {"kxx_n_per_mm": 0.0, "cxx_n_s_per_mm": 0.01}])
def test_a_shaft_its_bearings_do_not_hold_spins_about_its_centre_of_mass(support):
    """Far below its first bending mode (about 44,000 r/min) a shaft that nothing holds
    sideways, or only a light damper, turns about its centre of mass: its middle
    orbits at the eccentricity U / m (rigid-body estimate) within 1 %."""
    from shaftfem.workflows.campbell import turning
    from shaftfem.workflows.unbalance import unbalance_response

    scene = load_scene(free_bar(**support))
    result, model, _ = turning(scene)
    r = unbalance_response(scene, result, model, np.array([2000.0]))
    mass = 7810.0 * math.pi / 4 * 0.04**2 * 0.5
    middle = r.bode[0]
    assert middle.major[0] == pytest.approx(100e-6 / mass, rel=0.01)


def test_an_undamped_rotor_has_no_finite_peak(pulley):
    """No damping: each peak is unbounded, at a 1x critical speed found directly."""
    from shaftfem.fem.tracking import direct_crossings
    from shaftfem.scene.model import Unbalance
    from shaftfem.workflows.unbalance import unbalance_response

    scene, result, model, _ = pulley
    heavy = replace(scene, unbalances=(Unbalance("disk", 0.3, 50e-6),))
    r = unbalance_response(heavy, result, model)
    assert not r.damped and r.peaks
    ones = [d.omega / RPM for d in direct_crossings(model, (1,), 12000 * RPM)]
    for p in r.peaks:
        assert p.unbounded and math.isinf(p.amplitude) and p.amplification is None
        assert min(abs(p.speed_rpm / n - 1) for n in ones) < 1e-3


def test_unbalances_that_cancel_give_no_peak_and_one_off_the_shaft_is_refused(pulley):
    from shaftfem.errors import SceneError
    from shaftfem.scene.model import Unbalance
    from shaftfem.workflows.unbalance import unbalance_response

    scene, result, model, _ = pulley
    pair = (Unbalance("a", 0.3, 50e-6, 0.0), Unbalance("b", 0.3, 50e-6, math.pi))
    damped = replace(model, bearings=tuple(
        replace(b, coefficients=replace(b.coefficients, cxx=(300.0,), cyy=(300.0,)))
        for b in model.bearings))
    r = unbalance_response(replace(scene, unbalances=pair), result, damped)
    assert r.damped and r.peaks == ()
    with pytest.raises(SceneError, match="off the shaft"):
        unbalance_response(replace(scene, unbalances=(Unbalance("far", 0.9, 1e-6),)),
                           result, model)


# --------------------------------------------------------------------------------------
# What the commands write


@pytest.fixture(scope="module")
def spindle_run(tmp_path_factory):
    """`shaftfem campbell` of the grinding spindle (20 mm elements) into a folder, and
    its JSON."""
    from pathlib import Path

    from shaftfem.cli import main

    out = tmp_path_factory.mktemp("spindle")
    scene = Path(__file__).parents[1] / "examples" / "overhung_spindle.toml"
    code = main(["campbell", str(scene), "--mesh-size", "20", "-q", "--out", str(out / "c"),
                 "--json", str(out / "c.json")])
    assert code == 0
    return scene, out


def test_campbell_writes_its_curves_shapes_and_valid_json(spindle_run):
    """campbell.csv holds every curve at every speed (each curve's frequency continuous:
    no spikes), critical_shapes.png the deflected lines, the JSON the crossings with
    their curves and the stability, and no Infinity."""
    import csv
    import json

    scene, out = spindle_run
    rows = list(csv.DictReader((out / "c" / "campbell.csv").open()))
    assert set(rows[0]) == {"speed_rpm", "curve", "frequency_hz", "whirl", "whirl_index",
                            "log_dec", "kind"}
    by_curve: dict[str, list[tuple[float, float]]] = {}
    for r in rows:
        by_curve.setdefault(r["curve"], []).append((float(r["speed_rpm"]),
                                                    float(r["frequency_hz"])))
    assert len(by_curve) >= 6
    for pts in by_curve.values():
        s, f = np.array(pts).T
        assert np.all(np.diff(s) > 0)
        # a whirl frequency moves less than twice as fast as the spin (no jump)
        assert np.all(np.abs(np.diff(f)) <= 2 * np.diff(s) / 60 + 1e-6 * f[1:])
    assert (out / "c" / "critical_shapes.png").stat().st_size > 10_000
    text = (out / "c.json").read_text()
    assert "Infinity" not in text and "NaN" not in text
    c = json.loads(text)
    assert {cs["curve"] for cs in c["critical_speeds"]} and c["stability"]["ok"]
    assert c["unbalance"]["amplitudes"] == "0-peak"


def test_campbell_publishes_all_its_files_or_none(spindle_run, monkeypatch):
    """Interrupted while it writes into a folder of an earlier run, campbell leaves that
    run's files as they were and adds none."""
    import shaftfem.outputs.whirl_files as wf
    from shaftfem.cli import main

    scene, out = spindle_run
    before = {p.name: p.read_bytes() for p in (out / "c").iterdir() if p.is_file()}

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(wf, "write_whirl_files", interrupted)
    code = main(["campbell", str(scene), "--mesh-size", "20", "-q", "--out", str(out / "c")])
    assert code == 130
    after = {p.name: p.read_bytes() for p in (out / "c").iterdir() if p.is_file()}
    assert after == before


def test_check_exits_1_for_an_unstable_rotor_and_0_for_a_sound_one(tmp_path):
    """The check's exit status, as CI reads it: a rotor whose bearings' cross-coupling
    makes it unstable fails (1) naming the instability; the same with the cross-coupling
    gone passes (0)."""
    import json
    import tomllib
    from pathlib import Path

    import tomli_w

    from shaftfem.cli import main

    data = tomllib.loads((Path(__file__).parents[1] / "examples" / "overhung_spindle.toml")
                         .read_text())
    data["mesh"]["element_size_mm"] = 20.0
    data["rotor"]["campbell_points"] = 11
    for s in data["support"]:
        s["kxy_n_per_mm"], s["kyx_n_per_mm"] = 6e4, -6e4
    path = tmp_path / "unstable.toml"
    path.write_text(tomli_w.dumps(data))
    assert main(["check", str(path), "-q", "--json", str(tmp_path / "v.json")]) == 1
    v = json.loads((tmp_path / "v.json").read_text())
    assert v["unstable"] and "grows" in v["unstable"][0]
    for s in data["support"]:
        s.pop("kxy_n_per_mm"), s.pop("kyx_n_per_mm")
    path.write_text(tomli_w.dumps(data))
    assert main(["check", str(path), "-q"]) == 0


def keyed_rotor() -> dict:
    """The keyed stepped shaft of the examples (not of revolution: the turning frame),
    12 mm elements, in damped isotropic bearings, 20 g mm at its keyway, to 30,000 r/min."""
    import tomllib
    from pathlib import Path

    data = tomllib.loads((Path(__file__).parents[1] / "examples" / "stepped_shaft.toml")
                         .read_text())
    data["mesh"]["element_size_mm"] = 12.0
    data["modes"] = {"count": 4}
    for s in data["support"]:
        s.update({"kind": "bearing", "kxx_n_per_mm": 2e4, "cxx_n_s_per_mm": 0.3})
    data["unbalance"] = [{"position_mm": 150.0, "amount_g_mm": 20.0}]
    data["rotor"] = {"speed_rpm": 6000.0, "max_speed_rpm": 30000.0}
    data.pop("excitation", None)
    return data


@pytest.mark.slow
def test_the_keyed_rotor_s_forward_critical_is_found_near_its_bode_peak():
    """A keyed stepped shaft (not of revolution: the turning frame) in damped isotropic
    bearings: its forward 1x crossings, at the ends of the stretch where its pair's roots
    stand at zero frequency in the turning frame, found on 31 speeds and on 310 alike
    (1e-5), and the peak of its unbalance response between them."""
    from shaftfem.workflows.campbell import campbell_of, turning

    scene = load_scene(keyed_rotor())
    result, model, why = turning(scene)
    assert model.frame == "rotating"
    c = campbell_of(scene, result, model, why)
    forward = sorted(cs.speed_rpm for cs in c.critical_speeds
                     if cs.order == 1 and cs.whirl == "forward")
    # the stretch where its roots stand at zero frequency: one crossing at each end
    assert len(forward) == 2 and forward[1] / forward[0] - 1 < 0.03
    fine = campbell_of(scene, result, model, why, np.linspace(0.0, 30000.0, 310))
    again = sorted(cs.speed_rpm for cs in fine.critical_speeds
                   if cs.order == 1 and cs.whirl == "forward")
    assert again == pytest.approx(forward, rel=1e-5)
    assert c.unbalance is not None
    peak = max(c.unbalance.peaks, key=lambda p: p.amplitude)
    assert forward[0] * 0.99 <= peak.speed_rpm <= forward[1] * 1.01


def test_a_shaft_not_of_revolution_diverges_between_its_two_critical_speeds():
    """The keyed shaft in undamped isotropic bearings: between the critical speeds of its
    soft and its stiff diameter (the forward 1x crossings, 340 r/min apart: no grid
    speed inside on 31 speeds to 30,000 r/min) its pair's roots stand at zero frequency
    in the turning frame and one of them grows (the asymmetric shaft's classical band):
    one zone of divergence, its edges those two crossings, stable above it."""
    from shaftfem.workflows.campbell import campbell_of, turning

    data = keyed_rotor()
    for s in data["support"]:
        s["cxx_n_s_per_mm"] = 0.0
    scene = load_scene(data)
    result, model, why = turning(scene)
    c = campbell_of(scene, result, model, why)
    forward = sorted(cs.speed_rpm for cs in c.critical_speeds
                     if cs.order == 1 and cs.whirl == "forward")
    assert len(forward) == 2 and not any(forward[0] < w < forward[1] for w in c.speeds_rpm)
    (zone,) = c.zones
    assert "divergence" in zone.holds and zone.growth_per_s > 0
    assert (zone.from_rpm, zone.to_rpm) == pytest.approx(forward, rel=1e-4)


def test_an_undamped_model_says_so_and_design_draws_no_base_motion_for_a_rotor(pulley):
    from shaftfem.workflows.campbell import campbell_of
    from shaftfem.workflows.design import base_motion_drawn

    scene, result, model, why = pulley
    c = campbell_of(scene, result, model, why)
    assert any("no bearing has damping" in n for n in c.notes)
    assert c.stability is not None and not c.stability.judged
    assert not base_motion_drawn(scene)
    assert base_motion_drawn(replace(scene, rotor=None))


def test_modes_at_a_speed_writes_its_whirl_in_the_json(tmp_path):
    import json
    from pathlib import Path

    from shaftfem.cli import main

    scene = Path(__file__).parents[1] / "examples" / "overhung_spindle.toml"
    code = main(["modes", str(scene), "--mesh-size", "20", "--no-estimate", "-q",
                 "--speed-rpm", "9000", "--json", str(tmp_path / "m.json")])
    assert code == 0
    turning = json.loads((tmp_path / "m.json").read_text())["turning"]
    assert turning["speed_rpm"] == 9000
    whirl = [w for w in turning["whirl"] if w["kind"] == "bending"]
    assert [w["whirl"] for w in whirl[:2]] == ["backward", "forward"]
    assert whirl[0]["frequency_hz"] < whirl[1]["frequency_hz"]


def test_a_zone_of_growth_inside_the_running_range_fails_and_beyond_it_warns(pulley):
    """A periodic rotor's zone of growth (Campbell.zones) judged as a divergence band is:
    one that reaches into the running range fails the check (exit 1) naming its speeds
    and growth; one beyond it is a warning with its margin from the nearest running
    speed (here 25 %)."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.fem.whirl import GrowthZone
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    c = campbell_of(at_speed(scene, 3000.0), result, model, why)

    def zone(lo: float, hi: float) -> tuple[GrowthZone]:
        return (GrowthZone(lo, hi, 4.2, 0.5 * (lo + hi), ("parametric",)),)

    inside = check_whirl(replace(c, zones=zone(2900.0, 3100.0)), 0.15)
    assert not inside.ok and inside.exit_status == 1
    assert any("zone of growth" in u and "2,900" in u and "4.2 1/s" in u
               for u in inside.unstable)
    beyond = check_whirl(replace(c, zones=zone(3750.0, 3900.0)), 0.15)
    assert not any("zone of growth" in u for u in beyond.unstable)
    assert any("zone of growth" in w and "25.0 %" in w for w in beyond.warnings)


def test_an_undamped_cross_coupled_rotor_grows_from_standstill_and_says_so(pulley):
    """No damping anywhere and a constant cross-coupling kxy = -kyx: a forward mode
    grows from standstill on (its log decrement a little below zero, with no positive
    stretch to fall from). The onset is the diagram's first speed, one zone of growth
    runs to its end, the check fails, and no note calls the log decrements zero."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.scene.model import BearingCoefficients
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    zero = (0.0,)
    coeffs = BearingCoefficients(speeds=(), kxx=(5e7,), kxy=(2e6,), kyx=(-2e6,),
                                 kyy=(5e7,), cxx=zero, cxy=zero, cyx=zero, cyy=zero)
    coupled = replace(model, bearings=tuple(replace(b, coefficients=coeffs)
                                            for b in model.bearings))
    c = campbell_of(scene, result, coupled, why)
    growing = [cv for cv in c.curves if cv.whirling and np.all(cv.log_dec[1:] < 0)]
    assert growing, "a circulatory force with no damping makes one mode of a pair grow"
    assert c.onsets and c.onsets[0].speed_rpm == pytest.approx(0.0, abs=1e-6)
    assert len(c.zones) == 1 and c.zones[0].from_rpm == pytest.approx(0.0, abs=1e-6)
    assert c.zones[0].open and c.stable_above_rpm is None
    assert not any("log decrements are zero" in n for n in c.notes)
    v = check_whirl(c, 0.15)
    assert not v.ok and v.exit_status == 1 and any("starts to grow" in u for u in v.unstable)


def test_overlapping_growth_is_one_zone_and_the_rotor_is_stable_above_it():
    """Three overlapping bands of growth (a parametric zone and two onsets inside it)
    are one zone with the outer edges and the fastest growth; a band apart stays
    apart; the zone that stops short of the diagram's end leaves the rotor stable."""
    from shaftfem.fem.whirl import growth_zones

    parts = [(4507.0, 4815.0, 1.0, 4700.0, "parametric"),
             (4507.0, 5501.0, 3.0, 5000.0, "curve 3 (forward whirl)"),
             (5108.0, 5502.0, 2.0, 5300.0, "curve 4 (backward whirl)"),
             (7000.0, 9000.0, 0.5, 9000.0, "divergence")]
    one, two = growth_zones(parts, 9000.0)
    assert (one.from_rpm, one.to_rpm, one.growth_per_s, one.fastest_rpm) == (
        4507.0, 5502.0, 3.0, 5000.0)
    assert len(one.holds) == 3 and not one.open
    assert two.open and two.holds == ("divergence",)
    (alone,) = growth_zones(parts[:3], 9000.0)
    assert not alone.open and alone.to_rpm == 5502.0


def test_a_crossing_inside_a_zone_of_growth_is_judged_by_its_zone(pulley):
    """A 1x crossing in a zone where the rotor grows has no steady resonance to keep a
    margin from: the check judges the zone (it fails, inside the running range) and
    measures no margin from that crossing; a crossing outside every zone is judged."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.fem.whirl import GrowthZone
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    c = campbell_of(scene, result, model, why)
    cs = next(x for x in c.critical_speeds if x.order == 1 and x.whirl == "forward"
              and not x.critically_damped)
    n = cs.speed_rpm
    before = check_whirl(c, 0.15)
    assert any(f"critical at {n:,.0f} r/min" in a.kind for a in before.approaches)
    zone = GrowthZone(0.9 * n, 1.1 * n, 2.0, n, ("parametric",))
    after = check_whirl(replace(c, zones=(zone,)), 0.15)
    assert not any(f"critical at {n:,.0f} r/min" in a.kind for a in after.approaches)


def test_the_shapes_picture_of_a_rotor_below_its_criticals_shows_the_nearest_modes(pulley):
    """A diagram that ends below every 1x critical speed: critical_shapes.png draws the
    lightly damped whirling modes nearest the range (at its top speed) instead of an
    empty frame, over the whole shaft, end to end."""
    from shaftfem.outputs.campbell_plot import critical_shapes_figure, deflected_lines
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why = pulley
    full = campbell_of(scene, result, model, why)
    first = min(cs.speed_rpm for cs in full.critical_speeds if cs.order == 1)
    top = 0.5 * first
    c = campbell_of(at_speed(scene, 0.4 * first, max_speed=top * RPM), result, model, why,
                    speeds_rpm=np.linspace(0.0, top, 5))
    assert not [cs for cs in c.critical_speeds if cs.order == 1]
    lines = deflected_lines(c)
    assert lines and all(label.startswith("nearest: curve") for label, *_ in lines)
    assert all(np.isclose(major.max(), 1.0) for _, _, major, _ in lines)
    ax = critical_shapes_figure(c).axes[0]
    z = result.system.nodes[:, 2] * 1e3
    assert ax.get_xlim() == pytest.approx((z.min(), z.max()))


def test_a_basis_that_will_not_settle_stops_with_a_message(monkeypatch):
    """Where the whirl still moves on the largest basis allowed, the run stops with one
    message saying by how much and what to check, instead of climbing on in silence."""
    from shaftfem.errors import SolverError
    from shaftfem.fem.whirl import Truncation
    from shaftfem.workflows import campbell

    monkeypatch.setattr(campbell, "_MODELS", {})
    monkeypatch.setattr(campbell, "MAX_MODE_COUNT", campbell.basis_size(
        load_scene(pulley_rotor())))
    monkeypatch.setattr(campbell, "truncation", lambda model, speeds, count: Truncation(
        size=model.size, smaller=model.size - 2, speeds_rpm=(0.0,), change=0.05))
    with pytest.raises(SolverError, match=r"does not settle.*still moves by 5 %"):
        campbell.turning(load_scene(pulley_rotor()))


def test_each_crossing_is_listed_once_with_the_whirl_that_dominates_its_mode():
    """A periodic rotor's pair locked to the speed meets the 1x line as two curves at
    one speed: listed once, by the curve that carries more of its mode; a crossing met
    by a component carrying 41 % of the motion whirls the other way; crossings of the
    stationary frame are never merged."""
    from shaftfem.fem.whirl import CriticalSpeed
    from shaftfem.workflows.campbell import dominant, once

    assert dominant("forward", "backward", 0.41) == "forward"
    assert dominant("backward", "backward", 0.79) == "backward"
    a = CriticalSpeed(1, "forward", 4854.0, 80.9, 3, 3.6, "forward", 0.7)
    b = CriticalSpeed(1, "backward", 4854.2, 80.9, 4, -3.43, "backward", 0.3)
    c = CriticalSpeed(1, "forward", 5502.0, 91.7, 3, 0.2, "forward", 0.8)
    assert once([b, c, a]) == [a, c]
    still = [replace(a, component=""), replace(b, component="")]
    assert len(once(still)) == 2
