"""Cross-check with CalculiX (ccx), a solver nobody here wrote, on the same mesh.

CalculiX's C3D10 integrates stiffness and mass with the 4-point rule. With the
same rule our frequencies must agree to round-off; with our exact (order-4)
consistent mass they differ by about 1e-4 on coarse meshes, less on finer ones.
"""

import shutil
import subprocess

import numpy as np
import pytest

from shaftfem.fem.assembly import assemble
from shaftfem.fem.modes import modal_analysis
from shaftfem.outputs.calculix import read_calculix_eig, read_calculix_frequencies, write_calculix
from shaftfem.scene.load import load_scene
from shaftfem.workflows.pipeline import run_modes, with_mesh

pytestmark = pytest.mark.skipif(
    shutil.which("ccx") is None,
    reason="CalculiX (ccx) is not installed: `apt-get install calculix-ccx` (scripts/setup.sh "
    "tries it) to run the cross-check",
)


def _ccx(result, folder):
    write_calculix(result, folder / "shaft.inp")
    p = subprocess.run(["ccx", "-i", "shaft"], cwd=folder, capture_output=True, text=True,
                       timeout=600)
    assert p.returncode == 0, p.stdout[-2000:]
    full = read_calculix_eig(folder / "shaft.eig")
    printed = read_calculix_frequencies(folder / "shaft.dat")
    assert np.allclose(full[6:], printed[6:], rtol=1e-6)  # the binary file was read right
    return full[6:16]


# the grooved shaft's case takes about 70 s, the cylinder's 8 mm mesh 7 s: slow (pytest -m
# slow); the cylinder's 12 mm mesh (3 s) is their twin
CASES = [("plain_cylinder", 12.0),
         pytest.param("plain_cylinder", 8.0, marks=pytest.mark.slow),
         pytest.param("paper2018", 12.0, marks=pytest.mark.slow)]


@pytest.mark.parametrize("scene,size", CASES)
def test_same_mesh_same_frequencies(scene, size, tmp_path, capsys):
    exact = run_modes(with_mesh(load_scene(scene), size))  # our default: exact P2 mass
    # CalculiX's 4-point mass on the very same mesh (gmsh's high-order optimiser does
    # not place curved nodes bit-identically twice, so the mesh is not re-made)
    s = assemble(exact.mesh, exact.scene.material, mass_intorder=2)
    four = modal_analysis(s)
    ccx = _ccx(exact, tmp_path)
    d4 = np.max(np.abs(four.frequencies / ccx - 1))
    dx = np.max(np.abs(exact.modes.frequencies / ccx - 1))
    with capsys.disabled():
        print(f"\n  CalculiX vs shaftfem, {scene} at {size:g} mm ({exact.modes.n_dofs} DOFs): "
              f"same 4-point rule {d4:.1e}, exact mass {dx:.1e}")
    assert d4 < 1e-7
    assert 1e-6 < dx < 1e-3


def test_exact_mass_difference_shrinks_with_the_mesh(tmp_path):
    diffs = []
    for size in (12.0, 8.0):
        r = run_modes(with_mesh(load_scene("plain_cylinder"), size))
        (tmp_path / str(size)).mkdir()
        ccx = _ccx(r, tmp_path / str(size))
        diffs.append(np.max(np.abs(r.modes.frequencies / ccx - 1)))
    assert diffs[1] < diffs[0]


@pytest.mark.parametrize("coupling,joint", [("distributing", "rigid"), ("rigid", "rigid"),
                                           ("distributing", "distributing")])
def test_installed_shaft_same_mesh_same_frequencies(tmp_path, capsys, coupling, joint):
    """A rigid locating bearing, a spring bearing (radial, axial and tilting) and a gear:
    CalculiX's *EQUATION, SPRING1 and *RIGID BODY cards against our elimination, with the
    same 4-point mass; the bearings distributing (mean motion) or rigid rings (*RIGID
    BODY with springs and holds on its nodes); the gear on a rigid joint (the shaft's
    slice under its hub held rigid) or a distributing one (two mass nodes that six
    *EQUATIONs tie to the mean motion of the section at its centre)."""
    from dataclasses import replace

    from shaftfem.fem.installation import install
    from shaftfem.scene.load import scene_from_dict

    data = {"shaft": {"length_mm": 320.0, "diameter_mm": 32.0},
            "material": {"youngs_modulus_mpa": 211000.0, "poisson_ratio": 0.277,
                         "density_kg_m3": 7870.0},
            "mesh": {"element_size_mm": 12.0},
            "support": [dict(position_mm=5, width_mm=10, kind="rigid", coupling=coupling),
                        dict(position_mm=310, width_mm=10, kind="springs",
                             radial_stiffness_n_per_mm=1e4, axial_stiffness_n_per_mm=1e3,
                             tilting_stiffness_nmm_per_rad=1e5, coupling=coupling)],
            "attachment": [dict(position_mm=160, width_mm=6, mass_kg=2.0, joint=joint,
                                polar_inertia_kg_m2=6e-4, diametral_inertia_kg_m2=4e-4)]}
    exact = run_modes(scene_from_dict(data, "installed.toml"))
    assert exact.modes.n_rigid == 1
    s = assemble(exact.mesh, exact.scene.material, mass_intorder=2)
    inst = install(exact.scene, s.K, s.M, s.nodes, exact.mesh.to_skfem(), 2)
    four = modal_analysis(s, installed=inst)
    # a distributing joint's means are weighted by the mass: the 4-point mass's here
    write_calculix(replace(exact, installed=inst), tmp_path / "shaft.inp")
    p = subprocess.run(["ccx", "-i", "shaft"], cwd=tmp_path, capture_output=True, text=True,
                       timeout=600)
    assert p.returncode == 0, p.stdout[-2000:]
    ccx = read_calculix_eig(tmp_path / "shaft.eig")[1:11]
    d = np.max(np.abs(four.frequencies / ccx - 1))
    with capsys.disabled():
        print(f"\n  CalculiX vs shaftfem, installed cylinder, {coupling} bearings, {joint} gear "
              f"({four.n_dofs} DOFs): {d:.1e}")
    assert d < 1e-6
