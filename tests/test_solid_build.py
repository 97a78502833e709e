"""The grooved solid built fast (cells glued on their shared faces) is the solid a
general boolean fragment of the same pieces makes: same volume, same mesh."""

import numpy as np
import pytest

from shaftfem.cad import build
from shaftfem.cad.mesher import mesh_solid
from shaftfem.scene.model import Grooves, MeshSettings, Shaft


def _general_fragment(gmsh, first, rest):
    """What the solid was glued with before: a fragment that intersects every face."""
    gmsh.model.occ.fragment([(3, first)], [(3, t) for t in rest])


@pytest.mark.parametrize("start, root_radius", [
    pytest.param(0.02, 0.001, marks=pytest.mark.slow), (0.0, 0.0)])
def test_glued_cells_make_the_solid_and_mesh_of_a_general_fragment(
        tmp_path, monkeypatch, start, root_radius):
    # two full cells and a 15 mm one, with and without a plain start
    g = Grooves(hands=(1, -1), pitch=0.06, width=0.008, depth=0.003,
                root_radius=root_radius, length=0.075, start=start)
    shaft = Shaft(length=start + 0.075 + 0.02, diameter=0.032)
    settings = MeshSettings(size=0.008, groove_size=0.004, edge_size=0.004, order=2)
    glued = build.build_solid(shaft, g, tmp_path / "glued.brep")
    monkeypatch.setattr(build, "glue", _general_fragment)
    general = build.build_solid(shaft, g, tmp_path / "general.brep")
    assert glued == general       # volume (m^3) to the last bit, and the volume count
    a = mesh_solid(tmp_path / "glued.brep", shaft, g, settings)
    b = mesh_solid(tmp_path / "general.brep", shaft, g, settings)
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
