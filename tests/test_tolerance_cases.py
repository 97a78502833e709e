"""The cases an API 684 study runs: journals and seals given a clearance range, oil a
temperature or viscosity range, parts without a joint of their own; each case's films
against the film solved directly for its clearance and viscosity, and the verdict the
worst of the cases'.

The rotor is our own: a 45 mm, 800 mm shaft with a 20 kg wheel between two plain
journals (L/D 0.49, 40 to 50 um clearance, ISO VG 46 between 35 and 55 C).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from shaftfem.checks.resonance import Approach, ResonanceVerdict
from shaftfem.cli import main
from shaftfem.fem.whirl import RPM
from shaftfem.parts import journal, oil
from shaftfem.scene.load import load_scene
from shaftfem.workflows.cases import Case, CaseResult, case_scene, cases_of, combined

STEEL = {"name": "steel", "youngs_modulus_mpa": 206000.0, "poisson_ratio": 0.29,
         "density_kg_m3": 7850.0}
RUNNING = 3600.0


def wheel(clearance=(40.0, 50.0), temperature=(35.0, 55.0), joint="distributing") -> dict:
    def bearing(name: str, z: float) -> dict:
        return {"name": name, "position_mm": z, "width_mm": 22.0, "kind": "journal",
                "radial_clearance_um": list(clearance), "oil_iso_vg": 46,
                "oil_temperature_c": list(temperature)}
    part = {"name": "wheel", "position_mm": 430.0, "width_mm": 50.0, "mass_kg": 20.0,
            "polar_inertia_kg_m2": 0.16, "diametral_inertia_kg_m2": 0.09}
    if joint is not None:
        part["joint"] = joint
    return {"name": "wheel_cases", "shaft": {"length_mm": 800.0, "diameter_mm": 45.0},
            "material": STEEL, "mesh": {"element_size_mm": 22.0}, "modes": {"count": 6},
            "resonance": {"criterion": "api684"},
            "support": [bearing("inboard", 40.0), bearing("outboard", 760.0)],
            "attachment": [part],
            "rotor": {"speed_rpm": RUNNING, "max_speed_rpm": 9000.0, "campbell_points": 19}}


def test_a_range_gives_its_nominal_and_its_ends():
    """[min, max] runs at its middle, [min, nominal, max] at its nominal; the oil's ends
    are its viscosity at the temperatures' ends (cold oil the most viscous), which the
    part gives from the oil's grade (the scene holds the temperatures)."""
    from shaftfem.workflows.equip import with_parts

    declared = load_scene(wheel()).supports[0]
    assert declared.journal.viscosity is None and declared.tolerance.viscosity is None
    assert declared.tolerance.temperature == (35.0, 45.0, 55.0)
    s = with_parts(load_scene(wheel())).supports[0]
    assert s.journal.clearance == pytest.approx(45e-6)
    assert s.journal.viscosity == pytest.approx(oil.dynamic(46, 45.0))
    assert s.tolerance.clearance == pytest.approx((40e-6, 45e-6, 50e-6))
    assert s.tolerance.viscosity == pytest.approx(
        tuple(oil.dynamic(46, t) for t in (55.0, 45.0, 35.0)))
    s = load_scene(wheel(clearance=(40.0, 42.0, 50.0))).supports[0]
    assert s.journal.clearance == pytest.approx(42e-6)


@pytest.mark.parametrize("key,value,said", [
    ("radial_clearance_um", [50.0, 40.0], "ascending"),
    ("radial_clearance_um", [40.0], "tolerance range"),
    ("radial_clearance_um", [40.0, 45.0, 50.0, 55.0], "tolerance range"),
    ("radial_clearance_um", [0.0, 50.0], "radial_clearance_um = 0"),
    ("radial_clearance_um", ["40", 50.0], "tolerance range"),
    ("radial_clearance_um", [0.05, 0.08], "0.05 mm is 50 um"),   # mm typed as um
    ("oil_temperature_c", [-40.0, 50.0], "oil_temperature_c = -40"),
])
def test_a_bad_range_is_refused_naming_its_key(tmp_path, capsys, key, value, said):
    import tomli_w

    scene = wheel()
    scene["support"][0][key] = value
    path = tmp_path / "wheel.toml"
    path.write_bytes(tomli_w.dumps(scene).encode())
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "[[support]] #1" in err or "support" in err
    assert key in err and said in err and "Traceback" not in err


