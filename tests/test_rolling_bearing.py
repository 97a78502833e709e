"""A rolling bearing's stiffness from its elements (shaftfem.parts.rolling): Gargiulo's
Hertz-contact fits as Friswell et al. (2010, section 5.6) give them, checked against
the worked example of ross's BallBearingElement (8 balls of 30 mm, 500 N, 30 deg:
kyy 1.00906269e8 and kxx 4.64168838e7 N/m) and against Hertz's exponents; the scene
kinds "ball" and "roller" and their errors."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.optimize

from shaftfem.errors import SceneError
from shaftfem.parts import rolling
from shaftfem.scene.load import load_scene
from shaftfem.workflows.equip import with_parts

STEEL = {"name": "steel", "youngs_modulus_mpa": 211000.0, "poisson_ratio": 0.3,
         "density_kg_m3": 7810.0}


def test_the_ball_bearing_of_the_published_example():
    along, across = rolling.stiffness("ball", 8, 0.03, 500.0, math.pi / 6)
    assert along == pytest.approx(1.00906269e8, rel=1e-8)
    assert across == pytest.approx(4.64168838e7, rel=1e-8)


def test_hertz_point_and_line_contact_exponents():
    """A ball contact stiffens as the load to the 1/3, a roller's as the load to 0.1;
    more or bigger elements are stiffer; the across-load shares are the published ones."""
    k1 = rolling.stiffness("ball", 12, 0.01, 1000.0)[0]
    k8 = rolling.stiffness("ball", 12, 0.01, 8000.0)[0]
    assert k8 / k1 == pytest.approx(2.0, rel=1e-12)
    r1 = rolling.stiffness("roller", 12, 0.01, 1000.0)[0]
    r2 = rolling.stiffness("roller", 12, 0.01, 1e4)[0]
    assert r2 / r1 == pytest.approx(10**0.1, rel=1e-12)
    for kind, shares in rolling.ACROSS.items():
        for n, share in shares:
            along, across = rolling.stiffness(kind, n, 0.01, 1000.0)
            assert across / along == pytest.approx(share, rel=1e-12)


def rotor(**bearing) -> dict:
    def support(name: str, z: float) -> dict:
        return {"name": name, "position_mm": z, "width_mm": 15.0, "kind": "ball",
                "elements": 9, "element_diameter_mm": 7.9, "load_n": 150.0, **bearing}
    return {"name": "ball_rotor", "shaft": {"length_mm": 400.0, "diameter_mm": 30.0},
            "material": STEEL, "mesh": {"element_size_mm": 12.0}, "modes": {"count": 4},
            "support": [support("front", 30.0), support("rear", 370.0)],
            "rotor": {"speed_rpm": 6000.0}}


def test_a_ball_bearing_in_a_scene_is_its_stiffness_along_and_across_its_load():
    scene = with_parts(load_scene(rotor(load_angle_deg=-90.0)))
    along, across = rolling.stiffness("ball", 9, 7.9e-3, 150.0)
    K = np.array(scene.supports[0].bearing.stiffness(0.0))
    np.testing.assert_allclose(K, [[across, 0.0], [0.0, along]], atol=1e-6 * along)
    C = np.array(scene.supports[0].bearing.damping(0.0))
    np.testing.assert_allclose(C, rolling.DAMPING_TIME * K, atol=1e-12 * along)
    tilted = with_parts(load_scene(rotor(load_angle_deg=0.0, contact_angle_deg=15.0)))
    along, across = rolling.stiffness("ball", 9, 7.9e-3, 150.0, math.radians(15.0))
    K = np.array(tilted.supports[0].bearing.stiffness(0.0))
    np.testing.assert_allclose(K, [[along, 0.0], [0.0, across]], atol=1e-6 * along)


@pytest.mark.parametrize("key, value, said", [
    ("elements", 3, "elements"),
    ("element_diameter_mm", 0.0, "element_diameter_mm"),
    ("load_n", -5.0, "load_n"),
    ("roller_length_mm", 10.0, "roller_length_mm"),
    ("radial_clearance_um", 30.0, "radial_clearance_um"),
    ("radial_stiffness_n_per_mm", 1e5, "its elements give its stiffness"),
    ("pitch_diameter_mm", 20.0, "they do not fit"),
])
def test_a_rolling_bearing_refuses_what_it_cannot_be(key, value, said):
    with pytest.raises(SceneError, match=said):
        load_scene(rotor(**{key: value}))


def test_a_roller_bearing_needs_its_length_and_no_ball_diameter():
    data = rotor(kind="roller")
    with pytest.raises(SceneError, match='element_diameter_mm = 7.9: only with kind = "ball"'):
        load_scene(data)
    for s in data["support"]:
        del s["element_diameter_mm"]
    with pytest.raises(SceneError, match="roller_length_mm: missing"):
        load_scene(data)


def stribeck_palmgren(n: int, d: float, load: float, angle: float) -> float:
    """A ball bearing with no clearance under a radial load, written here on its own:
    each ball's contacts deflect as Palmgren's law for steel (delta = 4.36e-4 Q^(2/3)
    d^(-1/3) in mm, N), the rings displaced by delta_r, the load shared as the balls'
    deflections give it; its stiffness dF / d delta_r (N/m) by central differences."""
    psi = 2 * np.pi * np.arange(n) / n

    def force(dr: float) -> float:
        dn = np.maximum(dr * math.cos(angle) * np.cos(psi), 0.0) * 1e3       # mm
        q = (dn / (4.36e-4 * (d * 1e3) ** (-1 / 3))) ** 1.5
        return float(np.sum(q * np.cos(psi)) * math.cos(angle))

    dr = scipy.optimize.brentq(lambda x: force(x) - load, 1e-12, 1e-3, xtol=1e-18)
    return (force(dr * (1 + 1e-6)) - force(dr * (1 - 1e-6))) / (2e-6 * dr)


@pytest.mark.parametrize("n", [8, 12, 16])
@pytest.mark.parametrize("angle_deg", [0.0, 25.0])
def test_gargiulo_against_palmgren_contacts_shared_ball_by_ball(n, angle_deg):
    """Gargiulo's fit within 2 % (0.6 to 1.0 % measured) of the bearing solved ball by
    ball from Palmgren's published contact law; the preloaded model, with no preload,
    within 1e-6 of that same bearing."""
    angle = math.radians(angle_deg)
    ref = stribeck_palmgren(n, 0.0095, 1500.0, angle)
    assert rolling.stiffness("ball", n, 0.0095, 1500.0, angle)[0] == pytest.approx(ref, rel=0.02)
    if angle_deg > 0:
        assert rolling.preloaded(n, 0.0095, angle, 1e-9, 1500.0)[0] == pytest.approx(ref,
                                                                                     rel=1e-5)


def test_a_preloaded_bearing_has_every_ball_loaded():
    """Under an axial preload alone each of the n balls carries Fa / (n sin alpha), and the
    bearing is as stiff across every diameter: (n / 2) cos^2(alpha) 3 Q / (2 delta)."""
    n, d, angle, fa = 16, 0.0095, math.radians(25.0), 500.0
    q = fa / (n * math.sin(angle))
    delta = rolling.PALMGREN * q ** (2 / 3) * d ** (-1 / 3)
    k = n / 2 * math.cos(angle) ** 2 * 1.5 * q / delta
    along, across = rolling.preloaded(n, d, angle, fa)
    assert along == pytest.approx(k, rel=1e-9)
    assert across == pytest.approx(k, rel=1e-9)
    # a radial load on top unloads the balls opposite it: less stiff across than along
    along, across = rolling.preloaded(n, d, angle, fa, 3000.0)
    assert across < along


def test_a_preload_in_a_scene():
    scene = with_parts(load_scene(rotor(contact_angle_deg=25.0, preload_n=400.0,
                                        load_angle_deg=-90.0)))
    along, across = rolling.preloaded(9, 7.9e-3, math.radians(25.0), 400.0, 150.0)
    K = np.array(scene.supports[0].bearing.stiffness(0.0))
    np.testing.assert_allclose(K, [[across, 0.0], [0.0, along]], atol=1e-6 * along)
    with pytest.raises(SceneError, match="preload_n = 400: an axial preload needs an angular"):
        load_scene(rotor(preload_n=400.0))
    data = rotor(kind="roller", roller_length_mm=10.0, preload_n=400.0, contact_angle_deg=10.0)
    for s in data["support"]:
        del s["element_diameter_mm"]
    with pytest.raises(SceneError, match='preload_n = 400.0: only with kind = "ball"'):
        load_scene(data)
