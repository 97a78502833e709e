"""A plain annular seal from its physics (shaftfem.parts.seal), against what it must
meet:

* Lomakin's stiffness at standstill, found here independently: the leakage solved
  around the circumference gap by gap, each with its own friction, and the mean
  pressures integrated into the force;
* the leakage's pressure balance, and the relations of the short-seal model that a
  published run of it shows (k = Omega C / 2, c = Omega M);
* a rotor with a seal against ross-rotordynamics 2.3's SealElement with the same
  coefficients (tests/data/ross_rotors.json, benchmarks/ross_reference.py --seal);
* the scene: a seal's keys refused clearly when wrong.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import scipy.integrate
import scipy.optimize

from shaftfem.errors import SceneError
from shaftfem.parts import seal
from shaftfem.scene.load import load_scene

ROSS = json.loads((Path(__file__).parent / "data" / "ross_rotors.json").read_text())["5.9.1 seal"]
RPM = math.pi / 30


def water_seal(omega: float = 300.0) -> seal.AnnularSeal:
    """A wear ring: 50 mm long, 100 mm across, 200 um clearance, 2 MPa of water."""
    return seal.AnnularSeal(length=0.05, diameter=0.1, clearance=2e-4, pressure_drop=2e6,
                            rated=omega, density=998.0, viscosity=1e-3)


def gap_pressure(s: seal.AnnularSeal, h: float) -> float:
    """The mean pressure (above the exit's) along a gap h that leaks on its own, with
    Blasius-Hirs friction on its own Reynolds number: the inlet loses (1 + xi) rho V^2 / 2,
    friction the rest linearly along the length, so the mean is sigma rho V^2 / 2."""
    def balance(v: float) -> float:
        lam = seal.N0 * (2 * v * h * s.density / s.viscosity) ** seal.M0
        return (1 + s.inlet_loss + 2 * lam * s.length / h) * s.density * v**2 / 2 \
            - s.pressure_drop
    v = scipy.optimize.brentq(balance, 1e-3, 1e3, xtol=1e-14, rtol=1e-14)
    lam = seal.N0 * (2 * v * h * s.density / s.viscosity) ** seal.M0
    return lam * s.length / h * s.density * v**2 / 2


def test_lomakin_stiffness_from_the_gaps_around_the_seal():
    """The direct stiffness at (nearly) standstill within 0.1 % of the force the
    leakage makes, gap by gap, on a shaft moved 0.05 % of the clearance."""
    s = water_seal(omega=1e-6)
    e = 5e-4 * s.clearance
    force, _ = scipy.integrate.quad(
        lambda t: -gap_pressure(s, s.clearance - e * math.cos(t)) * math.cos(t), 0, 2 * math.pi,
        epsabs=0, epsrel=1e-10, limit=200)
    K0 = -force * s.diameter / 2 * s.length / e
    assert K0 > 0
    ours = seal.state(s, 1e-6).K
    assert ours == pytest.approx(K0, rel=1e-3)


def test_the_leakage_balances_the_pressure_drop():
    s = water_seal()
    st = seal.state(s, 300.0)
    assert (1 + s.inlet_loss + 2 * st.sigma) * s.density * st.velocity**2 / 2 \
        == pytest.approx(s.pressure_drop, rel=1e-10)
    assert st.leakage == pytest.approx(math.pi * s.diameter * s.clearance * st.velocity)
    assert st.axial_reynolds > 2000   # turbulent: the model's premise


def test_the_short_seal_relations_a_published_run_shows():
    """A run of Black's model published with its results (ecomputingx.com, tool RD-04,
    at 1,200 r/min: k = 6.873e6 N/m, C = 1.094e5 N s/m, c = 9355 N s/m, M = 74.44 kg)
    has k / C = Omega / 2 and c / M = Omega; so must ours, at every speed, and the
    direct stiffness falls as M Omega^2 / 4 once the friction's swirl is held."""
    omega = 1200 * RPM
    k, C, c, M = 6872962.45, 109386.59, 9354.766, 74.44286
    assert k / C == pytest.approx(omega / 2, rel=1e-5)
    assert c / M == pytest.approx(omega, rel=1e-5)
    s = water_seal(omega=500.0)
    for w in (100.0, 300.0, 500.0):
        st = seal.state(s, w)
        assert st.k == pytest.approx(w * st.C / 2, rel=1e-12)
        assert st.c == pytest.approx(w * st.M, rel=1e-12)
        assert st.K > 0 and st.C > 0 and st.M > 0


def seal_scene(**override) -> dict:
    """Friswell's 5.9.1 rotor with 2 N s/mm in each bearing and ross_reference.SEAL at
    mid-span."""
    from test_rotor import ends, friswell, two_disks

    p = ROSS["seal"]
    wear_ring = {"name": "wear ring", "position_mm": 750.0, "width_mm": p["length_m"] * 1e3,
                 "kind": "seal", "diameter_mm": p["diameter_m"] * 1e3,
                 "radial_clearance_um": p["clearance_m"] * 1e6,
                 "pressure_drop_mpa": p["pressure_drop_pa"] / 1e6,
                 "fluid_density_kg_m3": p["density_kg_m3"],
                 "viscosity_mpa_s": p["viscosity_pa_s"] * 1e3, **override}
    return friswell([*ends(kxx_n_per_mm=1000.0,
                           cxx_n_s_per_mm=ROSS["bearing_damping_n_s_per_m"] / 1e3), wear_ring],
                    two_disks(), {"speed_rpm": p["rated_rpm"], "max_speed_rpm": p["top_rpm"],
                                  "rated_speed_rpm": p["rated_rpm"],
                                  "campbell_points": 5})


