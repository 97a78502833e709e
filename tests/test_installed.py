"""The installed shaft: a plain cylinder in bearings and with a part on it, against the
simply supported Timoshenko beam (closed form), a 1D Timoshenko beam FE with the
disk (tests/references.py), and the free-free solve on the same mesh."""

import os
import re

import numpy as np
import pytest

from references import timoshenko_beam_hz, timoshenko_free_free_hz, timoshenko_ss_hz
from shaftfem.cli import main
from shaftfem.errors import SceneError
from shaftfem.scene.load import scene_from_dict

STEEL = {"youngs_modulus_mpa": 211000.0, "poisson_ratio": 0.277, "density_kg_m3": 7870.0}
L_MM, D_MM, SEAT_MM = 320.0, 32.0, 2.0


def _scene(supports=(), attachments=(), size_mm=8.0):
    data = {"shaft": {"length_mm": L_MM, "diameter_mm": D_MM}, "material": dict(STEEL),
            "mesh": {"element_size_mm": size_mm}, "modes": {"count": 8}}
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
    from shaftfem.workflows.pipeline import run_modes

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
    from shaftfem.workflows.pipeline import run_modes

    rigid = _bending(on_rigid_seats, 2)
    stiff = _bending(run_modes(_scene(_springs(1e9))), 2)
    assert np.all(stiff <= rigid * (1 + 1e-9))
    assert np.max(np.abs(stiff / rigid - 1)) < 1e-4


def test_zero_stiffness_is_the_free_shaft_on_the_same_mesh():
    from shaftfem.workflows.pipeline import run_modes

    scene = _scene(_springs(0.0), size_mm=12.0)  # the same mesh for both: any size will do
    held, free = run_modes(scene), run_modes(scene.free())
    assert held.installed is not None and free.installed is None
    assert held.modes.n_rigid == free.modes.n_rigid == 6
    assert held.modes.n_dofs == free.modes.n_dofs
    assert np.max(np.abs(held.modes.frequencies / free.modes.frequencies - 1)) < 1e-8


def test_a_disk_at_mid_span_matches_a_timoshenko_beam_with_the_disk():
    """A 2 kg gear (I_d = 3e-4 kg m^2) on a 2 mm hub at mid-span: the hub is narrow so
    that the shaft under it is the beam's (a wide hub stiffens a 3D shaft partly, which
    a beam cannot say)."""
    from shaftfem.workflows.pipeline import run_modes

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
    from shaftfem.workflows.pipeline import run_modes

    r = run_modes(_scene([dict(position_mm=L_MM / 2, width_mm=SEAT_MM, kind="rigid-radial")]))
    assert r.modes.n_rigid == 4
    assert set(r.installed.free) == {"translation along z", "tilting about x",
                                     "tilting about y", "rotation about the axis (z)"}