def test_the_cases_bracket_the_tolerances_and_a_joint_left_to_the_default():
    scene = load_scene(wheel())
    assert [c.name for c in cases_of(scene)] == [
        "nominal", "min clearance, cold oil", "max clearance, hot oil"]
    corners = wheel()
    corners["rotor"]["tolerance_cases"] = "corners"
    four = cases_of(load_scene(corners))
    assert {(c.clearance, c.oil) for c in four[1:]} == {
        ("min", "cold"), ("max", "hot"), ("min", "hot"), ("max", "cold")}
    scene = load_scene(wheel(clearance=(45.0, 45.0 + 1e-9), joint=None))
    names = [c.name for c in cases_of(scene)]
    assert names[0] == "nominal" and names[-1] == "distributing joints"
    assert case_scene(scene, cases_of(scene)[-1]).attachments[0].joint == "distributing"
    assert scene.attachments[0].joint == "rigid"
    fixed = load_scene(wheel(clearance=(45.0, 45.0 + 1e-9), temperature=(45.0, 45.0 + 1e-9)))
    assert len(cases_of(fixed)) == 3   # ranges, however narrow, are cases
    one = dict(wheel())
    for s in one["support"]:
        s["radial_clearance_um"], s["oil_temperature_c"] = 45.0, 45.0
    assert [c.name for c in cases_of(load_scene(one))] == ["nominal"]


def film_directly(b: journal.JournalBearing, omega: float) -> tuple[np.ndarray, np.ndarray]:
    """A loaded journal's K and C (N/m, N s/m) from the film solved at the eccentricity
    its Sommerfeld number asks (found by root-finding on the film itself)."""
    S = b.sommerfeld(omega)

    def gap(e: float) -> float:
        F = float(np.hypot(*journal.state(b.ratio, e).force))
        return math.log(2 * b.ratio / (math.pi * F)) - math.log(S)

    e = brentq(gap, 0.02, 0.95, xtol=1e-6)
    s = journal.state(b.ratio, e)
    F = float(np.hypot(*s.force))
    Q = journal.rotation(-math.pi / 2 - (math.atan2(s.force[1], s.force[0]) + math.pi))
    K, C = Q @ s.stiffness @ Q.T / F, Q @ s.damping @ Q.T / F   # the load along -y
    R = journal.rotation(math.atan2(b.direction[1], b.direction[0]) + math.pi / 2)
    unit = b.load / b.clearance
    return unit * R @ K @ R.T, unit / omega * R @ C @ R.T


@pytest.mark.parametrize("case,clearance,temperature", [
    (Case("min clearance, cold oil", "min", "cold"), 40e-6, 35.0),
    (Case("max clearance, hot oil", "max", "hot"), 50e-6, 55.0),
])
def test_each_case_s_film_is_the_film_of_its_clearance_and_oil(case, clearance, temperature):
    """At the running speed, each journal's eight coefficients in the case's scene
    against the film solved directly for that clearance and the oil's viscosity at that
    temperature, under the same static load: within 1 %."""
    from shaftfem.workflows.static import equipped

    scene = equipped(case_scene(load_scene(wheel()), case))
    omega = RUNNING * RPM
    for s in scene.held:
        b = s.journal
        assert b.clearance == pytest.approx(clearance)
        assert b.viscosity == pytest.approx(oil.dynamic(46, temperature))
        K, C = film_directly(b, omega)
        np.testing.assert_allclose(s.bearing.stiffness(omega), K, atol=0.01 * np.abs(K).max())
        np.testing.assert_allclose(s.bearing.damping(omega), C, atol=0.01 * np.abs(C).max())


