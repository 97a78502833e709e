"""Will the shaft hold (`shaftfem strength`): a plain round bar's stresses and stress
gradients against the closed forms of bending, torsion and tension, its slope at the
seats against the beam's, the FKM factors against the guideline's formulas evaluated
here by hand, a shoulder fillet's stress concentration against Peterson's chart, and the
errors of a duty that cannot stand."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from shaftfem.errors import SceneError
from shaftfem.scene.load import load_scene
from shaftfem.workflows import strength as ws

E, NU = 210e9, 0.3
D = 0.032
STEEL = {"name": "42CrMo4", "youngs_modulus_mpa": E / 1e6, "poisson_ratio": NU,
         "density_kg_m3": 7850.0}
# the right seat's spring is stiff enough to be a rigid hold (1e9 N/mm) and locates axially
SEATS = [{"name": "left", "position_mm": 10.0, "width_mm": 16.0, "kind": "rigid-radial"},
         {"name": "right", "position_mm": 390.0, "width_mm": 16.0, "kind": "springs",
          "radial_stiffness_n_per_mm": 1e9, "axial_stiffness_n_per_mm": 1e9}]


GEAR = {"name": "gear", "position_mm": 200.0, "width_mm": 40.0, "mass_kg": 0.0,
        "polar_inertia_kg_m2": 0.0, "diametral_inertia_kg_m2": 0.0}


def bar(**tables) -> dict:
    """A 32 mm bar 400 mm long on seats centred at 10 and 390 mm, without weight."""
    return {"name": "bar", "shaft": {"length_mm": 400.0, "diameter_mm": D * 1e3},
            "material": STEEL, "static": {"gravity_m_s2": 0.0},
            "mesh": {"element_size_mm": 6.0}, "support": SEATS, **tables}


# The closed-form bar: 240 mm on seats centred at 10 and 230 mm, the load at 120 mm, the
# torque between 40 and 200 mm, on a 3 mm mesh (the flexure's cubic field within 0.5
# %). It is read at 75 and 165 mm, more than a diameter from the load's and the seats'
# bands; a torque enters as the exact linear shear (fem.stress.band_loads), so its
# stations need no such distance.
SHORT, LOAD, READ = 240.0, 120.0, (75.0, 165.0)
# the duty on the 400 mm bar: the load at mid-span, the torque between 60 and 340 mm
DUTY = dict(force=[{"name": "load", "position_mm": 200.0, "fy_n": -2000.0, "fz_n": 5000.0}],
            torque=[{"name": "in", "position_mm": 60.0, "torque_nm": 100.0},
                    {"name": "out", "position_mm": 340.0}],
            strength={"speed_rpm": 1000.0})


def beam_moment(z: np.ndarray | float) -> np.ndarray:
    """The standing load's bending moment (N m) at z (m): 1000 N at each seat's centre."""
    z = np.asarray(z)
    return 1000.0 * np.where(z < LOAD * 1e-3, z - 0.010, (SHORT - 10.0) * 1e-3 - z)


@pytest.fixture(scope="module")
def field():
    data = bar(force=[{**DUTY["force"][0], "position_mm": LOAD}],
               torque=[{**DUTY["torque"][0], "position_mm": 40.0},
                       {**DUTY["torque"][1], "position_mm": 200.0}],
               strength=DUTY["strength"])
    data["shaft"] = {**data["shaft"], "length_mm": SHORT}
    data["support"] = [SEATS[0], {**SEATS[1], "position_mm": SHORT - 10.0}]
    scene = load_scene({**data, "mesh": {"element_size_mm": 3.0}})
    return scene, ws._solve(scene, ws.RunOptions())[0]


def ring(field, z_mm: float):
    """The surface points of the mantle within 3 mm of z."""
    f = field
    r = np.hypot(f.points[:, 0], f.points[:, 1])
    return np.flatnonzero((np.abs(f.points[:, 2] - z_mm * 1e-3) < 3e-3) & (r > 0.999 * D / 2))


def test_a_plain_bar_under_rotating_bending_torsion_and_tension_has_the_closed_forms(field):
    scene, f = field
    W = math.pi * D**3 / 32          # section modulus, m^3
    tau = 100.0 / (2 * W)            # torsion between 40 and 200 mm
    sigma_n = -5000.0 / (math.pi * D**2 / 4)   # compression from the load to the locating seat
    for z in READ:
        idx = ring(f, z)
        # the moment at each point's own z
        assert np.allclose(f.amplitude[idx], beam_moment(f.points[idx, 2]) / W, rtol=5e-3)
        mean = math.sqrt(3 * tau**2 + (sigma_n**2 if z > LOAD else 0.0))
        assert np.allclose(np.abs(f.mean[idx]), mean, rtol=5e-3)
        # tension after the load is compression here: FKM's signed mean is negative
        assert np.all(np.sign(f.mean[idx]) == (-1 if z > LOAD else 1))


def test_the_relative_stress_gradient_of_a_round_bar_is_two_over_d(field):
    scene, f = field
    for i in ring(f, READ[0])[:5]:
        assert ws._gradient(f, int(i), True) == pytest.approx(2 / D, rel=0.02)
    # torsion alone, standing: the peak is the torsion's, its gradient 2/d too (the
    # duty's torque case alone, by linearity the bar under that torque standing)
    from dataclasses import replace

    from shaftfem.fem.stress import CASES, cycle

    torque = np.array([c == "T" for c in CASES], dtype=float)[:, None, None, None]
    stress = f.stress * torque
    _, _, peak = cycle(stress, False)
    g = replace(f, stress=stress, all_stress=f.all_stress * torque, peak=peak)
    for i in ring(g, LOAD)[:5]:
        assert g.peak[i] == pytest.approx(math.sqrt(3) * 100.0 * 16 / (math.pi * D**3),
                                          rel=5e-3)
        assert ws._gradient(g, int(i), False) == pytest.approx(2 / D, rel=0.02)


def test_what_a_section_carries_is_the_beams_moment_torque_and_axial_force(field):
    """The resultants of the solid's stress through a cross-section (the nominal stress
    of a notch factor) against the beam's statics: the standing load's moment
    (reactions 1000 N at 10 and 390 mm), the torque between 60 and 340 mm, the axial
    force from the load to the locating seat."""
    from shaftfem.fem.section import resultants

    scene, f = field
    for z in (r * 1e-3 for r in READ):
        c = resultants(f.read, f.all_stress, z, D / 2)
        moment = float(beam_moment(z))
        # case A is the standing load (fy -2000 N), case B the same turned a right angle
        assert math.hypot(c[0, 1], c[0, 2]) == pytest.approx(moment, rel=5e-3)
        assert math.hypot(c[1, 1], c[1, 2]) == pytest.approx(moment, rel=5e-3)
        assert abs(c[2, 3]) == pytest.approx(100.0, rel=5e-3)
        assert abs(c[3, 0]) == pytest.approx(5000.0 if z > LOAD * 1e-3 else 0.0, abs=25.0)


def test_a_loads_resultants_are_exact_on_a_mesh_not_symmetric_about_the_axis():
    """A force at a band's middle on the axis, a torque and a bending moment spread over
    the band's elements of gmsh's unstructured bar (never quite symmetric about the
    axis): the nodal loads' sum is the force and their moment about the load's point is
    (m_x, m_y, T), to round-off (spread as F / V alone, a 20 kN pull bent a 30 mm bar by
    2.6 N m, and a torque pushed it sideways)."""
    import gmsh
    from skfem import Basis, ElementTetP2, MeshTet

    from shaftfem.fem.stress import Band, band_loads

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 0.3, 0.015)
        gmsh.model.occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.008)
        gmsh.model.mesh.generate(3)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        _, _, conn = gmsh.model.mesh.getElements(3)
    finally:
        gmsh.finalize()
    index = np.zeros(int(tags.max()) + 1, dtype=int)
    index[tags.astype(int)] = np.arange(tags.size)
    mesh = MeshTet(xyz.reshape(-1, 3).T.copy(), index[conn[0].astype(int)].reshape(-1, 4).T.copy())
    element = ElementTetP2()
    where = Basis(mesh, element).doflocs          # (3, nodes)
    F, T, M = np.array([300.0, -200.0, 20000.0]), 150.0, (12.0, -7.0)
    nodal = band_loads(mesh, element, Band(0.0325, 0.0475), F, T, 3 * where.shape[1], M)
    f = nodal.reshape(-1, 3)
    assert np.allclose(f.sum(axis=0), F, rtol=0, atol=1e-9 * 20000.0)
    arm = where.T - np.array([0.0, 0.0, 0.040])
    assert np.allclose(np.cross(arm, f).sum(axis=0), [12.0, -7.0, 150.0], rtol=0, atol=1e-9 * 150)


def test_a_helical_gears_force_comes_from_its_geometry_and_its_torque():
    """A helical gear (d 100 mm, alpha_n 20 deg, beta 15 deg, meshing above, +y) passing
    100 N m out of the shaft: F_t = 2 T / d = 2000 N, F_r = F_t tan(alpha_n) / cos(beta)
    = 753.6 N, F_a = F_t tan(beta) = 535.9 N, and the thrust at the pitch radius bends
    the shaft by F_a d / 2 = 26.8 N m: the moment the solid's sections carry jumps by
    that across the gear (the beam's lines either side, extrapolated to it), the x
    plane's does not, and the locating seat takes the thrust."""
    from shaftfem.fem.section import resultants

    data = bar(attachment=[GEAR],
               force=[{"part": "gear", "gear_pitch_diameter_mm": 100.0,
                       "gear_helix_angle_deg": 15.0}],
               torque=[{"name": "coupling", "position_mm": 60.0, "torque_nm": 100.0},
                       {"part": "gear"}], strength={"speed_rpm": 1000.0})
    scene = load_scene(data)
    (f,) = scene.forces
    ft, fr, fa = 2000.0, 2000.0 * math.tan(math.radians(20)) / math.cos(math.radians(15)), \
        2000.0 * math.tan(math.radians(15))
    # power leaves through the gear: the teeth push it along +x (against its turning);
    # the radial force points to the axis; the thrust to -z (beta > 0, power leaving)
    assert (f.fx, f.fy, f.fz) == pytest.approx((ft, -fr, -fa))
    assert (f.mx, f.my) == pytest.approx((0.05 * -fa, 0.0), abs=1e-9)
    field = ws._solve(scene, ws.RunOptions())[0]

    def carried(z):
        return resultants(field.read, field.all_stress, z, D / 2)[0]     # case A

    def at_gear(z1, z2, k):
        m1, m2 = carried(z1)[k], carried(z2)[k]
        return m1 + (m2 - m1) * (0.200 - z1) / (z2 - z1)

    jump_x = at_gear(0.120, 0.150, 1) - at_gear(0.280, 0.250, 1)
    jump_y = at_gear(0.120, 0.150, 2) - at_gear(0.280, 0.250, 2)
    assert abs(jump_x) == pytest.approx(0.05 * fa, rel=0.02)
    assert abs(jump_y) < 0.02 * 0.05 * fa
    axial = resultants(field.read, field.all_stress, 0.300, D / 2)[3, 0]     # case Z
    assert abs(axial) == pytest.approx(fa, rel=0.01)


def test_strength_finds_the_bending_peak_beside_the_load_and_the_seat_slope(tmp_path):
    import subprocess
    import sys

    out, path = tmp_path / "s.json", tmp_path / "bar.toml"
    load_scene(bar(**DUTY)).to_toml(path)
    run = subprocess.run([sys.executable, "-m", "shaftfem", "strength", str(path), "--json",
                          str(out), "-q", "--out", str(tmp_path / "files")],
                         capture_output=True, text=True, timeout=600)
    data = json.loads(out.read_text())
    # the right seat turns by F L^2 / (16 E I) = 1.67 mrad, over the 1 mrad a ball takes:
    # the check fails, exit 1
    I = math.pi * D**4 / 64
    right = next(s for s in data["seats"] if s["name"] == "right")
    assert right["slope_mrad"] == pytest.approx(2000 * 0.38**2 / (16 * E * I) * 1e3, rel=0.01)
    assert not right["ok"] and not data["deflection_ok"] and run.returncode == 1
    assert "deflection FAILS" in run.stdout and "EXCEEDED" in run.stdout
    # the worst spots sit at the load band's edges, on the plain surface, not sharp
    worst = data["hot_spots"][0]
    assert abs(worst["z_mm"] - 200.0) < 20.0, worst
    assert worst["feature"] == "plain surface" and worst["converging"], worst
    # strength.vtp for ParaView: the surface's amplitude against the beam's M / W, the
    # utilisation NaN in the seats' and the load's bands, the worst spot's as judged
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(str(tmp_path / "files" / "strength.vtp"))
    reader.Update()
    surface = reader.GetOutput()
    points = vtk_to_numpy(surface.GetPoints().GetData())
    arrays = {name: vtk_to_numpy(surface.GetPointData().GetArray(name)) for name in (
        "amplitude_MPa", "fatigue_utilisation_a_BK", "yield_utilisation_a_SK")}
    r = np.hypot(points[:, 0], points[:, 1])
    ring = (np.abs(points[:, 2] - 0.100) < 1e-3) & (r > 0.999 * D / 2)
    moment = 1000.0 * (points[ring, 2] - 0.010)
    assert np.allclose(arrays["amplitude_MPa"][ring], moment / (math.pi * D**3 / 32) / 1e6,
                       rtol=0.02)
    assert np.isnan(arrays["fatigue_utilisation_a_BK"][np.abs(points[:, 2] - 0.010) < 5e-3]).all()
    spot = np.argmin(np.linalg.norm(points - [worst["radius_mm"] * 1e-3 * math.cos(
        math.radians(worst["angle_deg"])), worst["radius_mm"] * 1e-3 * math.sin(
        math.radians(worst["angle_deg"])), worst["z_mm"] * 1e-3], axis=1))
    assert arrays["fatigue_utilisation_a_BK"][spot] == pytest.approx(
        worst["fkm"]["fatigue_utilisation"], rel=1e-6)
    assert surface.GetNumberOfCells() > 1000


def test_design_reports_the_strength_beside_the_modes(tmp_path):
    """`design` of a scene with a duty: the strength verdict at the top of both reports
    (the bar's seat slope fails: exit 1), the section with its tables, strength.vtp and
    strength.json among the published files."""
    import subprocess
    import sys

    path = tmp_path / "bar.toml"
    load_scene(bar(**DUTY)).to_toml(path)
    out = tmp_path / "design"
    run = subprocess.run([sys.executable, "-m", "shaftfem", "design", str(path), "--out",
                          str(out), "-q", "--no-estimate"], capture_output=True, text=True,
                         timeout=900)
    assert run.returncode == 1, run.stdout[-2000:] + run.stderr[-2000:]
    md, page = (out / "report.md").read_text(), (out / "report.html").read_text()
    top = md.split("## Shaft")[0]
    assert "**STRENGTH: FAIL** - fatigue ok, yield ok, deflection FAILS" in top
    assert "STRENGTH: FAIL - fatigue ok, yield ok, deflection FAILS" in page.split(
        "Mode shapes")[0]
    assert '<section id="strength">' in page and "EXCEEDED" in page
    manifest = json.loads((out / "design.manifest.json").read_text())
    assert {"strength.vtp", "strength.json", "hot_spots.png"} <= set(manifest["files"])
    json.loads((out / "strength.json").read_text())      # valid JSON, no Infinity


def test_a_warm_run_reads_its_solved_meshes_from_the_cache(monkeypatch):
    """Each mesh's solved duty is kept: the same scene again solves nothing, and gives
    the same hot spots."""
    scene = load_scene(bar(**DUTY))
    first = ws.run_strength(scene)

    def solve_again(*args, **kwargs):
        raise AssertionError("a warm run solved a mesh again")

    monkeypatch.setattr(ws, "_solved", solve_again)
    again = ws.run_strength(scene)
    assert [(s.z, s.amplitude, s.bound) for s in again.spots] == [
        (s.z, s.amplitude, s.bound) for s in first.spots]
    assert again.dofs == first.dofs


def test_a_damaged_solved_mesh_in_the_cache_is_discarded_and_solved_again(monkeypatch,
                                                                         tmp_path):
    """A kept solved duty whose file is damaged is said to be so, removed and solved
    again: the hot spots come out as from a cold run."""
    from shaftfem.store import CacheWarning, cache_dir

    monkeypatch.setenv("SHAFTFEM_CACHE", str(tmp_path))   # no other test's entries
    monkeypatch.setattr(ws, "MAX_REFINEMENTS", 0)           # two meshes are enough here
    scene = load_scene(bar(**DUTY))
    first = ws.run_strength(scene)
    kept = sorted((cache_dir() / "strength" / "fields").glob("*.npz"),
                  key=lambda p: p.stat().st_mtime)[-1]
    kept.write_bytes(kept.read_bytes()[:1000])
    with pytest.warns(CacheWarning, match="damaged"):
        again = ws.run_strength(scene)
    assert [(s.z, s.amplitude) for s in again.spots] == [(s.z, s.amplitude)
                                                          for s in first.spots]


def test_a_refined_mesh_the_mesher_spoils_stops_the_refinement_and_says_so(monkeypatch):
    """A refinement round whose mesh fails the Jacobian guard (it happens with gmsh's
    size fields) ends the refinement: the spots keep the last mesh's values and bounds,
    the reader is told why, and nothing is half done."""
    from shaftfem.errors import MeshError
    from shaftfem.outputs.tables import strength_text

    scene = load_scene(bar(**{**DUTY, "strength": {"speed_rpm": 1000.0,
                                                   "target_error_percent": 0.1}}))

    def spoiled(*args, **kwargs):
        raise MeshError("the mesh has an inverted or degenerate element")

    monkeypatch.setattr(ws, "_remeshed", spoiled)
    result = ws.run_strength(scene)
    assert len(result.dofs) == 2 and result.spots and not result.bounded
    assert result.notes and "inverted" in result.notes[0]
    assert result.notes[0] in strength_text(result)


def test_fkm_factors_are_the_guidelines_formulas():
    from shaftfem.checks.fkm import assess
    from shaftfem.scene.model import Strength

    st = Strength(speed=10.0, tensile_strength=900e6, yield_strength=700e6,
                  strength_diameter=0.016, roughness=10e-6, fatigue_safety=1.5,
                  yield_safety=1.5, peak_factor=2.0, target_error=0.02)
    d, G = 0.040, 800.0                      # 40 mm, G = 0.8 / mm
    a = assess(120e6, 60e6, 200e6, G, d, st)
    # FKM 2012 by hand: size factor for quenched and tempered steel (a_d,m 0.3, a_d,p 0.4)
    kdm = (1 - 0.7686 * 0.3 * math.log10(40 / 7.5)) / (1 - 0.7686 * 0.3 * math.log10(16 / 7.5))
    kdp = (1 - 0.7686 * 0.4 * math.log10(40 / 7.5)) / (1 - 0.7686 * 0.4 * math.log10(16 / 7.5))
    rm, rp = 900 * kdm, 700 * kdp
    assert a.tensile_strength == pytest.approx(rm) and a.yield_strength == pytest.approx(rp)
    sw = 0.45 * rm                                              # f_W,sigma of steel
    n = 1 + math.sqrt(0.8) * 10 ** -(0.5 + rm / 2700)          # Stieler, 0.1 < G <= 1
    kr = 1 - 0.22 * math.log10(10) * math.log10(2 * rm / 400)  # a_R 0.22, R_m,N,min 400
    kwk = (1 / n) * (1 + (1 / 2.0) * (1 / kr - 1))              # K_f~ = 2 for steel
    m = 0.35e-3 * rm - 0.1                                      # M_sigma
    kak = 1 / (1 + m * 60 / 120)                                # F2, R = -1/3 (range II)
    sak = kak * sw / kwk
    assert (a.support, a.roughness, a.design, a.mean_stress) == pytest.approx(
        (n, kr, kwk, kak), rel=1e-9)
    assert a.fatigue_utilisation == pytest.approx(120 * 1.5 / sak, rel=1e-9)
    assert a.yield_utilisation == pytest.approx(200 * 2.0 * 1.5 / rp, rel=1e-9)


def test_fkm_reproduces_a_published_worked_example():
    """IMA Dresden's FKM guideline training example (chapter 4, local stresses): a
    150 mm steel shaft, R_m 473 MPa, R_z 25 um, G = 0.172 / mm (Stieler), sigma_a
    94.7 MPa, sigma_m 5.2 MPa. Its published results, as transcribed in pyLife's test
    data (boschresearch/pylife, tests/strength/fkm_linear/, example_IMA_FKM_training):
    sigma_W,zd 213, K_R 0.885, n 1.088, K_WK 0.979, sigma_WK 218 (rounded), K_AK 0.996,
    sigma_AK 216 MPa."""
    from shaftfem.checks.fkm import assess
    from shaftfem.scene.model import Strength

    # R_m is the component's own (the blank is the shaft: no size factor)
    st = Strength(speed=10.0, tensile_strength=473e6, yield_strength=300e6,
                  strength_diameter=0.150, roughness=25e-6, fatigue_safety=1.0,
                  yield_safety=1.0, peak_factor=1.0, target_error=0.02)
    a = assess(94.7e6, 5.2e6, 99.9e6, 0.172e3, 0.150, st)
    assert round(a.reversed_strength) == 213
    assert round(a.roughness, 3) == 0.885 and round(a.support, 3) == 1.088
    assert round(a.design, 3) == 0.979 and round(a.mean_stress, 3) == 0.996
    assert abs(a.reversed_strength / a.design - 218) < 1.0     # 217.4 unrounded
    assert abs(a.amplitude_strength - 216) < 1.0      # 216.6 unrounded
    assert a.fatigue_utilisation == pytest.approx(94.7 / 216.6, rel=1e-3)


@pytest.mark.parametrize("tables, says", [
    (dict(torque=[{"position_mm": 60.0, "torque_nm": 100.0},
                  {"position_mm": 340.0, "torque_nm": -90.0}], strength={}),
     "a torque with nowhere to go"),
    (dict(torque=[{"position_mm": 60.0}, {"position_mm": 340.0}], strength={}),
     "only one torque may leave out"),
    (dict(torque=[{"position_mm": 60.0, "power_kw": 1.0}, {"position_mm": 340.0}],
          strength={}), "a power needs the speed"),
    (dict(material={**STEEL, "name": "unobtainium"}, strength={}),
     "tensile_strength_mpa: missing"),
    (dict(strength={"tensile_strength_mpa": 500.0, "yield_strength_mpa": 600.0}),
     "must be below the tensile strength"),
    (dict(strength={"roughness_rz_um": 500.0}), "roughness_rz_um"),
    (dict(attachment=[GEAR], force=[{"part": "gear", "gear_pitch_diameter_mm": 100.0,
                                     "fy_n": 10.0}]), "force 1: fy_n: a gear's force comes from"),
    (dict(force=[{"position_mm": 200.0, "gear_pitch_diameter_mm": 100.0}]),
     "a gear is a part: give `part`"),
    (dict(attachment=[GEAR], force=[{"part": "gear", "gear_pitch_diameter_mm": 100.0}]),
     "needs one \\[\\[torque\\]\\] on the same part"),
    (dict(attachment=[GEAR], force=[{"part": "gear", "gear_pitch_diameter_mm": 100.0,
                                     "gear_helix_angle_deg": 50.0}]), "gear_helix_angle_deg"),
    (dict(force=[{"position_mm": 100.0, "travel_to_mm": 450.0, "fy_n": 10.0}]),
     "travel_to_mm = 450: must lie on the shaft"),
    (dict(attachment=[GEAR], force=[{"part": "gear", "travel_to_mm": 300.0, "fy_n": 10.0}]),
     "a part's load stays at its part"),
    (dict(force=[{"position_mm": 100.0, "travel_to_mm": 100.0, "fy_n": 10.0}]),
     "leave travel_to_mm out"),
    (dict(strength={"travel_positions": 1}), "travel_positions"),
])
def test_a_duty_that_cannot_stand_is_refused_by_key(tables, says):
    with pytest.raises(SceneError, match=says):
        load_scene(bar(**tables))


def test_an_axial_force_with_no_axial_hold_is_refused():
    data = bar(force=[{"position_mm": 200.0, "fz_n": 1000.0}], strength={})
    data["support"] = [dict(s, kind="rigid-radial") for s in SEATS]
    for s in data["support"]:
        s.pop("radial_stiffness_n_per_mm", None)
        s.pop("axial_stiffness_n_per_mm", None)
    with pytest.raises(SceneError, match="the axial loads push the shaft"):
        ws.run_strength(load_scene(data))


def test_a_shoulder_fillets_stress_concentration_is_petersons():
    """D/d = 1.5, r/d = 3/32 in bending: Peterson's chart as Pilkey fits it (Peterson's
    Stress Concentration Factors, chart 3.10; h/r = 2.67: 2 <= h/r <= 20) gives
    K_t = 1.78; the FE's largest principal stress over the nominal 32 M / (pi d^3),
    within the chart's scatter (about 7 %)."""
    data = {"name": "fillet", "material": STEEL, "static": {"gravity_m_s2": 0.0},
            "section": [{"length_mm": 150.0, "diameter_mm": 32.0, "fillet_mm": 3.0},
                        {"length_mm": 150.0, "diameter_mm": 48.0}],
            "mesh": {"element_size_mm": 6.0, "groove_element_size_mm": 1.0,
                     "edge_element_size_mm": 1.0},
            "support": [dict(s, position_mm=z, kind="springs", radial_stiffness_n_per_mm=1e9)
                        for s, z in zip(SEATS, (10.0, 290.0))],
            "force": [{"position_mm": 220.0, "fy_n": -2000.0}], "strength": {}}
    for s in data["support"]:
        s.pop("axial_stiffness_n_per_mm", None)
    f = ws._solve(load_scene(data), ws.RunOptions())[0]
    # the standing load's own stress (case A), largest principal, at the fillet
    near = (np.abs(f.points[:, 2] - 0.1485) < 2.5e-3)
    principal = np.linalg.eigvalsh(f.stress[0][near]).max(axis=1)
    k = int(np.argmax(principal))
    z = f.points[near][k, 2]
    nominal = 500.0 * (z - 0.010) * 32 / (math.pi * 0.032**3)
    h_r, two_h_D = 8 / 3, 16 / 48
    c1 = 1.232 + 0.832 * math.sqrt(h_r) - 0.008 * h_r
    c2 = -3.813 + 0.968 * math.sqrt(h_r) - 0.260 * h_r
    c3 = 7.423 - 4.868 * math.sqrt(h_r) + 0.869 * h_r
    c4 = -3.839 + 3.070 * math.sqrt(h_r) - 0.600 * h_r
    kt = c1 + c2 * two_h_D + c3 * two_h_D**2 + c4 * two_h_D**3
    assert principal[k] / nominal == pytest.approx(kt, rel=0.07)


def sharp_shoulder(fillet_mm: float) -> dict:
    """A 32/48 mm shoulder in bending, its fillet `fillet_mm` (0: a sharp corner)."""
    data = {"name": "shoulder", "material": STEEL, "static": {"gravity_m_s2": 0.0},
            "section": [{"length_mm": 150.0, "diameter_mm": 32.0, "fillet_mm": fillet_mm},
                        {"length_mm": 150.0, "diameter_mm": 48.0}],
            "mesh": {"element_size_mm": 8.0, "groove_element_size_mm": 2.0,
                     "edge_element_size_mm": 2.0},
            "support": [dict(s, position_mm=z, kind="springs", radial_stiffness_n_per_mm=1e9)
                        for s, z in zip(SEATS, (10.0, 290.0))],
            "force": [{"position_mm": 220.0, "fy_n": -2000.0}],
            "strength": {"speed_rpm": 1000.0}}
    for s in data["support"]:
        s.pop("axial_stiffness_n_per_mm", None)
    return data


def test_a_spot_anywhere_on_a_large_fillet_is_the_shoulders():
    """A 64/32 mm step with an r 5 mm fillet: the fillet spans the 5 mm beside the step's
    face, on the smaller section, and its torsion peak lies near its far tangent (4.1 mm
    from the face, more than a quarter of the 16 mm radius). A spot anywhere on the
    fillet is the shoulder's; one a radius away on the plain mantle is not."""
    data = sharp_shoulder(5.0)
    data["section"][1]["diameter_mm"] = 64.0
    scene = load_scene(data)
    face = scene.shaft.section_bounds()[0][1]
    for off, what in ((-4.1e-3, "shoulder at 150 mm"), (-1.0e-3, "shoulder at 150 mm"),
                      (-16e-3, "plain surface")):
        assert ws._feature(scene, np.array([0.016, 0.0, face + off]), 0.016)[0] == what


@pytest.mark.slow
def test_a_sharp_corner_is_reported_as_such_not_given_a_number():
    """A shoulder without a fillet: its elastic stress has no limit, so refining around
    it keeps raising it; the spot is a sharp edge, the check does not pass on it."""
    result = ws.run_strength(load_scene(sharp_shoulder(0.0)))
    worst = result.spots[0]
    assert abs(worst.z - 0.150) < 3e-3 and not worst.converging
    assert result.sharp and not result.ok and len(result.dofs) >= 3


def test_a_keyed_shaft_lists_one_spot_on_a_shoulders_circle_away_from_its_keyway():
    """A keyed shaft is not of revolution, but about its shoulder, far from the keyway,
    it is: the rotating bending's cycle is the same all round the fillet's circle, one
    hot spot there (not one at every vertex round it)."""
    from shaftfem.workflows.pipeline import with_mesh

    data = sharp_shoulder(3.0)
    data["keyway"] = [{"position_mm": 60.0, "length_mm": 30.0, "width_mm": 8.0,
                       "depth_mm": 4.0}]
    scene = load_scene(data)
    fine = ws._solve(scene, ws.RunOptions())[0]
    coarse = ws._solve(with_mesh(scene, scene.mesh.size * 1e3 * ws.COARSER), ws.RunOptions())[0]
    spots = ws._spots(scene, fine, coarse, None)
    assert not scene.axisymmetric and spots[0].feature.startswith("shoulder")
    assert len([s for s in spots if abs(s.z - 0.1485) < 4e-3]) == 1, [
        (round(s.z * 1e3, 1), round(math.degrees(s.angle))) for s in spots]


def test_a_keyed_parts_torque_enters_through_its_key_and_its_keyway_is_judged():
    """A coupling given by its position at a keyway's middle (10 x 5 mm, 40 mm long, 0.8
    mm corners) passes 100 N m into the bar: the key's pressure on the flank it drives,
    and the bore of the hub taking its net force, add up to the torque and nothing else
    (the nodal loads' sum and moment); the bar beyond carries that torque (its sections),
    at the closed form's torsion stress; the keyway's floor, corners and ends under the
    hub are judged on the side the key does not drive, the half it drives (its flank, the
    corner below it: the contact's stress) is not."""
    from shaftfem.fem.assembly import _element, assemble
    from shaftfem.fem.section import resultants
    from shaftfem.fem.stress import Band, key_bearings, key_loads
    from shaftfem.workflows.pipeline import built

    T = 100.0
    data = bar(keyway=[{"position_mm": 60.0, "length_mm": 40.0, "width_mm": 10.0,
                        "depth_mm": 5.0, "corner_radius_mm": 0.8}],
               torque=[{"name": "coupling", "position_mm": 60.0, "torque_nm": T},
                       {"name": "out", "position_mm": 340.0}],
               strength={"speed_rpm": 1000.0})
    data["mesh"] = {"element_size_mm": 5.0, "groove_element_size_mm": 1.5,
                    "edge_element_size_mm": 1.5}
    scene = load_scene(data)
    (key,) = key_bearings(scene)
    # a positive torque turns the shaft towards +y at a keyway on +x
    assert key.side == 1.0 and key.torque == T and (key.z0, key.z1) == pytest.approx((0.045, 0.075))
    placed, _, mesh = built(scene, ws.RunOptions())
    system = assemble(mesh, placed.material)
    skmesh = mesh.to_skfem()
    from skfem import Basis

    element = _element(system.order)
    where = Basis(skmesh, element).doflocs
    nodal = key_loads(skmesh, element, key, Band(0.053, 0.067), 3 * where.shape[1])
    f = nodal.reshape(-1, 3)
    assert np.allclose(f.sum(axis=0), 0.0, atol=1e-9 * T / 0.016)
    arm = where.T - np.array([0.0, 0.0, 0.060])
    assert np.allclose(np.cross(arm, f).sum(axis=0), [0.0, 0.0, T], atol=1e-9 * T)

    fine = ws._solve(scene, ws.RunOptions())[0]
    for z in (0.120, 0.200, 0.280):
        c = resultants(fine.read, fine.all_stress, z, D / 2)
        assert abs(c[2, 3]) == pytest.approx(T, rel=5e-3)
    idx = ring(fine, 200.0)
    # (5 mm elements: P2's nodal stress within 1 %)
    assert np.allclose(fine.mean[idx], math.sqrt(3) * 16 * T / (math.pi * D**3), rtol=1e-2)
    p = fine.points
    r = np.hypot(p[:, 0], p[:, 1])
    pocket = (np.abs(p[:, 2] - 0.060) < 0.020) & (r < D / 2 - 0.5e-3) & (p[:, 0] > 0)
    driven = pocket & (p[:, 1] > 1e-6)
    other = pocket & (np.abs(p[:, 1] + 0.005) < 1e-4)
    floor = pocket & (np.abs(p[:, 0] - (D / 2 - 0.005)) < 1e-6) & (p[:, 1] < -1e-6)
    ends = pocket & (np.abs(p[:, 2] - 0.060) > 0.016) & (p[:, 1] < -1e-6)
    assert driven.sum() > 10 and other.sum() > 10 and floor.sum() > 10 and ends.sum() > 10
    assert not fine.allowed[driven].any()
    assert fine.allowed[other].all() and fine.allowed[floor].all() and fine.allowed[ends].all()
    # the mantle under the hub (the key's length) is the fit's
    mantle = (np.abs(p[:, 2] - 0.060) < 0.020) & (r > 0.999 * D / 2)
    assert not fine.allowed[mantle].any()


def test_a_spot_followed_round_its_circle_keeps_the_bound_an_earlier_round_gave_it():
    """A torque on a shoulder: the stress is the same all round the fillet's circle, and
    a mesh refined elsewhere puts the spot at another vertex round it. Read against a mesh
    alike there, the spot has no bound of its own; an earlier round's spot at its place,
    some way round the circle, lends it its: the new interval holds the old one."""
    from dataclasses import replace

    data = sharp_shoulder(3.0)
    data.pop("force")
    data["torque"] = [{"name": "in", "position_mm": 40.0, "torque_nm": 200.0},
                      {"name": "out", "position_mm": 260.0}]
    data["strength"] = {}
    scene = load_scene(data)
    fine = ws._solve(scene, ws.RunOptions())[0]
    alone = ws._spots(scene, fine, fine, None)
    spot = alone[0]
    assert spot.feature.startswith("shoulder") and spot.bound is None
    # the earlier round's spot: the same circle, a quarter turn round, 2 % lower, +-3 %
    turned = spot.angle + math.pi / 2
    old = replace(spot, angle=turned, peak=0.98 * spot.peak, amplitude=0.98 * spot.amplitude,
                  bound=0.03, difference=0.03)
    i = int(np.argmin(np.linalg.norm(fine.points - ws._xyz(spot), axis=1)))
    assert ws._same_spot([old], fine, i, True) is None
    lent = ws._spots(scene, fine, fine, [], [[old]])[0]
    assert lent.bound is not None
    lo, hi = lent.peak * (1 - lent.bound), lent.peak * (1 + lent.bound)
    assert lo <= old.peak * (1 - old.bound) + 1e-6 and old.peak * (1 + old.bound) <= hi + 1e-6
    # ... and a spot elsewhere lends nothing
    far = replace(old, z=old.z + 0.05)
    assert ws._spots(scene, fine, fine, [], [[far]])[0].bound is None


@pytest.mark.slow
def test_a_keyway_ends_floor_fillet_is_found_and_bounded_in_bending():
    """An end-milled keyway (10 x 5 mm, 40 mm long, 1 mm floor corners) on a 32 mm bar
    bent by two balancing couples (M = 100 N m over it): the largest stress is in its
    ends' floor fillets, which the first mesh does not resolve (it reads them low, below
    the mantle at the keyway's rim); refined first as the spots that may be the worst,
    they are found and bounded. K_t against NGSolve on netgen's curved mesh of the same
    solid, clamped and loaded by pure bending (benchmarks/notch_reference.py, the ends'
    floor fillets at a quarter of their radius: 2.1295 at order 3, 2.1249 at order 4)."""
    F = 10000.0 / 3
    data = {"name": "keyway", "material": STEEL, "static": {"gravity_m_s2": 0.0},
            "shaft": {"length_mm": 300.0, "diameter_mm": 32.0},
            "keyway": [{"position_mm": 150.0, "length_mm": 40.0, "width_mm": 10.0,
                        "depth_mm": 5.0, "angle_deg": 90.0, "corner_radius_mm": 1.0}],
            "mesh": {"element_size_mm": 8.0, "groove_element_size_mm": 1.0,
                     "edge_element_size_mm": 1.0},
            "support": [{"name": "left", "position_mm": 10.0, "width_mm": 16.0,
                         "kind": "springs", "radial_stiffness_n_per_mm": 1e9},
                        {"name": "right", "position_mm": 290.0, "width_mm": 16.0,
                         "kind": "springs", "radial_stiffness_n_per_mm": 1e9}],
            "force": [{"name": n, "position_mm": z, "fy_n": f} for n, z, f in
                      (("a", 40.0, F), ("b", 70.0, -F), ("c", 230.0, -F), ("d", 260.0, F))],
            "strength": {}}
    result = ws.run_strength(load_scene(data))
    nominal = F * 0.030 * 32 / (math.pi * 0.032**3)
    worst = max(result.spots, key=lambda s: s.peak)
    assert worst.feature == "keyway end" and worst.radius < 0.0125, worst
    kt, reference = worst.peak / nominal, 2.1249
    assert kt == pytest.approx(reference, rel=0.01)
    assert worst.bound is not None and abs(kt / reference - 1) <= worst.bound


@pytest.mark.parametrize("target,shrink", [
    # the bound takes in the spot's vertex scatter: the three rounds, within the 400,000
    # DOF budget, end at +-2.08 % here (a fourth round reached +-2.16 %), above the 2 %
    # target; its K_t in bending 1.861 against the axisymmetric 1.8373 (+1.3 %)
    pytest.param(2.0, 2.5, marks=[pytest.mark.slow, pytest.mark.xfail(
        reason="three rounds end at +-2.08 % against the 2 % target", strict=False)]),
    pytest.param(5.0, 1.5, marks=pytest.mark.slow)])
def test_a_filleted_shoulder_is_refined_around_its_hot_spot_until_bounded(target, shrink):
    """The same shoulder with a 3 mm fillet, bent by two balancing couples (M = 60 N m
    over it, whatever the seats do): a smooth notch, refined around the spot until its
    bound meets the target (2 %, and 5 % in the default suite): the spot's elements at
    least `shrink` times smaller than the fillet's 2 mm, the DOFs less than 6 times the
    first mesh's (not everywhere: shrinking every element 2.5 times would multiply them
    by 15; each round keeps the refinement of the rounds before)."""
    data = sharp_shoulder(3.0)
    data["force"] = [{"position_mm": z, "fy_n": f} for z, f in
                     ((40.0, 2000.0), (70.0, -2000.0), (230.0, -2000.0), (260.0, 2000.0))]
    data["strength"]["target_error_percent"] = target
    result = ws.run_strength(load_scene(data))
    worst = result.spots[0]
    assert abs(worst.z - 0.1485) < 2e-3 and worst.converging and result.ok
    assert worst.bound is not None and worst.bound <= target / 100
    assert worst.size < 2e-3 / shrink and len(result.dofs) >= 3
    assert result.dofs[-1] < 6 * result.dofs[1]
    # its K_t in bending beside Peterson's: the chart (Pilkey's fit, chart 3.10, h/r
    # 2.67) 1.777 by hand; the largest principal stress over nominal from NGSolve's
    # axisymmetric solution of this shoulder in pure bending, 1.8373 at orders 5 and 6
    # (benchmarks/axisymmetric_reference.py, docs/verification.md), here within the
    # target (the spot's bound is its von Mises stress's)
    (kt,) = [k for k in worst.factors if k.load == "bending"]
    h_r, x = 8 / 3, 16 / 48
    c = [a + b * math.sqrt(h_r) + e * h_r for a, b, e in (
        (1.232, 0.832, -0.008), (-3.813, 0.968, -0.260), (7.423, -4.868, 0.869),
        (-3.839, 3.070, -0.600))]
    assert kt.table == pytest.approx(c[0] + c[1] * x + c[2] * x**2 + c[3] * x**3, rel=1e-9)
    assert kt.computed == pytest.approx(1.8373, rel=target / 100)
    assert (kt.large, kt.small, kt.radius) == pytest.approx((0.048, 0.032, 0.003))


@pytest.mark.slow
def test_the_gear_shaft_example_holds_with_its_worst_spot_at_a_shoulder(tmp_path):
    """examples/gear_shaft.toml as a user runs it: 15 kW through a helical gear between
    two ball bearings. Its worst spots are the shoulders' fillets, bounded; the gear's
    slope is the beam's order of magnitude (F L^3-ish microns, far within the limits)."""
    stdout, worst = _gear_shaft(tmp_path)
    assert worst["converging"]
    # the torque passes the shoulder at 210 mm: its K_t in torsion beside Peterson's
    # chart 3.12 (D/d 40/30, r 1.5 mm: 1.63), printed beside it
    torsion = next(k for k in worst["stress_concentration"] if k["load"] == "torsion")
    assert torsion["kt"] == pytest.approx(torsion["kt_table"], rel=0.04)
    assert "stress concentration at shoulder fillets" in stdout
    assert f"torsion {torsion['kt']:.2f} (chart {torsion['kt_table']:.2f})" in stdout


def test_the_gear_shaft_example_within_a_smaller_budget(tmp_path):
    """The same example as a user runs it with `--max-dofs 140000` (the default suite's
    time: the run above, to the 400,000 DOFs it needs, is slow): its second mesh has
    137,970 DOFs, so no refinement around its spots fits the budget, however coarse;
    it stops on its first two meshes, before making a third, with the same worst spot,
    mean stress and seat slopes, and says so. That spot, a fillet 6 mm from the right
    bearing's seat, is then bounded in a local model that stops short of the seat's
    band (on the whole it read 55.0 MPa +-14.1 % at 383,700 DOFs)."""
    stdout, worst = _gear_shaft(tmp_path, ["--max-dofs", "140000"])
    assert worst["feature"] == "shoulder at 210 mm"
    assert "above the budget of 140,000 however far" in stdout
    assert worst["local_model_dofs"] > 0 and worst["bound_percent"] <= 2.0
    assert abs(worst["peak_mpa"] / 55.0 - 1) < 0.141


def _gear_shaft(tmp_path, flags: list[str] | None = None) -> tuple[str, dict]:
    """`shaftfem strength examples/gear_shaft.toml` with `flags`: it passes, its worst spot
    on a shoulder carries the torque's mean and the gear's seat is within its given
    slope; its output and worst spot."""
    import subprocess
    import sys
    from pathlib import Path

    scene = Path(__file__).parents[1] / "examples" / "gear_shaft.toml"
    out = tmp_path / "gear.json"
    run = subprocess.run([sys.executable, "-m", "shaftfem", "strength", str(scene),
                          "--json", str(out), "-q", *(flags or [])], capture_output=True, text=True,
                         timeout=900)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-2000:]
    data = json.loads(out.read_text())
    worst = data["hot_spots"][0]
    assert worst["feature"].startswith("shoulder")
    # a steady torque: the mean at the worst spot is at least the torsion's sqrt(3) tau
    tau = 15e3 / (1450 * math.pi / 30) * 16 / (math.pi * 0.030**3) / 1e6
    assert worst["mean_mpa"] >= math.sqrt(3) * tau * 0.99
    gear = next(s for s in data["seats"] if s["name"] == "gear")
    assert gear["ok"] and gear["slope_limit_mrad"] == 0.5
    return run.stdout, worst


