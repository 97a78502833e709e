"""Shafts as designers draw them: stepped, conical and hollow sections with fillets and
chamfers, keyways, and STEP files, checked against a 1D Timoshenko beam and rods of the
same profile (tests/references.py), closed forms, OpenCASCADE's own volumes and
CalculiX on the same mesh.

The 3D solid is not a beam at a shoulder: the larger section carries its full bending
stress only some way past the step, so the 3D shaft is more flexible than the beam of
the same profile, more so the shorter the mode's half-wave. On the stepped shaft below
the beam is high by 0.01 % (bending mode 1), 0.5 % (mode 2), 1.4 % (mode 3) and 1.8 %
(mode 4), where on a uniform 35 x 300 mm bar it is low by 0.06, 0.21, 0.39 and 0.58 %
(its shear coefficient): the tolerances follow that.
"""

import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from references import rod_profile_hz, timoshenko_profile_hz
from shaftfem.errors import SceneError
from shaftfem.scene.load import SceneText, load_scene

MATERIAL = """
[material]
youngs_modulus_mpa = 210000.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0
"""

STEPPED = """
name = "stepped"
[[section]]
length_mm = 40.0
diameter_mm = 25.0
fillet_mm = 1.0
chamfer_mm = 0.5
[[section]]
length_mm = 220.0
diameter_mm = 35.0
fillet_mm = 1.0
chamfer_mm = 0.5
[[section]]
length_mm = 40.0
diameter_mm = 25.0
[mesh]
element_size_mm = 8.0
groove_element_size_mm = 3.0
""" + MATERIAL

TUBE = """
name = "tube"
[[section]]
length_mm = 400.0
diameter_mm = 40.0
bore_mm = 30.0
[mesh]
element_size_mm = 8.0
""" + MATERIAL

KEYWAY = """
[[keyway]]
position_mm = 150.0
length_mm = 40.0
"""

BEARINGS = """
[[support]]
position_mm = 20.0
width_mm = 15.0
kind = "rigid"
[[support]]
position_mm = 280.0
width_mm = 15.0
kind = "rigid-radial"
"""


def scene(text: str):
    return load_scene(SceneText(text=text, source="test.toml"))


def segments(s):
    return [(x.length, x.diameter_start / 2, x.diameter_end / 2, x.bore / 2)
            for x in s.shaft.profile]


def by_kind(run, kind):
    m = run.result.modes
    idx = [i for i, k in enumerate(m.kinds) if k == kind]
    return m.frequencies[idx], run.estimate.relative_error[idx]


@pytest.fixture(scope="module")
def stepped_free():
    import shaftfem

    return shaftfem.run_bounded(scene(STEPPED))


def test_stepped_shaft_free_free_against_beam_and_rods(stepped_free):
    s = stepped_free.result.scene
    mat = s.material
    bend = timoshenko_profile_hz(4, segments(s), mat.youngs_modulus, mat.poisson_ratio,
                                 mat.density)
    f, _ = by_kind(stepped_free, "bending")
    pairs = f[: 2 * 3].reshape(3, 2)
    # each bending pair is degenerate to the mesh's asymmetry
    assert np.all(np.abs(pairs[:, 1] / pairs[:, 0] - 1) < 2e-3)
    diff = pairs.mean(axis=1) / np.array(bend[:3]) - 1
    assert abs(diff[0]) < 3e-3            # the first mode barely sees the steps
    assert -0.025 < diff[1] < 0 and -0.025 < diff[2] < 0  # the steps: 3D more flexible
    tor = rod_profile_hz(1, segments(s), mat.shear_modulus, mat.density, polar=True)
    t, bound = by_kind(stepped_free, "torsion")
    assert abs(t[0] / tor[0] - 1) < 2e-3
    ax = rod_profile_hz(1, segments(s), mat.youngs_modulus, mat.density, polar=False)
    a, _ = by_kind(stepped_free, "axial")
    assert -6e-3 < a[0] / ax[0] - 1 < 0   # lateral inertia lowers it (Love)


def test_stepped_shaft_on_two_bearings_against_beam():
    import shaftfem

    run = shaftfem.run_bounded(scene(STEPPED + BEARINGS))
    s = run.result.scene
    mat = s.material
    ref = timoshenko_profile_hz(2, segments(s), mat.youngs_modulus, mat.poisson_ratio,
                                mat.density, pins=(0.02, 0.28))
    f, _ = by_kind(run, "bending")
    # a "rigid" seat holds its band's mean radial motion and lets it tilt: the beam's pin
    # at the seat's centre (measured: -0.16 % at mode 1, the steps' flexibility)
    assert abs(f[0] / ref[0] - 1) < 5e-3 and abs(f[1] / f[0] - 1) < 1e-2
    assert -0.025 < f[2] / ref[1] - 1 < 5e-3