def _verdict(margin: float, unstable: tuple[str, ...] = (),
             warnings: tuple[str, ...] = ("onset at 7,200 r/min",)) -> ResonanceVerdict:
    a = Approach(mode=1, frequency=60.0, kind="forward whirl (curve 1), critical at 3,600 "
                 "r/min", source="shaft at 3,000 r/min", order=1, excitation=50.0,
                 margin=margin, required=0.15)
    return ResonanceVerdict(approaches=[a], required=0.15, turning="the shaft turning",
                            unstable=list(unstable), warnings=list(warnings))


def test_the_study_takes_the_worst_case():
    """A study passes only where every case passes; its tightest pair and its reasons
    to fail are named by their case."""
    def result(name: str, v: ResonanceVerdict) -> CaseResult:
        return CaseResult(Case(name), None, v, None)   # type: ignore[arg-type]

    good = [result("nominal", _verdict(0.20)), result("min clearance, cold oil", _verdict(0.18))]
    assert combined(good).ok
    assert combined(good).warnings == ["onset at 7,200 r/min"]   # said once, the nominal's
    bad = good + [result("max clearance, hot oil", _verdict(0.12, ("curve 2 grows",),
                                                            ("onset at 6,900 r/min",)))]
    v = combined(bad)
    assert not v.ok and v.exit_status == 1
    assert v.violations[0].source.endswith("(max clearance, hot oil)")
    assert v.unstable == ["max clearance, hot oil: curve 2 grows"]
    assert v.warnings == ["onset at 7,200 r/min", "max clearance, hot oil: onset at 6,900 r/min"]
    assert len(v.approaches) == 3 and "3 cases" in (v.turning or "")
    assert combined(good[:1]) is good[0].verdict


@pytest.mark.slow
def test_check_prints_the_cases_side_by_side_and_fails_on_the_worst(tmp_path, capsys):
    """`check` of the wheel with its tolerances and its joint left to the default: four
    cases side by side, each case's clearance and viscosity in its column; the wheel on
    a distributing joint lowers the first 1x critical speed (its hub no longer stiffens
    the shaft under it); the exit status the worst case's verdict gives."""
    import json

    import tomli_w

    path = tmp_path / "wheel.toml"
    path.write_bytes(tomli_w.dumps(wheel(joint=None)).encode())
    status = main(["check", str(path), "--json", str(tmp_path / "v.json")])
    out = capsys.readouterr().out
    data = json.loads((tmp_path / "v.json").read_text())
    cases = data["cases"]
    assert [c["case"] for c in cases] == ["nominal", "min clearance, cold oil",
                                          "max clearance, hot oil", "distributing joints"]
    assert status == (0 if all(c["ok"] for c in cases) else 1)
    table = out[out.index("the study's cases"):]
    line = next(x for x in table.splitlines() if x.startswith("inboard: radial clearance"))
    assert line.split()[-4:] == ["45.0", "40.0", "50.0", "45.0"]
    line = next(x for x in table.splitlines() if x.startswith("inboard: oil viscosity"))
    assert [float(v) for v in line.split()[-4:-1]] == pytest.approx(
        [oil.dynamic(46, t) * 1e3 for t in (45.0, 35.0, 55.0)], abs=0.006)
    runs = [data["campbell"], *(c["campbell"] for c in cases[1:])]

    def lowest(c: dict) -> float:
        return min(x["speed_rpm"] for x in c["critical_speeds"]
                   if x["order"] == 1 and not x["critically_damped"])
    assert lowest(runs[-1]) < 0.97 * lowest(runs[0])


def friswell_tolerances() -> dict:
    """Friswell's 5.9.1 rotor on its two journals (tests/test_journal_bearing.
    friswell_journals) with a clearance of 45 to 55 um and oil of 16 to 24 mPa s."""
    from test_journal_bearing import friswell_journals

    scene = friswell_journals()
    for s in scene["support"]:
        s["radial_clearance_um"], s["viscosity_mpa_s"] = [45.0, 55.0], [16.0, 24.0]
    return scene


