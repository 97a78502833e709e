"""A plain journal bearing from its film (shaftfem.parts.journal), against the closed
forms and tables it must meet:

* Ocvirk's short bearing (Ocvirk 1952; the eight coefficients as Friswell et al. 2010,
  section 5.5, give them): the same film without its circumferential pressure flow
  must meet them at L/D = 0.25, and the full film must approach them as L/D -> 0;
* Raimondi and Boyd's full bearing at L/D = 1 (1958; Swift-Stieber film, oil entering
  at the widest gap), as Shigley's table 12-4 reprints it;
* the scene: a journal's keys refused clearly when wrong, and a rotor on two journals
  whirling at about half its speed once the film turns it unstable (oil whip).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfem.errors import SceneError
from shaftfem.parts import journal, oil
from shaftfem.scene.load import load_scene

PI = math.pi


def ocvirk(e: float) -> tuple[float, np.ndarray, np.ndarray]:
    """The short bearing at eccentricity ratio e: the modified Sommerfeld number
    Ss = pi (L/D)^2 S, and K c / W, C c omega / W, in the frame where the load is
    along -y (the first row and column across it, the second along it)."""
    Ss = (1 - e**2) ** 2 / (e * math.sqrt(PI**2 * (1 - e**2) + 16 * e**2))
    h0 = 1 / (PI**2 * (1 - e**2) + 16 * e**2) ** 1.5
    root = math.sqrt(1 - e**2)
    K = h0 * np.array([
        [4 * (PI**2 * (2 - e**2) + 16 * e**2), PI * (PI**2 * (1 - e**2) ** 2 - 16 * e**4) / (e * root)],
        [-PI * (PI**2 * (1 - e**2) * (1 + 2 * e**2) + 32 * e**2 * (1 + e**2)) / (e * root),
         4 * (PI**2 * (1 + 2 * e**2) + 32 * e**2 * (1 + e**2) / (1 - e**2))]])
    C = h0 * np.array([
        [2 * PI * root * (PI**2 * (1 + 2 * e**2) - 16 * e**2) / e,
         -8 * (PI**2 * (1 + 2 * e**2) - 16 * e**2)],
        [-8 * (PI**2 * (1 + 2 * e**2) - 16 * e**2),
         2 * PI * (PI**2 * (1 - e**2) ** 2 + 48 * e**2) / (e * root)]])
    return Ss, K, C


def in_load_frame(s: journal.FilmState, ratio: float) -> tuple[float, np.ndarray, np.ndarray]:
    """A film state as ocvirk() gives its values."""
    F = float(np.hypot(*s.force))
    Q = journal.rotation(-PI / 2 - (math.atan2(s.force[1], s.force[0]) + PI))
    S = 2 * ratio / (PI * F)
    return PI * ratio**2 * S, Q @ s.stiffness @ Q.T / F, Q @ s.damping @ Q.T / F


@pytest.mark.parametrize("e", [0.1, 0.3, 0.5, 0.8, 0.9])
def test_the_short_film_meets_ocvirk_at_l_over_d_one_quarter(e):
    """Each coefficient within 2 % (away from e = 0.66, where Ocvirk's kxy passes
    through zero)."""
    Ss, K, C = in_load_frame(journal.state(0.25, e, "gumbel", theta_cells=480, short=True), 0.25)
    Ss0, K0, C0 = ocvirk(e)
    assert Ss == pytest.approx(Ss0, rel=0.02)
    np.testing.assert_allclose(K, K0, rtol=0.02)
    np.testing.assert_allclose(C, C0, rtol=0.02)


def test_the_full_film_approaches_ocvirk_as_the_bearing_shortens():
    """The circumferential flow the short bearing leaves out costs less and less."""
    gaps = []
    for ratio in (0.25, 0.1, 0.05):
        Ss, K, _ = in_load_frame(journal.state(ratio, 0.5, "gumbel", theta_cells=480), ratio)
        Ss0, K0, _ = ocvirk(0.5)
        gaps.append(max(abs(Ss / Ss0 - 1), float(np.abs(K / K0 - 1).max())))
    assert gaps[0] > gaps[1] > gaps[2]
    assert gaps[2] < 0.015


# Raimondi and Boyd, L/D = 1, full bearing: eccentricity ratio, Sommerfeld number,
# attitude angle (deg)
RAIMONDI_BOYD = [(0.1, 1.33, 79.5), (0.2, 0.631, 74.02), (0.4, 0.264, 63.10),
                 (0.6, 0.121, 50.58), (0.8, 0.0446, 36.24), (0.9, 0.0188, 26.45),
                 (0.97, 0.00474, 15.47)]


@pytest.mark.parametrize("eps, S, phi", RAIMONDI_BOYD)
def test_a_square_bearing_meets_raimondi_and_boyd(eps, S, phi):
    """A bearing whose speed makes the table's Sommerfeld number: its eccentricity,
    attitude angle and minimum film within 3 %."""
    c = 50e-6
    b = journal.JournalBearing(diameter=0.05, length=0.05, clearance=c, viscosity=0.02,
                               load=1000.0)
    omega = 2 * PI * S / b.sommerfeld(2 * PI)
    op = journal.operating(b, omega)
    assert op.sommerfeld == pytest.approx(S, rel=1e-12)
    assert op.eccentricity == pytest.approx(eps, rel=0.03)
    assert math.degrees(op.attitude) == pytest.approx(phi, rel=0.03)
    assert op.min_film == pytest.approx(c * (1 - eps), rel=0.03)


def test_the_table_between_its_rows_is_the_film_itself():
    """operating() interpolates the film's table; at eccentricities between its rows it
    gives the film solved there."""
    b = journal.JournalBearing(diameter=0.1, length=0.05, clearance=80e-6, viscosity=0.03,
                               load=2000.0)
    t = journal.table(0.5)
    for e in (0.137, 0.555, 0.9):
        s = journal.state(0.5, e)
        S = 2 * 0.5 / (PI * float(np.hypot(*s.force)))
        omega = 2 * PI * S / b.sommerfeld(2 * PI)
        op = journal.operating(b, omega)
        assert op.eccentricity == pytest.approx(e, abs=2e-3)
        _, K, C = in_load_frame(s, 0.5)
        unit = b.load / b.clearance
        np.testing.assert_allclose(op.K / unit, K, atol=0.01 * np.abs(K).max())
        np.testing.assert_allclose(op.C * omega / unit, C, atol=0.01 * np.abs(C).max())
    assert t.sommerfeld[0] > t.sommerfeld[-1]


def test_a_grade_reads_its_viscosity_at_forty_degrees():
    """ISO VG n is n mm^2/s at 40 C; hotter is thinner."""
    for grade in (32, 46, 68):
        assert oil.kinematic(grade, 40.0) == pytest.approx(grade * 1e-6, rel=1e-9)
        assert oil.kinematic(grade, 100.0) == pytest.approx(oil.VI100_AT_100C[grade] * 1e-6,
                                                            rel=1e-9)
        assert oil.dynamic(grade, 60.0) < oil.dynamic(grade, 50.0)


STEEL = {"name": "steel", "youngs_modulus_mpa": 211000.0, "poisson_ratio": 0.3,
         "density_kg_m3": 7810.0}


def journal_rotor(mesh_mm: float = 25.0, **bearing) -> dict:
    """A 1 m, 50 mm shaft with a 30 kg disk at its middle on two journal bearings."""
    def support(name: str, z: float) -> dict:
        return {"name": name, "position_mm": z, "width_mm": 25.0, "kind": "journal",
                "radial_clearance_um": 50.0, "oil_iso_vg": 32, "oil_temperature_c": 50.0,
                "load_n": 220.0, **bearing}
    return {"name": "journal_rotor", "shaft": {"length_mm": 1000.0, "diameter_mm": 50.0},
            "material": STEEL, "mesh": {"element_size_mm": mesh_mm}, "modes": {"count": 4},
            "support": [support("left", 20.0), support("right", 980.0)],
            "attachment": [{"name": "disk", "position_mm": 500.0, "width_mm": 40.0,
                            "mass_kg": 30.0, "polar_inertia_kg_m2": 0.3,
                            "diametral_inertia_kg_m2": 0.15, "joint": "distributing"}],
            "rotor": {"speed_rpm": 4000.0, "max_speed_rpm": 12000.0, "campbell_points": 25}}


@pytest.mark.parametrize("key, value, said", [
    ("radial_clearance_um", 0.0, "radial_clearance_um"),
    ("radial_clearance_um", 3000.0, "radial_clearance_um"),
    ("radial_clearance_um", 0.06, "radial_clearance_um = 0.06: 1.2e-06 of the diameter"),
    ("viscosity_mpa_s", -3.0, "viscosity_mpa_s"),
    ("load_n", 2e6, "load_n"),
    ("oil_iso_vg", 33, "oil_iso_vg"),
    ("cavitation", "elrod", "cavitation"),
])
def test_a_journal_refuses_what_no_film_can_be(key, value, said):
    data = journal_rotor(**{key: value})
    if key == "viscosity_mpa_s":
        for s in data["support"]:
            del s["oil_iso_vg"], s["oil_temperature_c"]
    from shaftfem.workflows.equip import with_parts

    # a load too large for any film is found when the film is asked for its coefficients
    with pytest.raises(SceneError, match=said):
        with_parts(load_scene(data))


def test_a_journal_needs_its_oil_once_and_a_speed():
    data = journal_rotor(viscosity_mpa_s=20.0)
    with pytest.raises(SceneError, match="viscosity_mpa_s, or as oil_iso_vg"):
        load_scene(data)
    data = journal_rotor()
    del data["rotor"]
    with pytest.raises(SceneError, match=r"add \[rotor\]"):
        load_scene(data)
    data = journal_rotor(radial_stiffness_n_per_mm=1e5)
    with pytest.raises(SceneError, match="its film gives its stiffness"):
        load_scene(data)


def test_a_journal_scene_holds_its_film_against_speed():
    from shaftfem.workflows.equip import with_parts

    scene = with_parts(load_scene(journal_rotor()))
    s = scene.supports[0]
    b = s.journal
    assert b is not None and b.viscosity == pytest.approx(oil.dynamic(32, 50.0))
    assert b.diameter == pytest.approx(0.05) and b.length == pytest.approx(0.025)
    coefficients = s.bearing
    # each speed's coefficients are the film's there
    for w in (300.0, 700.0, 1200.0):
        op = journal.operating(b, w)
        np.testing.assert_allclose(coefficients.stiffness(w), op.K, rtol=2e-3,
                                   atol=1e-3 * np.abs(op.K).max())
        np.testing.assert_allclose(coefficients.damping(w), op.C, rtol=2e-3,
                                   atol=1e-3 * np.abs(op.C).max())
    # the standstill modes hold the film's direct stiffness at the operating speed
    op = journal.operating(b, coefficients.reference)
    assert s.radial_xy == pytest.approx((op.K[0, 0], op.K[1, 1]), rel=1e-3)


@pytest.mark.slow
def test_a_rotor_on_journals_whips_at_half_its_speed():
    """Past its onset the film's cross-coupling drives the first forward mode, which
    then whirls near half the running speed (Newkirk and Taylor's oil whip)."""
    from shaftfem.workflows.campbell import run_campbell

    c = run_campbell(load_scene(journal_rotor()))
    assert c.onsets, "no onset of instability below 12,000 r/min"
    first = c.onsets[0]
    assert first.whirl == "forward"
    assert 0.4 < first.frequency_hz / (first.speed_rpm / 60) < 0.55
    # above the first critical speed, as Newkirk found it
    assert first.speed_rpm > min(x.speed_rpm for x in c.critical_speeds
                                 if x.whirl == "forward" and x.speed_rpm > 1000)


@pytest.mark.slow
def test_the_reduced_whirl_is_the_whirl_on_a_basis_made_for_each_speed():
    """The whirl is solved on standstill modes that hold the journals' stiffness at the
    operating speed (here kyy 6.9 MN/m at 4,000 r/min), plus the bearings' residual
    modes. At 15, 300 and 11,000 r/min, where the film's kyy is 26 times, 3.7 times
    and 0.8 times that (32 times from the first to the last), it is the whirl on a basis
    of twice the modes made with that speed's stiffness, within 1e-6 (without the
    residual modes: 4e-4)."""
    from dataclasses import replace

    from shaftfem.fem.rotor import rotor_model
    from shaftfem.workflows.campbell import whirl_at
    from shaftfem.workflows.equip import with_parts
    from shaftfem.workflows.pipeline import run_modes, with_modes

    scene = with_parts(load_scene(journal_rotor()))
    model = rotor_model(run_modes(with_modes(scene, count=30)), "stationary")
    assert model.residual == 4
    stiff = []
    for rpm in (15.0, 300.0, 11000.0):
        w = rpm * 2 * PI / 60
        there = replace(scene, supports=tuple(
            replace(s, bearing=replace(s.bearing, reference=w)) for s in scene.supports))
        stiff.append(there.supports[0].radial_xy[1] / scene.supports[0].radial_xy[1])
        full = rotor_model(run_modes(with_modes(there, count=60)), "stationary")
        for a, b in zip(whirl_at(model, w, 4), whirl_at(full, w, 4)):
            assert a.frequency_hz == pytest.approx(b.frequency_hz, rel=1e-6)
            assert a.log_dec == pytest.approx(b.log_dec, rel=1e-5, abs=1e-6)
    assert max(stiff) / min(stiff) > 30


def friswell_journals() -> dict:
    """Friswell's 5.9.1 rotor (1.5 m x 50 mm, disks of 280 and 350 mm at 0.5 and 1.0 m) on
    two plain journals 25 mm long with 50 um clearance, 20 mPa s oil, at ross's nodes 1
    and 47 (31.25 and 1468.75 mm); their loads from the static solution."""
    from test_rotor import friswell, two_disks

    def journal(name: str, z: float) -> dict:
        return {"name": name, "position_mm": z, "width_mm": 25.0, "kind": "journal",
                "radial_clearance_um": 50.0, "viscosity_mpa_s": 20.0}
    return friswell([journal("left", 31.25), journal("right", 1468.75)], two_disks(),
                    {"speed_rpm": 3000.0, "max_speed_rpm": 8000.0, "campbell_points": 33})


@pytest.mark.slow
def test_friswell_591_on_journals_against_ross():
    """Friswell's 5.9.1 rotor on two journals, its bearings from shaftfem's film, against
    ross-rotordynamics 2.3's beam model with the same bearings (tests/data/
    journal_591.json, benchmarks/journal_tables.py; ross's values: ross_reference.py
    --journals): the whirl and log decrements at 1,000, 3,000 and 6,000 r/min, the first
    two 1x critical speeds and the onset of oil whip, each within 2 %."""
    import json
    from pathlib import Path

    from shaftfem.workflows.campbell import run_campbell
    from shaftfem.workflows.static import equipped

    data = Path(__file__).parent / "data"
    table = json.loads((data / "journal_591.json").read_text())
    ross = json.loads((data / "ross_rotors.json").read_text())["5.9.1 journals"]
    scene = equipped(load_scene(friswell_journals()))
    for s, theirs in zip(scene.supports, table["bearings"]):   # the same bearings
        assert s.journal.load == pytest.approx(theirs["load_n"], rel=1e-6)
        for k in ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"):
            np.testing.assert_allclose(getattr(s.bearing, k), theirs[k], rtol=1e-6)
    meets_ross_591(run_campbell(scene), ross, 0.02)


def meets_ross_591(c, ross: dict, rel: float) -> None:
    """A Campbell run of 5.9.1 on journals against ross's values (ross_reference.py
    --journals): the whirl and log decrements at 1,000, 3,000 and 6,000 r/min, the onset
    of oil whip and the first two lightly damped 1x critical speeds, each within `rel`."""
    for rpm in ("1000", "3000", "6000"):
        ours = sorted((w for w in c.whirl if abs(w.speed_rpm - float(rpm)) < 1e-6
                       and w.kind not in ("torsion", "axial")), key=lambda w: w.frequency_hz)
        for w, wd, dec in zip(ours, ross[rpm]["wd"], ross[rpm]["log_dec"]):
            assert w.frequency_hz * 2 * PI == pytest.approx(wd, rel=rel)
            assert w.log_dec == pytest.approx(dec, rel=rel, abs=0.002)
    assert c.onsets[0].speed_rpm * PI / 30 == pytest.approx(ross["onset_speed"], rel=rel)
    light = sorted(x.speed_rpm for x in c.critical_speeds if x.order == 1 and x.log_dec < 1)
    for ours, theirs in zip(light[:2], (ross["critical_1x"]["first"],
                                         ross["critical_1x"]["second"])):
        assert ours * PI / 30 == pytest.approx(theirs, rel=rel)


def test_a_short_bearing_against_ross_cylindrical_bearing():
    """ross's CylindricalBearing (Ocvirk's closed form) on the bearing of its docstring
    made 10 mm long (L/D = 0.1, 525 N, 0.1 Pa s), at 1,500 and 2,000 r/min
    (tests/data/ross_rotors.json, benchmarks/ross_reference.py --cylindrical): the
    default film's eccentricity within 1 % and its eight coefficients within 5 % (2.3 %
    measured; the rest is the circumferential flow the short bearing leaves out)."""
    import json
    from pathlib import Path

    ref = json.loads((Path(__file__).parent / "data" / "ross_rotors.json").read_text())[
        "cylindrical bearing"]
    b = journal.JournalBearing(diameter=ref["diameter_m"], length=ref["length_m"],
                               clearance=ref["clearance_m"], viscosity=ref["viscosity_pa_s"],
                               load=ref["load_n"])
    names = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")
    for i, rpm in enumerate(ref["speed_rpm"]):
        op = journal.operating(b, rpm * PI / 30)
        assert op.eccentricity == pytest.approx(ref["eccentricity"][i], rel=0.01)
        ours = [*op.K.ravel(), *op.C.ravel()]
        for name, v in zip(names, ours):
            assert v == pytest.approx(ref[name][i], rel=0.05), name


def test_a_film_table_comes_back_from_the_cache_whole_or_not_at_all(tmp_path, monkeypatch):
    """The film's table is kept in the cache and read back the same; a damaged entry is
    discarded with a warning and solved again."""
    from shaftfem.scene.model import JournalBearing
    from shaftfem.store import CacheWarning
    from shaftfem.workflows.equip import film_table

    b = JournalBearing(diameter=0.04, length=0.03, clearance=5e-5, viscosity=0.02, load=100.0,
                       cavitation="gumbel")

    monkeypatch.setenv("SHAFTFEM_CACHE", str(tmp_path))
    monkeypatch.setattr(journal, "_KNOWN", {})
    film_table(b)
    (path,) = (tmp_path / "films").glob("*.npz")
    solved = journal.table(0.75, "gumbel")
    journal._KNOWN.clear()
    film_table(b)
    read = journal._KNOWN[(0.75, "gumbel", None)]
    for name in journal.TABLE_FIELDS:
        np.testing.assert_array_equal(getattr(read, name), getattr(solved, name))
    path.write_bytes(path.read_bytes()[:100])
    journal._KNOWN.clear()
    with pytest.warns(CacheWarning, match="journal film table"):
        film_table(b)
    assert path.exists()


def test_a_film_table_solved_beside_the_run_is_the_table_solved_in_it(tmp_path, monkeypatch):
    """films_ahead solves a table in another process while the static loads are solved;
    the journal then takes that one (no solve of its own) and keeps it in the cache, the
    same to the last bit as the table solved in this process; one started and not taken
    is stopped."""
    from shaftfem.scene.model import JournalBearing
    from shaftfem.workflows import equip

    b = JournalBearing(diameter=0.04, length=0.026, clearance=5e-5, viscosity=0.02,
                       load=100.0, cavitation="gumbel")
    monkeypatch.setenv("SHAFTFEM_CACHE", str(tmp_path))
    monkeypatch.setenv("SHAFTFEM_ASIDE", "1")   # as a user's run has it
    monkeypatch.setattr(journal, "_KNOWN", {})
    started = equip.films_ahead([b])
    assert len(started) == 1 and equip.films_ahead([b]) == []   # one job per table
    inline = journal.table.__wrapped__(0.65, "gumbel")
    monkeypatch.setattr(journal, "table", lambda *a: pytest.fail("solved in the run"))
    equip.film_table(b)
    equip.films_dropped(started)                  # taken already: nothing to stop
    beside = journal._KNOWN[(0.65, "gumbel", None)]
    for name in journal.TABLE_FIELDS:
        np.testing.assert_array_equal(getattr(beside, name), getattr(inline, name))
    assert len(list((tmp_path / "films").glob("*.npz"))) == 1
    other = JournalBearing(diameter=0.04, length=0.03, clearance=5e-5, viscosity=0.02,
                           load=100.0, cavitation="gumbel")
    (path,) = equip.films_ahead([other])
    job = equip._AHEAD[path]
    equip.films_dropped([path])
    assert path not in equip._AHEAD and job._process is None     # stopped