def test_tube_torsion_is_ct_over_2l_within_its_bound():
    import shaftfem

    run = shaftfem.run_bounded(scene(TUBE))
    mat = run.result.scene.material
    exact = math.sqrt(mat.shear_modulus / mat.density) / (2 * 0.4)
    t, bound = by_kind(run, "torsion")
    assert t[0] >= exact * (1 - 1e-9)              # conforming: from above
    assert t[0] * (1 - bound[0]) <= exact          # and within its bound
    bend = timoshenko_profile_hz(2, segments(run.result.scene), mat.youngs_modulus,
                                 mat.poisson_ratio, mat.density)
    f, _ = by_kind(run, "bending")
    assert abs(f[0] / bend[0] - 1) < 3e-3 and abs(f[2] / bend[1] - 1) < 6e-3


def test_profile_volume_against_opencascade():
    """The half-section's volume by Pappus (cad.outline) against OpenCASCADE's volume of
    the revolved, filleted and chamfered solid."""
    import tempfile
    from pathlib import Path

    from shaftfem.cad.build import build_solid
    from shaftfem.cad.outline import outline, revolved_volume

    s = scene(STEPPED + "[shaft]\nend_chamfer_mm = 1.0\n").shaft

    with tempfile.TemporaryDirectory() as folder:
        volume, n = build_solid(s, None, Path(folder) / "s.brep")
    assert n == 1
    assert abs(revolved_volume(outline(s)) / volume - 1) < 1e-9


def test_keyway_volume_against_opencascade():
    """The keyway's analytic volume (an integral over its plan) against what
    OpenCASCADE's boolean removed, both ends' forms."""
    import tempfile
    from pathlib import Path

    from shaftfem.cad.build import build_solid
    from shaftfem.cad.outline import keyway_volume, outline, revolved_volume

    for form in ('"rounded"', '"sled"'):
        s = scene(STEPPED + KEYWAY + f"form = {form}\nangle_deg = 30.0\n").shaft
        with tempfile.TemporaryDirectory() as folder:
            volume, _ = build_solid(s, None, Path(folder) / "s.brep")
        removed = revolved_volume(outline(s)) - volume
        k = s.keyways[0]
        assert (k.width, k.depth) == pytest.approx((0.010, 0.005))  # DIN 6885-1, 35 mm
        assert abs(removed / keyway_volume(k, 0.0175) - 1) < 2e-3


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) is not installed")
def test_keyed_stepped_shaft_against_calculix_on_the_same_mesh(tmp_path):
    from shaftfem.fem.assembly import assemble
    from shaftfem.fem.modes import modal_analysis
    from shaftfem.outputs.calculix import read_calculix_eig, write_calculix
    from shaftfem.workflows.pipeline import run_modes

    result = run_modes(scene(STEPPED.replace("element_size_mm = 8.0", "element_size_mm = 10.0")
                             + KEYWAY))
    four = modal_analysis(assemble(result.mesh, result.scene.material, mass_intorder=2))
    write_calculix(result, tmp_path / "shaft.inp")
    p = subprocess.run(["ccx", "-i", "shaft"], cwd=tmp_path, capture_output=True, text=True,
                       timeout=600)
    assert p.returncode == 0, p.stdout[-2000:]
    ccx = read_calculix_eig(tmp_path / "shaft.eig")[6:16]
    assert np.max(np.abs(four.frequencies / ccx - 1)) < 1e-6
    # the keyway splits the first bending pair (3.3 % measured at 10 mm): it takes 15 %
    # of the section's bending stiffness in its plane where mode 1 bends most
    pairs = result.modes.frequencies[[0, 1]]
    assert 1e-2 < pairs[1] / pairs[0] - 1 < 6e-2


