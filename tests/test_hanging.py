"""The shaft hanging free on the turning shaft's basis (fem.hanging): the design's
free-free comparison of a rotor in bearings, against the free shaft solved on its own."""

from pathlib import Path

import numpy as np

from shaftfem.fem.hanging import CHANGE, hanging_modes, held_by_bearings_alone
from shaftfem.scene.load import load_scene

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_a_rotor_hangs_free_on_its_basis_as_on_its_own_solve():
    """The pump (journals, a wear ring, a coupled motor) on a 30 mm mesh: its bearings
    taken out of the rotor's basis, the free shaft's six modes (the train's torsion, two
    bending pairs, the third bending mode) are the free shaft's own solve on the same
    mesh to 1e-6, of the same kinds; on two thirds of the basis they move by less than
    CHANGE."""
    from shaftfem.workflows.campbell import turning
    from shaftfem.workflows.pipeline import solve_mesh

    scene = load_scene(EXAMPLES / "pump_on_journals.toml",
                       overrides={"mesh.element_size_mm": 30.0})
    assert held_by_bearings_alone(scene)
    result, model, _ = turning(scene)
    hanging = hanging_modes(result, model, scene.modes.count)
    assert hanging is not None and hanging.change <= CHANGE
    own = solve_mesh(result.scene.free(), result.shape, result.mesh).modes.lowest(
        scene.modes.count)
    assert hanging.count == own.count == scene.modes.count
    assert np.max(np.abs(hanging.frequencies / own.frequencies - 1)) < 1e-6
    assert hanging.kinds == list(own.kinds)
    # hanging free, the journals no longer hold it: every bending mode rises
    bending = [i for i, k in enumerate(own.kinds) if k == "bending"]
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