@pytest.mark.slow
def test_a_tolerance_case_on_journals_against_ross():
    """The case "min clearance, cold oil" of Friswell's 5.9.1 rotor on journals (45 um,
    24 mPa s) against ross-rotordynamics 2.3's beam model fed the same bearings (tests/
    data/journal_591_tight.json, benchmarks/journal_tables.py --case; ross's values:
    ross_reference.py --journals ... "5.9.1 journals, tight"): the whirl and log
    decrements at 1,000, 3,000 and 6,000 r/min, the first two 1x critical speeds and the
    onset of oil whip, each within 1 %."""
    import json
    from pathlib import Path

    from shaftfem.workflows.campbell import run_campbell
    from shaftfem.workflows.static import equipped
    from test_journal_bearing import meets_ross_591

    data = Path(__file__).parent / "data"
    table = json.loads((data / "journal_591_tight.json").read_text())
    ross = json.loads((data / "ross_rotors.json").read_text())["5.9.1 journals, tight"]
    ranged = load_scene(friswell_tolerances())
    case = next(c for c in cases_of(ranged) if c.name == "min clearance, cold oil")
    scene = equipped(case_scene(ranged, case))
    for s, theirs in zip(scene.supports, table["bearings"]):   # the same bearings
        assert s.journal.clearance == pytest.approx(45e-6)
        assert s.journal.viscosity == pytest.approx(24e-3)
        for k in ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"):
            np.testing.assert_allclose(getattr(s.bearing, k), theirs[k], rtol=1e-6)
    meets_ross_591(run_campbell(scene), ross, 0.01)


@pytest.mark.slow
def test_a_pump_that_passes_at_nominal_fails_on_its_loose_hot_case(tmp_path):
    """The shipped pump on journals with a wider clearance tolerance (45 to 75 um) and a
    looser oil system (40 to 60 C): its nominal case (60 um, 50 C) keeps its margins,
    as the shipped scene does; the loose, hot case (75 um, 60 C) has softer films, so
    its first 1x critical speed comes down towards the running speed and misses its
    margin. The study fails (exit 1) on that case and names it."""
    import json
    import tomllib
    from pathlib import Path

    import tomli_w

    data = tomllib.loads((Path(__file__).parents[1] / "examples" /
                          "pump_on_journals.toml").read_text())
    for s in data["support"]:
        if s["kind"] == "journal":
            s["radial_clearance_um"], s["oil_temperature_c"] = [45.0, 75.0], [40.0, 60.0]
    path = tmp_path / "loose_pump.toml"
    path.write_bytes(tomli_w.dumps(data).encode())
    status = main(["check", str(path), "-q", "--json", str(tmp_path / "v.json")])
    cases = {c["case"]: c for c in json.loads((tmp_path / "v.json").read_text())["cases"]}
    assert cases["nominal"]["ok"] and not cases["max clearance, hot oil"]["ok"]
    assert status == 1

    def first(c: dict) -> float:
        return min(x["speed_rpm"] for x in c["campbell"]["critical_speeds"]
                   if x["order"] == 1 and not x["critically_damped"])
    assert first(cases["max clearance, hot oil"]) < first(cases["min clearance, cold oil"])


def test_a_case_turns_on_the_nominal_basis_as_on_a_basis_of_its_own():
    """Within a study a tolerance case turns on the nominal case's basis (workflows.
    campbell.turning shares it: only the journals' coefficients differ, and the basis
    holds their static shapes): its whirl and log decrements at the operating speed and
    its critical speeds are those on a basis made with its own journals, within 1e-7
    (log decrements within 1e-7; measured: 5e-9 at most)."""
    from shaftfem.workflows import campbell as cb

    ranged = load_scene(wheel())
    tight = case_scene(ranged, next(c for c in cases_of(ranged) if c.clearance == "min"))
    cb._MODELS.clear()
    own = cb.run_campbell(tight)
    cb._MODELS.clear()
    nominal = cb.run_campbell(ranged)
    shared = cb.run_campbell(tight)
    assert shared.result is nominal.result and own.result is not nominal.result
    assert len(shared.operating) == len(own.operating) >= 4
    for a, b in zip(shared.operating, own.operating):
        assert a.frequency_hz == pytest.approx(b.frequency_hz, rel=1e-7)
        assert a.log_dec == pytest.approx(b.log_dec, abs=1e-7)
    assert [c.order for c in shared.critical_speeds] == [c.order for c in own.critical_speeds]
    for a, b in zip(shared.critical_speeds, own.critical_speeds):
        assert a.speed_rpm == pytest.approx(b.speed_rpm, rel=1e-7)