@pytest.mark.slow
def test_the_pump_shaft_example_runs_with_its_torque_and_rotating_bending(tmp_path):
    """examples/pump_shaft.toml as a user runs it: a stepped pump shaft with a keyed
    coupling and a keyed overhung impeller on two ball bearings, 15 kW at 2,950 r/min.
    Every hot spot sits on a notch or beside one, none is sharp (every notch is rounded),
    the steady torque gives the coupling end's spots a mean of at least the torsion's
    sqrt(3) tau, and the overhang's rotating bending an amplitude at the outboard seat."""
    import subprocess
    import sys
    from pathlib import Path

    scene = Path(__file__).parents[1] / "examples" / "pump_shaft.toml"
    out = tmp_path / "pump.json"
    run = subprocess.run([sys.executable, "-m", "shaftfem", "strength", str(scene),
                          "--json", str(out), "-q"], capture_output=True, text=True,
                         timeout=1800)
    assert run.returncode in (0, 1), run.stdout[-3000:] + run.stderr[-2000:]
    data = json.loads(out.read_text())
    assert data["sharp_edges"] == 0 and data["hot_spots"]
    tau = 15e3 / (2950 * math.pi / 30) * 16 / (math.pi * 0.028**3) / 1e6
    coupling = [s for s in data["hot_spots"] if s["z_mm"] < 60.0]
    # the mean von Mises stress is signed by the hydrostatic stress, which pure torsion
    # leaves near zero: either sign
    assert coupling and all(abs(s["mean_mpa"]) >= math.sqrt(3) * tau * 0.99
                            for s in coupling)
    assert (run.returncode == 0) == data["passed"]