PAPER_GROOVES_MM = (545.0 - 360.0) / 2  # where the paper shaft's centred grooved zone starts
SUPPORT = 'position_mm = {p}\nwidth_mm = {w}\nkind = "{kind}"\n{extra}'
BAD = [
    # (support table, attachment table, key named)
    (dict(p=5, w=12, kind="rigid", extra=""), None, "support 1: position_mm"),   # off the end
    (dict(p=100, w=10, kind="rigid", extra=""), None, "support 1: position_mm"),  # on grooves
    # seats too narrow to mean anything or to mesh (once exit 3 after 19 s of CAD), and
    # seats ending a sliver away from an end, the grooves or another seat
    (dict(p=20, w=1e-6, kind="rigid", extra=""), None, "support 1: width_mm"),
    (dict(p=20, w=0.01, kind="rigid", extra=""), None, "support 1: width_mm"),
    (dict(p=20, w=0.9, kind="rigid", extra=""), None, "support 1: width_mm"),
    (dict(p=5.25, w=10, kind="rigid", extra=""), None, "support 1: position_mm"),  # 0.25 mm
    (dict(p=PAPER_GROOVES_MM - 5.5, w=10, kind="rigid", extra=""), None,
     "support 1: position_mm"),                                         # 0.5 mm from grooves
    (dict(p=20, w=10, kind="rigid", extra=""), "position_mm = 30.5\nwidth_mm = 10\nmass_kg = 1",
     "attachment 1: position_mm"),                                      # 0.5 mm apart
    (dict(p=20, w=10, kind="springs", extra="radial_stiffness_n_per_mm = -5"), None,
     "support 1: radial_stiffness_n_per_mm"),
    (dict(p=20, w=10, kind="rigid", extra="radial_stiffness_n_per_mm = 5"), None,
     "support 1: radial_stiffness_n_per_mm"),
    (dict(p=20, w=10, kind="springs", extra=""), None, "support 1: radial_stiffness_n_per_mm"),
    (dict(p=20, w=10, kind="springs", extra="radial_stiffness_n_per_mm = 1e5\n"
          "tilting_stiffness_nmm_per_rad = 1e18"), None,
     "support 1: tilting_stiffness_nmm_per_rad"),                       # beyond the cap
    (dict(p=20, w=10, kind="hinged", extra=""), None, "support 1: kind"),
    (dict(p=20, w=10, kind="rigid", extra=""), "position_mm = 26\nwidth_mm = 8\nmass_kg = 1",
     "attachment 1: position_mm"),                                      # seats overlap
    (dict(p=20, w=10, kind="rigid", extra=""), "position_mm = 29\nwidth_mm = 8\nmass_kg = 1",
     "attachment 1: position_mm"),                                      # seats touch
    (None, "position_mm = 20\nwidth_mm = 8\nmass_kg = 1\npolar_inertia_kg_m2 = 0.01\n"
     "diametral_inertia_kg_m2 = 0.001", "attachment 1: diametral_inertia_kg_m2"),
]


