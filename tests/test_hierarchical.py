"""Hierarchical elements of orders 3 and 4: the same space as the Lagrange cubic, conforming
on any vertex order, nested (frequencies fall with the order), free of strain under rigid
motions, and converging towards the closed form."""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as sla

from references import torsion_hz


@pytest.fixture(scope="module")
def runs(cylinder):
    """The 32 x 550 mm cylinder on one 16 mm mesh at orders 2, 3 and 4."""
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    return {p: run_modes(with_mesh(cylinder.scene, 16.0, order=p)) for p in (2, 3, 4)}


def _elastic_hz(K, M, n=10):
    """The first n elastic frequencies of a free body, Hz (six rigid modes skipped), each
    the Rayleigh quotient of its eigenvector: ARPACK's eigenvalues near its shift of
    almost zero (the rigid modes) came out only to about 1e-10, the quotient of the same
    vectors is exact to the square of their error."""
    sigma = -1e-8 * np.median(K.diagonal() / M.diagonal())
    _, X = sla.eigsh(K, n + 6, M, sigma=sigma, which="LM", tol=1e-13)
    w = np.einsum("ij,ij->j", X, K @ X) / np.einsum("ij,ij->j", X, M @ X)
    return np.sqrt(np.sort(w)[6:]) / (2 * np.pi)


def test_order_3_is_the_lagrange_cubic_space(runs, cylinder):
    """The cubic Lagrange element, assembled by scikit-fem's own forms on the same mesh and
    quadrature, gives the hierarchical order-3 frequencies to 1e-10: one space, two bases."""
    from skfem import Basis, BilinearForm

    from shaftfem.cad.tetrahedra import lagrange_cubic
    from shaftfem.fem.assembly import MASS_INTORDER, STIFFNESS_INTORDER

    mesh = runs[3].mesh.to_skfem()
    m = cylinder.scene.material
    lam, mu = m.lame
    kb = Basis(mesh, lagrange_cubic()(), intorder=STIFFNESS_INTORDER[3])
    blocks = [[None] * 3 for _ in range(3)]
    for c in range(3):
        for d in range(3):
            def form(u, v, _, c=c, d=d):  # test component c, trial component d
                val = lam * u.grad[d] * v.grad[c] + mu * u.grad[c] * v.grad[d]
                return val + mu * sum(u.grad[k] * v.grad[k] for k in range(3)) * (c == d)
            blocks[c][d] = BilinearForm(form).assemble(kb)
    mb = Basis(mesh, lagrange_cubic()(), intorder=MASS_INTORDER[3])
    Ms = BilinearForm(lambda u, v, _: m.density * u * v).assemble(mb)
    f = _elastic_hz(sp.bmat(blocks).tocsr(), sp.block_diag([Ms] * 3).tocsr())
    assert np.max(np.abs(runs[3].modes.frequencies / f - 1)) < 1e-10


def test_hierarchical_elements_are_conforming_for_any_vertex_order():
    """A quartic field lies in the order-4 space of a mesh whose cells list their vertices
    in any order (sorted as the elements need them): its L2 projection is itself, and its
    energy int |grad u|^2 over the unit cube is exact. A function whose edge or face
    coefficients neighbours read in different orders would miss it."""
    from skfem import Basis, BilinearForm, LinearForm, MeshTet1
    from skfem.helpers import dot, grad

    from shaftfem.cad.mesh import sorted_cells
    from shaftfem.fem.elements import hierarchical

    m = MeshTet1().refined(1)
    t = m.t.T.copy()
    rng = np.random.default_rng(2)
    for row in t:
        rng.shuffle(row)
    mesh = MeshTet1(m.p, sorted_cells(t).T)
    basis = Basis(mesh, hierarchical(4), intorder=8)
    M = BilinearForm(lambda u, v, _: u * v).assemble(basis)
    K = BilinearForm(lambda u, v, _: dot(grad(u), grad(v))).assemble(basis)
    b = LinearForm(lambda v, w: (w.x[0] ** 4 + w.x[0] * w.x[1] * w.x[2] ** 2) * v).assemble(basis)
    c = sla.spsolve(M.tocsc(), b)
    # int (4x^3 + y z^2)^2 + (x z^2)^2 + (2 x y z)^2 over the unit cube
    exact = (16 / 7 + 8 / 24 + 1 / 15) + 1 / 15 + 4 / 27
    assert abs(c @ K @ c - exact) < 1e-10


