"""Parts on their seats against a 1D Timoshenko beam FE (tests/references.py) with the hub
modelled the same way: a 32 x 550 mm cylinder on radial bearings at 25 and 525 mm (4 mm
seats), a 2.48 kg gear at mid-span on a 16 or 30 mm hub, joined rigidly (a rigid
segment the hub's length) or distributing (a disk on w and psi of the section at the
hub's centre)."""

import math

import numpy as np
import pytest

from references import timoshenko_rotor_hz
from shaftfem.scene.load import GEOMETRY_DIR, scene_from_dict
from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes

GEAR = dict(name="gear", position_mm=275.0, mass_kg=2.48, polar_inertia_kg_m2=0.00478,
            diametral_inertia_kg_m2=0.002577)


def _scene(k_n_per_mm: float, hub_mm: float, joint: str):
    import tomllib

    data = tomllib.loads((GEOMETRY_DIR / "plain_cylinder.toml").read_text())
    held = ({"kind": "rigid-radial"} if math.isinf(k_n_per_mm)
            else {"kind": "springs", "radial_stiffness_n_per_mm": k_n_per_mm})
    data["support"] = [dict(name=n, position_mm=z, width_mm=4.0, **held)
                       for n, z in (("left", 25.0), ("right", 525.0))]
    data["attachment"] = [dict(GEAR, width_mm=hub_mm, joint=joint)]
    return scene_from_dict(data, "rotor.toml")


def _bending_pairs(result, n: int = 4) -> np.ndarray:
    """The first n bending frequencies, each the mean of its (x, y) pair."""
    f = [x for x, kind in zip(result.modes.frequencies, result.modes.kinds) if kind == "bending"]
    return np.array([(f[2 * i] + f[2 * i + 1]) / 2 for i in range(n)])


def _beam(scene, k_n_per_mm: float, hub_mm: float, joint: str) -> np.ndarray:
    s, m = scene.shaft, scene.material
    z0, z1 = (275.0 - hub_mm / 2) * 1e-3, (275.0 + hub_mm / 2) * 1e-3
    if joint == "distributing":  # a disk at the hub's centre
        z0 = z1 = 0.275
    return np.array(timoshenko_rotor_hz(
        4, s.length, s.radius, m.youngs_modulus, m.poisson_ratio, m.density,
        [(0.025, k_n_per_mm * 1e3), (0.525, k_n_per_mm * 1e3)],
        (z0, z1, GEAR["mass_kg"], GEAR["diametral_inertia_kg_m2"], joint)))


def _compare(k, hub, joint, mesh_mm=None):
    scene = _scene(k, hub, joint)
    r = run_modes(scene if mesh_mm is None else with_mesh(scene, mesh_mm))
    return _bending_pairs(r), _beam(scene, k, hub, joint)


@pytest.mark.slow
@pytest.mark.parametrize("hub", [16.0, 30.0])
@pytest.mark.parametrize("k", [1e4, 1e5, 1e6, math.inf])
def test_a_rigid_joint_matches_a_rigid_segment_at_every_stiffness(hub, k):
    f, beam = _compare(k, hub, "rigid")
    assert np.max(np.abs(f / beam - 1)) < 5e-3, (f, beam)


@pytest.mark.slow
@pytest.mark.parametrize("hub", [16.0, 30.0])
@pytest.mark.parametrize("k", [1e4, 1e5, 1e6, math.inf])
def test_a_distributing_joint_matches_a_disk_at_every_stiffness(hub, k):
    f, beam = _compare(k, hub, "distributing")
    assert np.max(np.abs(f / beam - 1)) < 5e-3, (f, beam)


@pytest.mark.slow
@pytest.mark.parametrize("joint", ["rigid", "distributing"])
def test_halving_the_mesh_moves_the_frequencies_less_than_their_bound(joint):
    """Rigid bearings, where the part's tilting mode is furthest from the beam: the
    frequencies on a mesh half the size move by less than the bound printed for them."""
    from shaftfem.workflows.bounded import run_bounded

    scene = _scene(math.inf, 16.0, joint)
    b = run_bounded(scene)
    half = run_modes(with_mesh(scene, scene.mesh.size * 1e3 / 2))
    moved = np.abs(half.modes.frequencies / b.result.modes.frequencies - 1)
    bound = b.estimate.relative_error
    assert np.all(moved < bound), (moved, bound)


def test_a_distributing_part_carries_its_mass_into_the_effective_masses():
    """Base motion along x moves the part as the band's mean moves it: the total r^T M r
    is the shaft's mass plus the gear's, and the modes with the rigid share add up to it."""
    from shaftfem.fem.response import influence, modal_basis, participation

    r = run_modes(with_modes(with_mesh(_scene(1e5, 30.0, "distributing"), 16.0), count=20))
    shaft_x = influence(r.system.nodes, 0, "x")[0]
    shaft = float(shaft_x @ (r.system.M @ shaft_x))
    p = participation(modal_basis(r))
    assert p.total[0] == pytest.approx(shaft + GEAR["mass_kg"], rel=1e-9)
    assert 0.9 * p.total[0] < p.effective[:, 0].sum() + p.rigid[0] <= p.total[0] * (1 + 1e-9)


@pytest.mark.parametrize("hub,warned", [(4.0, True), (30.0, False)])
def test_a_hub_shorter_than_the_radius_is_warned_of(hub, warned):
    from shaftfem.workflows.pipeline import scene_warnings

    said = " ".join(scene_warnings(_scene(1e5, hub, "rigid")))
    assert ("shorter than its radius" in said) == warned, said