def _edge_field(concave: bool):
    """Points 0.1 mm apart on two faces meeting at a right-angled edge along y: the face
    z = 0 (x > 0, material below it) and the face x = 0, above it with the material at
    x < 0 (a re-entrant edge: the material fills three quadrants) or below it with the
    material at x > 0 (a convex edge: one quadrant)."""
    from types import SimpleNamespace

    t = np.linspace(0.0, 1e-3, 11)
    y = np.linspace(-5e-4, 5e-4, 11)
    a = np.array([[u, v, 0.0] for u in t for v in y])
    side = 1.0 if concave else -1.0
    b = np.array([[0.0, v, side * w] for w in t[1:] for v in y])
    nb = (1.0, 0.0, 0.0) if concave else (-1.0, 0.0, 0.0)
    normals = np.vstack([np.tile((0.0, 0.0, 1.0), (len(a), 1)), np.tile(nb, (len(b), 1))])
    points = np.vstack([a, b])
    return SimpleNamespace(points=points, normals=normals, edge=np.full(len(points), 1e-4))


def test_only_a_re_entrant_edge_turns_the_surface_concavely():
    """A re-entrant edge turns the normal by a right angle within an element however
    fine the mesh (its stress is singular); across a convex edge (where two grooves' root
    fillets meet at a land's corner) the concave turn is nil: its stress is bounded, and
    its spot is not to be called sharp."""
    i = 5  # on the face z = 0, at the edge
    assert math.degrees(ws._edge_turn(_edge_field(True), i)) == pytest.approx(90.0, abs=1e-6)
    assert ws._edge_turn(_edge_field(False), i) == pytest.approx(0.0, abs=1e-9)


