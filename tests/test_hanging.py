"""The shaft hanging free on the turning shaft's basis (fem.hanging): the design's
free-free comparison of a rotor in bearings, against the free shaft solved on its own."""

import math
from pathlib import Path

import numpy as np
import pytest

from references import timoshenko_free_free_hz
from shaftfem.fem.hanging import CHANGE, hanging_modes, held_by_bearings_alone
from shaftfem.scene.load import load_scene

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def bar_in_bearings() -> dict:
    """A 30 x 400 mm steel bar in two stiff isotropic bearings 20 mm from its ends."""
    brg = {"kind": "bearing", "width_mm": 10.0, "kxx_n_per_mm": 1e5, "cxx_n_s_per_mm": 0.2}
    return {"name": "bar", "shaft": {"length_mm": 400.0, "diameter_mm": 30.0},
            "material": {"name": "steel", "youngs_modulus_mpa": 211000.0,
                         "poisson_ratio": 0.3, "density_kg_m3": 7810.0},
            "mesh": {"element_size_mm": 10.0}, "modes": {"count": 6},
            "support": [{**brg, "name": "left", "position_mm": 20.0},
                        {**brg, "name": "right", "position_mm": 380.0}],
            "rotor": {"speed_rpm": 3000.0}}


def hanging_and_own(scene):
    """The scene's rotor basis (its standstill run), its free modes from that basis, and
    the free shaft's own solve on the same mesh, checked against each other: the same
    count and kinds, the frequencies to 1e-6, the basis' own check within CHANGE."""
    from shaftfem.workflows.campbell import turning
    from shaftfem.workflows.pipeline import solve_mesh

    assert held_by_bearings_alone(scene)
    result, model, _ = turning(scene)
    hanging = hanging_modes(result, model, scene.modes.count)
    assert hanging is not None and hanging.change <= CHANGE
    own = solve_mesh(result.scene.free(), result.shape, result.mesh).modes.lowest(
        scene.modes.count)
    assert hanging.count == own.count == scene.modes.count
    assert np.max(np.abs(hanging.frequencies / own.frequencies - 1)) < 1e-6
    assert hanging.kinds == list(own.kinds)
    return result, hanging


def test_a_bar_hangs_free_on_its_rotor_basis_as_timoshenko_says():
    """The bar's bearings taken out of its rotor basis: its free modes are the free bar's
    own solve on the same mesh to 1e-6, and its first two bending pairs a free-free
    Timoshenko beam's (0.03 % and 0.11 % above it on the 10 mm mesh)."""
    _, hanging = hanging_and_own(load_scene(bar_in_bearings()))
    bending = hanging.frequencies[[i for i, k in enumerate(hanging.kinds) if k == "bending"]]
    beam = timoshenko_free_free_hz(2, 0.4, 0.015, 211e9, 0.3, 7810.0)
    assert bending[[0, 2]] == pytest.approx(beam, rel=3e-3)
    assert math.isclose(bending[0], bending[1], rel_tol=1e-3)


@pytest.mark.slow
def test_a_rotor_hangs_free_on_its_basis_as_on_its_own_solve():
    """The pump (journals, a wear ring, a coupled motor) on a 30 mm mesh: its bearings
    taken out of the rotor's basis, the free shaft's six modes (the train's torsion, two
    bending pairs, the third bending mode) are the free shaft's own solve on the same
    mesh to 1e-6, of the same kinds; on two thirds of the basis they move by less than
    CHANGE."""
    result, hanging = hanging_and_own(load_scene(EXAMPLES / "pump_on_journals.toml",
                                                 overrides={"mesh.element_size_mm": 30.0}))
    # hanging free, the journals no longer hold it: every bending mode rises
    bending = [i for i, k in enumerate(hanging.kinds) if k == "bending"]
    assert np.all(hanging.frequencies[bending] > result.modes.frequencies[bending])


def test_a_support_the_basis_cannot_take_out_is_left_to_the_free_solve():
    """A support with an axial hold (the spindle's angular-contact ball bearings) or a
    rigid seat is in the stiffness matrix beside the bearings' modal terms: the free
    shaft is not taken from the basis there."""
    from dataclasses import replace

    assert not held_by_bearings_alone(load_scene(EXAMPLES / "ball_spindle.toml"))
    pump = load_scene(EXAMPLES / "pump_on_journals.toml")
    rigid = replace(pump, supports=tuple(replace(s, coupling="rigid") if i == 0 else s
                                         for i, s in enumerate(pump.supports)))
    assert not held_by_bearings_alone(rigid)
