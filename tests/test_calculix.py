"""Cross-check with CalculiX (ccx), a solver nobody here wrote, on the same mesh.

CalculiX's C3D10 integrates stiffness and mass with the 4-point rule. With the
same rule our frequencies must agree to round-off; with our exact (order-4)
consistent mass they differ by about 1e-4 on coarse meshes, less on finer ones.
"""

import shutil
import subprocess

import numpy as np
import pytest

from shaftfem.assembly import assemble
from shaftfem.export import read_calculix_eig, read_calculix_frequencies, write_calculix
from shaftfem.modal import modal_analysis
from shaftfem.pipeline import run_modes, with_mesh
from shaftfem.scene import load_scene

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


# the grooved shaft's case takes about 70 s: slow (pytest -m slow)
CASES = [("plain_cylinder", 12.0), ("plain_cylinder", 8.0),
         pytest.param("paper2018", 12.0, marks=pytest.mark.slow)]


@pytest.mark.parametrize("scene,size", CASES)
def test_same_mesh_same_frequencies(scene, size, tmp_path, capsys):
    exact = run_modes(with_mesh(load_scene(scene), size))  # our default: exact P2 mass
    # CalculiX's 4-point mass on the very same mesh (gmsh's high-order optimiser does
    # not place curved nodes bit-identically twice, so the mesh is not re-made)
    s = assemble(exact.mesh, exact.scene.material, mass_intorder=2)
    four = modal_analysis(s.K, s.M, s.nodes, s.mass_scalar)
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