def test_a_refined_mesh_is_never_coarser_than_the_scenes_own():
    """A strength round's size field refines the scene's mesh and never coarsens it: asked
    for elements ten times the scene's largest everywhere, the mesher still gives the
    scene's own mesh (its fillet at 2 mm), not a coarser one; without `refine` it follows
    the field alone and the fillet coarsens. (Left coarse round a notch, the far side of
    a fillet shifts load onto the refined spot.)"""
    from shaftfem.cad.mesh import generate_mesh
    from shaftfem.runtime import RunOptions
    from shaftfem.workflows.pipeline import built

    placed, shape, mesh = built(load_scene(sharp_shoulder(3.0)), RunOptions())
    coarse = np.full(mesh.points.shape[0], 10 * placed.mesh.size)
    args = (shape, placed.shaft, placed.grooves, placed.mesh,
            (mesh.points, mesh.cells[:, :4], coarse), placed.seat_cuts(), placed.hubs())
    kept, followed = generate_mesh(*args, refine=True), generate_mesh(*args)
    n0 = mesh.points.shape[0]
    assert 0.9 * n0 < kept.points.shape[0] < 1.1 * n0
    assert followed.points.shape[0] < 0.5 * n0


def test_a_refined_mesh_whose_surface_facets_cross_is_asked_again_a_little_finer(
        monkeypatch):
    """gmsh's boundary recovery refuses a surface mesh whose facets cross ("PLC Error: A
    segment and a facet intersect", "overlapping facets"): where its vertices fell, not
    the sizes, is at fault, so the refined mesh is asked again with its sizes PLC_RETRIES
    times smaller, in turn; any other failure, or a crossing at every try, is the
    caller's MeshError."""
    import shaftfem.cad.mesh as cm
    from shaftfem.errors import MeshError

    asked: list[float] = []

    def once(brep, shaft, grooves, settings, sizes, *rest):
        asked.append(float(sizes[2][0]))
        if len(asked) < 3 or how["again"]:
            raise MeshError(f"gmsh could not mesh the solid: Exception: {how['message']}")
        return np.zeros((4, 3)), np.zeros((1, 4), dtype=int), False

    monkeypatch.setattr(cm, "_refined_once", once)
    sizes = (np.zeros((4, 3)), np.zeros((1, 4), dtype=int), np.full(4, 1e-3))
    how = {"again": False, "message": "PLC Error:  A segment and a facet intersect at point"}
    cm._refined("b", None, None, None, sizes, (), (), True)
    assert asked == pytest.approx([1e-3, *(r * 1e-3 for r in cm.PLC_RETRIES)])
    how.update(message="Invalid boundary mesh (overlapping facets) on surface 30")
    asked.clear()
    cm._refined("b", None, None, None, sizes, (), (), True)
    assert len(asked) == 3
    for again, message in ((True, "PLC Error:  A segment and a facet intersect"),
                           (False, "No elements in volume 1")):
        how.update(again=again, message=message)
        asked.clear()
        with pytest.raises(MeshError):
            cm._refined("b", None, None, None, sizes, (), (), True)
        assert len(asked) == (1 + len(cm.PLC_RETRIES) if again else 1)


