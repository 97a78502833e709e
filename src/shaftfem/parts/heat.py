"""The oil film's heating: a journal's effective film temperature from a heat balance,
fed by the oil's supply temperature (a plain bore, or a bore of pads with its pads'
friction and flows: parts.pads.pad_heat_terms).

The film's friction power H (parts.journal.heat_terms) heats the oil that flows
through it, adiabatically (the journal and the shell carry none away, the usual
assumption for a journal whose oil takes the heat: Raimondi and Boyd, Shigley's
section 12-9). The flow Q enters the film at its feed at T_in and rises linearly across
it by dT; the side flow Q_s leaves through its ends at the mean rise, the rest at T_in
+ dT:

    H = rho c_p (Q - Q_s / 2) dT.

The supply replaces the side flow; the oil carried round from the film's end past the
feed (Q - Q_s) keeps a share `carry_over` of its rise (hot-oil carry-over):

    T_in = T_s + carry_over (Q - Q_s) / Q (T_in + dT - T_s),

and the film runs at its effective temperature T_in + dT / 2, whose viscosity (the
oil's ISO VG grade, parts.oil) the film is solved with: a fixed point in T_eff.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from shaftfem.scene.model import JournalBearing

# the share of the carried-over oil's temperature rise it keeps when it enters the film
# again: 0.8, ross-rotordynamics 3.1's default (hot_oil_lambda); 1 keeps all of it, 0
# none (the feed's fresh oil flushes it)
CARRY_OVER = 0.8
# a mineral oil's specific heat, J/(kg K) (1.8 to 2.0 across the ISO VG grades between
# 40 and 100 C)
SPECIFIC_HEAT = 1900.0
# the fixed point stops when T_eff moves by less than this (K)
SETTLED = 1e-3
HOTTEST = 200.0   # C: a film above this is refused (the grade's viscosity line ends)


@dataclass(frozen=True)
class FilmHeat:
    """A journal's film at one speed: the supply, inlet, outlet and effective
    temperatures (C), the friction power (W), the flow into the film and its side flow
    (m^3/s), and the viscosity at the effective temperature (Pa s)."""

    supply: float
    inlet: float
    outlet: float
    effective: float
    power: float
    flow: float
    side_flow: float
    viscosity: float


def heat_balance(b: JournalBearing, omega: float, supply: float,
                 carry_over: float = CARRY_OVER, specific_heat: float = SPECIFIC_HEAT
                 ) -> FilmHeat:
    """The film of the journal `b` (its oil given by its ISO VG grade) at the spin omega
    (rad/s) fed at `supply` (C): its effective temperature by the module's heat balance;
    a ValueError where the film would run hotter than HOTTEST."""
    from shaftfem.parts import journal, oil

    if b.oil_iso_vg is None:
        raise ValueError("a film's heating needs its oil's ISO VG grade")
    t = supply + 10.0
    for _ in range(200):
        film = replace(b, viscosity=oil.dynamic(b.oil_iso_vg, t))
        power, Q, Qs = journal.heat_terms(film, omega)
        rise = power / (oil.density(t) * specific_heat * (Q - 0.5 * Qs))
        kept = carry_over * (Q - Qs) / Q
        inlet = supply + kept * rise / (1 - kept)
        new = inlet + 0.5 * rise
        if new > HOTTEST:
            raise ValueError(f"the film would run above {HOTTEST:g} C (fed at {supply:g} C)")
        if abs(new - t) < SETTLED:
            assert film.viscosity is not None
            return FilmHeat(supply=supply, inlet=inlet, outlet=inlet + rise, effective=new,
                            power=power, flow=Q, side_flow=Qs, viscosity=film.viscosity)
        t += 0.5 * (new - t)
    raise ValueError(f"the film's temperature did not settle (fed at {supply:g} C)")


def at_speed(b: JournalBearing, omega: float) -> JournalBearing:
    """The bearing with its film's viscosity at the spin omega (rad/s): an oil given by
    its supply temperature runs at its film's effective temperature there (heat_balance),
    as `oil_temperature`; any other as it is."""
    if b.oil_supply_temperature is None or omega <= 0:
        return b
    return running(b, heat_balance(b, omega, b.oil_supply_temperature))


def running(b: JournalBearing, h: FilmHeat) -> JournalBearing:
    """The bearing with its film at the heat balance h: its viscosity and temperature."""
    return replace(b, viscosity=h.viscosity, oil_temperature=h.effective)


def petroff_power(b: JournalBearing, omega: float) -> float:
    """Petroff's friction power (W) of a concentric film of viscosity b.viscosity: the
    light-load limit, 2 pi mu omega^2 R^3 L / c."""
    assert b.viscosity is not None
    R = b.diameter / 2
    return 2 * math.pi * b.viscosity * omega**2 * R**3 * b.length / b.clearance
