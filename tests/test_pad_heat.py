"""The film's energy equation on a pad (shaftfem.parts.pad_heat) against its closed forms."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from shaftfem.parts import pad_heat, pads
from shaftfem.parts.heat import CARRY_OVER, SPECIFIC_HEAT


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


def test_a_centred_journal_in_pads_loses_petroffs_power_and_draws_the_couette_flow():
    """A two-axial-groove bore (two 160-degree pads) round a journal barely loaded (1 N):
    the films are even and carry no pressure, so each pad's shear is Petroff's, 2 pi mu omega^2 R^3
    L / c over its share of the turn, at the supply's viscosity (an oil that cannot warm:
    a vast specific heat); the journal takes nothing from films at its own temperature;
    and each pad draws the Couette flow omega R c L / 2 at its leading edge, of which the
    pad before gives back CARRY_OVER, so the supply makes up the rest."""
    from shaftfem.parts import oil
    from shaftfem.scene.model import JournalBore

    bore = pads.bore_of(JournalBore("two_axial_groove"), 0.5)
    R, c, omega = 0.05, 100e-6, 3000 * math.pi / 30
    h = pad_heat.heated(bore, 1.0, omega, R, c, 32, 50.0, specific_heat=1e12)
    mu, L = oil.dynamic(32, 50.0), 0.5 * 2 * R
    petroff = 2 * math.pi * mu * omega**2 * R**3 * L / c * (2 * 160 / 360)
    assert h.power == pytest.approx(petroff, rel=1e-3)
    assert abs(h.journal_power) < 1e-6 * h.power
    couette = omega * R * c * L / 2
    assert h.fresh == pytest.approx(2 * (1 - CARRY_OVER) * couette, rel=1e-3)


FILLON_ROSS = Path(__file__).parent / "data" / "fillon_ross.json"


def test_the_thd_reference_was_run_on_our_oil():
    """ross's heated film of Fillon's bearing (benchmarks/tilting_pad_reference.py --heat)
    was fed shaftfem's specific heat, conductivity and carry-over."""
    b = json.loads(FILLON_ROSS.read_text())["bearing"]
    assert b["specific_heat"] == SPECIFIC_HEAT and b["carry_over"] == CARRY_OVER
    assert b["conductivity"] == pad_heat.CONDUCTIVITY


@pytest.mark.slow
@pytest.mark.parametrize("rpm", [1000.0, 4000.0])
def test_fillons_bearing_heats_as_an_independent_thd_film(rpm):
    """Fillon, Bligoud & Frene's (1992) 4-pad bearing at 10 kN: the peak pad temperature
    within 1.5 C of ross 3.1's thermohydrodynamic film (its 3D energy equation and
    conducting pads) on the same rig and oil, the journal within 2 C, the eccentricity
    within 0.02; a loaded pad the hottest, below the measured peak."""
    ref = {r["speed_rpm"]: r for r in json.loads(FILLON_ROSS.read_text())["results"]}[rpm]
    bore = pads.tilting(0.7, 4, math.radians(75), 0.47, 0.5, math.radians(45))
    h = pad_heat.heated(bore, 10e3, rpm * math.pi / 30, 0.05, 148e-6 * (1 - 0.47), 32, 40.0)
    assert abs(h.peak - ref["peak_c"]) < 1.5
    assert abs(h.journal - ref["journal_c"]) < 3.0
    assert abs(math.hypot(*h.state.q[:2]) - ref["eccentricity"]) < 0.02
    assert h.hottest in (2, 3) and 40.0 < h.journal < h.peak < {1000.0: 49.5, 4000.0: 76.5}[rpm]


def _film_between(R: float, centre: np.ndarray, radius: float, theta: np.ndarray) -> np.ndarray:
    """The gap along each ray theta from the bore's centre between a journal of radius R
    and a pad's face, a circle about `centre` of `radius` (exact: the ray meets it where
    |r u - centre| = radius)."""
    u = np.stack([np.cos(theta), np.sin(theta)])
    b = centre @ u
    return b + np.sqrt(b**2 - centre @ centre + radius**2) - R