def test_a_refined_mesh_whose_delaunay_does_not_end_in_time_is_made_by_hxt(monkeypatch,
                                                                           tmp_path):
    """A refined mesh's Delaunay runs beside the run within a time (cad.mesh.DELAUNAY_
    SECONDS); given none, the mesh comes from gmsh's HXT: valid (generate_mesh checks
    every Jacobian), as fine as the Delaunay's where the field asks half the scene's
    sizes (node counts within 25 %), and the same on a second run (one thread), which
    goes to HXT at once; the mesh and its cache entry say HXT made it."""
    import shaftfem.cad.mesh as cm
    from shaftfem.runtime import RunOptions
    from shaftfem.workflows.pipeline import built

    placed, shape, mesh = built(load_scene(sharp_shoulder(3.0)), RunOptions())
    half = np.full(mesh.points.shape[0], 0.5 * placed.mesh.size)
    args = (shape, placed.shaft, placed.grooves, placed.mesh,
            (mesh.points, mesh.cells[:, :4], half), placed.seat_cuts(), placed.hubs())
    delaunay = cm.generate_mesh(*args, refine=True)
    monkeypatch.setenv("SHAFTFEM_ASIDE", "1")
    monkeypatch.setattr(cm, "DELAUNAY_SECONDS", 0.0)
    monkeypatch.setattr(cm, "DELAUNAY_PER_ELEMENT", 0.0)
    monkeypatch.setattr(cm, "_UNSETTLED", set())   # this solid's later meshes: HXT at once
    hxt, again = cm.generate_mesh(*args, refine=True), cm.generate_mesh(*args, refine=True)
    n, m = delaunay.points.shape[0], hxt.points.shape[0]
    assert 0.75 * n < m < 1.25 * n and m > 2 * mesh.points.shape[0]
    assert np.array_equal(hxt.points, again.points) and np.array_equal(hxt.cells, again.cells)
    assert str(shape.brep) in cm._UNSETTLED
    assert not np.array_equal(hxt.points.shape, delaunay.points.shape) or not np.allclose(
        hxt.points, delaunay.points)
    # the mesh says which mesher made it, and so does its cache entry to a warm run
    assert hxt.hxt and again.hxt and not delaunay.hxt
    monkeypatch.setenv("SHAFTFEM_CACHE", str(tmp_path))
    cold = ws._remeshed((placed, shape), mesh, half)
    warm = ws._remeshed((placed, shape), mesh, half)
    assert cold.hxt and not cold.from_cache and warm.hxt and warm.from_cache


