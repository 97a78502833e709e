"""Cubic geometry ([mesh] geometry_order = 3): gmsh's 20-node tetrahedra as the elements
take them, every node on the CAD surface, the guards kept, the files other programs read
in their own node order, and a crash of native code in the mesher contained."""

import subprocess
import sys

import numpy as np
import pytest

from references import torsion_hz


@pytest.fixture(scope="module")
def cubic_runs(cylinder):
    """The 32 x 550 mm cylinder at 12 mm, cubic geometry, orders 3 and 4."""
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    return {p: run_modes(with_mesh(cylinder.scene, 12.0, order=p, geometry_order=3))
            for p in (3, 4)}


def test_tables_of_node_order_are_gmsh_and_vtk_own():
    import gmsh
    from vtkmodules.vtkCommonDataModel import vtkLagrangeTetra

    from shaftfem.cad.cubic import GMSH_NODES, VTK_NODES

    gmsh.initialize(readConfigFiles=False)
    try:
        t = gmsh.model.mesh.getElementType("tetrahedron", 3)
        theirs = np.array(gmsh.model.mesh.getElementProperties(t)[4]).reshape(-1, 3)
    finally:
        gmsh.finalize()
    assert np.allclose(theirs, GMSH_NODES, atol=1e-12)
    cell = vtkLagrangeTetra()
    cell.GetPointIds().SetNumberOfIds(20)
    cell.GetPoints().SetNumberOfPoints(20)
    cell.Initialize()
    p = cell.GetParametricCoords()
    assert np.allclose(np.array([p[i] for i in range(60)]).reshape(20, 3), VTK_NODES, atol=1e-12)


def test_every_node_of_the_boundary_is_on_the_cylinder(cubic_runs, cylinder):
    """The cubic map interpolates the surface at 20 nodes per element: every node on a
    boundary face (vertices, edge thirds, face centres) lies on r = R, z = 0 or z = L."""
    from shaftfem.cad.cubic import _boundary_nodes

    mesh, shaft = cubic_runs[3].mesh, cylinder.scene.shaft
    assert mesh.cells.shape[1] == 20 and mesh.geometry_order == 3
    p = mesh.points[_boundary_nodes(mesh.cells)]
    off = np.minimum.reduce([np.abs(np.hypot(p[:, 0], p[:, 1]) - shaft.radius),
                             np.abs(p[:, 2]), np.abs(p[:, 2] - shaft.length)])
    assert off.max() < 1e-9 * shaft.length
    # and more of them than a quadratic mesh has: two per edge and one per face
    assert len(p) > 2 * np.unique(mesh.cells[:, :4]).size / 3


def test_guards_hold_and_torsion_converges_on_cubic_geometry(cubic_runs, cylinder):
    """Six rigid modes (a conforming mesh), small residuals, K t = 0 (run_modes checks it),
    and the torsion mode near c_t / 2L at both orders, order 4 closer than order 3."""
    m, L = cylinder.scene.material, cylinder.scene.shaft.length
    ct = torsion_hz(1, L, m.youngs_modulus, m.poisson_ratio, m.density)
    err = {}
    for p, r in cubic_runs.items():
        assert r.modes.n_rigid == 6 and r.modes.residuals.max() < 1e-8, p
        assert r.mesh.min_jacobian_ratio > 0.02
        err[p] = abs(r.modes.frequencies[r.modes.kinds.index("torsion")] / ct - 1)
    # quadratic geometry reaches about 5e-6 here (its midpoints even by symmetry)
    assert err[4] < 2e-5 < err[3] < 3e-4, err


def test_boundary_nodes_sit_at_their_parametric_places(cubic_runs, cylinder):
    """On r = R, each boundary edge's two nodes at a third and two thirds of its angle
    and height (gmsh alone puts them nearer the ends: 0.325 of a 45-degree arc)."""
    from shaftfem.cad.tetrahedra import EDGES

    mesh, R = cubic_runs[3].mesh, cylinder.scene.shaft.radius
    p, c = mesh.points, mesh.cells
    on = np.abs(np.hypot(p[:, 0], p[:, 1]) - R) < 1e-9 * R
    theta = np.arctan2(p[:, 1], p[:, 0])
    checked = 0
    for k, (a, b) in enumerate(EDGES):
        for j, third in ((0, 1 / 3), (1, 2 / 3)):
            n = c[:, 4 + 2 * k + j]
            rows = on[c[:, a]] & on[c[:, b]] & on[n]
            ta, tb, tn = theta[c[rows, a]], theta[c[rows, b]], theta[n[rows]]
            tb = ta + np.angle(np.exp(1j * (tb - ta)))
            tn = ta + np.angle(np.exp(1j * (tn - ta)))
            za, zb, zn = p[c[rows, a], 2], p[c[rows, b], 2], p[n[rows], 2]
            assert np.allclose(tn, ta + third * (tb - ta), atol=1e-9)
            assert np.allclose(zn, za + third * (zb - za), atol=1e-12)
            checked += rows.sum()
    assert checked > 100