@pytest.mark.parametrize("tilts", [True, False])
def test_a_pad_grown_by_its_heat_has_the_film_its_expanded_geometry_gives(tilts):
    """A journal 12 K above the supply and a 20 mm pad 25 K above it, the housing at the
    supply (parts.pad_heat.grown): the film is that between the journal's circle grown
    about the bore's centre and the pad's face grown about its pivot (a fixed pad, the
    housing's bore, keeps its size), built point by point, to 1 % of its change."""
    R, c_b, m, t = 0.05, 80e-6, 0.4, 0.02
    dT_j, dT_p, alpha = 12.0, 25.0, pad_heat.EXPANSION
    pivot = math.radians(-60.0)
    pad = pads.Pad(start=pivot - 0.6, arc=1.2, pivot=pivot, preload=m, tilts=tilts)
    hot = pad_heat.grown(pad, R, c_b, dT_j, dT_p, t)
    n = np.array([math.cos(pivot), math.sin(pivot)])
    c_p = c_b / (1 - m)
    centre, radius = -(c_p - c_b) * n, R + c_p        # the face: R + c_b out at the pivot
    back = (R + c_b + t) * n                            # the pivot, held by the housing
    e = alpha * dT_p if tilts else 0.0
    theta = np.linspace(pad.start, pad.start + pad.arc, 9)
    cold = _film_between(R, centre, radius, theta)
    grown = _film_between(R * (1 + alpha * dT_j), back + (1 + e) * (centre - back),
                          (1 + e) * radius, theta)
    ours = pads._film(hot, theta, np.zeros(3 if tilts else 2))[0] * c_b
    assert np.abs(ours - grown).max() < 0.01 * np.abs(grown - cold).max()
    assert np.abs(grown - cold).max() > 5e-6        # the growth is microns, not round-off
    assert pad_heat.grown(pad, R, c_b, 0.0, 0.0, t) == pad


def test_parts_that_grow_through_the_clearance_are_refused():
    pad = pads.Pad(start=0.0, arc=1.0, pivot=0.5, preload=0.3, tilts=True)
    with pytest.raises(ValueError, match="grow through the clearance"):
        pad_heat.grown(pad, 0.05, 50e-6, 100.0, 100.0, 0.02)


FILLON_GROWN = Path(__file__).parent / "data" / "fillon_ross_grown.json"


@pytest.mark.slow
@pytest.mark.parametrize("rpm", [1000.0, 4000.0])
def test_fillons_bearing_grown_by_its_heat_runs_as_an_independent_tehd_film(rpm):
    """The same bearing with its parts grown by their heat (20 mm pads): the peak pad
    temperature within 1 C of ross 3.1's film on pads deformed by their pressure and heat
    (2D plane-strain pads) with its journal and shell grown, the eccentricity within
    0.02; and hotter than on rigid parts of their cold size."""
    ref = {r["speed_rpm"]: r for r in json.loads(FILLON_GROWN.read_text())["results"]}[rpm]
    bore = pads.tilting(0.7, 4, math.radians(75), 0.47, 0.5, math.radians(45))
    args = (bore, 10e3, rpm * math.pi / 30, 0.05, 148e-6 * (1 - 0.47), 32, 40.0)
    h = pad_heat.heated(*args, thickness=0.02)
    assert abs(h.peak - ref["peak_c"]) < 1.0
    assert abs(h.journal - ref["journal_c"]) < 3.0
    assert abs(math.hypot(*h.state.q[:2]) - ref["eccentricity"]) < 0.02
    assert h.peak > pad_heat.heated(*args).peak
    assert all(c < 148e-6 * (1 - 0.47) for c in h.clearance)


def fillon(**kw):
    """Fillon's bearing as a scene's journal (its oil by its supply), its film table
    solved."""
    from shaftfem.parts import journal
    from shaftfem.scene.model import JournalBearing, JournalBore

    spec = JournalBore(kind="tilting_pad", pads=4, arc=math.radians(75), preload=0.47)
    b = JournalBearing(diameter=0.1, length=0.07, clearance=148e-6 * (1 - 0.47),
                       viscosity=None, load=10e3, bore=spec, oil_iso_vg=32,
                       oil_supply_temperature=40.0, pad_thickness=0.02, **kw)
    journal.remember(pads.film_table(spec, round(b.ratio, 9)))
    return journal.with_oil(b)