BAD = [
    (STEPPED.replace("fillet_mm = 1.0\nchamfer_mm = 0.5\n[[section]]\nlength_mm = 220.0",
                     "fillet_mm = 6.0\nchamfer_mm = 0.5\n[[section]]\nlength_mm = 220.0", 1),
     "section 1: fillet_mm = 6: the fillet and chamfer together"),
    (STEPPED.replace("diameter_mm = 35.0", "diameter_mm = 35.0\nbore_mm = 35.0"),
     "section 2: bore_mm = 35: must be smaller than the section's outer diameter"),
    (STEPPED.replace("length_mm = 220.0\ndiameter_mm = 35.0",
                     "length_mm = 220.0\ndiameter_mm = 35.0\nbore_mm = 28.0"),
     "section 2: bore_mm: sections 1 and 2 do not join"),
    (STEPPED + KEYWAY + "depth_mm = 17.5\n", "keyway 1: depth_mm = 17.5: the keyway is deeper"),
    (STEPPED + KEYWAY.replace("150.0", "45.0"), "must lie within one section"),
    (STEPPED + BEARINGS.replace("20.0", "38.0", 1), "crosses the shoulder at 40 mm"),
    (STEPPED.replace("[[section]]", "[[shaft.section]]"), "write the sections as [[section]]"),
    (STEPPED + "[shaft]\nlength_mm = 300.0\ndiameter_mm = 35.0\n", "give the shaft one way"),
    ('[shaft]\nstep_file = "no_such.step"\n[mesh]\nelement_size_mm = 8.0\n' + MATERIAL,
     "shaft.step_file = 'no_such.step': cannot be read"),
    (STEPPED + '[grooves]\nhands = ["right"]\npitch_mm = 80.0\nwidth_mm = 8.0\ndepth_mm = 3.0\n'
     'grooved_length_mm = 100.0\nstart_mm = 20.0\n', "must lie within one cylindrical section"),
]


@pytest.mark.parametrize("text,message", BAD)
def test_bad_profiles_are_refused_naming_the_key(text, message):
    with pytest.raises(SceneError) as err:
        scene(text)
    assert message in str(err.value), str(err.value)


def test_a_file_that_is_not_step_is_refused(tmp_path):
    (tmp_path / "shaft.step").write_text("solid shaft\nendsolid\n")
    (tmp_path / "s.toml").write_text('[shaft]\nstep_file = "shaft.step"\n[mesh]\n'
                                     'element_size_mm = 8.0\n' + MATERIAL)
    with pytest.raises(SceneError, match="not a STEP file"):
        load_scene(tmp_path / "s.toml")
    out = subprocess.run([sys.executable, "-m", "shaftfem", "modes", str(tmp_path / "s.toml")],
                         capture_output=True, text=True)
    assert out.returncode == 2 and "Traceback" not in out.stderr


EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.mark.slow
def test_a_step_file_from_another_cad_kernel_gives_the_parametric_frequencies():
    """examples/keyed_stepped_shaft.step, written by build123d (tests/data/make_keyed_step.py)
    from cylinders, edge fillets and chamfers and a slot: imported, its frequencies lie
    within the two bounds of the same shaft's parametric scene."""
    import shaftfem
    from shaftfem.workflows import stages

    step, _ = stages.solid(load_scene(EXAMPLES / "step_shaft.toml"))
    assert step.shaft.length == pytest.approx(0.300, abs=1e-9)
    # what the import prints: build123d's own volume of its solid, 249135.62 mm^3
    assert "300 mm long, 249136 mm^3, outer radius 12.5 to 17.5 mm" in step.shaft.step.summary
    a = shaftfem.run_bounded(step)
    b = shaftfem.run_bounded(scene(STEPPED + KEYWAY))
    fa, fb = a.result.modes.frequencies, b.result.modes.frequencies
    allowed = a.estimate.relative_error + b.estimate.relative_error
    assert np.all(np.abs(fa / fb - 1) <= allowed), (fa / fb - 1, allowed)