def test_the_elements_hold_the_cylinder_volume(cubic_runs, cylinder):
    """The cubic map's volume (on a rule exact for its det J) against pi R^2 L. A cubic
    through a circular arc of angle a at its parametric thirds lies outside it by
    R a^4 t (t - 1/3)(t - 2/3)(t - 1) / 24, on average R a^4 / 6480: the volume is
    high by at most twice that over R, a_max^4 / 3240 (the end faces are flat)."""
    from skfem import Basis

    from shaftfem.cad.tetrahedra import EDGES
    from shaftfem.fem.elements import element

    mesh, shaft = cubic_runs[3].mesh, cylinder.scene.shaft
    b = Basis(mesh.to_skfem(), element(3), intorder=7)
    volume = np.abs((b.mapping.detDF(b.X) * b.W).sum(axis=1)).sum()
    p, c = mesh.points, mesh.cells
    on = np.abs(np.hypot(p[:, 0], p[:, 1]) - shaft.radius) < 1e-9 * shaft.radius
    theta = np.arctan2(p[:, 1], p[:, 0])
    arc = 0.0
    for k, (i, j) in enumerate(EDGES):  # edges on the surface: their nodes on it too
        rows = on[c[:, i]] & on[c[:, j]] & on[c[:, 4 + 2 * k]]
        turn = np.angle(np.exp(1j * (theta[c[rows, j]] - theta[c[rows, i]])))
        arc = max(arc, float(np.abs(turn).max(initial=0.0)))
    error = volume / (np.pi * shaft.radius**2 * shaft.length) - 1
    assert 0 < error <= 1.05 * arc**4 / 3240, (error, arc)


def test_order_4_is_bounded_by_order_3_on_cubic_geometry(cubic_runs, cylinder):
    """No order below the geometry's moves the body rigidly, so order 4 on cubic geometry
    is bounded by order 3 alone, with both recovery estimates: every mode bounded, and
    the torsion mode's bound above its true error against c_t / 2L."""
    from shaftfem.workflows.bounded import estimate_errors

    r = cubic_runs[4]
    est = estimate_errors(r)
    assert "order 3 in the same space" in est.method
    assert np.all(np.isfinite(est.relative_error)) and np.all(est.relative_error > 0)
    m, L = cylinder.scene.material, cylinder.scene.shaft.length
    k = r.modes.kinds.index("torsion")
    ct = torsion_hz(1, L, m.youngs_modulus, m.poisson_ratio, m.density)
    assert est.relative_error[k] > abs(r.modes.frequencies[k] / ct - 1)


def test_order_3_on_cubic_geometry_is_bounded_on_a_coarser_mesh(cubic_runs, cylinder):
    """Order 3 on cubic geometry has no order below it that moves the body rigidly: its
    bound comes from a coarser cubic mesh, and the torsion mode lies inside it."""
    from shaftfem.workflows.bounded import estimate_errors

    r = cubic_runs[3]
    est = estimate_errors(r)
    assert "coarser mesh" in est.method
    m, L = cylinder.scene.material, cylinder.scene.shaft.length
    k = r.modes.kinds.index("torsion")
    ct = torsion_hz(1, L, m.youngs_modulus, m.poisson_ratio, m.density)
    assert est.relative_error[k] > abs(r.modes.frequencies[k] / ct - 1)


def test_orders_do_not_adapt_on_cubic_geometry():
    """--accuracy at order 4 on cubic geometry: a clear error (exit 2) before any
    meshing, naming the geometry order and what to use instead."""
    from shaftfem.errors import SceneError

    run = subprocess.run([sys.executable, "-m", "shaftfem", "modes", "plain_cylinder",
                          "--order", "4", "--geometry-order", "3", "--accuracy", "0.1", "-q"],
                         capture_output=True, text=True)
    assert run.returncode == SceneError.exit_code and "Traceback" not in run.stderr
    assert "cubic geometry" in run.stderr and "geometry order 2" in run.stderr, run.stderr