def test_the_rotor_takes_the_heated_films_coefficients_at_its_operating_speed(monkeypatch):
    """Fed tilting pads' speed table (parts.pad_heat.heated_table) at an operating speed:
    the heated film's matrices on the grown parts there, to round-off, the table's
    other rows moved off the heat balance's; a load along +x turns them with it."""
    from shaftfem.parts import heat, journal
    from shaftfem.scene.model import condensed

    monkeypatch.setattr(pad_heat, "SAMPLES", 2)
    b = fillon(direction=(1.0, 0.0))
    t = journal.speed_table(b, 4000 * math.pi / 30, points=21, film=heat.at_speed)
    w = float(t.speeds[15])
    amended = pad_heat.heated_table(b, t, at=(w,))
    K, C = pad_heat.film_matrices(b, pad_heat.heated_at(b, w), w)
    Z = condensed(K + 1j * w * C)
    assert np.abs(amended.pad_K[15] - K).max() < 1e-9 * np.abs(K).max()
    assert np.abs(amended.K[15] - Z.real).max() < 1e-9 * np.abs(Z.real).max()
    assert np.abs(amended.C[15] * w - Z.imag).max() < 1e-9 * np.abs(Z.imag).max()
    assert abs(amended.K[15][0, 0] / t.K[15][0, 0] - 1) > 0.02
    # the same film under a load along -y: the journal's coordinates turned by 90 deg
    down = fillon()
    K_down, _ = pad_heat.film_matrices(down, pad_heat.heated_at(down, w), w)
    T = np.eye(K.shape[0])
    T[:2, :2] = journal.rotation(math.pi / 2)
    assert np.abs(T @ K_down @ T.T - K).max() < 1e-9 * np.abs(K).max()
    assert np.abs(K_down - K).max() > 1e-3 * np.abs(K).max()


@pytest.mark.slow
@pytest.mark.parametrize("rpm", [1000.0, 4000.0])
def test_fillons_heated_grown_coefficients_are_an_independent_tehd_films(rpm):
    """The rotor model's K_xx and C_xx of Fillon's bearing fed at 40 C (its heated film
    on grown parts, at an operating speed) within 6 % of ross 3.1's synchronously reduced
    ones on its deformed and grown film, massless pads; its table between samples within
    1.5 % of the heated film solved there."""
    from shaftfem.parts import heat, journal
    from shaftfem.scene.model import condensed

    ref = {r["speed_rpm"]: r for r in json.loads(FILLON_GROWN.read_text())["results"]}[rpm]
    b = fillon()
    w = rpm * math.pi / 30
    t = journal.speed_table(b, 5000 * math.pi / 30, film=heat.at_speed)
    amended = pad_heat.heated_table(b, t, at=(w,))
    K, C = pad_heat.film_matrices(b, pad_heat.heated_at(b, w), w)
    Z = condensed(K + 1j * w * C)
    assert Z.real[0, 0] == pytest.approx(ref["kxx"], rel=0.06)
    assert Z.imag[0, 0] / w == pytest.approx(ref["cxx"], rel=0.06)
    # a table speed between the samples
    i = int(np.argmin(np.abs(t.speeds - 1.3 * w)))
    wi = float(t.speeds[i])
    K, C = pad_heat.film_matrices(b, pad_heat.heated_at(b, wi), wi)
    Z = condensed(K + 1j * wi * C)
    assert amended.K[i][0, 0] == pytest.approx(Z.real[0, 0], rel=0.015)
    assert amended.C[i][0, 0] * wi == pytest.approx(Z.imag[0, 0], rel=0.015)


def test_a_heated_table_is_kept_and_read_back(monkeypatch):
    """Fed tilting pads' heated speed table (workflows.equip) is kept in the cache by its
    content: the second ask reads the same arrays without solving a heated film."""
    from shaftfem.parts import heat, journal
    from shaftfem.workflows import equip

    monkeypatch.setattr(pad_heat, "SAMPLES", 2)
    b = fillon()
    t = journal.speed_table(b, 3000 * math.pi / 30, points=11, film=heat.at_speed)
    first = equip._heated_table(b, t, at=(float(t.speeds[8]),))

    def unsolvable(*args, **kw):
        raise AssertionError("solved again")

    monkeypatch.setattr(pad_heat, "heated_table", unsolvable)
    again = equip._heated_table(b, t, at=(float(t.speeds[8]),))
    for name in ("K", "C", "pad_K", "pad_C"):
        assert np.array_equal(getattr(first, name), getattr(again, name))
    assert not np.array_equal(first.K, t.K)
