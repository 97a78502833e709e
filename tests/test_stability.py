"""Stiff, soft, scaled, nearly incompressible, slender, stubby, deep-grooved, coarse, fine.

Every case must give exactly six rigid-body modes (else modal_analysis raises),
no negative frequency, residuals and M-orthonormality below 1e-8, and obey the
scaling law that holds exactly.
"""

from dataclasses import replace

import numpy as np
import pytest

from references import timoshenko_free_free_hz, torsion_hz
from shaftfem.fem.assembly import assemble
from shaftfem.fem.eigen import SolverSettings
from shaftfem.fem.modes import modal_analysis
from shaftfem.scene.load import scene_from_dict
from shaftfem.scene.model import Material
from shaftfem.workflows.pipeline import run_modes


def _scene(length_mm, diameter_mm, size_mm, nu=0.277, order=2, grooves=None):
    d = {
        "shaft": {"length_mm": length_mm, "diameter_mm": diameter_mm},
        "material": {"youngs_modulus_mpa": 211000.0, "poisson_ratio": nu,
                     "density_kg_m3": 7870.0},
        "mesh": {"element_size_mm": size_mm, "order": order, "max_dofs": 2_000_000},
    }
    if grooves:
        d["grooves"] = grooves
    return scene_from_dict(d, source="stability")


def _healthy(modes):
    assert modes.n_rigid == 6
    assert np.all(modes.frequencies > 0) and np.all(np.isfinite(modes.frequencies))
    # ||K x - w^2 M x|| / ||K x|| has a round-off floor of eps w_max^2 / w^2 (5e-8 for
    # the slender shaft's first mode); the normwise backward error has none.
    assert np.all(modes.backward_errors < 1e-11)  # round-off level (SuperLU ~1e-17, PARDISO ~1e-13)
    assert np.all(modes.residuals < 1e-6)
    assert modes.orthonormality_error < 1e-8


def _solve(mesh, material):
    s = assemble(mesh, material)
    return modal_analysis(s)


@pytest.mark.parametrize("factor", [1e6, 1e-6])
def test_frequencies_scale_exactly_with_sqrt_E(cylinder, factor):
    m = cylinder.scene.material
    modes = _solve(cylinder.mesh, replace(m, youngs_modulus=m.youngs_modulus * factor))
    _healthy(modes)
    ratio = modes.frequencies / cylinder.modes.frequencies
    assert np.max(np.abs(ratio / np.sqrt(factor) - 1)) < 1e-10


@pytest.mark.parametrize("factor", [1e6, 1e-6])
def test_the_one_factorisation_at_a_hint_scales_too(cylinder, factor):
    """The solve from a shift hint (PARDISO, one factorisation, Lanczos below the
    hint) under the same extreme stiffnesses: healthy modes, the same sqrt(E) law."""
    from shaftfem.fem.factor import available_factorisers

    if "pardiso" not in available_factorisers():
        pytest.skip("PARDISO is not installed")
    m = cylinder.scene.material
    s = assemble(cylinder.mesh, replace(m, youngs_modulus=m.youngs_modulus * factor))
    hint = cylinder.modes.inertia_shift * factor
    modes = modal_analysis(s, settings=SolverSettings("pardiso"),
                           shift_hint=hint)
    _healthy(modes)
    assert modes.inertia_shift == hint  # solved at the hint, not by the fallback
    ratio = modes.frequencies / cylinder.modes.frequencies
    assert np.max(np.abs(ratio / np.sqrt(factor) - 1)) < 1e-10


def test_density_scaling(cylinder):
    m = cylinder.scene.material
    modes = _solve(cylinder.mesh, replace(m, density=m.density * 1e3))
    _healthy(modes)
    assert np.max(np.abs(modes.frequencies * np.sqrt(1e3) / cylinder.modes.frequencies - 1)) < 1e-10


