"""A flexible coupling from the shaft to another machine's rotor (a motor, a load): the
drive train's torsion against the two-inertia closed form, the shaft's lateral modes
left as they are, and the keys refused clearly when wrong."""

from __future__ import annotations

import math

import pytest

from shaftfem.errors import SceneError
from shaftfem.scene.load import load_scene
from shaftfem.workflows.pipeline import run_modes

G_MODULUS = 210e9 / (2 * 1.3)
RHO, D, L = 7850.0, 0.040, 0.600
HUB = (0.0, 0.050)            # the coupling hub's seat, m
IMPELLER = (0.540, 0.580)     # the impeller's
J_IMPELLER, J_HUB, J_MOTOR, K_T = 0.2, 0.002, 0.5, 2000.0


def train(**hub) -> dict:
    """A pump shaft, 600 x 40 mm, in two radial bearings, its impeller overhung at the
    right end, its coupling hub at the left joined to a motor's rotor."""
    return {
        "name": "train", "shaft": {"length_mm": 600.0, "diameter_mm": 40.0},
        "material": {"name": "steel", "youngs_modulus_mpa": 210000.0, "poisson_ratio": 0.3,
                     "density_kg_m3": RHO},
        "mesh": {"element_size_mm": 20.0}, "modes": {"count": 10},
        "support": [{"name": "drive end", "position_mm": 150.0, "width_mm": 20.0,
                     "kind": "springs", "radial_stiffness_n_per_mm": 1e5},
                    {"name": "non-drive end", "position_mm": 450.0, "width_mm": 20.0,
                     "kind": "springs", "radial_stiffness_n_per_mm": 1e5,
                     "axial_stiffness_n_per_mm": 1e4}],
        "attachment": [
            {"name": "impeller", "position_mm": 560.0, "width_mm": 40.0, "mass_kg": 20.0,
             "polar_inertia_kg_m2": J_IMPELLER, "diametral_inertia_kg_m2": 0.12},
            {"name": "coupling hub", "position_mm": 25.0, "width_mm": 50.0, "mass_kg": 2.0,
             "polar_inertia_kg_m2": J_HUB, "diametral_inertia_kg_m2": 0.0015, **hub}]}


def two_inertia() -> float:
    """The train's torsion, Hz: the shaft's inertia with the impeller and the hub on one
    side, the motor on the other; between them the coupling in series with the shaft's
    free length between its two rigid hubs (the slices under them do not twist)."""
    J_shaft = RHO * math.pi * D**4 / 32 * L
    J1 = J_IMPELLER + J_HUB + J_shaft
    k_shaft = G_MODULUS * math.pi * D**4 / 32 / (IMPELLER[0] - HUB[1])
    k = 1 / (1 / K_T + 1 / k_shaft)
    return math.sqrt(k * (J1 + J_MOTOR) / (J1 * J_MOTOR)) / (2 * math.pi)


@pytest.fixture(scope="module")
def coupled():
    return run_modes(load_scene(train(coupling_stiffness_nm_per_rad=K_T,
                                      coupled_inertia_kg_m2=J_MOTOR)))


def test_the_train_torsion_against_two_inertias(coupled):
    """The first torsional mode within 0.5 % of the closed form; one rigid motion, the
    turn of shaft and motor together."""
    first = next(f for f, k in zip(coupled.modes.frequencies, coupled.modes.kinds)
                 if k == "torsion")
    assert first == pytest.approx(two_inertia(), rel=0.005)
    assert coupled.modes.n_rigid == 1
    # the motor turns against the shaft: its coordinate holds most of the mode's inertia
    j = list(coupled.modes.frequencies).index(first)
    turn = float(coupled.modes.trains[0, j]) ** 2       # J phi^2 of a unit-mass mode
    assert 0.2 < turn * J_MOTOR < 0.4


def test_the_lateral_modes_are_not_dragged(coupled):
    """The motor's rotor is held by its own bearings: the shaft's bending and axial modes
    are those of the shaft with its hub alone, to 1e-9 (a motor fixed rigidly on the
    hub instead lowers them)."""
    alone = run_modes(load_scene(train()))
    ours = [f for f, k in zip(coupled.modes.frequencies, coupled.modes.kinds) if k != "torsion"]
    theirs = [f for f, k in zip(alone.modes.frequencies, alone.modes.kinds) if k != "torsion"]
    n = min(len(ours), len(theirs))
    assert n >= 6
    assert ours[:n] == pytest.approx(theirs[:n], rel=1e-9)


@pytest.mark.parametrize("hub, key", [
    ({"coupling_stiffness_nm_per_rad": 2000.0}, "coupled_inertia_kg_m2"),
    ({"coupled_inertia_kg_m2": 0.5}, "coupling_stiffness_nm_per_rad"),
    ({"coupling_stiffness_nm_per_rad": -1.0, "coupled_inertia_kg_m2": 0.5},
     "coupling_stiffness_nm_per_rad"),
    ({"coupling_stiffness_nm_per_rad": 2000.0, "coupled_inertia_kg_m2": 0.0},
     "coupled_inertia_kg_m2"),
])
def test_a_coupling_refused_clearly(hub, key):
    with pytest.raises(SceneError, match=key):
        load_scene(train(**hub))


def test_the_train_torsion_does_not_move_with_speed():
    """Turning about its own axis changes nothing of a rigid turn (a symmetry), so the
    train's torsion, nearly rigid on the shaft, stays within 0.05 % of standstill at
    3,000 r/min in both frames (0.035 % measured: the shaft's own twist); the slices
    under the rigid hubs turn with them, unsoftened."""
    from shaftfem.workflows.campbell import run_campbell

    data = train(coupling_stiffness_nm_per_rad=K_T, coupled_inertia_kg_m2=J_MOTOR)
    still = run_modes(load_scene(data)).modes
    f0 = next(f for f, k in zip(still.frequencies, still.kinds) if k == "torsion")
    for frame in ("stationary", "rotating"):
        data["rotor"] = {"speed_rpm": 3000.0, "max_speed_rpm": 3000.0, "campbell_points": 2,
                         "frame": frame}
        c = run_campbell(load_scene(data))
        f = min(w.frequency_hz for w in c.whirl
                if abs(w.speed_rpm - 3000.0) < 1e-6 and w.kind == "torsion")
        assert f == pytest.approx(f0, rel=5e-4), frame