def test_frequencies_fall_with_the_order(runs):
    """Nested spaces on one mesh: every frequency at order p + 1 at or below order p's,
    and order 4's functions of degree <= 3 are order 3's space: K and M restricted to them
    give frequencies at or above order 4's, and order 3's but for the quadrature (order 3
    integrates on a coarser rule, inexact on curved elements)."""
    from shaftfem.fem.hierarchy import lower_order

    f = [runs[p].modes.frequencies for p in (2, 3, 4)]
    # runs of their own order integrate on their own rules: nested up to quadrature
    assert np.all(f[1] <= f[0] * (1 + 1e-6)) and np.all(f[2] <= f[1] * (1 + 1e-6))
    assert runs[4].modes.n_dofs > 2 * runs[3].modes.n_dofs > 6 * runs[2].modes.n_dofs
    three, keep = lower_order(runs[4].system)
    two, _ = lower_order(three)
    assert three.n_dofs == runs[3].modes.n_dofs and two.n_dofs == runs[2].modes.n_dofs
    g3 = _elastic_hz(three.K.tocsc(), three.M.tocsc())
    g2 = _elastic_hz(two.K.tocsc(), two.M.tocsc())
    assert np.all(g3 >= f[2] * (1 - 1e-12)) and np.all(g2 >= g3 * (1 - 1e-12))
    # the same spaces as orders 3 and 2 but for quadrature (order 2 integrates its
    # stiffness on 4 points, exact on straight elements only: 5e-4 on 16 mm curved ones)
    assert np.max(np.abs(g3 / f[1] - 1)) < 1e-5 and np.max(np.abs(g2 / f[0] - 1)) < 1e-3
    # the same functions: any vector of order 3's restricted system, raised into order
    # 4's space, has the same strain energy and mass there
    from shaftfem.fem.hierarchy import raised

    X = np.random.default_rng(1).standard_normal((three.n_dofs, 2))
    Y = raised(X, keep, runs[4].system.nodes.shape[0])
    K4, M4 = runs[4].system.K, runs[4].system.M
    assert np.allclose(Y.T @ K4 @ Y, X.T @ three.K @ X, rtol=1e-12)
    assert np.allclose(Y.T @ M4 @ Y, X.T @ three.M @ X, rtol=1e-12)


def test_rigid_motions_cost_no_strain_at_every_order(runs):
    from shaftfem.fem.supports import rigid_body_modes

    for p in (3, 4):
        s = runs[p].system
        R = rigid_body_modes(s.nodes, constant=s.constant)
        KR = s.K @ R
        assert np.max(np.linalg.norm(KR, axis=0)
                      / (abs(s.K).max() * np.linalg.norm(R, axis=0))) < 1e-12, p
        assert runs[p].modes.n_rigid == 6 and runs[p].modes.residuals.max() < 1e-8, p
        assert runs[p].modes.kinds == runs[2].modes.kinds, p


def test_torsion_converges_with_the_order_towards_ct_over_2l(runs, cylinder):
    m, L = cylinder.scene.material, cylinder.scene.shaft.length
    ct = torsion_hz(1, L, m.youngs_modulus, m.poisson_ratio, m.density)
    err = [runs[p].modes.frequencies[runs[p].modes.kinds.index("torsion")] / ct - 1
           for p in (2, 3, 4)]
    # orders 3 and 4 both reach the floor of the quadratic geometry (about 5e-6 here)
    assert 0 < err[2] < 2e-5 < 1e-4 < err[0] and 0 < err[1] < 2e-5, err


