"""Tilting pads in the rotor model (fem.rotor, the module's equation): each pad's tilt a
coordinate of the model, against the synchronously reduced 2x2 that other tools give."""

import math
from dataclasses import replace

import numpy as np
import pytest

from shaftfem.fem.rotor import BearingModal, RotorModel, roots


@pytest.fixture(scope="module")
def pad_bearing():
    """The coefficients of tests/test_pads.py's wheel rotor's journal on 4 tilting pads,
    loaded between pads (scene, film table, equilibrium and speed table as a run makes
    them)."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.static import equipped
    from test_pads import wheel_on

    bore = {"bore": "tilting_pad", "pads": 4, "pad_arc_deg": 70.0, "preload": 0.25}
    scene = equipped(load_scene(wheel_on(**bore)))
    return scene.supports[0].bearing


def jeffcott(coefficients, mass: float = 40.0, inertia: float = 0.0) -> RotorModel:
    """A rigid mass (kg) on the bearing alone: two modal coordinates q = sqrt(m) u, so
    beta = I / sqrt(m), the standstill modes holding no spring; each pad's inertia over R^2
    (kg) as given."""
    if inertia:
        coefficients = replace(coefficients, pads=replace(
            coefficients.pads, masses=(inertia,) * (coefficients.pads.size - 2)))
    b = BearingModal(name="pads", beta=np.eye(2) / math.sqrt(mass), coefficients=coefficients,
                     standstill=(0.0, 0.0))
    z = np.zeros((2, 2))
    return RotorModel(frame="stationary", omega2=np.zeros(2), G=z, K2=z, bearings=(b,),
                      lateral=np.eye(2), turning=np.array([[0, -1j], [1j, 0]]),
                      kinds=("bending", "bending"))


def condensed_at(model: RotorModel, omega: float, lam: complex) -> np.ndarray:
    """The model's K + lam D + lam^2 M on its modal coordinates with the tilts condensed
    out at lam: singular exactly where lam is a root of the model with its tilts."""
    M, D, K, _ = model.augmented(omega)
    Z = K + lam * D + lam * lam * M
    n = model.size
    return Z[:n, :n] - Z[:n, n:] @ np.linalg.solve(Z[n:, n:], Z[n:, :n])


SPEEDS_RPM = (1200.0, 3600.0, 7000.0)


def test_the_pads_model_reduces_to_the_synchronous_coefficients_exactly(pad_bearing):
    """At a whirl at the spin, the model with the pads' tilts as coordinates has the
    dynamic stiffness of the synchronously reduced 2x2 that the tables give, within 1e-8
    (at the speed table's speeds and between them); the bearing has 2 + 4 coordinates."""
    assert pad_bearing.pads is not None and pad_bearing.pads.size == 6
    model = jeffcott(pad_bearing)
    reduced = replace(model, reduced=True)
    assert model.tilting and not reduced.tilting
    speeds = list(pad_bearing.speeds[::40]) + [n * math.pi / 30 for n in SPEEDS_RPM]
    for w in speeds:
        D, K = reduced.matrices(w)
        Z = K - w * w * reduced.mass(w) + 1j * w * D
        assert np.abs(model.dynamic(w, w) - Z).max() <= 1e-8 * np.abs(Z).max()
        # and those are the tables' own numbers at their speeds
    for i in range(0, len(pad_bearing.speeds), 40):
        w = pad_bearing.speeds[i]
        k = np.array([pad_bearing.kxx[i], pad_bearing.kxy[i], pad_bearing.kyx[i],
                      pad_bearing.kyy[i]])
        assert np.abs(np.ravel(pad_bearing.stiffness(w)) - k).max() <= 1e-8 * np.abs(k).max()


@pytest.mark.parametrize("inertia", [0.0, 0.5])
def test_every_root_of_the_pads_model_is_exact_at_its_own_frequency(pad_bearing, inertia):
    """Each root lam of the model with massless pads (first-order tilts) or pads with
    inertia: the film with the tilts condensed at lam itself (not at the spin) makes the
    rotor's matrix singular, to round-off; the synchronously reduced model's roots are not
    (the frequency dependence that reducing at the spin leaves out)."""
    model = jeffcott(pad_bearing, inertia=inertia)
    for n in SPEEDS_RPM:
        w = n * math.pi / 30
        r = roots(model, w)
        assert r.lam.size >= 2
        M, D, K, _ = model.augmented(w)
        for lam, y in zip(r.lam, r.y.T):
            # against the size of the terms that cancel there
            terms = np.linalg.norm(K) + abs(lam) * np.linalg.norm(D) + abs(lam)**2 * np.linalg.norm(M)
            Z = condensed_at(model, w, lam)
            assert np.linalg.norm(Z @ y) <= 1e-10 * terms * np.linalg.norm(y)
        red = roots(replace(model, reduced=True), w)
        off = [np.linalg.svd(condensed_at(model, w, lam), compute_uv=False)[-1]
               / (np.linalg.norm(K) + abs(lam) * np.linalg.norm(D)
                  + abs(lam)**2 * np.linalg.norm(M)) for lam in red.lam]
        assert max(off) > 1e-4, off


def test_pads_with_inertia_lock_at_high_frequency(pad_bearing):
    """A pad's tilt with inertia m_p cannot follow a fast whirl: as the whirl grows the
    condensed film tends to the journal's own block (the pads fixed at their tilts), while
    a massless pad's follows its film's damping (Z_jj - Z_jp Z_pp^-1 Z_pj at every w)."""
    heavy = jeffcott(pad_bearing, inertia=50.0)
    w = 3600 * math.pi / 30
    K, C = pad_bearing.pad_film(w)
    nu = 1e4 * w
    fixed = (K + 1j * nu * C)[:2, :2]                   # the seat's block alone
    # the model's matrix on the seat's motion (beta = I / sqrt(m)) less the mass's
    seat = condensed_at(heavy, w, 1j * nu) * 40.0 + nu * nu * 40.0 * np.eye(2)
    assert np.abs(seat - fixed).max() <= 1e-3 * np.abs(fixed).max()
    light = jeffcott(pad_bearing)
    seat = condensed_at(light, w, 1j * nu) * 40.0 + nu * nu * 40.0 * np.eye(2)
    assert np.abs(seat - fixed).max() > 0.1 * np.abs(fixed).max()


def test_a_scenes_pad_inertia_enters_the_model_and_its_reduced_coefficients(pad_bearing):
    """pad_inertia_kg_mm2 = 20,000 on the same journals: the model's pads carry I / R^2 on
    their tilts, and the 2x2 the tables give is the film condensed with it at the spin
    (the model's dynamic stiffness there within 1e-8), no longer the massless one."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.static import equipped
    from test_pads import wheel_on

    bore = {"bore": "tilting_pad", "pads": 4, "pad_arc_deg": 70.0, "preload": 0.25,
            "pad_inertia_kg_mm2": 20000.0}
    scene = equipped(load_scene(wheel_on(**bore)))
    b = scene.supports[0]
    heavy = b.bearing
    R = b.journal.diameter / 2
    assert heavy.pads.masses == pytest.approx((0.02 / R**2,) * 4)
    model = jeffcott(heavy)
    for n in SPEEDS_RPM:
        w = n * math.pi / 30
        D, K = replace(model, reduced=True).matrices(w)
        Z = K - w * w * model.mass(w) + 1j * w * D
        assert np.abs(model.dynamic(w, w) - Z).max() <= 1e-8 * np.abs(Z).max()
        light = np.array(pad_bearing.stiffness(w))
        assert np.abs(np.array(heavy.stiffness(w)) - light).max() > 1e-3 * np.abs(light).max()


def test_a_flexible_pivot_acts_in_series_with_each_pads_film():
    """Each pad's radial motion r on a pivot of stiffness k_p (its film sees the journal's
    motion less r n): condensed, a massless pad's film c_k n n^T (its tilt condensed, at
    any whirl) and the pivot act in series, sum c_k k_p / (c_k + k_p) n_k n_k^T; a
    pivot a million times stiffer gives back the rigid pivots' film within 1e-5."""
    from shaftfem.parts import journal, pads
    from shaftfem.scene.model import condensed

    bore = pads.tilting(0.5, 4, math.radians(70.0), 0.25, 0.5, math.radians(-45.0))
    state = pads.equilibrium(bore, np.array([0.0, -pads.sommerfeld_load(0.5, 0.3)]))
    blocks = [pads._on_pivot(p, s) for p, s in zip(bore.pads, state.pads)]
    for nu in (0.5, 1.0, 2.0):
        Z = np.array([K + 1j * nu * C for K, C in blocks])
        rigid = condensed(journal.assembled(Z, pivots=False))
        series = np.zeros((2, 2), dtype=complex)
        for p, z in zip(bore.pads, Z):
            n = np.array([math.cos(p.pivot), math.sin(p.pivot)])
            ck = n @ condensed(z[:3, :3]) @ n          # the pad's own film, c_k n n^T
            series += ck * 3.0 / (ck + 3.0) * np.outer(n, n)
        for k_p, expected, tol in ((3.0, series, 1e-9), (3e6 * np.abs(rigid).max(), rigid, 1e-5)):
            A = journal.assembled(Z, pivots=True)
            A[6:, 6:] += k_p * np.eye(4)
            assert np.abs(condensed(A) - expected).max() <= tol * np.abs(expected).max()