@pytest.mark.parametrize("support,attachment,named", BAD)
def test_a_bad_seat_is_one_line_naming_the_key(tmp_path, capsys, support, attachment, named):
    from shaftfem.scene.load import GEOMETRY_DIR

    text = (GEOMETRY_DIR / "paper2018.toml").read_text()
    if support is not None:
        text += "\n[[support]]\n" + SUPPORT.format(**support) + "\n"
    if attachment is not None:
        text += "\n[[attachment]]\n" + attachment + "\n"
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(SceneError, match=named.replace("[", r"\[").replace("]", r"\]")):
        from shaftfem.scene.load import load_scene

        load_scene(f)
    assert main(["modes", str(f), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert named in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


@pytest.fixture(scope="module", params=["distributing", "rigid"])
def on_soft_springs(request):
    """Soft bearings (100 N/mm), distributing or rigid rings, and a 1 kg gear: the
    shaft bounces and rocks on them well below its first bending mode, so ten modes
    hold nearly all of its mass."""
    from shaftfem.workflows.pipeline import run_modes

    springs = dict(kind="springs", width_mm=10.0, radial_stiffness_n_per_mm=100.0,
                   coupling=request.param)
    gear = dict(position_mm=160, width_mm=4, mass_kg=1.0, polar_inertia_kg_m2=4e-4,
                diametral_inertia_kg_m2=2e-4)
    return run_modes(_scene([dict(position_mm=20, axial_stiffness_n_per_mm=100.0, **springs),
                             dict(position_mm=300, **springs)], [gear]))


def test_effective_masses_add_up_to_shaft_and_gear(on_soft_springs):
    from shaftfem.fem.response import modal_basis, participation

    r = on_soft_springs
    p = participation(modal_basis(r))
    R, L = 16e-3, 320e-3
    shaft = np.pi * R**2 * L * 7870.0
    mass = shaft + 1.0
    polar = shaft * R**2 / 2 + 4e-4
    assert np.allclose(p.total, [mass, mass, mass, polar], rtol=1e-3)  # mesh volume ~1e-4
    # x, y, z over the ten elastic modes; the turn about the axis is the free rigid mode
    assert np.all(p.cumulative[-1] > 0.99) and np.all(p.cumulative[-1] < 1 + 1e-9)
    assert p.rigid[3] / p.total[3] > 0.999


def test_participation_factor_is_x_transpose_M_r(on_soft_springs):
    """G_i = x_i^T M r computed on the full mesh: the shaft's DOFs plus the gear's
    rigid motion, which its band nodes carry."""
    from shaftfem.fem.response import influence, modal_basis, participation
    from shaftfem.fem.supports import part_mass

    r = on_soft_springs
    p = participation(modal_basis(r))
    X, M, nodes = r.modes.shapes, r.system.M, r.system.nodes
    band = r.installed.tied[0]
    gear = r.scene.attachments[0]
    for k, d in enumerate(("x", "y", "z")):
        rv, rp = influence(nodes, 1, d)
        # the gear moves as its band: a rigid motion (U, Theta) fitted to the band's nodes
        u = X.reshape(-1, 3, X.shape[1])[band]                   # (m, 3, modes)
        d_ = nodes[band] - np.array([0, 0, gear.position])
        B = np.zeros((band.size, 3, 6))
        B[:, :, :3] = np.eye(3)
        B[:, :, 3:] = -np.einsum("ijk,nk->nij", _levi_civita(), d_)
        fit = np.linalg.lstsq(B.reshape(-1, 6), u.reshape(-1, X.shape[1]), rcond=None)[0]
        G = X.T @ (M @ rv) + fit.T @ (part_mass(gear) @ rp[0])
        assert np.allclose(G, p.factors[:, k], rtol=1e-8, atol=1e-10 * np.abs(G).max())


def _levi_civita():
    e = np.zeros((3, 3, 3))
    e[0, 1, 2] = e[1, 2, 0] = e[2, 0, 1] = 1.0
    e[0, 2, 1] = e[2, 1, 0] = e[1, 0, 2] = -1.0
    return e


def test_base_motion_far_below_the_first_mode_moves_the_shaft_rigidly(on_soft_springs):
    from shaftfem.fem.response import base_response

    r = on_soft_springs
    f = 1e-2 * r.modes.frequencies[0]
    for d in ("x", "z"):
        assert abs(base_response(r, np.array([f]), d).transmissibility[0] - 1) < 1e-3


def test_at_a_separated_mode_its_coordinate_is_amplified_one_over_two_zeta(on_rigid_seats):
    from shaftfem.fem.response import modal_basis, modal_coordinates

    r = on_rigid_seats
    basis = modal_basis(r)
    i = r.modes.kinds.index("axial")          # alone between the bending pairs
    w = 2 * np.pi * r.modes.frequencies[i]
    zeta = r.scene.damping_ratio
    eta = modal_coordinates(basis, "z", np.array([w]), zeta)[i, 0]
    static = (basis.X[:, i] @ basis.loads[:, 2]) * w**2 / w**2  # G W^2 U / w^2 at W = w
    assert abs(abs(eta) / abs(static) * 2 * zeta - 1) < 1e-2


def test_a_mechanism_the_seats_did_not_leave_free_is_refused(on_rigid_seats):
    """If the seats' analysis missed the turn about the axis, the solve finds one zero
    mode beside the expected ones and says so instead of returning it as a mode."""
    from dataclasses import replace

    from shaftfem.errors import SolverError
    from shaftfem.fem.modes import modal_analysis
    from shaftfem.scene.model import ModeRequest

    r = on_rigid_seats
    blind = replace(r.installed, rigid=r.installed.rigid[:, :0], free=())
    with pytest.raises(SolverError,
                       match="found 1 zero-frequency modes .* beside the 0 rigid-body modes, "
                             "where the supports leave 0 rigid-body modes .*: a mechanism"):
        modal_analysis(r.system, ModeRequest(4),
                       installed=blind)


INSTALLED_TOML = """
name = "installed_cylinder"
[shaft]
length_mm = 320.0
diameter_mm = 32.0
[material]
youngs_modulus_mpa = 211000.0
poisson_ratio = 0.277
density_kg_m3 = 7870.0
[mesh]
element_size_mm = 12.0
[modes]
count = 4
[[excitation]]
name = "engine"
speed_rpm = 3600.0
orders = [1, 2]
[[support]]
position_mm = 10.0
width_mm = 20.0
kind = "springs"
radial_stiffness_n_per_mm = 2.0e5
axial_stiffness_n_per_mm = 2.0e4
[[support]]
position_mm = 310.0
width_mm = 20.0
kind = "springs"
radial_stiffness_n_per_mm = 2.0e5
"""


def test_the_commands_use_the_supports_and_free_leaves_them_off(tmp_path, capsys):
    import json

    f = tmp_path / "installed.toml"
    f.write_text(INSTALLED_TOML)
    assert main(["check", str(f), "-q", "--json", str(tmp_path / "v.json")]) == 0
    out = capsys.readouterr().out
    assert "amplification" in out and "rotation about the axis (z)" not in out
    verdict = json.loads((tmp_path / "v.json").read_text())
    # 60 Hz, far below the first mode: the shaft moves with its bearings
    first = [a for a in verdict["approaches"] if a["order"] == 1][0]
    assert abs(first["amplification"] - 1) < 0.05
    assert main(["modes", str(f), "-q", "--no-estimate", "--json",
                 str(tmp_path / "m.json")]) == 0
    out = capsys.readouterr().out
    assert "rotation about the axis (z)" in out and "effective modal mass" in out
    held = json.loads((tmp_path / "m.json").read_text())
    assert held["rigid_body_modes"] == 1
    assert len(held["installation"]["supports"]) == 2
    assert main(["modes", str(f), "-q", "--no-estimate", "--free", "--json",
                 str(tmp_path / "free.json")]) == 0
    out = capsys.readouterr().out
    assert "supports are left off" in out and "effective modal mass" not in out
    free = json.loads((tmp_path / "free.json").read_text())
    assert free["rigid_body_modes"] == 6 and free["dofs"] == held["dofs"]
    # in bearings the first bending mode sits well below the free-free one
    assert held["modes"][0]["frequency_hz"] < 0.8 * free["modes"][0]["frequency_hz"]


def test_design_prints_the_effective_masses_as_modes_does(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("shaftfem.outputs.render.render_into", lambda *a, **k: [])  # no pictures
    f = tmp_path / "installed.toml"
    f.write_text(INSTALLED_TOML)
    assert main(["design", str(f), "-q", "--no-estimate", "--out", str(tmp_path / "d")]) == 0
    out = capsys.readouterr().out
    table = out[out.index("effective modal mass"):].splitlines()
    # one row per mode solved (4), numbered, with its frequency
    rows = [r for r in table if r.split()[:1] in (["1"], ["2"], ["3"], ["4"])]
    assert len(rows) == 4 and all(" Hz " in r for r in rows), table


def test_api684_margin_follows_the_amplification_factor():
    """API 684: no margin below AF 2.5; 17 (1 - 1/(AF - 1.5)) % above; 2 % damping is
    AF 25, a margin of 16.3 %."""
    from shaftfem.checks.resonance import api684_margin

    assert api684_margin(2.4) == 0.0
    assert abs(api684_margin(1 / (2 * 0.02)) - 0.17 * (1 - 1 / 23.5)) < 1e-15
    assert abs(api684_margin(1 / (2 * 0.02)) - 0.16277) < 1e-5
    assert api684_margin(1e9) < 0.17


def test_the_api684_criterion_sets_the_required_margin(tmp_path, capsys):
    f = tmp_path / "installed.toml"
    f.write_text(INSTALLED_TOML + '\n[resonance]\ncriterion = "api684"\n')
    assert main(["check", str(f), "-q"]) == 0
    out = capsys.readouterr().out
    assert "16.3 %" in out
    # every printed margin to three digits at most: no "within 16.2766 %"
    assert not re.search(r"\d+\.\d{2,} %", out), out


def test_a_sweep_or_calibration_names_a_bearing_by_its_index(tmp_path):
    """'support[1].position_mm' moves the second bearing; an index the base scene does
    not have is refused with the file and the count."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.calibrate import load_calibration
    from shaftfem.workflows.sweep_file import load_sweep

    scene = load_scene("paper2018_installed", overrides={
        "support[1].position_mm": 500.0, "support[0].radial_stiffness_n_per_mm": 1e5})
    assert scene.supports[1].position == pytest.approx(0.5)
    assert scene.supports[0].radial == pytest.approx(1e8)
    sweep = tmp_path / "bearings.toml"
    sweep.write_text('base = "paper2018_installed"\n[axes]\n'
                     '"support[1].position_mm" = [480.0, 500.0, 525.0]\n')
    s = load_sweep(sweep)
    assert [v["support[1].position_mm"] for v in s.variants] == [480.0, 500.0, 525.0]
    sweep.write_text('base = "paper2018_installed"\n[axes]\n"support[2].position_mm" = [1.0]\n')
    with pytest.raises(SceneError, match=r"support\[2\].position_mm: the base scene .* 2 "):
        load_sweep(sweep)
    cal = tmp_path / "stiffness.toml"
    cal.write_text('base = "paper2018_installed"\n[unknowns]\n'
                   '"support[0].radial_stiffness_n_per_mm" = {min = 1e4, max = 1e6}\n'
                   '[targets]\nfrequencies_hz = [224.0]\n')
    assert "support[0].radial_stiffness_n_per_mm" in load_calibration(cal).unknowns


def test_a_clamped_seat_leaves_no_rigid_motion():
    from shaftfem.workflows.pipeline import run_modes

    r = run_modes(_scene([dict(position_mm=5.0, width_mm=10.0, kind="clamped")], size_mm=12.0))
    assert r.modes.n_rigid == 0 and r.installed.free == ()
    # a cantilever's first bending mode lies far below the free-free one (3.52 against
    # 22.37 on the Euler-Bernoulli scale)
    R, E, nu, rho = _beam(r)
    free_free = timoshenko_free_free_hz(1, L_MM * 1e-3, R, E, nu, rho)[0]
    assert r.modes.frequencies[0] < 0.25 * free_free


def test_the_response_picture_reads_at_the_harmonics():
    """Two panels: every mode on a log frequency axis from below the lowest harmonic,
    and the excitation band (to 1.5 x the highest harmonic) with the transmissibility
    written at each harmonic, labels at staggered heights."""
    from shaftfem.fem.response import FrequencyResponse
    from shaftfem.outputs.plots import response_figure

    f = np.union1d(np.linspace(0, 3000, 1200), np.geomspace(0.3, 3000, 1200))
    fn, zeta = 230.0, 0.02
    r = f / fn
    t = np.sqrt((1 + (2 * zeta * r) ** 2) / ((1 - r**2) ** 2 + (2 * zeta * r) ** 2))
    fr = FrequencyResponse(frequencies=f, transmissibility=t, direction="x",
                           point=np.zeros(3), damping=zeta)
    marks = [(name, hz, float(np.interp(hz, f, t))) for name, hz in
             (("shaft x1", 1.333), ("engine x1", 60.0), ("engine x2", 120.0))]
    fig = response_figure(fr, marks, "test")
    wide, near = fig.axes
    assert wide.get_xscale() == "log" and wide.get_xlim()[0] < 1.333
    assert near.get_xlim() == pytest.approx((0, 180.0))
    texts = [a.get_text() for a in near.texts]
    assert any("engine x2" in s and "120 Hz: x1.3" in s for s in texts), texts  # 1/(1-r^2)
    heights = sorted(a.xyann[1] for a in near.texts)
    assert len(set(heights)) == 3                       # no two labels at one height


def test_the_same_scene_gives_byte_identical_tables_every_run(tmp_path, capsys):
    """A round shaft on two bearings (its bending pairs split only by the mesh), run three
    times: the first builds the mesh and finds the shift, the others start from the
    cache's. The modes and effective-mass tables come out byte for byte the same (the
    solver's residuals and the run time, which do move, are not in them)."""
    scene = tmp_path / "round.toml"
    scene.write_text(
        'name = "round"\n[shaft]\nlength_mm = 400.0\ndiameter_mm = 30.0\n'
        '[material]\nname = "steel"\nyoungs_modulus_mpa = 210000.0\npoisson_ratio = 0.3\n'
        'density_kg_m3 = 7850.0\n[mesh]\nelement_size_mm = 10.0\n'
        '[[support]]\nposition_mm = 20.0\nwidth_mm = 15.0\nkind = "rigid"\n'
        '[[support]]\nposition_mm = 380.0\nwidth_mm = 15.0\nkind = "rigid-radial"\n')
    outputs = []
    for _ in range(3):
        assert main(["modes", str(scene), "--no-estimate", "-q"]) == 0
        out = capsys.readouterr().out
        assert "effective modal mass" in out
        outputs.append([line for line in out.splitlines() if not line.startswith("time:")])
    assert outputs[0] == outputs[1] == outputs[2]


@pytest.mark.slow
def test_the_models_choices_flipped_move_the_frequencies_the_way_physics_says(capsys):
    """`modes --sensitivity` on the stepped example: the sprocket made rigid (the scene has
    it distributing) and each bearing's band made a rigid ring (the scene's distribute)
    add constraints on the same mesh, so no frequency falls and the bending modes rise;
    the moves stand beside the bounds and in the JSON."""
    import json
    from pathlib import Path

    examples = Path(__file__).resolve().parents[1] / "examples"
    out = Path(os.environ["SHAFTFEM_CACHE"]) / "sensitivity.json"
    assert main(["modes", str(examples / "stepped_shaft.toml"), "-q", "--sensitivity",
                 "--mesh-size", "12", "--no-estimate", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "model's choices move it" in text and "sprocket: joint rigid (scene: distributing)" in text
    record = json.loads(out.read_text())
    flips = {f["choice"]: np.array(f["moves_percent"], float) for f in record["model_sensitivity"]}
    assert set(flips) == {"sprocket: joint rigid (scene: distributing)",
                          "left bearing: coupling rigid (scene: distributing)",
                          "right bearing: coupling rigid (scene: distributing)"}
    kinds = [m["kind"] for m in record["modes"]]
    bending = np.array([k == "bending" for k in kinds])
    for choice, moves in flips.items():
        assert np.all(moves >= -1e-7), (choice, moves)    # stiffer: none falls
    sprocket = flips["sprocket: joint rigid (scene: distributing)"]
    assert sprocket[bending].max() > 0.1                   # a 40 mm rigid hub: > 0.1 %


def test_a_warm_solve_of_an_installed_shaft_refines_its_kept_solve(on_soft_springs,
                                                                    monkeypatch):
    """The installed shaft's last solve on its mesh is kept in its reduced coordinates:
    solved again, it is refined from there (Lanczos never runs) to the cold run's
    frequencies (1e-9) with small residuals; the shaft hanging free from the same scene
    is another solve (its own count of rigid motions), not this one's start."""
    from shaftfem.fem import eigen
    from shaftfem.workflows.pipeline import run_modes

    cold = on_soft_springs
    monkeypatch.setattr(eigen, "eigsh", lambda *a, **k: pytest.fail("Lanczos ran"))
    warm = run_modes(cold.scene)
    assert np.max(np.abs(warm.modes.frequencies / cold.modes.frequencies - 1)) < 1e-8
    # 1e-7, not the Davidson target 3e-9: round-off alone leaves |K x - w^2 M x| / |K x|
    # near 3e-8 on the 75 Hz pair (with K x and M x recomputed from x, cold or warm), and
    # a warm run measured 1.6e-8 when the tests shared the cache across two workers
    assert warm.modes.residuals.max() < 1e-7
    monkeypatch.undo()
    free = run_modes(cold.scene.free())
    assert free.modes.frequencies[0] > cold.modes.frequencies[0]
