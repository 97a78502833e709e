"""The error estimate: Richardson with measured orders, and whether it bounds the truth."""

import numpy as np
import pytest
from references import axial_love_hz, torsion_hz

from shaftfem.study import estimate_errors, richardson


def test_richardson_recovers_a_known_rate():
    # f(h) = 100 + 3 h^p: three meshes must give back p and the limit
    h = np.array([1.0, 1.5, 2.25])
    for p in (1.2, 2.0, 4.0):
        f = 100 + 3 * h**p
        est = richardson(f[[0]], f[[1]], f[[2]], 1.5, element_order=2)
        assert abs(est.observed_order[0] - p) < 1e-9
        assert est.reliable[0]
        assert abs(est.extrapolated[0] - 100) < 1e-9
        assert est.relative_error[0] * f[0] >= 3 * 1.0**p  # bounds the true error


def test_oscillating_sequence_is_flagged_and_kept_conservative():
    est = richardson(np.array([100.0]), np.array([100.5]), np.array([100.2]), 1.5)
    assert not est.reliable[0]
    assert est.relative_error[0] > 0.5 / 100  # larger than the finest change itself


def test_a_mode_missing_on_a_coarse_mesh_gets_no_estimate():
    est = richardson(np.array([100.0, 200.0]), np.array([100.5, np.nan]),
                     np.array([101.5, 201.0]), 1.5)
    assert est.reliable[0] and np.isfinite(est.relative_error[0])
    assert not est.reliable[1] and np.isnan(est.relative_error[1])


def test_matched_frequencies_pair_kinds_in_order():
    from shaftfem.study import matched_frequencies

    ref = ["bending", "bending", "torsion", "axial"]
    coarse = ["bending", "torsion", "bending"]  # torsion overtook the second bending mode
    f = matched_frequencies(ref, coarse, np.array([1.0, 2.0, 3.0]))
    assert f[0] == 1.0 and f[1] == 3.0 and f[2] == 2.0 and np.isnan(f[3])


def test_singular_cap_makes_the_estimate_larger():
    h = np.array([1.0, 1.5, 2.25])
    f = 100 + 3 * h**3
    smooth = richardson(f[[0]], f[[1]], f[[2]], 1.5, singular=False)
    capped = richardson(f[[0]], f[[1]], f[[2]], 1.5, singular=True)
    assert capped.relative_error[0] > smooth.relative_error[0]


def test_estimate_bounds_the_true_error_on_the_cylinder(cylinder):
    """True errors against closed forms (torsion, axial) and, for bending, against the
    3D frequencies of a much finer mesh (4 mm, 8x the elements)."""
    from shaftfem.pipeline import run_modes, with_mesh

    est = estimate_errors(cylinder)
    fine = run_modes(with_mesh(cylinder.scene, 4.0)).modes.frequencies
    s, m = cylinder.scene.shaft, cylinder.scene.material
    f = cylinder.modes.frequencies
    ref = fine.copy()
    kinds = cylinder.modes.kinds
    ref[kinds.index("torsion")] = torsion_hz(1, s.length, m.youngs_modulus, m.poisson_ratio,
                                             m.density)
    ref[kinds.index("axial")] = axial_love_hz(1, s.length, s.radius, m.youngs_modulus,
                                              m.poisson_ratio, m.density)
    true = np.abs(f / ref - 1)
    assert np.all(est.relative_error >= true), (est.relative_error, true)
    # and it is not absurdly loose where the order was measured
    assert np.all(est.relative_error[est.reliable] < 0.01)


@pytest.mark.slow
def test_estimate_bounds_the_true_error_on_the_grooved_shaft(paper):
    """Reference: the same scene at half the element size (4 mm, ~350k DOFs).

    With monotone convergence at any order p >= 1, the true error of the 8 mm
    frequency is e8 = (f8 - f4) 2^p / (2^p - 1) <= 2 |f8 - f4|: the estimate
    must be at least that, for every mode.
    """
    from shaftfem.pipeline import run_modes, with_mesh
    from shaftfem.study import matched_frequencies

    est = estimate_errors(paper)
    fine = run_modes(with_mesh(paper.scene, 4.0))
    f8 = paper.modes.frequencies
    f4 = matched_frequencies(paper.modes.kinds, fine.modes.kinds, fine.modes.frequencies)
    bound = 2 * np.abs(f8 - f4) / f8
    print("\n  mode, estimate, 2 |f8 - f4| / f8:")
    for i, (e, b) in enumerate(zip(est.relative_error, bound)):
        print(f"  {i + 1:2d}  {100 * e:.3f} %  {100 * b:.3f} %")
    assert np.all(est.relative_error >= bound)
