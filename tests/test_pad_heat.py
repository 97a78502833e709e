"""The film's energy equation on a pad (shaftfem.parts.pad_heat) against its closed forms."""

import math

import numpy as np
import pytest

from shaftfem.parts import pad_heat, pads


def uniform(H: float = 0.8, cells: int = 400):
    """A film of even thickness H with no pressure: Couette flow H / 2 and dissipation
    1 / H (m = 1) everywhere, on a 1-rad pad."""
    theta, Z = np.linspace(0.0, 1.0, cells + 1), np.linspace(0.0, 0.5, 9)
    shape = (theta.size, Z.size)
    return np.full(shape, H), np.zeros(shape), np.ones(shape), theta, Z


def test_an_adiabatic_film_heats_linearly_along_the_pad():
    """With no heat into the walls, q dT/dtheta = rise phi: T = T_in + 2 rise theta / H^2,
    the same along every line (no side flow without pressure); the upwind march is exact
    on a linear profile."""
    H, P, m, theta, Z = uniform()
    T, q = pad_heat.march(H, P, m, theta, Z, inlet=40.0, rise=3.0)
    exact = 40.0 + 2 * 3.0 * theta / 0.8**2
    assert np.allclose(T, exact[:, None], rtol=0, atol=1e-9)
    assert np.allclose(q, 0.4)


def test_a_film_cooled_by_the_journal_settles_where_it_gives_what_it_makes():
    """Against a journal at T_j through Nu k / h: q dT/dtheta = (rise - kappa (T - T_j)) / H,
    so T - T_eq = (T_in - T_eq) exp(-2 kappa theta / H^2), T_eq = T_j + rise / kappa;
    within 0.5 % of the excess on 400 cells (the march is first order)."""
    H, P, m, theta, Z = uniform()
    kappa, Tj = 0.6, 50.0
    T, _ = pad_heat.march(H, P, m, theta, Z, inlet=40.0, rise=3.0, kappa=kappa, journal=Tj)
    Teq = Tj + 3.0 / kappa
    exact = Teq + (40.0 - Teq) * np.exp(-2 * kappa * theta / 0.8**2)
    assert np.abs(T - exact[:, None]).max() < 0.005 * abs(40.0 - Teq)


@pytest.mark.slow
def test_fillons_bearing_runs_between_its_supply_and_its_measured_peak():
    """Fillon, Bligoud & Frene's (1992) 4-pad bearing at 10 kN and 4,000 r/min: its
    pads heat above the supply's 40 C, the downstream loaded pad the hottest, and the
    peak stays below the measured 76.5 C (docs/journal-bearing.md: the model's reading
    against the paper's theory and measurement)."""
    bore = pads.tilting(0.7, 4, math.radians(75), 0.47, 0.5, math.radians(45))
    h = pad_heat.heated(bore, 10e3, 4000 * math.pi / 30, 0.05, 148e-6 * (1 - 0.47), 32, 40.0)
    assert 40.0 < h.journal < h.peak < 76.5
    assert h.hottest == 3
