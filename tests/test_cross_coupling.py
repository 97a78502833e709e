"""A stage's aerodynamic cross-coupling (shaftfem.parts.wachel): Wachel's estimate in
its physical form against API 617's own (C = 63, hp, in, r/min, klbf/in), the scene's
keys, and its effect on a rotor: it drives forward whirl and damps backward whirl."""

from __future__ import annotations

import math

import pytest

from shaftfem.errors import SceneError
from shaftfem.parts import wachel
from shaftfem.scene.load import load_scene
from shaftfem.workflows.equip import with_parts


def test_wachel_is_api_617s_formula():
    """API 617's C = 63 is 63,025 hp in lbf / (r/min) rounded: the two forms within
    0.05 %, for centrifugal and axial stages and a density ratio."""
    for kind, ratio in (("centrifugal", 1.0), ("axial", 1.8)):
        ours = wachel.cross_coupling(1340 * wachel.HP, 10_000 * wachel.RPM, 19.7 * wachel.IN,
                                     0.79 * wachel.IN, kind, ratio)
        theirs = wachel.api617(1340, 10_000, 19.7, 0.79, kind, ratio) * wachel.KLBF_PER_IN
        assert ours == pytest.approx(theirs, rel=5e-4)


def rotor(power_kw: float | None, **stage) -> dict:
    from test_rotor import disk, ends, friswell

    disks = [disk(500.0, 0.28, "disk 1"), disk(1000.0, 0.35, "wheel")]
    if power_kw is not None:
        disks[1] = {**disks[1], "stage_power_kw": power_kw, "stage_diameter_mm": 350.0,
                    "stage_width_mm": 20.0, **stage}
    return friswell(ends(kxx_n_per_mm=1000.0, cxx_n_s_per_mm=0.5), disks,
                    {"speed_rpm": 4000.0, "max_speed_rpm": 6000.0, "campbell_points": 7,
                     "rated_speed_rpm": 4000.0})


def test_a_stage_on_a_part_is_its_cross_coupling_against_speed():
    scene = with_parts(load_scene(rotor(500.0)))   # the stage asked for its q
    wheel = scene.attachments[1]
    q = 3 * (500e3 / (4000 * math.pi / 30)) / (0.35 * 0.02)
    (kxx, kxy), (kyx, kyy) = wheel.cross_coupling.stiffness(4000 * math.pi / 30)
    assert (kxx, kyy) == (0.0, 0.0)
    assert kxy == pytest.approx(q, rel=1e-9) and kyx == pytest.approx(-q, rel=1e-9)
    (_, half), _ = wheel.cross_coupling.stiffness(2000 * math.pi / 30)
    assert half == pytest.approx(q / 4, rel=1e-4)     # the fan law


@pytest.mark.parametrize("keys, said", [
    ({"stage_width_mm": None}, "stage_width_mm: missing"),
    ({"stage_kind": "radial"}, "stage_kind"),
    ({"density_ratio": -1.0}, "density_ratio"),
])
def test_a_stage_refuses_what_it_cannot_be(keys, said):
    data = rotor(500.0)
    wheel = data["attachment"][1]
    for k, v in keys.items():
        if v is None:
            del wheel[k]
        else:
            wheel[k] = v
    with pytest.raises(SceneError, match=said):
        load_scene(data)


@pytest.mark.slow
def test_cross_coupling_drives_forward_whirl_and_damps_backward():
    from shaftfem.fem.rotor import rotor_model
    from shaftfem.workflows.campbell import whirl_at
    from shaftfem.workflows.pipeline import run_modes, with_modes

    w = 4000 * math.pi / 30
    plain = load_scene(rotor(None))
    staged = load_scene(rotor(2000.0))
    a = whirl_at(rotor_model(run_modes(with_modes(plain, count=20)), "stationary"), w, 2)
    b = whirl_at(rotor_model(run_modes(with_modes(staged, count=20)), "stationary"), w, 2)
    back = [x for x in (a, b) for x in x if x.whirl == "backward"]
    fore = [x for x in (a, b) for x in x if x.whirl == "forward"]
    assert fore[1].log_dec < fore[0].log_dec
    assert back[1].log_dec > back[0].log_dec
