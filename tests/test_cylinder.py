"""The plain cylinder against closed-form and independent beam references."""

import numpy as np

from references import axial_love_hz, timoshenko_free_free_hz, torsion_hz

# Expected order of the first ten modes of a 32 x 550 mm steel bar, from the
# references below: bending pairs 1-3, torsion, bending pair 4, axial.
EXPECTED_KINDS = ["bending"] * 6 + ["torsion"] + ["bending"] * 2 + ["axial"]


def _props(result):
    s, m = result.scene.shaft, result.scene.material
    return s.length, s.radius, m.youngs_modulus, m.poisson_ratio, m.density


def test_six_rigid_body_modes(cylinder):
    assert cylinder.modes.n_rigid == 6
    assert np.all(cylinder.modes.rigid_frequencies < 0.1)  # Hz, against 483 Hz for mode 1


def test_kinds_follow_the_analytic_order(cylinder):
    assert cylinder.modes.kinds == EXPECTED_KINDS


def test_first_torsion_within_1e4_of_ct_over_2L(cylinder):
    L, R, E, nu, rho = _props(cylinder)
    f = cylinder.modes.frequencies[cylinder.modes.kinds.index("torsion")]
    assert abs(f / torsion_hz(1, L, E, nu, rho) - 1) < 1e-4


def test_first_axial_within_1e4_of_love_rod(cylinder):
    L, R, E, nu, rho = _props(cylinder)
    f = cylinder.modes.frequencies[cylinder.modes.kinds.index("axial")]
    assert abs(f / axial_love_hz(1, L, R, E, nu, rho) - 1) < 1e-4


def test_bending_pairs_within_half_percent_of_timoshenko(cylinder):
    L, R, E, nu, rho = _props(cylinder)
    ref = timoshenko_free_free_hz(4, L, R, E, nu, rho)
    f = cylinder.modes.frequencies
    bending = [f[i] for i, k in enumerate(cylinder.modes.kinds) if k == "bending"]
    for n in range(4):
        a, b = bending[2 * n], bending[2 * n + 1]
        assert abs(a / ref[n] - 1) < 5e-3, (n, a, ref[n])
        assert abs(b / a - 1) < 1e-6, f"pair {n + 1} split: {a} vs {b} Hz"


def test_residuals_and_mass_orthonormality(cylinder):
    assert np.all(cylinder.modes.residuals < 1e-8)
    assert cylinder.modes.orthonormality_error < 1e-8
    # and independently of the solver's own bookkeeping:
    X, M = cylinder.modes.shapes, cylinder.system.M
    assert np.max(np.abs(X.T @ (M @ X) - np.eye(X.shape[1]))) < 1e-8


def test_p1_is_stiffer_than_p2(cylinder):
    """Linear tets lock: at the same mesh P1 frequencies sit well above P2's."""
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    p1 = run_modes(with_mesh(cylinder.scene, order=1))
    L, R, E, nu, rho = _props(cylinder)
    ft = torsion_hz(1, L, E, nu, rho)
    f1 = p1.modes.frequencies[p1.modes.kinds.index("torsion")]
    assert f1 / ft - 1 > 10 * abs(
        cylinder.modes.frequencies[cylinder.modes.kinds.index("torsion")] / ft - 1)
    assert p1.modes.n_rigid == 6
