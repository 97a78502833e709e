"""Installed shafts whose modes lie low: soft bearings, heavy parts, tilting stiffness.

The rigid motions come from the seats (the turn about the axis in two bearings), and
every other mode is elastic however low: a shaft on soft springs bounces, rocks and
moves axially on them at the closed forms of a rigid body on springs."""

import math

import numpy as np
import pytest

from shaftfem.scene.load import scene_from_dict
from shaftfem.workflows.pipeline import run_modes

STEEL = {"youngs_modulus_mpa": 211000.0, "poisson_ratio": 0.277, "density_kg_m3": 7870.0}
L, D, A = 0.55, 0.032, 0.25          # m: length, diameter, bearings at the centre +- A


def _cylinder(supports, attachments=(), count=6, size_mm=12.0):
    data = {"shaft": {"length_mm": L * 1e3, "diameter_mm": D * 1e3}, "material": dict(STEEL),
            "mesh": {"element_size_mm": size_mm}, "modes": {"count": count},
            "support": list(supports)}
    if attachments:
        data["attachment"] = list(attachments)
    return scene_from_dict(data, "low.toml")


def _bearings(**stiffness):
    return [dict(position_mm=(L / 2 + s * A) * 1e3, width_mm=16.0, kind="springs", **stiffness)
            for s in (-1, 1)]


def _mass_and_inertia():
    rho = STEEL["density_kg_m3"]
    m = rho * math.pi * (D / 2) ** 2 * L
    return m, m * (3 * (D / 2) ** 2 + L**2) / 12


@pytest.mark.parametrize("coupling", ["distributing", "rigid"])
@pytest.mark.parametrize("k_n_per_mm", [15.0, 0.5])
def test_soft_bearings_give_the_rigid_body_on_springs(k_n_per_mm, coupling):
    """Radial and axial springs of k at both bearings: bounce (a pair) and axial motion
    at sqrt(2 k / m) / 2 pi, rocking (a pair) at sqrt(2 k a^2 / I_d) / 2 pi, however low
    (0.5 N/mm: about 2.7 Hz); the turn about the axis stays the one rigid mode."""
    k = k_n_per_mm * 1e3
    r = run_modes(_cylinder(_bearings(radial_stiffness_n_per_mm=k_n_per_mm,
                                      axial_stiffness_n_per_mm=k_n_per_mm, coupling=coupling)))
    m, I_d = _mass_and_inertia()
    bounce = math.sqrt(2 * k / m) / (2 * math.pi)
    rocking = math.sqrt(2 * k * A**2 / I_d) / (2 * math.pi)
    f = r.modes.frequencies
    assert r.modes.n_rigid == 1 and r.installed.free == ("rotation about the axis (z)",)
    assert np.all(np.abs(f[:3] / bounce - 1) < 0.01), (f[:3], bounce)
    assert np.all(np.abs(f[3:5] / rocking - 1) < 0.01), (f[3:5], rocking)
    assert f[5] > 10 * rocking          # then the shaft's own bending
    assert r.modes.residuals.max() < 1e-6


def test_a_heavy_part_on_soft_bearings_gives_its_low_modes():
    """A 20 kg disk at mid-span on 15 N/mm bearings: the bounce of shaft and disk
    together, sqrt(2 k / (m + M)) / 2 pi, about 4 Hz."""
    k = 15e3
    disk = dict(position_mm=L / 2 * 1e3, width_mm=20.0, mass_kg=20.0,
                polar_inertia_kg_m2=0.1, diametral_inertia_kg_m2=0.05)
    r = run_modes(_cylinder(_bearings(radial_stiffness_n_per_mm=15.0), [disk]))
    m, _ = _mass_and_inertia()
    bounce = math.sqrt(2 * k / (m + 20.0)) / (2 * math.pi)
    radial = [f for f, e in zip(r.modes.frequencies, r.modes.energy) if e[1] > 0.3][:2]
    assert np.all(np.abs(np.array(radial) / bounce - 1) < 0.01), (radial, bounce)
    # free axially: the axial translation is a rigid motion, as is the turn
    assert r.modes.n_rigid == 2


@pytest.fixture(scope="module")
def tilting():
    """Stiff radial bearings with a tilting stiffness from none to far stiffer than the
    shaft, and clamped seats: the first bending frequency of each."""
    out = {}
    for kt in (0.0, 1.0, 1e9, 1e12, 1e14, 1e15):
        extra = {} if kt == 0 else {"tilting_stiffness_nmm_per_rad": kt}
        scene = _cylinder(_bearings(radial_stiffness_n_per_mm=1e6,
                                    axial_stiffness_n_per_mm=1e6, **extra), count=2)
        out[kt] = run_modes(scene).modes
    clamped = [dict(position_mm=(L / 2 + s * A) * 1e3, width_mm=16.0, kind="clamped")
               for s in (-1, 1)]
    out["clamped"] = run_modes(_cylinder(clamped, count=2)).modes
    return out


def test_a_tilting_stiffness_solves_at_any_value(tilting):
    for kt, modes in tilting.items():
        assert modes.count == 2 and modes.residuals.max() < 1e-6, kt
        assert modes.n_rigid == (0 if kt == "clamped" else 1), kt


