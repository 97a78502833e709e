"""An API 684 study on an oil-film rotor gives the verdicts its definitions give:
stability judged where the shaft runs and only above the journals' lift-off, no
critical speed from a critically damped root (AF below 2.5), a FAIL whose message
agrees with its table, and bad options refused at once (exit 2).

The rotor is our own: a 45 mm, 800 mm shaft with a 20 kg wheel between two plain
journals (L/D 0.49, 45 um clearance, ISO VG 46 at 45 C), slow roll at 25 r/min and
running at 3,600 r/min.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from shaftfem.cli import main
from shaftfem.fem.whirl import RPM, WHIRLING
from shaftfem.scene.load import load_scene

STEEL = {"name": "steel", "youngs_modulus_mpa": 206000.0, "poisson_ratio": 0.29,
         "density_kg_m3": 7850.0}
SLOW_ROLL, RUNNING = 25.0, 3600.0


def wheel_on_journals(**rotor) -> dict:
    def journal(name: str, z: float) -> dict:
        return {"name": name, "position_mm": z, "width_mm": 22.0, "kind": "journal",
                "radial_clearance_um": 45.0, "oil_iso_vg": 46, "oil_temperature_c": 45.0}
    return {"name": "wheel_on_journals", "shaft": {"length_mm": 800.0, "diameter_mm": 45.0},
            "material": STEEL, "mesh": {"element_size_mm": 22.0}, "modes": {"count": 6},
            "resonance": {"criterion": "api684"},
            "support": [journal("inboard", 40.0), journal("outboard", 760.0)],
            "attachment": [{"name": "wheel", "position_mm": 430.0, "width_mm": 50.0,
                            "mass_kg": 20.0, "polar_inertia_kg_m2": 0.16,
                            "diametral_inertia_kg_m2": 0.09, "joint": "distributing"}],
            "rotor": {"speed_rpm": [SLOW_ROLL, RUNNING], "max_speed_rpm": 9000.0,
                      "campbell_points": 19, **rotor}}


@pytest.fixture(scope="module")
def wheel():
    """The rotor loaded on its journals, its basis and model, and its Campbell diagram."""
    from shaftfem.workflows.campbell import campbell_of, turning
    from shaftfem.workflows.static import equipped

    scene = equipped(load_scene(wheel_on_journals()))
    result, model, why = turning(scene)
    return scene, result, model, why, campbell_of(scene, result, model, why)


def test_the_lift_off_speed_is_where_the_least_film_clears_its_limit(wheel):
    """parts.journal.lift_off inverts the film: there the least film is the bearing's
    min_film, thinner below it, thicker above."""
    from shaftfem.parts.journal import lift_off, operating

    scene = wheel[0]
    for s in scene.held:
        b = s.journal
        w = lift_off(b)
        assert operating(b, w).min_film == pytest.approx(b.min_film, rel=1e-3)
        assert operating(b, 0.8 * w).min_film < b.min_film < operating(b, 1.25 * w).min_film
        assert SLOW_ROLL * RPM < w < RUNNING * RPM


def test_stability_is_judged_where_the_shaft_runs_above_lift_off(wheel):
    """At standstill and at slow roll some whirling mode has a log decrement far below
    API 684's 0.1 (the films are stiff and damp little there): no verdict rests on
    it. The least log decrement judged is the running speed's, as whirl_at gives it."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.workflows.campbell import whirl_at

    scene, _, model, _, c = wheel
    still = [w.log_dec for w in whirl_at(model, 0.0, 6) if w.kind in WHIRLING]
    assert min(still) < 0.1
    st = c.stability
    assert st is not None and st.speed_rpm == pytest.approx(RUNNING)
    there = [w.log_dec for w in whirl_at(model, RUNNING * RPM, 6) if w.kind in WHIRLING]
    assert st.log_dec == pytest.approx(min(there), rel=1e-6, abs=1e-9)
    assert st.unjudged_rpm == (SLOW_ROLL,)
    v = check_whirl(c)
    if st.log_dec > 0.1:
        assert not v.unstable
    assert any("no stability verdict at 25 r/min" in w for w in v.warnings)