def test_files_carry_the_cubic_cells_in_each_program_order(cubic_runs, tmp_path):
    """The mode file: VTK Lagrange tetrahedra whose nodes sit where the cubic map puts
    VTK's reference points; mesh.msh: gmsh's 20-node tetrahedra, read back by gmsh."""
    import gmsh
    from vtkmodules.vtkCommonDataModel import VTK_LAGRANGE_TETRAHEDRON
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    from shaftfem.cad.cubic import GMSH_NODES, VTK_NODES
    from shaftfem.outputs.export import export_modes

    r = cubic_runs[3]
    mesh = r.mesh
    files = export_modes(r, tmp_path / "out")
    skmesh = mesh.to_skfem()

    def mapped(local, elements):
        """x at reference points `local` (20, 3) of `elements`: (E, 20, 3)."""
        return np.asarray(skmesh._mapping().F(np.ascontiguousarray(local.T),
                                              tind=elements)).transpose(1, 2, 0)

    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(next(f for f in files if f.name == "mode_01.vtu")))
    reader.Update()
    g = reader.GetOutput()
    assert g.GetNumberOfCells() == mesh.n_elements
    assert g.GetCellType(0) == VTK_LAGRANGE_TETRAHEDRON
    from vtkmodules.util.numpy_support import vtk_to_numpy

    pts = vtk_to_numpy(g.GetPoints().GetData())
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 20)
    sample = np.arange(0, mesh.n_elements, 7)
    # the reference points of VTK's order, vertices possibly swapped (positive orientation)
    got = pts[conn[sample]]
    for e, x in zip(sample, got):
        vols = np.linalg.det(x[1:4] - x[0])
        assert vols > 0
        assert np.isclose(x[:4], mesh.points[mesh.cells[e, :4]]).all(axis=1).sum() >= 2
    # each VTK cell's nodes are the cubic map at VTK's reference points, over its vertices
    from shaftfem.cad.tetrahedra import barycentric

    lam = barycentric(VTK_NODES)
    assert np.allclose(np.einsum("nk,ekd->end", lam[:4], got[:, :4]), got[:, :4])
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(tmp_path / "out" / "mesh.msh"))
        t = gmsh.model.mesh.getElementType("tetrahedron", 3)
        tags, _ = gmsh.model.mesh.getElementsByType(t)
        assert len(tags) == mesh.n_elements
        # gmsh's own map of its elements, at its nodes' reference points, is where our
        # cubic map puts the same physical points (the cells' vertex order may differ)
        jac, det, xg = gmsh.model.mesh.getJacobians(t, GMSH_NODES.ravel().tolist())
    finally:
        gmsh.finalize()
    assert (np.asarray(det) > 0).all()  # every element positively oriented
    xg = np.asarray(xg).reshape(len(tags), 20, 3)
    ours = np.sort(mapped(GMSH_NODES, np.arange(mesh.n_elements)).reshape(-1, 3), axis=0)
    assert np.allclose(np.sort(xg.reshape(-1, 3), axis=0), ours, atol=1e-12)


def test_geometry_order_3_needs_the_hierarchical_elements(tmp_path):
    """--geometry-order 3 at order 2: a clear error naming both settings, the scene
    error's exit status, no file written."""
    from shaftfem.errors import SceneError

    run = subprocess.run([sys.executable, "-m", "shaftfem", "export", "plain_cylinder",
                          "--order", "2", "--geometry-order", "3", "-q",
                          "--out", str(tmp_path / "o")],
                         capture_output=True, text=True)
    assert run.returncode == SceneError.exit_code and "Traceback" not in run.stderr
    assert "geometry order 3" in run.stderr and "element orders 3 to 5" in run.stderr
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_order_5_on_cubic_geometry(cylinder):
    """Order 5 on a cubic mesh (16 mm): six rigid modes at zero strain; its bound from
    orders 3 and 4 inside its space (three nested orders) measures a rate on every mode,
    which takes frequencies falling from order 3 to 4 to 5; the torsion mode within 2e-6
    of c_t / 2L (the floor of this cubic geometry: orders 4 and 5 sit on it, 8e-7 and
    9e-7 off) and inside its bound."""
    from shaftfem.fem.supports import rigid_body_modes
    from shaftfem.workflows.bounded import estimate_errors
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    r = run_modes(with_mesh(cylinder.scene, 16.0, order=5, geometry_order=3))
    s, f5 = r.system, r.modes.frequencies
    R = rigid_body_modes(s.nodes, constant=s.constant)
    assert np.max(np.linalg.norm(s.K @ R, axis=0)
                  / (abs(s.K).max() * np.linalg.norm(R, axis=0))) < 1e-12
    assert r.modes.n_rigid == 6 and r.modes.residuals.max() < 1e-8
    m, L = cylinder.scene.material, cylinder.scene.shaft.length
    ct = torsion_hz(1, L, m.youngs_modulus, m.poisson_ratio, m.density)
    k = r.modes.kinds.index("torsion")
    assert abs(f5[k] / ct - 1) < 2e-6
    est = estimate_errors(r)
    assert "three nested orders" in est.method and est.reliable.all()
    assert est.relative_error[k] > abs(f5[k] / ct - 1)


@pytest.mark.slow
def test_a_cubic_mesh_of_the_grooved_shaft_is_the_same_every_time():
    """The paper's shaft meshed twice at 16/12/12 mm with cubic geometry, from nothing
    cached: the same points and cells, bit for bit (nothing in the route depends on
    thread timing), every element valid."""
    from dataclasses import replace

    from shaftfem.cad.tetrahedra import MIN_JACOBIAN_RATIO
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows import stages

    scene = load_scene("paper2018")
    settings = replace(scene.mesh, size=16e-3, groove_size=12e-3, edge_size=12e-3, order=4,
                       geometry_order=3)
    _, shape = stages.solid(scene)
    a, b = (stages.mesh(shape, scene.shaft, scene.grooves, settings, use_cache=False)
            for _ in range(2))
    assert a.cells.shape[1] == 20 and a.n_elements > 1000
    assert np.array_equal(a.cells, b.cells)
    assert np.array_equal(a.points, b.points)
    assert a.min_jacobian_ratio > MIN_JACOBIAN_RATIO
