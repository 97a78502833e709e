"""The installed shaft under its static loads (shaftfem.fem.static, `shaftfem static`):
reactions against statics, deflections against Timoshenko's beam, a continuous beam's
middle reaction against its closed form, journal bearings loaded by their reactions,
and the errors."""

from __future__ import annotations

import json
import math

import pytest

from shaftfem.errors import SceneError
from shaftfem.scene.load import load_scene
from shaftfem.workflows.static import equipped, run_static

E, NU, RHO, G0 = 211e9, 0.3, 7810.0, 9.80665
STEEL = {"name": "steel", "youngs_modulus_mpa": E / 1e6, "poisson_ratio": NU,
         "density_kg_m3": RHO}


def bar(length_mm: float = 1000.0, d_mm: float = 40.0, supports=(2.5, 997.5), **tables) -> dict:
    """A plain bar on narrow seats (5 mm), the first holding it axially too."""
    seats = [{"name": f"S{i}", "position_mm": z, "width_mm": 5.0,
              "kind": "rigid" if i == 0 else "rigid-radial"} for i, z in enumerate(supports)]
    return {"name": "bar", "shaft": {"length_mm": length_mm, "diameter_mm": d_mm},
            "material": STEEL, "mesh": {"element_size_mm": 8.0}, "support": seats, **tables}


def timoshenko_midspan(P: float, w: float, span: float, d: float) -> float:
    """A simply supported round bar's midspan deflection under P at midspan and w per
    length: bending plus shear (kappa = 6 (1 + nu) / (7 + 6 nu))."""
    I, A = math.pi * d**4 / 64, math.pi * d**2 / 4
    kGA = 6 * (1 + NU) / (7 + 6 * NU) * E / (2 * (1 + NU)) * A
    return (P * span**3 / (48 * E * I) + P * span / (4 * kGA)
            + 5 * w * span**4 / (384 * E * I) + w * span**2 / (8 * kGA))


def test_a_force_at_midspan_is_shared_and_bends_the_bar_as_timoshenko_says():
    s = run_static(load_scene(bar(force=[{"position_mm": 500.0, "fx_n": 300.0,
                                          "fy_n": -1000.0}], static={"gravity_m_s2": 0.0})))
    r = {x.name: x.force for x in s.solution.reactions}
    for name in ("S0", "S1"):
        assert r[name][0] == pytest.approx(-150.0, rel=1e-6)
        assert r[name][1] == pytest.approx(500.0, rel=1e-6)
    x, y = s.solution.deflection_at(0.5)
    assert -y == pytest.approx(timoshenko_midspan(1000.0, 0.0, 0.995, 0.04), rel=2e-3)
    assert x == pytest.approx(0.3 * timoshenko_midspan(1000.0, 0.0, 0.995, 0.04), rel=2e-3)


def test_a_travelling_force_stands_at_its_start_and_says_so():
    """A force that travels (a follower, [[force]] travel_to_mm) loads the static line at
    its start, position_mm: the reactions share it by moments about the seats, and the
    text says where it was taken and which command moves it. A seat's long name is
    printed whole in its row, not cut to the column."""
    from shaftfem.outputs.tables import static_text

    long = "non-drive-end bearing at the coupling"
    data = bar(force=[{"name": "follower", "position_mm": 250.0, "travel_to_mm": 750.0,
                       "fy_n": -1000.0}], static={"gravity_m_s2": 0.0})
    data["support"][1]["name"] = long
    s = run_static(load_scene(data))
    r = {x.name: x.force for x in s.solution.reactions}
    assert r["S0"][1] == pytest.approx(1000.0 * (997.5 - 250.0) / 995.0, rel=1e-6)
    assert r[long][1] == pytest.approx(1000.0 * (250.0 - 2.5) / 995.0, rel=1e-6)
    text = static_text(s)
    assert ("force follower travels from 250 to 750 mm: taken here at its start; "
            "`shaftfem strength` moves it along its way") in text
    assert any(line.startswith(long + "  ") and "997.5 mm" in line
               for line in text.splitlines())