def test_a_hub_on_a_keyway_left_to_the_default_is_keyed_and_bracketed_by_rigid():
    """A part whose joint the scene leaves out sits as a keyed fit where its hub
    overlaps a keyway (distributing: its hub adds no stiffness, the conservative side)
    and as a shrink fit elsewhere; the study runs the other joint as a case beside."""
    import tomllib
    from pathlib import Path

    path = Path(__file__).parent.parent / "examples" / "keyed_pump_on_journals.toml"
    data = tomllib.loads(path.read_text())
    for a in data["attachment"]:
        a.pop("joint", None)
    scene = load_scene(data)
    joints = {a.name: a.joint for a in scene.attachments}
    assert joints == {"coupling hub": "rigid", "impeller": "distributing"}
    names = [c.name for c in cases_of(scene)]
    assert "rigid joints" in names and "distributing joints" in names


@pytest.mark.parametrize("change,key,said", [
    ({"oil_supply_temperature_c": 40.0}, "oil_temperature_c", "one of them"),
    ({"oil_flow_l_min": 2.0}, "oil_flow_l_min", "only with oil_supply_temperature_c"),
    ({"pad_temperature_limit_c": 110.0}, "pad_temperature_limit_c", "tilting_pad"),
    ({"pad_thickness_mm": 15.0}, "pad_thickness_mm", "tilting_pad"),
    ({"oil_temperature_c": None, "oil_supply_temperature_c": 200.0},
     "oil_supply_temperature_c", "in [-20, 150] C"),
    ({"oil_temperature_c": None, "oil_iso_vg": None, "viscosity_mpa_s": 20.0,
      "oil_supply_temperature_c": 40.0}, "oil_supply_temperature_c", "only with oil_iso_vg"),
])
def test_a_supply_that_cannot_be_is_refused_naming_its_key(tmp_path, capsys, change, key,
                                                            said):
    """The oil by its supply: in place of the film's temperature, with a grade, in range;
    its flow only with it."""
    import tomli_w

    scene = wheel()
    for s in scene["support"]:
        for k, v in change.items():
            if v is None:
                s.pop(k, None)
            else:
                s[k] = v
    path = tmp_path / "wheel.toml"
    path.write_bytes(tomli_w.dumps(scene).encode())
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert key in err and said in err and "Traceback" not in err, err


def test_a_supply_range_runs_as_the_cases_with_the_film_heating_in_each():
    """oil_supply_temperature_c = [40, 60]: the cases are the oil's ends as for the film's
    temperature, each journal fed at its end, its film running above its supply."""
    from dataclasses import replace

    from shaftfem.parts.heat import at_speed
    from shaftfem.workflows.equip import film_table

    scene = wheel(clearance=(45.0, 45.0 + 1e-9))
    for s in scene["support"]:
        del s["oil_temperature_c"]
        s["oil_supply_temperature_c"] = [40.0, 60.0]
    loaded = load_scene(scene)
    cases = cases_of(loaded)
    assert [c.name for c in cases][1:] == ["min clearance, cold oil", "max clearance, hot oil"]
    omega = 3600 * math.pi / 30
    films = []
    for c in cases:
        j = replace(case_scene(loaded, c).supports[0].journal, load=500.0)
        film_table(j)
        films.append(at_speed(j, omega).oil_temperature - j.oil_supply_temperature)
        assert films[-1] > 0
    fed = [case_scene(loaded, c).supports[0].journal.oil_supply_temperature for c in cases]
    assert fed == [50.0, 40.0, 60.0]