def test_the_bound_of_three_nested_orders_is_exact_at_a_measured_rate():
    """Frequencies whose errors fall as C N^-b: the rate measured from the three drops is
    b, and the estimate of the top order's error is its true error (the bound
    HIERARCHY_SAFETY times it, plus the geometry allowance)."""
    from shaftfem.fem.estimate import HIERARCHY_SAFETY, SAFETY, hierarchy_estimate, measured_rate

    dofs = (30_000, 90_000, 210_000)
    for b in (0.7, 1.05, 2.0):
        e = [0.02 * (n / 1e4) ** -b for n in dofs]
        assert measured_rate(dofs, (e[1] - e[2]) / (e[0] - e[1])) == pytest.approx(b, rel=1e-9)
    exact = np.array([500.0, 900.0])
    errs = np.array([[0.02 * (n / 1e4) ** -b for n in dofs] for b in (0.8, 1.3)])
    f = tuple(exact * (1 + errs[:, k]) for k in range(3))
    est = hierarchy_estimate(f, dofs, recovery=np.zeros(2), geometry=1e-5)
    assert est.reliable.all()
    true = f[2] / exact - 1          # the estimate is relative to f_p: true / (1 + true)
    assert np.allclose(est.two_mesh, true / (1 + true), rtol=1e-6)
    assert np.allclose(est.relative_error, HIERARCHY_SAFETY * est.two_mesh + 1e-5)
    # drops that do not fall: no rate, the recovery estimate stands, and it is said
    flat = hierarchy_estimate((f[0], f[0] - (f[0] - f[1]) / 4, f[1]), dofs,
                              recovery=np.array([1e-3, 2e-3]))
    assert not flat.reliable.any() and np.allclose(flat.relative_error, SAFETY * np.array([1e-3, 2e-3]))
    assert "recovery estimate alone" in flat.notes[0]


def test_order_4_bound_holds_on_the_cylinder(runs, cylinder):
    """Order 4's bound from orders 2 and 3 inside its space: every mode's rate measured,
    and the torsion mode's bound above its true error against c_t / 2L."""
    from shaftfem.workflows.bounded import estimate_errors

    r = runs[4]
    est = estimate_errors(r)
    assert est.reliable.all() and "nested orders" in est.method
    # every rate measured: the recovery estimate, the fallback, was never computed
    assert np.isnan(est.recovery).all()
    m, L = cylinder.scene.material, cylinder.scene.shaft.length
    k = r.modes.kinds.index("torsion")
    ct = torsion_hz(1, L, m.youngs_modulus, m.poisson_ratio, m.density)
    assert est.relative_error[k] > abs(r.modes.frequencies[k] / ct - 1)


def test_a_space_inside_assembles_as_the_whole_space_restricted(runs):
    """Orders 2-4 at random per element: assembling only their space gives the K, M and
    values at the points of the whole order-4 space restricted to it (the same entries
    summed, to round-off), and keeps the same functions."""
    from shaftfem.fem.hierarchy import assemble_space, restricted, spanned

    r = runs[4]
    orders = np.random.default_rng(7).integers(2, 5, r.mesh.n_elements)
    keep = spanned(r.system, orders)
    whole = restricted(r.system, keep, 4)
    direct, inside = assemble_space(r.mesh, r.scene.material, orders)
    assert np.array_equal(np.flatnonzero(inside), keep) and inside.size == r.system.nodes.shape[0]
    assert whole.n_dofs < r.system.n_dofs
    for name in ("K", "M", "mass_scalar", "point_values"):
        a, b = getattr(whole, name), getattr(direct, name)
        assert abs(a - b).max() <= 1e-13 * abs(a).max(), name
    assert np.array_equal(whole.constant, direct.constant)
    assert np.array_equal(whole.degrees, direct.degrees)
    assert np.allclose(whole.nodes, direct.nodes, rtol=0, atol=1e-15)