def test_the_first_mode_rises_with_the_tilting_stiffness_towards_clamped(tilting):
    f1 = [tilting[kt].frequencies[0] for kt in (0.0, 1.0, 1e9, 1e12, 1e14, 1e15)]
    assert np.all(np.diff(f1) >= -1e-7 * f1[0]), f1
    assert f1[1] == pytest.approx(f1[0], rel=1e-6)     # 1 N mm/rad: nothing
    assert f1[-1] > 1.8 * f1[0]                        # near a clamped-clamped beam's 2.27
    assert f1[-1] == pytest.approx(f1[-2], rel=1e-5)   # the stiff limit is reached
    # (above the cap of 1e15 N mm/rad the scene is refused, tests/test_installed.py)
    # Clamping holds every point of the 16 mm seat, distributing springs the band's
    # mean motion only (the section under it deforms): the limit stays below clamped.
    clamped = tilting["clamped"].frequencies[0]
    assert 0.8 * clamped < f1[-1] < clamped, (f1[-1], clamped)


@pytest.mark.parametrize("seat_mm", [16.0, 4.0])
def test_a_rigid_ring_with_stiff_springs_is_a_clamped_seat(seat_mm):
    """coupling = "rigid": the band moves as a rigid ring held by the springs. As they
    stiffen, the bending modes rise to those of clamped seats of the same width (which
    also hold the turn about the axis, so torsion differs)."""
    clamped = run_modes(_cylinder([dict(position_mm=(L / 2 + s * A) * 1e3, width_mm=seat_mm,
                                        kind="clamped") for s in (-1, 1)], count=4)).modes
    f = {}
    for kt in (1e9, 1e12, 1e15):
        seats = [dict(position_mm=(L / 2 + s * A) * 1e3, width_mm=seat_mm, kind="springs",
                      coupling="rigid", radial_stiffness_n_per_mm=1e9,
                      axial_stiffness_n_per_mm=1e9, tilting_stiffness_nmm_per_rad=kt)
                 for s in (-1, 1)]
        m = run_modes(_cylinder(seats, count=4)).modes
        assert m.n_rigid == 1 and m.kinds[:4] == ["bending"] * 4
        f[kt] = m.frequencies[:4]
    assert np.all(f[1e9] < f[1e12]) and np.all(f[1e12] <= f[1e15] * (1 + 1e-9))
    assert np.all(np.abs(f[1e15] / clamped.frequencies[:4] - 1) < 1e-4), (f[1e15], clamped)
    assert np.all(np.abs(f[1e9] / clamped.frequencies[:4] - 1) > 0.02)   # a real approach


def test_a_clamped_seat_takes_no_coupling():
    from shaftfem.errors import SceneError

    with pytest.raises(SceneError, match=r"support 1: coupling"):
        _cylinder([dict(position_mm=100.0, width_mm=16.0, kind="clamped", coupling="rigid")])
    with pytest.raises(SceneError, match=r"support 1: coupling"):
        _cylinder([dict(position_mm=100.0, width_mm=16.0, kind="rigid", coupling="glued")])


@pytest.mark.slow
def test_the_installed_paper_shaft_takes_a_tilting_stiffness(tmp_path):
    """The example found: a tilting stiffness on both bearings of the installed paper
    shaft (once refused as a mechanism at 1 to 1e12 N mm/rad) gives its modes, rising
    with the stiffness, below the clamped seats."""
    import re

    from shaftfem.scene.load import GEOMETRY_DIR, load_scene

    text = (GEOMETRY_DIR / "paper2018_installed.toml").read_text()
    f1 = {}
    for kt in (1.0, 1e9, 1e12):
        scene = text.replace("radial_stiffness_n_per_mm = 2.0e5",
                             f"radial_stiffness_n_per_mm = 2.0e5\ntilting_stiffness_nmm_per_rad = {kt}")
        (tmp_path / "t.toml").write_text(scene)
        m = run_modes(load_scene(tmp_path / "t.toml")).modes
        assert m.n_rigid == 1 and m.residuals.max() < 1e-6
        f1[kt] = min(f for f, k in zip(m.frequencies, m.kinds) if k == "bending")
    clamped = re.sub(r"\n(radial|axial)_stiffness_n_per_mm = [^\n]*", "",
                     text.replace('kind = "springs"', 'kind = "clamped"'))
    (tmp_path / "c.toml").write_text(clamped)
    m = run_modes(load_scene(tmp_path / "c.toml")).modes
    f_clamped = min(f for f, k in zip(m.frequencies, m.kinds) if k == "bending")
    assert f1[1.0] < f1[1e9] < f1[1e12] < f_clamped, (f1, f_clamped)
    # as rigid rings (a shrunk-on inner ring), stiff bearings are clamped seats
    ring = text.replace('kind = "springs"', 'kind = "springs"\ncoupling = "rigid"').replace(
        "radial_stiffness_n_per_mm = 2.0e5",
        "radial_stiffness_n_per_mm = 1e9\naxial_stiffness_n_per_mm = 1e9\n"
        "tilting_stiffness_nmm_per_rad = 1e15").replace(
        "axial_stiffness_n_per_mm = 2.0e4   #", "#")
    (tmp_path / "r.toml").write_text(ring)
    m = run_modes(load_scene(tmp_path / "r.toml")).modes
    f_ring = min(f for f, k in zip(m.frequencies, m.kinds) if k == "bending")
    print(f"\n  installed paper shaft, first bending: tilting 1/1e9/1e12 N mm/rad "
          f"{f1[1.0]:.2f}/{f1[1e9]:.2f}/{f1[1e12]:.2f} Hz, rigid rings at 1e15 "
          f"{f_ring:.2f} Hz, clamped {f_clamped:.2f} Hz")
    assert f_ring == pytest.approx(f_clamped, rel=1e-4)