def test_the_weight_of_bar_and_parts_is_carried_by_statics():
    """A pulley overhung beyond the second bearing with a belt pull: the reactions by
    moments about the first seat."""
    data = bar(600.0, 40.0, supports=(50.0, 450.0),
               attachment=[{"name": "pulley", "position_mm": 560.0, "width_mm": 40.0,
                            "mass_kg": 8.0, "polar_inertia_kg_m2": 0.05,
                            "diametral_inertia_kg_m2": 0.03}],
               force=[{"part": "pulley", "fy_n": -2000.0}])
    s = run_static(load_scene(data)).solution
    shaft = RHO * math.pi * 0.02**2 * 0.6 * G0
    down = shaft + 8.0 * G0 + 2000.0
    assert -s.load[1] == pytest.approx(down, rel=2e-4)
    rb = (shaft * 0.25 + (8.0 * G0 + 2000.0) * 0.51) / 0.4
    r = {x.name: x.force for x in s.reactions}
    assert r["S1"][1] == pytest.approx(rb, rel=2e-4)
    assert r["S0"][1] == pytest.approx(down - rb, rel=2e-3)


def test_a_continuous_bar_on_three_seats_under_its_weight():
    """Two equal spans under a uniform load: the middle seat carries 5/4 w l, the ends
    3/8 w l each (Euler-Bernoulli; the bar is slender, l / d = 25)."""
    s = run_static(load_scene(bar(1000.0, 20.0, supports=(0.0 + 2.5, 500.0, 997.5)))).solution
    w = RHO * math.pi * 0.01**2 * G0
    r = {x.name: x.force[1] for x in s.reactions}
    span = 0.4975
    assert r["S1"] == pytest.approx(1.25 * w * span, rel=0.01)
    assert r["S0"] == pytest.approx(0.375 * w * span + w * 0.0025, rel=0.02)


def test_journals_without_a_load_carry_their_reactions():
    from test_journal_bearing import journal_rotor

    data = journal_rotor()
    for sup in data["support"]:
        del sup["load_n"]
    scene = load_scene(data)
    assert all(s.bearing is None for s in scene.supports)
    loaded = equipped(scene)
    weight = (RHO * math.pi * 0.025**2 * 1.0 + 30.0) * G0
    for s in loaded.supports:
        assert s.journal.load == pytest.approx(weight / 2, rel=1e-3)   # a 25 mm mesh
        assert s.journal.direction == pytest.approx((0.0, -1.0), abs=1e-9)
        assert s.bearing is not None


def test_the_static_command_prints_reactions_and_writes_json(tmp_path, capsys):
    from shaftfem.cli import main

    path = tmp_path / "bar.toml"
    import tomli_w

    path.write_text(tomli_w.dumps(bar(force=[{"name": "P", "position_mm": 500.0,
                                              "fy_n": -1000.0}])))
    code = main(["static", str(path), "-q", "--json", str(tmp_path / "s.json"),
                 "--out", str(tmp_path / "out")])
    assert code == 0
    text = capsys.readouterr().out
    assert "S0" in text and "largest deflection" in text and " N " in text
    data = json.loads((tmp_path / "s.json").read_text())
    assert len(data["reactions"]) == 2
    assert (tmp_path / "out" / "static.png").stat().st_size > 10_000


@pytest.mark.parametrize("tables, said", [
    ({"static": {"gravity_direction": [0.0, 0.0, 0.0]}}, "gravity_direction"),
    ({"static": {"gravity_m_s2": -1.0}}, "gravity_m_s2"),
    ({"force": [{"position_mm": 2000.0, "fy_n": 1.0}]}, "position_mm"),
    ({"force": [{"part": "gear", "fy_n": 1.0}]}, "no \\[\\[attachment\\]\\] of that name"),
])
def test_static_loads_refuse_what_cannot_be(tables, said):
    with pytest.raises(SceneError, match=said):
        load_scene(bar(**tables))


def test_a_load_nothing_holds_is_refused():
    data = bar(static={"gravity_direction": [0.0, 0.0, -1.0]})
    for s in data["support"]:
        s["kind"] = "rigid-radial"
    with pytest.raises(SceneError, match="leave free"):
        run_static(load_scene(data))
    data = bar()
    del data["support"]
    with pytest.raises(SceneError, match="no static solution"):
        run_static(load_scene(data))