def test_same_shaft_in_mm_gives_the_same_hz(cylinder):
    """Coordinates in mm, E in N/mm^2 (MPa), density in t/mm^3: a consistent unit set."""
    from shaftfem.cad.mesh import ShaftMesh

    m, mesh = cylinder.scene.material, cylinder.mesh
    mm = ShaftMesh(points=mesh.points * 1e3, cells=mesh.cells, order=2,
                   min_jacobian_ratio=mesh.min_jacobian_ratio, straightened=0)
    modes = _solve(mm, Material("40Cr (t, mm, s)", m.youngs_modulus * 1e-6,
                                m.poisson_ratio, m.density * 1e-12))
    _healthy(modes)
    assert np.max(np.abs(modes.frequencies / cylinder.modes.frequencies - 1)) < 1e-10


@pytest.fixture(scope="module")
def poisson_sweep():
    out = {}
    for nu in (0.0, 0.3, 0.45, 0.49, 0.499):
        for order in (1, 2):
            r = run_modes(_scene(550.0, 32.0, 8.0, nu=nu, order=order))
            ref = timoshenko_free_free_hz(1, 0.55, 0.016, 2.11e11, nu, 7870)[0]
            out[nu, order] = (r, r.modes.frequencies[0] / ref - 1)
    return out


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45, 0.49, 0.499])
def test_p2_holds_for_any_poisson_ratio(poisson_sweep, nu):
    r, err = poisson_sweep[nu, 2]
    _healthy(r.modes)
    assert abs(err) < 5e-3  # Timoshenko itself is good to ~1e-3 here
    ft = torsion_hz(1, 0.55, 2.11e11, nu, 7870)
    f = r.modes.frequencies[r.modes.kinds.index("torsion")]
    assert abs(f / ft - 1) < 2e-4  # 3e-5 at nu = 0.277, 1.0e-4 at nu = 0.499


def test_p1_locks_as_nu_approaches_one_half(poisson_sweep):
    errs = {nu: poisson_sweep[nu, 1][1] for nu in (0.0, 0.3, 0.45, 0.49, 0.499)}
    for nu in errs:
        _healthy(poisson_sweep[nu, 1][0].modes)
    assert errs[0.499] > 2 * errs[0.3] > 0  # stiffer and stiffer
    assert errs[0.499] > 0.1  # more than 10 % too high: locked
    assert poisson_sweep[0.499, 1][0].warnings  # and the run says so


def test_slender_shaft_l_over_d_100():
    r = run_modes(_scene(1000.0, 10.0, 5.0))
    _healthy(r.modes)
    ref = timoshenko_free_free_hz(1, 1.0, 0.005, 2.11e11, 0.277, 7870)[0]
    assert abs(r.modes.frequencies[0] / ref - 1) < 5e-3


def test_stubby_shaft_l_over_d_1():
    r = run_modes(_scene(32.0, 32.0, 4.0))
    _healthy(r.modes)
    if "torsion" in r.modes.kinds:  # sections turning rigidly: exact in 3D at any L/D
        f = r.modes.frequencies[r.modes.kinds.index("torsion")]
        assert abs(f / torsion_hz(1, 0.032, 2.11e11, 0.277, 7870) - 1) < 1e-3


@pytest.mark.slow  # about 55 s: the CAD of a 300 mm shaft with 40 % deep grooves
def test_very_deep_grooves_forty_percent_of_the_radius():
    grooves = {"hands": ["right", "left"], "pitch_mm": 80.0, "width_mm": 8.0,
               "depth_mm": 6.4, "root_radius_mm": 1.0, "grooved_length_mm": 160.0}
    r = run_modes(_scene(300.0, 32.0, 8.0, grooves=grooves))
    _healthy(r.modes)
    assert abs(r.shape.groove_volume_error) < 0.01
    plain = run_modes(_scene(300.0, 32.0, 8.0))
    assert r.modes.frequencies[0] < plain.modes.frequencies[0]  # grooves soften bending


def test_very_coarse_mesh_is_flagged():
    r = run_modes(_scene(550.0, 32.0, 24.0))
    _healthy(r.modes)
    assert any("exceeds the shaft radius" in w for w in r.warnings)


@pytest.mark.slow
def test_very_fine_mesh():
    r = run_modes(_scene(550.0, 32.0, 3.0))
    _healthy(r.modes)
    assert abs(r.modes.frequencies[r.modes.kinds.index("torsion")]
               / torsion_hz(1, 0.55, 2.11e11, 0.277, 7870) - 1) < 1e-5