def test_every_order_a_scene_may_ask_for_has_its_quadrature_and_dof_estimate():
    """The orders the schema and the CLI accept each have a stiffness, mass and
    positive-weight rule and a DOFs-per-element estimate for the budget check."""
    from shaftfem.cad.mesh import DOFS_PER_ELEMENT
    from shaftfem.fem.assembly import MASS_INTORDER, POSITIVE_INTORDER, STIFFNESS_INTORDER
    from shaftfem.scene.schema import ELEMENT_ORDERS

    for table in (STIFFNESS_INTORDER, MASS_INTORDER, POSITIVE_INTORDER, DOFS_PER_ELEMENT):
        assert set(ELEMENT_ORDERS) <= set(table), table


def test_a_warm_bounded_run_refines_each_kept_solve_without_lanczos(runs, monkeypatch):
    """Run again with the cache, order 4 and the two orders inside it that bound it are
    each refined from their last solve on the mesh (kept shift and shapes): Lanczos never
    runs, and the frequencies, bounds and inertia counts are the cold run's (1e-9)."""
    from shaftfem.fem import eigen
    from shaftfem.workflows.bounded import estimate_errors
    from shaftfem.workflows.pipeline import run_modes

    r = runs[4]
    cold = estimate_errors(r)  # keeps the lower orders' solves
    monkeypatch.setattr(eigen, "eigsh", lambda *a, **k: pytest.fail("Lanczos ran"))
    warm = run_modes(r.scene)
    again = estimate_errors(warm)
    assert np.max(np.abs(warm.modes.frequencies / r.modes.frequencies - 1)) < 1e-9
    assert warm.modes.residuals.max() < 1e-8
    assert warm.modes.inertia_count == r.modes.inertia_count == 16
    assert np.max(np.abs(again.relative_error / cold.relative_error - 1)) < 1e-6


def test_the_solvers_analysis_reads_the_upper_triangle_of_k_as_assembled(runs):
    """The sparsity the solver's analysis starts from (built from the blocks' pattern,
    before any value) is the upper triangle of K as assembled, entry for entry."""
    from shaftfem.fem.assembly import discretise
    from shaftfem.fem.factor import upper_triangle

    for r in (runs[2], runs[4]):
        d = discretise(r.mesh)
        got, want = d.upper_structure(), upper_triangle(r.system.K)
        assert np.array_equal(got.indptr, want.indptr)
        assert np.array_equal(got.indices, want.indices)


def test_a_lower_order_is_proven_complete_under_the_count_of_the_space_around_it(
        runs, monkeypatch):
    """Order 3 inside order 4 has no more eigenvalues below a shift than order 4 (min-max):
    its pairs are proven complete by order 4's count, with no inertia factorisation,
    and are the pairs an inertia count proves. A ceiling the pairs do not meet falls
    back to the count."""
    from shaftfem.fem import factor
    from shaftfem.fem.hierarchy import lower_order
    from shaftfem.fem.modes import modal_analysis

    r = runs[4]
    lower, _ = lower_order(r.system)
    counted = modal_analysis(lower, r.scene.modes)
    shifts: list[float] = []
    count = factor.ShiftedFactor.count_below
    monkeypatch.setattr(factor.ShiftedFactor, "count_below",
                        lambda self, s: shifts.append(s) or count(self, s))
    top = (r.modes.inertia_shift, r.modes.inertia_count)
    nested = modal_analysis(lower, r.scene.modes, ceiling=top)
    assert not shifts and nested.inertia_count == r.modes.inertia_count
    # the same pairs, to the round-off of MKL's threads from one factorisation to the next
    np.testing.assert_allclose(nested.frequencies, counted.frequencies, rtol=1e-11)
    assert np.all(nested.frequencies >= r.modes.frequencies)
    wrong = modal_analysis(lower, r.scene.modes, ceiling=(top[0], top[1] - 1))
    assert shifts and wrong.inertia_count == counted.inertia_count
    np.testing.assert_allclose(wrong.frequencies, counted.frequencies, rtol=1e-11)
