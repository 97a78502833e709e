"""The installed shaft: a plain cylinder in bearings and with a part on it, against the
simply supported Timoshenko beam (closed form), a 1D Timoshenko beam FE with the
disk (tests/references.py), and the free-free solve on the same mesh."""

import numpy as np
import pytest
from references import timoshenko_beam_hz, timoshenko_ss_hz

from shaftfem.cli import main
from shaftfem.errors import SceneError
from shaftfem.scene import scene_from_dict

STEEL = {"youngs_modulus_mpa": 211000.0, "poisson_ratio": 0.277, "density_kg_m3": 7870.0}
L_MM, D_MM, SEAT_MM = 320.0, 32.0, 2.0


def _scene(supports=(), attachments=()):
    data = {"shaft": {"length_mm": L_MM, "diameter_mm": D_MM}, "material": dict(STEEL),
            "mesh": {"element_size_mm": 8.0}, "modes": {"count": 8}}
    if supports:
        data["support"] = list(supports)
    if attachments:
        data["attachment"] = list(attachments)
    return scene_from_dict(data, "installed.toml")


def _ends(kind_left="rigid", kind_right="rigid-radial", **springs):
    """Two short seats at the ends, centred SEAT_MM / 2 from each end."""
    return [dict(position_mm=SEAT_MM / 2, width_mm=SEAT_MM, kind=kind_left, **springs),
            dict(position_mm=L_MM - SEAT_MM / 2, width_mm=SEAT_MM, kind=kind_right,
                 **springs)]


def _springs(k_n_per_mm):
    return _ends("springs", "springs", radial_stiffness_n_per_mm=k_n_per_mm,
                 axial_stiffness_n_per_mm=k_n_per_mm)


def _beam(result):
    s, m = result.scene.shaft, result.scene.material
    return s.radius, m.youngs_modulus, m.poisson_ratio, m.density


def _bending(result, n_pairs):
    """The first n bending pairs' frequencies, one per pair."""
    m = result.modes
    f = [f for f, k in zip(m.frequencies, m.kinds) if k == "bending"]
    assert np.allclose(f[0:2 * n_pairs:2], f[1:2 * n_pairs:2], rtol=1e-6)  # 4-fold mesh
    return np.array(f[0:2 * n_pairs:2])


@pytest.fixture(scope="module")
def on_rigid_seats():
    from shaftfem.pipeline import run_modes

    return run_modes(_scene(_ends()))


def test_rigid_seats_leave_only_the_turn_about_the_axis(on_rigid_seats):
    r = on_rigid_seats
    assert r.modes.n_rigid == 1
    assert r.installed.free == ("rotation about the axis (z)",)


def test_rigid_seats_give_the_simply_supported_timoshenko_beam(on_rigid_seats):
    R, E, nu, rho = _beam(on_rigid_seats)
    span = (L_MM - SEAT_MM) * 1e-3
    ref = np.array([timoshenko_ss_hz(n, span, R, E, nu, rho) for n in (1, 2, 3)])
    f = _bending(on_rigid_seats, 3)
    assert np.max(np.abs(f / ref - 1)) < 5e-3, (f, ref)


def test_stiff_springs_approach_the_rigid_seats(on_rigid_seats):
    from shaftfem.pipeline import run_modes

    rigid = _bending(on_rigid_seats, 2)
    soft, stiff = (_bending(run_modes(_scene(_springs(k))), 2) for k in (1e5, 1e9))
    assert np.all(soft < stiff) and np.all(stiff <= rigid * (1 + 1e-9))
    assert np.max(np.abs(stiff / rigid - 1)) < 1e-4
    assert np.max(np.abs(soft / rigid - 1)) > 1e-3  # 1e5 N/mm is felt


def test_zero_stiffness_is_the_free_shaft_on_the_same_mesh():
    from shaftfem.pipeline import run_modes

    scene = _scene(_springs(0.0))
    held, free = run_modes(scene), run_modes(scene.free())
    assert held.installed is not None and free.installed is None
    assert held.modes.n_rigid == free.modes.n_rigid == 6
    assert held.modes.n_dofs == free.modes.n_dofs
    assert np.max(np.abs(held.modes.frequencies / free.modes.frequencies - 1)) < 1e-8