def test_a_step_file_of_overlapping_solids_is_refused_saying_where(tmp_path, capsys):
    """A sleeve exported over the shaft (two solids sharing volume) is no one body: refused
    at import, exit 2, naming the solids and where they overlap."""
    from shaftfem.cli import main

    # written in a process of its own: OpenCASCADE keeps its STEP unit for the process
    make = ("import gmsh, sys; gmsh.initialize(); gmsh.option.setNumber('General.Terminal', 0);"
            "gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 300, 15);"
            "gmsh.model.occ.addCylinder(0, 0, 100, 0, 0, 50, 25);"
            "gmsh.model.occ.synchronize(); gmsh.write(sys.argv[1]); gmsh.finalize()")
    subprocess.run([sys.executable, "-c", make, str(tmp_path / "sleeve.step")], check=True,
                   capture_output=True)
    (tmp_path / "s.toml").write_text('[shaft]\nstep_file = "sleeve.step"\n[mesh]\n'
                                     'element_size_mm = 8.0\n' + MATERIAL)
    capsys.readouterr()
    assert main(["modes", str(tmp_path / "s.toml"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "solids 1 and 2 overlap" in err and "z 100 to 150 mm" in err, err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1


GROOVED_STEP = (
    "import gmsh, sys; gmsh.initialize(); gmsh.option.setNumber('General.Terminal', 0);"
    "occ = gmsh.model.occ; shaft = occ.addCylinder(0, 0, 0, 0, 0, 300, 15);"
    "ring = occ.addCylinder(0, 0, 100, 0, 0, 2, 20); core = occ.addCylinder(0, 0, 100, 0, 0, 2, 13);"
    "occ.synchronize(); groove, _ = occ.cut([(3, ring)], [(3, core)]);"
    "flat = occ.addBox(-20, 12, 200, 40, 10, 40);"
    "occ.cut([(3, shaft)], groove + [(3, flat)]); occ.synchronize();"
    "gmsh.write(sys.argv[1]); gmsh.finalize()")


@pytest.mark.parametrize("position,under", [(101.0, "13 to 15 mm"), (220.0, "12 to 15 mm")],
                         ids=["circlip groove", "flat"])
def test_a_bearing_seat_over_a_groove_or_a_flat_of_a_step_solid_is_refused(
        tmp_path, capsys, position, under):
    """A STEP shaft with a 2 mm ring groove at 100 mm and a 40 mm flat at 200 mm: a bearing
    seat over either is refused at placement, exit 2, naming the seat and the radii under
    it; one on the plain stretch is placed."""
    from shaftfem.cli import main
    from shaftfem.workflows import stages

    subprocess.run([sys.executable, "-c", GROOVED_STEP, str(tmp_path / "g.step")], check=True,
                   capture_output=True)
    seat = ('[[support]]\nname = "bearing"\nposition_mm = {}\nwidth_mm = 16.0\n'
            'kind = "rigid"\n')
    head = '[shaft]\nstep_file = "g.step"\n[mesh]\nelement_size_mm = 8.0\n' + MATERIAL
    (tmp_path / "bad.toml").write_text(head + seat.format(position))
    capsys.readouterr()
    assert main(["modes", str(tmp_path / "bad.toml"), "-q"]) == 2
    err = capsys.readouterr().err
    assert 'support 1 ("bearing")' in err and f"runs from {under}" in err, err
    (tmp_path / "good.toml").write_text(head + seat.format(50.0))
    placed, shape = stages.solid(load_scene(tmp_path / "good.toml"))
    assert placed.shaft.length == pytest.approx(0.3) and shape.found is not None


def test_a_step_file_is_imported_once_cold_and_never_warm(tmp_path, monkeypatch, capsys):
    """What the import found is kept with the solid: `shaftfem modes` (the bound's coarser
    mesh included) reads the STEP file once on a cold cache and never on a warm one."""
    import shaftfem.cad.step as step
    from shaftfem.cli import main

    monkeypatch.setenv("SHAFTFEM_CACHE", str(tmp_path))
    calls = []
    real = step.import_step
    monkeypatch.setattr(step, "import_step", lambda *a, **k: calls.append(a) or real(*a, **k))
    args = ["modes", str(EXAMPLES / "step_shaft.toml"), "--mesh-size", "16", "-q", "--json"]
    assert main([*args, str(tmp_path / "cold.json")]) == 0
    assert len(calls) == 1
    assert main([*args, str(tmp_path / "warm.json")]) == 0
    assert len(calls) == 1
    cold, warm = (json.loads((tmp_path / f"{w}.json").read_text()) for w in ("cold", "warm"))
    # the warm solve starts from the kept shapes: the same modes to round-off
    assert [m["frequency_hz"] for m in warm["modes"]] == pytest.approx(
        [m["frequency_hz"] for m in cold["modes"]], rel=1e-9)
    assert "300 mm long" in capsys.readouterr().out


@pytest.mark.slow
@pytest.mark.parametrize("text", [STEPPED + KEYWAY, TUBE], ids=["keyed stepped", "tube"])
def test_the_p2_bound_holds_against_order_4_on_the_same_mesh(text):
    """Each P2 frequency's interval [f (1 - bound), f] holds the order-4 frequency of the
    same mesh (a space holding P2's: nearer the solid's own frequencies, from above)."""
    import shaftfem
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    p2 = shaftfem.run_bounded(scene(text))
    p4 = run_modes(with_mesh(p2.result.scene, order=4))
    f, f4 = p2.result.modes.frequencies, p4.modes.frequencies
    bound = p2.estimate.relative_error
    assert np.all(f4 <= f * (1 + 1e-9)), f4 / f - 1
    assert np.all(f4 >= f * (1 - bound)), (f4 / f - 1, bound)


@pytest.mark.slow
def test_the_papers_shaft_through_step_gives_its_frequencies(tmp_path):
    """The STEP that shaftfem writes of the paper's shaft, imported back: the paper's
    frequencies within the two bounds (a different mesh: sizes from curvature, down to
    half the 4 mm edge size, no groove fields)."""
    import shaftfem
    from shaftfem.cad.build import write_solid

    paper = shaftfem.run_bounded(load_scene("paper2018"))
    write_solid(paper.result.shape.brep, paper.result.scene.shaft, [tmp_path / "shaft.step"])
    (tmp_path / "s.toml").write_text(
        '[shaft]\nstep_file = "shaft.step"\n[mesh]\nelement_size_mm = 8.0\n'
        'groove_element_size_mm = 4.0\nedge_element_size_mm = 4.0\n'
        + MATERIAL.replace("210000.0", "211000.0").replace("0.3\n", "0.277\n")
        .replace("7850.0", "7870.0"))
    back = shaftfem.run_bounded(load_scene(tmp_path / "s.toml"))
    assert "545 mm long" in back.result.scene.shaft.step.summary
    fa, fb = back.result.modes.frequencies, paper.result.modes.frequencies
    allowed = back.estimate.relative_error + paper.estimate.relative_error
    assert np.all(np.abs(fa / fb - 1) <= allowed), (fa / fb - 1, allowed)


@pytest.mark.slow
def test_the_tube_on_two_bearings_against_beam():
    import shaftfem

    run = shaftfem.run_bounded(scene(TUBE + BEARINGS.replace("280.0", "380.0")))
    mat = run.result.scene.material
    ref = timoshenko_profile_hz(2, segments(run.result.scene), mat.youngs_modulus,
                                mat.poisson_ratio, mat.density, pins=(0.02, 0.38))
    f, _ = by_kind(run, "bending")
    # pinned at the seats' centres, as on the stepped shaft
    assert abs(f[0] / ref[0] - 1) < 5e-3 and abs(f[2] / ref[1] - 1) < 1e-2


def test_sweeps_reach_every_section_and_keyway():
    """A sweep or calibration names a profile's keys as it names a support's:
    'section[i].key', 'keyway[i].key' (entries from 0), each value checked as in a file."""
    base = SceneText(text=STEPPED + KEYWAY, source="test.toml")
    s = load_scene(base, overrides={"section[1].diameter_mm": 36.0,
                                    "keyway[0].length_mm": 30.0})
    assert s.shaft.profile[1].diameter_start == pytest.approx(0.036)
    assert s.shaft.keyways[0].length == pytest.approx(0.030)
    with pytest.raises(SceneError, match=r"section 2: fillet_mm = 9"):
        load_scene(base, overrides={"section[1].fillet_mm": 9.0})


def test_a_keyway_may_run_into_a_shoulders_fillet_and_its_volume_is_exact():
    """A keyway on the 25 mm section running out into the 4 mm fillet of the step up to
    35 mm (its end 0.2 mm short of the step's face): the cutter reaches above the
    fillet's rise, and what OpenCASCADE removed is the integral over the keyway's plan
    down from the fillet's surface; to the step's face, or past it, it is refused."""
    import tempfile
    from pathlib import Path

    from shaftfem.cad.build import build_solid
    from shaftfem.cad.outline import keyway_volume, outline, revolved_volume, surface_radius

    stepped = STEPPED.replace("fillet_mm = 1.0\nchamfer_mm = 0.5\n[[section]]\nlength_mm = 220.0",
                              "fillet_mm = 4.0\nchamfer_mm = 0.5\n[[section]]\nlength_mm = 220.0", 1)
    into = "[[keyway]]\nposition_mm = 25.0\nlength_mm = 29.6\n"   # 10.2 to 39.8 mm
    s = scene(stepped + into).shaft
    z = np.array([30.0, 39.5, 39.8]) * 1e-3
    # the fillet (r 4 mm, its centre at z 36, r 16.5 mm) rises above the 12.5 mm section
    assert surface_radius(s, z) == pytest.approx(
        [0.0125, 0.0165 - math.sqrt(16e-6 - 0.0035**2), 0.0165 - math.sqrt(16e-6 - 0.0038**2)])
    with tempfile.TemporaryDirectory() as folder:
        volume, n = build_solid(s, None, Path(folder) / "s.brep")
    assert n == 1
    removed = revolved_volume(outline(s)) - volume
    k = s.keyways[0]
    flat = keyway_volume(k, 0.0125)
    exact = keyway_volume(k, 0.0125, surface=lambda z: surface_radius(s, z))
    assert exact > flat * 1.01         # the fillet's rise is cut too (1.5 %)
    assert abs(removed / exact - 1) < 2e-3
    for bad in ("length_mm = 30.0\n", "length_mm = 31.0\n"):   # to the step; past it
        with pytest.raises(SceneError) as err:
            scene(stepped + into.replace("length_mm = 29.6\n", bad))
        assert "may run into a fillet but not to its step" in str(err.value)


def test_a_keyed_grooved_shafts_removed_volume_is_set_against_grooves_and_keyways():
    """The paper's shaft with its keyway: what the CAD cut (grooves and keyway) is set
    against the analytic volume of both, as the build's check does, so the record and
    the report print two numbers that agree (the grooves' alone were printed beside
    both, 4 % apart)."""
    import tempfile

    from shaftfem.cad.outline import keyway_volume
    from shaftfem.cad.profile import groove_volume
    from shaftfem.cad.solid import make_shape

    s = load_scene("paper2018_keyed")
    with tempfile.TemporaryDirectory() as folder:
        shape = make_shape(s.shaft, s.grooves, Path(folder) / "s.brep")
    k = s.shaft.keyways[0]
    both = groove_volume(s.grooves, 0.016) + keyway_volume(k, 0.016)
    assert shape.groove_volume_analytic == pytest.approx(both, rel=1e-9)
    assert abs(shape.groove_volume_error) < 5e-3


@pytest.mark.parametrize("more", [{}, {"grooves.hands": ["right"]},
                                  {"grooves.root_radius_mm": 0.0}],
                         ids=["crossing", "one hand", "sharp root"])
def test_grooves_running_out_are_built_as_their_analytic_volume(tmp_path, more):
    """Grooves whose floors rise out over 8 mm beyond the grooved zone: the solid is one
    body and removes what the analytic runouts remove (a wrong lift or a runout lost in
    the booleans moves it by 2 % of the whole or more: the runouts hold 2.5 % of it). A
    sharp-cornered groove's tool reaches 0.5 mm below its floor: its runout rises from
    there (it first rose 0.5 mm short, and cut 2.2 % too much)."""
    from dataclasses import replace

    from shaftfem.cad.profile import groove_volume
    from shaftfem.cad.solid import make_shape

    s = load_scene("paper2018", overrides={"shaft.length_mm": 120.0,
                                           "grooves.grooved_length_mm": 80.0,
                                           "grooves.runout_mm": 8.0, **more})
    g = s.grooves
    assert g.cut == pytest.approx((0.012, 0.108))
    shape = make_shape(s.shaft, g, tmp_path / "s.brep")
    runouts = groove_volume(g, 0.016) - groove_volume(replace(g, runout=0.0), 0.016)
    assert runouts > 0.02 * shape.groove_volume_analytic
    assert abs(shape.groove_volume_error) < 1e-3
    assert shape.n_volumes == 4          # two plain ends, the two end cells


def test_a_runout_needs_room_and_no_keyway_over_it():
    """A runout beyond the shaft's end, or over a keyway, is refused naming the key and
    the span."""
    with pytest.raises(SceneError) as err:
        load_scene("paper2018", overrides={"grooves.runout_mm": 93.0})
    assert "runout_mm" in str(err.value) and "-0.5 to 92.5" in str(err.value)
    with pytest.raises(SceneError) as err:   # the gear's keyway is at 46-64 mm
        load_scene("paper2018_installed", overrides={"grooves.runout_mm": 40.0})
    assert "runout_mm" in str(err.value) and "a keyway lies over the grooved zone or its " \
        "runouts" in str(err.value)