def test_a_rotor_with_a_seal_against_ross():
    """The same coefficients as ross's SealElement (mass included), and the whirl and
    log decrements of the first five lateral modes at 1,000, 3,000 and 4,000 r/min, each
    within 1 %. (With 0.5 N s/mm in the bearings the first forward mode's log decrement
    at 4,000 r/min was 0.0527 against 0.0518: the seal's damping and its cross-coupling
    nearly cancel there, and the beam's 0.08 % lower frequency moved their small
    difference by 1.7 %; 2 N s/mm keeps every log decrement off zero.)"""
    from shaftfem.workflows.campbell import run_campbell
    from shaftfem.workflows.equip import with_parts

    scene = with_parts(load_scene(seal_scene()))
    b = scene.supports[2].bearing
    np.testing.assert_allclose(b.speeds, ROSS["table"]["speeds"], rtol=1e-12)
    for k in ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "mxx", "myy"):
        np.testing.assert_allclose(getattr(b, k), ROSS["table"][k], rtol=1e-9, atol=1e-9)
    c = run_campbell(scene)
    for rpm in ("1000", "3000", "4000"):
        ours = sorted((w for w in c.whirl if abs(w.speed_rpm - float(rpm)) < 1e-6
                       and w.kind not in ("torsion", "axial")), key=lambda w: w.frequency_hz)
        ref = [(wd, dec) for wd, dec, d in zip(ROSS[rpm]["wd"], ROSS[rpm]["log_dec"],
                                                ROSS[rpm]["whirl"]) if d != "None"]
        assert len(ref) >= 4
        for w, (wd, dec) in zip(ours, ref):
            assert w.frequency_hz * 2 * math.pi == pytest.approx(wd, rel=0.01), rpm
            assert w.log_dec == pytest.approx(dec, rel=0.01), rpm


@pytest.mark.parametrize("override, key", [
    ({"pressure_drop_mpa": None}, "pressure_drop_mpa"),
    ({"fluid_density_kg_m3": None}, "fluid_density_kg_m3"),
    ({"radial_clearance_um": 0.0}, "radial_clearance_um"),
    ({"radial_clearance_um": 2000.0}, "radial_clearance_um"),
    ({"viscosity_mpa_s": -1.0}, "viscosity_mpa_s"),
    ({"inlet_loss": 5.0}, "inlet_loss"),
    ({"coupling": "rigid"}, "coupling"),
    ({"load_n": 100.0}, "load_n"),
])
def test_a_seal_refused_clearly(override, key):
    data = seal_scene(**override)
    data["support"][2] = {k: v for k, v in data["support"][2].items() if v is not None}
    with pytest.raises(SceneError, match=key):
        load_scene(data)


def test_seal_keys_only_on_a_seal():
    from test_rotor import ends, friswell, two_disks

    supports = ends(kxx_n_per_mm=1000.0)
    supports[0]["inlet_loss"] = 0.2
    with pytest.raises(SceneError, match="inlet_loss.*only with kind = \"seal\""):
        load_scene(friswell(supports, two_disks(), {"speed_rpm": 3000.0}))


def test_a_seal_needs_the_shaft_turning():
    data = seal_scene()
    del data["rotor"]
    with pytest.raises(SceneError, match="add \\[rotor\\]"):
        load_scene(data)


@pytest.mark.slow
def test_the_diagram_is_the_machine_s_whatever_its_running_speed():
    """A seal's pressure drop is given at the machine's rated speed ([rotor]
    rated_speed_rpm), not at the running speed: moving speed_rpm moves where the
    machine runs, and its Campbell diagram and critical speeds stay as they were."""
    from shaftfem.workflows.campbell import run_campbell

    runs = []
    for rpm in (1000.0, 4000.0):
        data = seal_scene()
        data["rotor"]["speed_rpm"] = rpm
        runs.append(run_campbell(load_scene(data)))
    a, b = runs
    assert a.speeds_rpm == b.speeds_rpm
    for ca, cb in zip(a.curves, b.curves):
        np.testing.assert_allclose(ca.seen_hz, cb.seen_hz, rtol=1e-6)
        np.testing.assert_allclose(ca.decay, cb.decay, rtol=1e-6, atol=1e-9)
    assert [round(c.speed_rpm, 3) for c in a.critical_speeds] == [
        round(c.speed_rpm, 3) for c in b.critical_speeds]


def test_a_seal_needs_the_machine_s_rated_speed():
    data = seal_scene()
    del data["rotor"]["rated_speed_rpm"]
    with pytest.raises(SceneError, match=r"rotor\.rated_speed_rpm: missing"):
        load_scene(data)