def test_a_critically_damped_crossing_is_no_critical_speed(wheel):
    """The films' rigid-body roots cross 1x near the slow roll with AF = pi / log dec far
    below 2.5: listed as critically damped, never judged, never the closest pair,
    whatever the criterion; drawn nowhere as a critical speed."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.outputs.campbell_plot import deflected_lines
    from shaftfem.outputs.tables import campbell_text, verdict_rows

    c = wheel[4]
    # the films' own crossings lie below their lift-off, where the journal runs on its
    # shell: left out and said; a heavily damped crossing above it (log dec 5) is made
    assert all(cs.speed_rpm >= c.lift_rpm for cs in c.critical_speeds)
    assert any("below the journals' lift-off" in n for n in c.notes)
    first = c.critical_speeds[0]
    damped = [replace(first, log_dec=5.0)]
    c = replace(c, critical_speeds=(*damped, *c.critical_speeds[1:]))
    for cs in damped:
        assert cs.critically_damped and 0.5 <= cs.amplification < 2.5
    for flat in (None, 0.15):
        v = check_whirl(c, flat)
        exempt = [a for a in v.approaches if a.exempt]
        assert len(exempt) >= len(damped)
        assert all(a.required == 0.0 and a.ok for a in exempt)
        assert all(not a.exempt for a in v.judged)
        assert all(f"{cs.speed_rpm:,.0f} r/min" not in r[5] for cs in damped
                   for r in verdict_rows(v)[1] if v.judged)
    assert "critically damped" in campbell_text(c)
    shown = " ".join(label for label, *_ in deflected_lines(c))
    for cs in damped:
        assert f"{cs.speed_rpm:,.0f} r/min" not in shown


def test_the_critical_shapes_carry_their_phase(wheel):
    """The wheel's first 1x critical is its first bending shape on the films: no node
    between the journals (the phase never turns by 90 deg or more from its largest
    point; a conical or second shape would turn by 180), the middle third within 30 deg
    (towards the journals the damped films make it lag), its major semi-axis largest
    near the wheel; the phase panel is drawn."""
    from shaftfem.outputs.campbell_plot import critical_shapes_figure, deflected_lines

    c = wheel[4]
    label, z, major, phase = deflected_lines(c)[0]
    inside = (z > 40.0) & (z < 760.0)
    assert np.all(np.abs(phase[inside]) < 90.0), phase[inside]
    middle = (z > 280.0) & (z < 520.0)
    assert np.all(np.abs(phase[middle]) < 30.0), phase[middle]
    assert 300.0 < z[int(np.argmax(major))] < 560.0
    axes = critical_shapes_figure(c).axes
    assert len(axes) == 2 and axes[1].get_ylabel() == "phase of the whirl, deg"
    assert len(axes[1].lines) >= 2   # a phase line beside the bearings' planes


def test_a_fail_names_its_tightest_pair_and_the_table_shows_every_failing_one(wheel):
    """Running just below the first critical speed: the FAIL line names the pair with
    the least margin beyond its own required one, with that margin, and every failing
    pair is a row of the table."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.outputs.tables import verdict_line, verdict_rows
    from shaftfem.workflows.campbell import campbell_of

    scene, result, model, why, c = wheel
    first = min(cs.speed_rpm for cs in c.critical_speeds
                if not cs.critically_damped and cs.order == 1)
    # the separation alone: no least log decrement asked (API 684's 0.1 is judged above)
    near = replace(scene, rotor=replace(scene.rotor, min_log_dec=0.0,
                                        speeds=(SLOW_ROLL * RPM, 0.93 * first * RPM)))
    v = check_whirl(campbell_of(near, result, model, why))
    assert v.violations
    tight = min(v.violations, key=lambda a: a.margin - a.required)
    line = verdict_line(v)
    assert f"only {100 * tight.margin:.1f} %" in line
    assert f"({100 * tight.required:.3g} % required)" in line
    rows = verdict_rows(v)[1]
    for a in v.violations:
        assert any(r[5] == a.kind and r[0] == a.source and r[-1] == "TOO CLOSE" for r in rows)


