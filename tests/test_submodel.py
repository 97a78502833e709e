"""A hot spot's local model (fem.submodel, cad.local): the whole's field read on its cut
faces, and the slice's solve, against fields known in closed form."""

from __future__ import annotations

import numpy as np
import pytest

from shaftfem.fem.submodel import driven_solve, read_displacements


def p2_mesh(curved: bool):
    """A unit-ish cylinder's P2 mesh (points, VTK-ordered cells): curved onto the
    cylinder, or straight-sided."""
    from skfem import MeshTet

    m = MeshTet.init_tensor(np.linspace(-1, 1, 5), np.linspace(-1, 1, 5), np.linspace(0, 2, 5))
    p, t = m.p.T, m.t.T
    edges = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))
    mids = {}
    points = [*p]
    cells = []
    for tet in t:
        row = list(tet)
        for i, j in edges:
            key = tuple(sorted((tet[i], tet[j])))
            if key not in mids:
                mids[key] = len(points)
                x = 0.5 * (p[key[0]] + p[key[1]])
                if curved:   # bulge the midpoints: a curved map, as gmsh's on a surface
                    x = x + 0.05 * np.array([np.sin(3 * x[2]), np.cos(2 * x[0]), 0.0])
                points.append(x)
            row.append(mids[key])
        cells.append(row)
    return np.array(points) * 1e-2, np.array(cells)


@pytest.mark.parametrize("curved", [False, True])
def test_the_wholes_field_is_read_exactly_where_its_elements_hold_it(curved):
    points, cells = p2_mesh(curved)
    rng = np.random.default_rng(1)
    at = rng.uniform([-0.009, -0.009, 0.001], [0.009, 0.009, 0.019], (200, 3))
    # a linear field: every isoparametric element holds it exactly, curved or not
    A = rng.normal(size=(3, 3))
    u = (points @ A.T)[None]
    read = read_displacements(points, cells, u, at)
    assert np.abs(read[0] - at @ A.T).max() < 1e-12
    if not curved:   # and a quadratic one on straight elements
        q = points[:, :1] * points[:, 2:] * np.ones(3)
        read = read_displacements(points, cells, q[None], at)
        assert np.abs(read[0] - at[:, :1] * at[:, 2:]).max() < 1e-15 + 1e-12 * np.abs(q).max()


def test_a_point_outside_the_whole_is_refused():
    from shaftfem.errors import SolverError

    points, cells = p2_mesh(False)
    with pytest.raises(SolverError, match="outside the whole shaft's mesh"):
        read_displacements(points, cells, points[None], np.array([[0.0, 0.0, 0.05]]))


def test_a_slice_driven_by_a_uniform_stretch_carries_the_uniform_stress():
    """A bar slice, its two cut faces moved as a uniform axial strain e and Poisson's
    contraction say: sigma_zz = E e everywhere, the rest 0 (the patch test)."""
    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.fem.assembly import _element, assemble
    from shaftfem.fem.stress import surface_stress
    from shaftfem.scene.model import Material

    points, cells = p2_mesh(False)
    mesh = ShaftMesh(points=points, cells=cells, order=2, min_jacobian_ratio=1.0,
                     straightened=0)
    steel = Material(name="steel", youngs_modulus=210e9, poisson_ratio=0.3, density=7850.0)
    system = assemble(mesh, steel)
    nodes = system.nodes
    cut = (np.abs(nodes[:, 2]) < 1e-12) | (np.abs(nodes[:, 2] - 0.02) < 1e-12)
    e = 1e-3
    field = np.column_stack([-0.3 * e * nodes[:, 0], -0.3 * e * nodes[:, 1], e * nodes[:, 2]])
    held = np.flatnonzero(np.repeat(cut, 3))
    U = driven_solve(system.K, np.zeros((system.n_dofs, 1)), held, field[cut].reshape(-1, 1))
    sigma = surface_stress(mesh.to_skfem(), _element(2), steel.lame, U).all_stress[0]
    assert np.abs(sigma[:, 2, 2] / (210e9 * e) - 1).max() < 1e-9
    other = sigma.copy()
    other[:, 2, 2] = 0
    assert np.abs(other).max() < 1e-9 * 210e9 * e