def test_a_refinement_above_the_budget_is_enlarged_or_refused_before_meshing(monkeypatch):
    """A round whose field asks, by its estimate, more than the DOF budget is enlarged on
    the estimate alone and meshed once, within it; where the rounds before
    already asked too much (0.05 mm elements within 20 mm of the fillet: about a billion
    DOFs), no enlarging of this round's sizes helps and the round is refused with the
    budget's reason, no mesh made."""
    from types import SimpleNamespace

    from shaftfem.errors import BudgetError
    from shaftfem.runtime import RunOptions
    from shaftfem.workflows.pipeline import built

    placed, shape, mesh = built(load_scene(sharp_shoulder(3.0)), RunOptions())
    spot = SimpleNamespace(z=0.150, angle=-math.pi / 2, radius=0.016)
    made = []
    monkeypatch.setattr(ws, "_remeshed", lambda b, m, sizes: made.append(sizes) or mesh)
    _, asked = ws._within_budget((placed, shape), mesh, [], [ws._Request(spot, 0.05e-3, 3e-3)],
                                 placed, RunOptions())
    assert len(made) == 1 and asked[0].size > 4 * 0.05e-3
    monkeypatch.setattr(ws, "_remeshed", lambda *a: pytest.fail("a mesh was made"))
    with pytest.raises(BudgetError, match="however far this round's elements are enlarged"):
        ws._within_budget((placed, shape), mesh, [ws._Request(spot, 0.05e-3, 20e-3)],
                          [ws._Request(spot, 1e-3, 2e-3)], placed, RunOptions())