def test_a_disk_at_mid_span_matches_a_timoshenko_beam_with_the_disk():
    """A 2 kg gear (I_d = 3e-4 kg m^2) on a 2 mm hub at mid-span: the hub is narrow so
    that the shaft under it is the beam's (a wide hub stiffens a 3D shaft partly, which
    a beam cannot say)."""
    from shaftfem.pipeline import run_modes

    gear = dict(position_mm=L_MM / 2, width_mm=2.0, mass_kg=2.0, polar_inertia_kg_m2=6e-4,
                diametral_inertia_kg_m2=3e-4)
    r = run_modes(_scene(_ends(), [gear]))
    R, E, nu, rho = _beam(r)
    hub = (0.159, 0.161, 2.0, 3e-4)
    ref = np.array(timoshenko_beam_hz(2, L_MM * 1e-3, R, E, nu, rho, pins=(1e-3, 0.319),
                                      disk=hub, n_el=320))
    f = _bending(r, 2)
    assert np.max(np.abs(f / ref - 1)) < 5e-3, (f, ref)
    # the disk lowers the first mode from the bare shaft's 635.8 Hz to below 400 Hz
    assert f[0] < 400.0


def test_one_bearing_in_the_middle_leaves_four_rigid_motions():
    """Tilting about the bearing, turning and sliding along the axis are free."""
    from shaftfem.pipeline import run_modes

    r = run_modes(_scene([dict(position_mm=L_MM / 2, width_mm=SEAT_MM, kind="rigid-radial")]))
    assert r.modes.n_rigid == 4
    assert set(r.installed.free) == {"translation along z", "rotation about x",
                                     "rotation about y", "rotation about the axis (z)"}


SUPPORT = 'position_mm = {p}\nwidth_mm = {w}\nkind = "{kind}"\n{extra}'
BAD = [
    # (support table, attachment table, key named)
    (dict(p=5, w=12, kind="rigid", extra=""), None, "support[0].position_mm"),   # off the end
    (dict(p=100, w=10, kind="rigid", extra=""), None, "support[0].position_mm"),  # on grooves
    (dict(p=20, w=10, kind="springs", extra="radial_stiffness_n_per_mm = -5"), None,
     "support[0].radial_stiffness_n_per_mm"),
    (dict(p=20, w=10, kind="rigid", extra="radial_stiffness_n_per_mm = 5"), None,
     "support[0].radial_stiffness_n_per_mm"),
    (dict(p=20, w=10, kind="springs", extra=""), None, "support[0].radial_stiffness_n_per_mm"),
    (dict(p=20, w=10, kind="hinged", extra=""), None, "support[0].kind"),
    (dict(p=20, w=10, kind="rigid", extra=""), "position_mm = 26\nwidth_mm = 8\nmass_kg = 1",
     "attachment[0].position_mm"),                                      # seats overlap
    (None, "position_mm = 20\nwidth_mm = 8\nmass_kg = 1\npolar_inertia_kg_m2 = 0.01\n"
     "diametral_inertia_kg_m2 = 0.001", "attachment[0].diametral_inertia_kg_m2"),
]


@pytest.mark.parametrize("support,attachment,named", BAD)
def test_a_bad_seat_is_one_line_naming_the_key(tmp_path, capsys, support, attachment, named):
    from shaftfem.scene import GEOMETRY_DIR

    text = (GEOMETRY_DIR / "paper2018.toml").read_text()
    if support is not None:
        text += "\n[[support]]\n" + SUPPORT.format(**support) + "\n"
    if attachment is not None:
        text += "\n[[attachment]]\n" + attachment + "\n"
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(SceneError, match=named.replace("[", r"\[").replace("]", r"\]")):
        from shaftfem.scene import load_scene

        load_scene(f)
    assert main(["modes", str(f), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert named in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