def test_a_scenes_flexible_pivots_are_coordinates_of_the_model(pad_bearing):
    """pivot_stiffness_n_per_mm and pad_mass_kg on the 4-pad journals: the model carries
    each pad's tilt and radial motion (2 + 8 coordinates), reduces exactly to the tables'
    2x2 at the spin, every root exact at its own frequency; less damped than on rigid
    pivots."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.static import equipped
    from test_pads import wheel_on

    bore = {"bore": "tilting_pad", "pads": 4, "pad_arc_deg": 70.0, "preload": 0.25,
            "pivot_stiffness_n_per_mm": 2e5, "pad_mass_kg": 0.5}
    b = equipped(load_scene(wheel_on(**bore))).supports[0].bearing
    assert b.pads.size == 10 and b.pads.masses == pytest.approx((0.0,) * 4 + (0.5,) * 4)
    model = jeffcott(b)
    w = 3600 * math.pi / 30
    D, K = replace(model, reduced=True).matrices(w)
    Z = K - w * w * model.mass(w) + 1j * w * D
    assert np.abs(model.dynamic(w, w) - Z).max() <= 1e-8 * np.abs(Z).max()
    # the pivot in series takes damping from the film (its stiffness may rise: the
    # series of a heavily damped film and a spring)
    rigid = np.diag(pad_bearing.damping(w))
    assert np.all(np.diag(b.damping(w)) < rigid)
    M, Da, Ka, _ = model.augmented(w)
    r = roots(model, w)
    for lam, y in zip(r.lam, r.y.T):
        terms = np.linalg.norm(Ka) + abs(lam) * np.linalg.norm(Da) + abs(lam)**2 * np.linalg.norm(M)
        assert np.linalg.norm(condensed_at(model, w, lam) @ y) <= 1e-10 * terms * np.linalg.norm(y)