def test_a_spots_scatter_is_what_stands_off_a_smooth_fit():
    """The scatter added to a spot's bound: nothing where the surface stress is smooth
    (a field quadratic along a cylinder's axis is its own fit), and a vertex raised by
    1 % above such a field is read as standing off it by between half of that and all
    of it (the fit passes partly through the raised vertex)."""
    from types import SimpleNamespace

    h, r = 0.5e-3, 0.016
    z, t = np.meshgrid(np.arange(-10, 11) * h, np.arange(-10, 11) * h / r)
    z, t = z.ravel(), t.ravel()
    normals = np.column_stack([np.cos(t), np.sin(t), np.zeros_like(t)])
    field = SimpleNamespace(points=np.column_stack([r * normals[:, 0], r * normals[:, 1], z]),
                            normals=normals, edge=np.full(z.size, h),
                            allowed=np.ones(z.size, dtype=bool))
    value = 100e6 * (1 - (z / (8 * h)) ** 2 / 4)
    i = int(np.argmin(np.abs(z) + np.abs(t)))
    assert ws._scatter(field, i, value) < 1e-9
    raised = value.copy()
    raised[i] *= 1.01
    assert 0.005 < ws._scatter(field, i, raised) <= 0.01


def pulled_shoulder(big: float, radius: float, fillet_size: float) -> dict:
    """A big/32 mm shoulder with its fillet (mm) pulled by 20 kN, meshed at fillet_size
    (mm) on its fillet."""
    return {"name": "pulled", "material": STEEL, "static": {"gravity_m_s2": 0.0},
            "section": [{"length_mm": 150.0, "diameter_mm": 32.0, "fillet_mm": radius},
                        {"length_mm": 150.0, "diameter_mm": big}],
            "mesh": {"element_size_mm": 8.0, "groove_element_size_mm": fillet_size,
                     "edge_element_size_mm": fillet_size},
            "support": [{"name": "left", "position_mm": 10.0, "width_mm": 16.0,
                         "kind": "springs", "radial_stiffness_n_per_mm": 1e9},
                        {"name": "right", "position_mm": 290.0, "width_mm": 16.0,
                         "kind": "springs", "radial_stiffness_n_per_mm": 1e9,
                         "axial_stiffness_n_per_mm": 1e9}],
            "force": [{"name": "pull", "position_mm": 40.0, "fz_n": -20000.0}],
            "strength": {"target_error_percent": 2.0}}


@pytest.mark.slow
@pytest.mark.parametrize("big,radius,exact", [(64.0, 5.0, 1.72582), (48.0, 3.0, 1.958409)])
def test_a_shoulders_stress_in_tension_lies_within_its_bound_of_an_exact_solution(
        big, radius, exact):
    """A big/32 mm shoulder with its fillet pulled by 20 kN: K_t = sigma_vM,max /
    sigma_nom against NGSolve's axisymmetric solution of the same half-section (nu 0.3;
    64/32 r5 at orders 5 and 6: 1.725839, 1.725820; 48/32 r3 at orders 5, 6 and 7:
    1.958409; benchmarks/axisymmetric_reference.py), inside the spot's bound. (Refined
    rounds that coarsened the fillet's far side read 1.7484 +-0.19 % on the first; the
    second read 1.9970, +1.97 %, against +-1.79 % before its vertices' scatter was in
    the bound.)"""
    result = ws.run_strength(load_scene(pulled_shoulder(big, radius, radius / 2)))
    spot = max((s for s in result.spots if 0.140 <= s.z <= 0.160), key=lambda s: s.peak)
    kt = spot.peak / (20000.0 / (math.pi * 0.032**2 / 4))
    assert spot.bound is not None and spot.converging
    assert abs(kt / exact - 1) <= spot.bound


def test_a_travelling_load_is_screened_along_its_way_and_the_worst_place_bounded():
    """A radial force travelling from 60 to 340 mm between seats 380 mm apart, the shaft
    turning (fully reversed bending): on a plain bar the worst hot spot's utilisation
    at each place follows the beam's moment where that spot is, just beside the load's
    band, within 2.5 %; the worst place, mid-span, is the one bounded and judged,
    the seats each at the place that tilts them most."""
    duty = dict(force=[{"name": "follower", "position_mm": 60.0, "travel_to_mm": 340.0,
                        "fy_n": -2000.0}],
                strength={"speed_rpm": 1000.0, "travel_positions": 5,
                          "target_error_percent": 50.0})
    result = ws.run_strength(load_scene(bar(**duty)))
    assert [round(t.position * 1e3, 6) for t in result.travel] == [60.0, 130.0, 200.0,
                                                                    270.0, 340.0]
    l = 0.380
    # the beam's moment at each place's worst spot, F b z / l before the load, F a (l - z)
    # / l after it (z, a from the left seat, b = l - a)
    moment = []
    for t in result.travel:
        a, z = t.position - 0.010, t.spot - 0.010
        moment.append((l - a) * z / l if z <= a else a * (l - z) / l)
    use = [t.utilisation for t in result.travel]
    # (the ends' spots lie 3 cm from a seat's band: there the bar is not quite a beam yet)
    assert np.allclose(np.array(use) / use[2], np.array(moment) / moment[2], rtol=0.025)
    # each worst spot beside its load, outside the band it enters through (d / 4 each way)
    assert all(D / 4 <= abs(t.spot - t.position) < D / 4 + 0.012 for t in result.travel)
    assert result.scene.forces[0].position == pytest.approx(0.200)
    I = math.pi * D**4 / 64
    for seat in ("left", "right"):
        # the seat's slope under a load at a from the left seat, b = l - a from the right,
        # F a b (l + b) / (6 E I l) at the left, F a b (l + a) / (6 E I l) at the right:
        # the worst of the five places
        slopes = []
        for t in result.travel:
            a = t.position - 0.010
            b = l - a
            slopes.append(2000 * a * b * (l + (b if seat == "left" else a)) / (6 * E * I * l))
        got = next(c for c in result.seats if c.name == seat)
        assert got.slope == pytest.approx(max(slopes), rel=0.03), seat
    data = result.as_dict()
    assert [t["position_mm"] for t in data["travel"]] == pytest.approx([60, 130, 200, 270, 340])
    from shaftfem.outputs.tables import strength_text

    assert "screened at 5 places from 60.0 to 340.0 mm" in strength_text(result)
    assert "the worst place, 200.0 mm" in strength_text(result)


def test_williams_exponent_is_a_cracks_half_and_a_right_corners_0_5445():
    """Williams (1952): lambda = 1/2 at a crack's tip, 0.5445 at a right-angled
    re-entrant corner, and lambda -> 1 as the wedge flattens (a smooth surface: no
    singularity)."""
    from shaftfem.checks.singular import wedge_exponent

    assert wedge_exponent(2 * math.pi) == pytest.approx(0.5, abs=1e-9)
    assert wedge_exponent(1.5 * math.pi) == pytest.approx(0.5445, abs=1e-4)
    assert 0.999 < wedge_exponent(math.pi + 1e-3) < 1
    with pytest.raises(ValueError):
        wedge_exponent(math.pi)


def test_the_grooves_flat_ends_are_said_to_be_left_out():
    """Grooves without runouts end in flat walls: their edges with the floor are sharp
    (Williams' r^(0.5445 - 1) at a right-angled re-entrant corner), so the check says it
    leaves them out, at the grooved zone's ends (the paper's: 360 mm centred on 545 mm,
    92.5 and 452.5 mm); a shaft without grooves, or whose grooves run out, has nothing
    to say."""
    note = ws._runouts(load_scene("paper2018"))
    assert note is not None and "92.5 and 452.5 mm" in note and "r^-0.456" in note
    assert "not judged" in note and "runout_mm" in note
    assert ws._runouts(load_scene("plain_cylinder")) is None
    assert ws._runouts(load_scene("paper2018_installed")) is None


def test_each_keyway_end_and_groove_runout_is_judged_on_its_own():
    """The places a designer names are each searched for their own worst point: the
    keyway's two halves along the axis (46-55 and 55-64 mm on the paper's shaft) and the
    two runouts (82.5-92.5 and 452.5-462.5 mm), each below the surface; and a spot in a
    runout is called one."""
    s = load_scene("paper2018_installed")
    z = np.linspace(0.0, 0.545, 5451)
    deep = np.column_stack([np.full_like(z, 0.0145), np.zeros_like(z), z])
    masks = ws._owned(s, deep)
    assert len(masks) == 4
    spans = [(z[m].min() * 1e3, z[m].max() * 1e3) for m in masks]
    assert spans[0][0] == pytest.approx(46.0, abs=0.3) and spans[1][1] == pytest.approx(
        64.0, abs=0.3) and spans[0][1] < 55.0 <= spans[1][0]
    assert spans[2] == pytest.approx((82.6, 92.4), abs=0.05)
    assert spans[3] == pytest.approx((452.6, 462.4), abs=0.05)
    top = deep.copy()
    top[:, 0] = 0.016
    assert not any(m.any() for m in ws._owned(s, top)[2:])     # on the surface: no runout
    assert ws._feature(s, np.array([0.0145, 0.0, 0.088]), 0.016)[0] == "groove runout"
    assert ws._feature(s, np.array([0.0135, 0.0, 0.100]), 0.016)[0] == "groove root"