def test_the_unbalance_response_fails_the_verdict_where_the_report_marks_it(wheel):
    """The verdict and the report's rows judge the unbalance response alike: an orbit
    above [rotor] amplitude_limit_um at any speed of the Bode plot (a run-up rubs a seal
    on the way), or under API 684 a damped peak nearer the running speed than its AF's
    margin (a flat criterion shows the peaks for information), fails
    the check (exit 1) and is a FAIL row; under the limit and clear of its peaks it
    passes. The orbit where the shaft runs is the curve's at the running speed. The
    response is made here (a curve peaking at 12 um at 2,000 r/min; 3.8 um at 3,600
    r/min by linear reading between 5 and 3 um), the rotor's own crossings and stability
    kept: before, the report said FAIL under a passing verdict."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.fem.whirl import Bode, Peak, UnbalanceResponse
    from shaftfem.outputs.tables import _api684_case_rows, verdict_line, verdict_lines

    c = wheel[4]
    ANY = "largest unbalance response (any probe, any speed)"
    RUNS = "unbalance response where the shaft runs (any probe)"
    n = np.array([0.0, 1000.0, 2000.0, 3000.0, 4000.0, 9000.0])
    major = np.array([0.5, 2.0, 12.0, 5.0, 3.0, 2.0]) * 1e-6
    bode = Bode("wheel", 0.43, n, major, np.zeros_like(n), major)
    peak = Peak("wheel", 3400.0, 12e-6, (3200.0, 3625.0), 8.0, 0.0556, 0.16)

    def judged(limit_um, peaks=(), criterion="api684"):
        rotor = replace(c.rotor_scene.rotor, min_log_dec=0.0, amplitude_limit=(
            None if limit_um is None else limit_um * 1e-6))
        cc = replace(c, scene=replace(c.rotor_scene, rotor=rotor, criterion=criterion),
                     unbalance=UnbalanceResponse((bode,), tuple(peaks)))
        v = check_whirl(cc)
        rows = {r[0]: r for r in _api684_case_rows(cc, v, None, "")}
        return v, rows

    clear, rows = judged(15.0)
    assert clear.response == []
    assert rows[ANY][1:] == [
        "12 um at wheel, 2,000 r/min", "15 um", "pass"]
    assert rows[RUNS][1:] == [
        "3.8 um at wheel, 3,600 r/min", "15 um", "pass"]
    rubbed, rows = judged(10.0)
    assert not rubbed.ok and rubbed.exit_status == 1
    assert rubbed.response == ["unbalance orbit at wheel: 12 um at 2,000 r/min, above the "
                               "10 um limit ([rotor] amplitude_limit_um)"]
    assert rows[ANY][-1] == "FAIL"
    assert rows[RUNS][-1] == "pass"
    assert any(line.startswith("UNBALANCE RESPONSE NOT MET: unbalance orbit at wheel")
               for line in verdict_lines(rubbed))
    if clear.ok:
        assert "FAIL" in verdict_line(rubbed) and "unbalance response" in verdict_line(rubbed)
    _, rows = judged(3.0)
    assert rows[RUNS][-1] == "FAIL"
    near, rows = judged(None, [peak])
    assert not near.ok and len(near.response) == 1
    assert near.response[0].startswith("unbalance peak at wheel: 3,400 r/min (AF 8.0), 5.6 %")
    assert rows["unbalance peak at wheel"][-1] == "FAIL"
    assert RUNS in rows   # no limit: shown
    assert rows[RUNS][-1] == "-"
    # a flat margin judges the crossings; the peaks are shown for information
    flat, rows = judged(None, [peak], "flat")
    assert flat.response == [] and rows["unbalance peak at wheel"][-1] == "-"


def test_a_section_between_the_mesh_nodes_is_read_as_exactly_as_one_on_them(wheel):
    """fem.supports.section_means at a position with no node plane: each rigid motion of
    the section reads exactly (translation 1, tilt its angle, turn its angle), and a
    field linear along the shaft reads its value there."""
    from shaftfem.fem.supports import section_means

    result = wheel[1]
    nodes, mass = result.system.nodes, result.system.mass_scalar.diagonal()
    z0 = 0.3217
    assert not np.any(np.abs(nodes[:, 2] - z0) < 1e-7)
    c = section_means(nodes, mass, z0)
    x, y, z = nodes.T
    d = z - z0
    a = 1e-3
    fields = {
        "ux": (np.ones_like(z), 0 * z, 0 * z, 0),
        "uy": (0 * z, np.ones_like(z), 0 * z, 1),
        "tilt about y": (a * d, 0 * z, -a * x, 4),
        "tilt about x": (0 * z, -a * d, a * y, 3),
        "turn": (-a * y, a * x, 0 * z, 5),
    }
    for name, (ux, uy, uz, row) in fields.items():
        u = np.column_stack([ux, uy, uz]).ravel()[c.dofs]
        q = c.C @ u
        want = np.zeros(6)
        want[row] = a if row > 2 else 1.0
        np.testing.assert_allclose(q, want, atol=1e-9 * (1 if row < 3 else a), err_msg=name)
    bend = np.column_stack([5e-3 + 2e-2 * d, 0 * z, 0 * z]).ravel()[c.dofs]
    assert (c.C @ bend)[0] == pytest.approx(5e-3, rel=1e-9)


# --------------------------------------------------------------------------------------
# Options and scenes refused at once


@pytest.fixture()
def no_turning(monkeypatch):
    """Any turning solve is an error: a refusal must come before the work."""
    from shaftfem.workflows import campbell

    def never(*_a, **_k):
        raise AssertionError("the solve ran")

    monkeypatch.setattr(campbell, "turning", never)


def _exit_2(capsys, argv, named):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert named in err and "Traceback" not in err and len(err.splitlines()) == 1, err


@pytest.fixture()
def scene_file(tmp_path):
    import tomli_w

    def write(data: dict) -> str:
        f = tmp_path / "rotor.toml"
        f.write_bytes(tomli_w.dumps(data).encode())
        return str(f)
    return write


@pytest.mark.parametrize("argv,named", [
    (["level1", "--at-mm", "5000"], "--at-mm 5000"),
    (["level1", "--at-mm", "-10"], "--at-mm -10"),
    (["level1", "--qa-n-per-mm", "0"], "--qa-n-per-mm 0"),
    (["level1", "--qa-n-per-mm", "-5"], "--qa-n-per-mm -5"),
    (["frf", "--at-mm", "430", "--frequencies-hz", "1:100:5", "--speeds-rpm=-100"],
     "--speeds-rpm -100"),
])
def test_an_option_no_rotor_can_mean_is_refused_before_the_solve(capsys, no_turning,
                                                                  scene_file, argv, named):
    _exit_2(capsys, [argv[0], scene_file(wheel_on_journals()), *argv[1:]], named)


def test_level1_asked_with_nothing_to_screen_against_is_refused(capsys, scene_file):
    data = wheel_on_journals(level1=True)
    _exit_2(capsys, ["check", scene_file(data)], "level1")
    data["rotor"]["level1_qa_n_per_mm"] = 500.0
    load_scene(data)   # with Q_A it loads


@pytest.mark.parametrize("diameter,ok", [(30.0, False), (45.0, True), (45.3, True),
                                         (47.0, False)])
def test_a_journal_is_the_shaft_s_own_diameter(capsys, scene_file, diameter, ok):
    data = wheel_on_journals()
    data["support"][0]["diameter_mm"] = diameter
    if ok:
        assert load_scene(data).supports[0].journal.diameter == pytest.approx(diameter * 1e-3)
    else:
        _exit_2(capsys, ["check", scene_file(data)], "diameter_mm")


def test_a_study_figure_is_published_whole_with_its_manifest_or_not_at_all(tmp_path,
                                                                            monkeypatch):
    """runup --out (and level1, frf, static): the picture and its manifest, or on an
    interrupt nothing in the folder."""
    import json

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from shaftfem.cli.commands import _publish_figure
    from shaftfem.outputs import plots

    monkeypatch.setattr(plots, "runup_figure", lambda r: plt.figure())
    out = tmp_path / "out"
    _publish_figure(str(out), "runup", object())
    manifest = json.loads((out / "runup.manifest.json").read_text())
    assert set(manifest["files"]) == {"runup.png"}
    assert (out / "runup.png").read_bytes()[:4] == b"\x89PNG"

    def interrupted(_r):
        raise KeyboardInterrupt
    monkeypatch.setattr(plots, "runup_figure", interrupted)
    fresh = tmp_path / "fresh"
    with pytest.raises(KeyboardInterrupt):
        _publish_figure(str(fresh), "runup", object())
    assert not fresh.exists()


def test_the_version_is_printed(capsys):
    from shaftfem import __version__

    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"shaftfem {__version__}"


def test_a_curve_that_starts_or_ends_mid_range_says_why(monkeypatch):
    """Two real roots that meet and whirl as a pair start a curve mid-range, and part
    again to end it: the tracker says so (Curve.began "pair", Curve.ended "split"), the
    Campbell notes explain it, and a curve followed throughout says nothing. Spectra
    written here: one root throughout, another oscillating only from 50 to 80 rad/s."""
    from types import SimpleNamespace

    from shaftfem.fem import tracking
    from shaftfem.outputs.tables import curve_notes

    e1, e2 = np.eye(4)[:, 0].astype(complex), np.eye(4)[:, 1].astype(complex)

    def spectrum(model, omega):
        f, y = [10.0 + omega / 100], [e1]
        if 50.0 <= omega <= 80.0:
            f.append(20.0)
            y.append(e2)
        n = len(f)
        return tracking.Spectrum(omega, np.array(f), np.full(n, 1.0), np.ones(n),
                                 ("bending",) * n, np.column_stack(y), 0.0)

    monkeypatch.setattr(tracking, "spectrum", spectrum)
    model = SimpleNamespace(frame="stationary", size=4)
    curves = tracking.track(model, np.linspace(0.0, 100.0, 11), 2)   # type: ignore[arg-type]
    assert len(curves) == 2
    steady = next(c for c in curves if c.speeds_rpm[0] == 0.0)
    pair = next(c for c in curves if c is not steady)
    assert steady.began == steady.ended == ""
    assert pair.began == "pair" and pair.ended == "split"
    rpm = 30 / np.pi
    assert pair.speeds_rpm[0] == pytest.approx(50.0 * rpm)
    assert pair.speeds_rpm[-1] == pytest.approx(80.0 * rpm)
    notes = curve_notes(SimpleNamespace(curves=curves))
    assert len(notes) == 2
    assert notes[0].startswith(f"curve {pair.number} starts at 477 r/min: below it its two "
                               "roots are real")
    assert notes[1].startswith(f"curve {pair.number} ends at 764 r/min: above it the pair parts")


def test_the_run_up_text_says_what_its_numbers_say():
    """A run-up whose passage of the critical speed comes lower than the steady peak, and
    whose response then grows beyond an onset: the passage's peak said below the steady
    one, the run's largest response said to be no passage, and the finite-rate remark
    made; where a passage comes higher, no remark that it comes lower. Numbers written
    here, the steady peak at 3,600 r/min."""
    from types import SimpleNamespace

    from shaftfem.fem.whirl import RunUp
    from shaftfem.outputs.tables import runup_text

    n = np.linspace(200.0, 9000.0, 881)
    steady = 40e-6 / np.sqrt((1 - (n / 3600.0) ** 2) ** 2 + (0.2 * n / 3600.0) ** 2)
    passage = 0.8 * np.interp(n, n + 100.0, steady)        # lower and later
    grows = np.where(n > 7200.0, 40e-6 * np.exp((n - 7200.0) / 400.0), 0.0)
    envelope = np.maximum(passage, grows)
    k = int(np.argmax(envelope))

    def run(env, peak):
        return RunUp(scene=SimpleNamespace(name="rotor"), accel_rpm_per_s=1500.0,
                     names=("impeller",), speeds_rpm=n, envelopes=(env,), steady=(steady,),
                     peaks=(peak,), orbits=(np.zeros((2, 1)),), steps=1000)

    text = runup_text(run(envelope, (float(n[k]), float(envelope[k]))))
    assert "the passage's peak 20 % below the steady one, 100 r/min later" in text
    assert f"the run's largest response, {envelope[k] * 1e6:,.3g} um at 9,000 r/min" in text
    assert "its peak comes lower and later" in text
    higher = 1.1 * steady
    j = int(np.argmax(higher))
    text = runup_text(run(higher, (float(n[j]), float(higher[j]))))
    assert "10 % above the steady one" in text and "comes lower" not in text
    assert "largest response" not in text
