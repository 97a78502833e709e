"""The oil film's heating (shaftfem.parts.heat): the film's friction and flows against
Raimondi and Boyd's table, and a journal's effective temperature against the heat
balance worked by hand from that table."""

import math

import numpy as np
import pytest

from shaftfem.parts import heat, journal, oil
from shaftfem.scene.model import JournalBearing

# Raimondi and Boyd (1958), full journal bearing, L/D = 1, Swift-Stieber, as reprinted
# in Shigley's Mechanical Engineering Design, table 12-4: eps, S, (R/c) f, Q / (R c N L),
# Q_s / Q
RAIMONDI_BOYD = [(0.1, 1.33, 26.4, 3.37, 0.150), (0.2, 0.631, 12.8, 3.59, 0.280),
                 (0.4, 0.264, 5.79, 3.99, 0.497), (0.6, 0.121, 3.22, 4.33, 0.680),
                 (0.8, 0.0446, 1.70, 4.62, 0.842), (0.9, 0.0188, 1.05, 4.74, 0.919)]


@pytest.mark.parametrize("row", RAIMONDI_BOYD)
def test_the_films_friction_and_flows_are_raimondi_and_boyds(row):
    """At each eccentricity of the table: the friction variable, the flow into the film
    and the side flow's share within 1 %."""
    eps, S, friction, flow, side = row
    s = journal.state(1.0, eps)
    load = math.hypot(*s.force)
    assert s.friction / load == pytest.approx(friction, rel=0.01)
    assert math.pi * s.inflow == pytest.approx(flow, rel=0.01)
    assert s.side_flow / s.inflow == pytest.approx(side, rel=0.01)


def test_a_light_film_loses_petroffs_power():
    """Lightly loaded (eps 0.01), the film's friction power is Petroff's within 0.1 %."""
    b = JournalBearing(diameter=0.05, length=0.05, clearance=50e-6, viscosity=0.02,
                       load=20.0, oil_iso_vg=32)
    omega = 3000 * math.pi / 30
    power = journal.heat_terms(b, omega)[0]
    assert power == pytest.approx(heat.petroff_power(b, omega), rel=1e-3)


@pytest.mark.parametrize("carry_over", [0.0, 0.8])
def test_a_journals_effective_temperature_is_the_heat_balance_by_hand(carry_over):
    """A 50 x 50 mm journal, 50 um clearance, 2 kN at 3,000 r/min, ISO VG 32 fed at 40 C:
    at the effective temperature shaftfem settles on, the heat balance worked by hand
    from Raimondi and Boyd's table (eps from S, then (R/c) f, Q and Q_s / Q, each
    interpolated between the table's rows) gives the same temperature within 0.5 K,
    and the supply's side flow carries the friction's heat away."""
    b = JournalBearing(diameter=0.05, length=0.05, clearance=50e-6, viscosity=None,
                       load=2000.0, oil_iso_vg=32)
    omega = 3000 * math.pi / 30
    h = heat.heat_balance(b, omega, 40.0, carry_over)
    # by hand, at T = h.effective
    T = h.effective
    mu, rho = oil.dynamic(32, T), oil.density(T)
    R, c, N, L, D = 0.025, 50e-6, 50.0, 0.05, 0.05
    S = mu * N * L * D * (R / c) ** 2 / 2000.0
    eps_, S_, f_, q_, s_ = (np.array(col) for col in zip(*RAIMONDI_BOYD))
    eps = np.interp(-math.log(S), -np.log(S_), eps_)
    # the friction variable nearly as S (Petroff): interpolated in log-log
    f = math.exp(np.interp(-math.log(S), -np.log(S_), np.log(f_)))
    q, side = (float(np.interp(eps, eps_, col)) for col in (q_, s_))
    power = f * c / R * 2000.0 * omega * R
    Q = q * R * c * N * L
    Qs = side * Q
    rise = power / (rho * heat.SPECIFIC_HEAT * (Q - Qs / 2))
    kept = carry_over * (Q - Qs) / Q
    inlet = 40.0 + kept * rise / (1 - kept)
    assert inlet + rise / 2 == pytest.approx(T, abs=0.5)
    assert h.power == pytest.approx(power, rel=0.03)
    # the heat leaves with the oil: side flow at the mean rise, the rest at the outlet
    out = rho * heat.SPECIFIC_HEAT * (h.side_flow * (h.outlet - h.inlet) / 2
                                      + (h.flow - h.side_flow) * (h.outlet - h.inlet))
    assert out == pytest.approx(h.power, rel=1e-3)
    assert h.inlet == pytest.approx(40.0, abs=1e-9) if carry_over == 0 else h.inlet > 40.0


def test_a_light_film_on_pads_loses_petroffs_power_over_their_arcs():
    """A two-axial-groove bore barely loaded (eps 0.03): its pads' friction integral is
    Petroff's over their arcs, int 1 / H = arcs 2 L / D (whole length), within 0.5 %;
    the oil drawn into each pad is the Couette flow H / 2 over its length (L / D each,
    nondimensional) within 1 %, and the side flow nearly none (what rupture leaves: eps)."""
    from shaftfem.parts import pads

    bore = pads.two_axial_groove(1.0)
    state = pads.equilibrium(bore, np.array([0.0, -pads.sommerfeld_load(1.0, 5.0)]))
    assert math.hypot(*state.q[:2]) < 0.05
    friction, inflow, side = np.sum(
        [pads.pad_heat_terms(p, 1.0, state.q[bore.coordinates(k)], s.pressure)
         for k, (p, s) in enumerate(zip(bore.pads, state.pads))], axis=0)
    arcs = sum(p.arc for p in bore.pads)
    assert friction == pytest.approx(arcs * 2 * 1.0, rel=5e-3)
    assert inflow == pytest.approx(2 * 1.0, rel=0.01)
    assert abs(side) < 0.03 * inflow   # the gap the film opens into leaves it at eps