def test_a_verdict_says_the_largest_utilisation_read_where_its_spot_has_no_bound():
    """Spots whose bound is unknown (a notch the mesh does not follow, read low) above
    every bounded one: the verdict names their largest degree of utilisation first, so
    that the bounded spots' largest is not read as the shaft's."""
    from types import SimpleNamespace as NS

    from shaftfem.outputs.tables import strength_verdict

    def spot(use, bound, resolved):
        return NS(converging=True, resolved=resolved, bound=bound,
                  fkm=NS(fatigue_utilisation=0.01, yield_utilisation=use))

    result = NS(fatigue_ok=True, yield_ok=True, deflection_ok=True, target=0.02,
                spots=[spot(0.33, None, False), spot(0.10, 0.1, True)])
    line = strength_verdict(result)
    assert "largest degree of utilisation read is 0.33 (hot spot 1, its bound unknown" in line
    assert "with each known bound taken against it, the largest degree of utilisation is " \
           "0.11 (hot spot 2)" in line
    # the bounded spot the largest: said once, as before
    result.spots = [spot(0.30, 0.05, True), spot(0.20, None, False)]
    line = strength_verdict(result)
    assert "read is" not in line and "utilisation is 0.32 (hot spot 1)" in line


def test_a_relief_grooves_fillet_gets_no_shoulder_chart():
    """A section shorter than its diameter between two larger ones is a groove: the
    shoulder chart (whose smaller shaft runs on) is not printed beside its fillets; a
    shoulder's is."""
    def shaft(sections):
        data = bar(section=sections)
        data.pop("shaft")
        return load_scene(data)

    groove = shaft([{"length_mm": 150.0, "diameter_mm": 40.0, "fillet_mm": 1.5},
                    {"length_mm": 4.0, "diameter_mm": 35.0, "fillet_mm": 1.5},
                    {"length_mm": 246.0, "diameter_mm": 40.0}])
    assert ws._groove_section(groove, 1) and not ws._groove_section(groove, 0)
    long_ = shaft([{"length_mm": 150.0, "diameter_mm": 40.0, "fillet_mm": 1.5},
                   {"length_mm": 40.0, "diameter_mm": 35.0, "fillet_mm": 1.5},
                   {"length_mm": 210.0, "diameter_mm": 40.0}])
    assert not ws._groove_section(long_, 1)


def test_a_mesher_crashing_in_native_code_stops_the_refinement_not_the_run(monkeypatch):
    """gmsh's HXT once crashed in native code on a refined mesh (a keyway running into a
    shoulder's fillet: "munmap_chunk(): invalid pointer") and took the whole run with it;
    a refined mesh is now made in a process of its own, whose dying is a MeshError that
    the refinement stops at, saying so."""
    import os

    from shaftfem.aside import Aside
    from shaftfem.cad.mesh import _aside
    from shaftfem.errors import MeshError

    monkeypatch.setenv("SHAFTFEM_ASIDE", "1")   # the test workers run it in line
    with pytest.raises(MeshError, match="gmsh's HXT stopped without a mesh"):
        _aside(Aside(os.abort), None, "HXT")


def test_a_circle_not_of_revolution_lists_at_most_two_spots_round_it():
    """Near a keyway, or on a STEP solid, the shaft is not of revolution about a fillet,
    and each vertex round its circle may be a local maximum: the list keeps the worst two
    of one feature on each circle about the axis (worst first, the others' order kept),
    and every spot elsewhere or of another feature."""
    from types import SimpleNamespace as NS

    def spot(n, feature, z, r=0.015):
        return NS(feature=feature, z=z, radius=r, n=n)

    spots = ([spot(i, "shoulder at 80 mm", 0.0789 + 1e-4 * (i % 2)) for i in range(5)]
             + [spot(5, "keyway end", 0.0697), spot(6, "keyway end", 0.0696),
                spot(7, "shoulder at 80 mm", 0.0789, r=0.018),     # another circle
                spot(8, "plain surface", 0.0789), spot(9, "keyway end", 0.0696)])
    kept = ws._per_circle(spots)
    assert [s.n for s in kept] == [0, 1, 5, 6, 7, 8]


@pytest.mark.parametrize("big,radius,exact", [(48.0, 3.0, 1.958409), (64.0, 5.0, 1.72582)])
def test_a_notch_the_whole_mesh_does_not_resolve_is_bounded_in_a_local_model(
        monkeypatch, big, radius, exact):
    """The shoulders above pulled by 20 kN, meshed at 4.5 mm at their fillets (not
    resolved) and not refined on the whole: each spot is bounded in a slice round it
    (fem.submodel), to the target, and NGSolve's axisymmetric K_t lies within its
    bound (measured: +0.11 % inside +-0.61 %, +0.055 % inside +-1.34 %)."""
    monkeypatch.setattr(ws, "MAX_REFINEMENTS", 0)
    result = ws.run_strength(load_scene(pulled_shoulder(big, radius, 4.5)))
    spot = max((s for s in result.spots if 0.140 <= s.z <= 0.160), key=lambda s: s.peak)
    kt = spot.peak / (20000.0 / (math.pi * 0.032**2 / 4))
    assert spot.local_dofs > 0 and spot.converging and spot.resolved
    assert spot.bound is not None and spot.bound <= 0.02
    assert abs(kt / exact - 1) <= spot.bound


def test_a_local_models_slice_holds_a_hubs_band_whole_and_stops_short_of_a_seat():
    """The paper's gear keyway's end at 63.7 mm lies in the gear hub's band (45-65 mm,
    the key at 46-64 mm): its slice holds that band whole with a spare element beyond,
    and stops at the gear-end bearing's seat (12-28 mm).
    A spot on a seat gets no slice; a slice reaching into a groove runout holds it
    whole."""
    scene = load_scene("paper2018_installed")
    z = np.linspace(0.0, scene.shaft.length, 2000)
    points = np.column_stack([np.full_like(z, 0.016), np.zeros_like(z), z])
    fine = ws._Field(points=points, normals=points * 0, edge=np.full(len(z), 4e-3),
                     stress=np.zeros((4, len(z), 3, 3)), amplitude=z * 0, mean=z * 0,
                     peak=z * 0, all_stress=np.zeros((4, len(z), 3, 3)), vertices=points,
                     tets=np.zeros((0, 4), dtype=int), facets=np.zeros((0, 3), dtype=int),
                     allowed=z > 0, line=(z, z, z), dofs=0)
    spot = replace(ws.HotSpot(z=0.0637, angle=0.0, radius=0.0115, feature="keyway end",
                              amplitude=0.0, mean=1.0, peak=1.0, bound=None,
                              converging=True, gradient=0.0, diameter=0.032, fkm=None),
                   size=1e-3)
    # 24 mm (1.5 R) either side, grown to the hub's band widened by 4 mm, and 4 mm more;
    # on the other side to the runout's end (87.7 mm lies in it), and 4 mm more
    lo, hi = ws._local_span(scene, spot, fine, 4e-3)
    assert lo == pytest.approx(0.045 - 0.004 - 0.004) and hi == pytest.approx(0.0925 + 0.004)
    # a spot at 40 mm: 24 mm reaches into the seat's band (12-28 mm): cut an element (4
    # mm) short of it
    lo, hi = ws._local_span(scene, replace(spot, z=0.040), fine, 4e-3)
    assert lo == pytest.approx(0.028 + 0.004) and hi == pytest.approx(0.065 + 0.004 + 0.004)
    on_seat = replace(spot, z=0.020)
    assert ws._local_span(scene, on_seat, fine, 4e-3) is None
    # ... and the run says so, the spot kept as the whole bounded it
    from pathlib import Path
    from types import SimpleNamespace as NS

    from shaftfem.runtime import RunOptions

    notes: list[str] = []
    kept = ws._localised(scene, on_seat, fine, fine, (scene, NS(brep=Path("unused"))), 0.02,
                         RunOptions(), notes)
    assert kept is on_seat and len(notes) == 1 and "no local model for the spot at 20.0 mm" \
        in notes[0]
    # a crossing at 116.2 mm: 24 mm reaches into the runout at 82.5-92.5 mm, held whole
    # (a cut face beside its start meshed with crossing facets), 4 mm to spare
    lo, hi = ws._local_span(scene, replace(spot, z=0.1162), fine, 4e-3)
    assert lo == pytest.approx(0.0825 - 0.004) and hi == pytest.approx(0.1162 + 0.024)


def test_a_signed_stress_that_rounds_to_zero_prints_without_a_minus():
    """A runout that carries nothing but the weight's bending read "-0.0" MPa mean."""
    from shaftfem.outputs.tables import _mpa

    assert f"{_mpa(-4e3):.1f}" == "0.0" and f"{_mpa(-6e4):.1f}" == "-0.1"


def test_places_the_screening_does_not_tell_apart_give_the_first_as_the_worst():
    """The paper's follower from 352.5 mm on loads the crossings alike (0.193 to three
    decimals): the worst place must not hang on a solve's last digit; a place clearly
    worse is taken however late."""
    assert ws._worst_place([0.14, 0.18, 0.1931, 0.1932, 0.1930]) == 2
    assert ws._worst_place([0.14, 0.18, 0.1931, 0.21, 0.1930]) == 3