def test_a_floating_face_takes_its_bending_from_the_moment_it_carries_not_the_wholes_motion():
    """Pure bending of a square bar (curvature kappa about x, St Venant's exact field,
    quadratic): the first face held as the field moves it, the second given the field
    with a wrong rigid motion added (a stiffer whole's rotation) and the moment E kappa I
    it carries: sigma_zz = E kappa y everywhere, as the floating face turns by its own."""
    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.fem.assembly import _element, assemble
    from shaftfem.fem.stress import surface_stress
    from shaftfem.fem.submodel import rigid_motions
    from shaftfem.scene.model import Material

    points, cells = p2_mesh(False)
    mesh = ShaftMesh(points=points, cells=cells, order=2, min_jacobian_ratio=1.0,
                     straightened=0)
    E, nu = 210e9, 0.3
    steel = Material(name="steel", youngs_modulus=E, poisson_ratio=nu, density=7850.0)
    system = assemble(mesh, steel)
    nodes = system.nodes
    x, y, z = nodes.T
    k = 0.05
    exact = np.column_stack([-nu * k * x * y, 0.5 * k * (nu * (x * x - y * y) - z * z), k * y * z])
    left, right = np.abs(z) < 1e-12, np.abs(z - 0.02) < 1e-12
    centre = np.array([0.0, 0.0, 0.02])
    wrong = exact[right] + (rigid_motions(nodes[right], centre)
                            @ np.array([1e-5, -2e-5, 3e-6, 0.3 * k * 0.02, 1e-4, 2e-4])
                            ).reshape(-1, 3)
    inertia = 0.02 ** 4 / 12
    load = np.array([[0.0, 0.0, 0.0, E * k * inertia, 0.0, 0.0]])
    U = driven_solve(system.K, np.zeros((system.n_dofs, 1)),
                     np.flatnonzero(np.repeat(left, 3)), exact[left].reshape(-1, 1),
                     np.flatnonzero(np.repeat(right, 3)), wrong.reshape(-1, 1),
                     rigid_motions(nodes[right], centre), load)
    surface = surface_stress(mesh.to_skfem(), _element(2), steel.lame, U)
    sigma, p = surface.all_stress[0], surface.p1_basis.mesh.p.T
    used = np.unique(surface.p1_basis.mesh.t)
    sigma, p = sigma[used], p[used]
    assert np.abs(sigma[:, 2, 2] - E * k * p[:, 1]).max() < 1e-8 * E * k * 0.01
    assert np.abs(U[:, 0].reshape(-1, 3) - exact).max() < 1e-9 * k * 0.02 ** 2


def test_a_slice_whose_face_does_not_carry_what_the_whole_carries_there_is_refused():
    """The held face's reaction against the whole's resultant across it (the nodal
    forces beyond the plane): equal passes, 20 % short is refused."""
    import scipy.sparse as sp

    from shaftfem.errors import SolverError
    from shaftfem.workflows import strength as ws

    face = np.array([[0.01, 0.0, 0.1], [0.0, 0.01, 0.1], [-0.01, 0.0, 0.1], [0.0, -0.01, 0.1]])
    whole = ws._Field(points=face, normals=face, edge=face[:, 0], stress=None,
                      amplitude=None, mean=None, peak=None, all_stress=None, vertices=face,
                      tets=None, facets=None, allowed=None, line=None, dofs=0,
                      node_xyz=np.array([[0.0, 0.0, 0.05], [0.0, 0.0, 0.2]]),
                      node_force=np.array([[[0.0, 0.0, 100.0], [0.0, 0.0, -100.0]]]))
    K, F, dofs = sp.identity(12, format="csr"), np.zeros((12, 1)), np.arange(12)
    pull = np.tile([0.0, 0.0, 25.0], 4)[:, None]   # the slice beyond z = 0.1 is pulled back
    ws._check_balance(K, F, pull, dofs, face, 0.1, whole, True, np.zeros((1, 6)))
    with pytest.raises(SolverError, match="does not balance"):
        ws._check_balance(K, F, 0.8 * pull, dofs, face, 0.1, whole, True, np.zeros((1, 6)))


def test_a_point_among_many_small_elements_is_found_in_the_large_one_holding_it():
    """One large straight tetrahedron, and beside its face many small ones whose centres
    lie nearer a point inside it than its own centre (as at a runout's seam): the point is
    read in the large one, a linear field exactly (the nearest centres alone hold none)."""
    from shaftfem.fem.submodel import CANDIDATES

    edges = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))

    def tet(corners):
        c = np.asarray(corners, dtype=float)
        return np.vstack([c, [0.5 * (c[i] + c[j]) for i, j in edges]])

    big = tet([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)])
    small = [tet(np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, -1)]) * 0.02
                 + (0.01 * i, 0.01 * j, 0.0))
             for i in range(6) for j in range(6)]
    blocks = [big, *small]
    points = np.vstack(blocks)
    cells = np.arange(len(points)).reshape(len(blocks), 10)
    at = np.array([[0.03, 0.03, 0.03]])
    centres = points[cells[:, :4]].mean(axis=1)
    d = np.linalg.norm(centres - at, axis=1)
    assert (d[1:] < d[0]).sum() > CANDIDATES
    a = np.array([[1.0, 2.0, -1.0], [0.5, 0.0, 3.0], [2.0, -1.0, 1.0]])
    u = (points @ a.T)[None]
    got = read_displacements(points, cells, u, at)
    assert np.allclose(got[0], at @ a.T, atol=1e-12)
