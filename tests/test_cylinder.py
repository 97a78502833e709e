"""The plain cylinder against closed-form and independent beam references."""

import numpy as np

from references import axial_love_hz, timoshenko_free_free_hz, torsion_hz

# Expected order of the first ten modes of a 32 x 550 mm steel bar, from the
# references below: bending pairs 1-3, torsion, bending pair 4, axial.
EXPECTED_KINDS = ["bending"] * 6 + ["torsion"] + ["bending"] * 2 + ["axial"]


def _props(result):
    s, m = result.scene.shaft, result.scene.material
    return s.length, s.radius, m.youngs_modulus, m.poisson_ratio, m.density


def test_six_rigid_body_modes(cylinder):
    assert cylinder.modes.n_rigid == 6
    assert np.all(cylinder.modes.rigid_frequencies < 0.1)  # Hz, against 483 Hz for mode 1


def test_kinds_follow_the_analytic_order(cylinder):
    assert cylinder.modes.kinds == EXPECTED_KINDS


def test_first_torsion_within_1e4_of_ct_over_2L(cylinder):
    L, R, E, nu, rho = _props(cylinder)
    f = cylinder.modes.frequencies[cylinder.modes.kinds.index("torsion")]
    assert abs(f / torsion_hz(1, L, E, nu, rho) - 1) < 1e-4


def test_first_axial_within_1e4_of_love_rod(cylinder):
    L, R, E, nu, rho = _props(cylinder)
    f = cylinder.modes.frequencies[cylinder.modes.kinds.index("axial")]
    assert abs(f / axial_love_hz(1, L, R, E, nu, rho) - 1) < 1e-4


def test_bending_pairs_within_half_percent_of_timoshenko(cylinder):
    L, R, E, nu, rho = _props(cylinder)
    ref = timoshenko_free_free_hz(4, L, R, E, nu, rho)
    f = cylinder.modes.frequencies
    bending = [f[i] for i, k in enumerate(cylinder.modes.kinds) if k == "bending"]
    for n in range(4):
        a, b = bending[2 * n], bending[2 * n + 1]
        assert abs(a / ref[n] - 1) < 5e-3, (n, a, ref[n])
        assert abs(b / a - 1) < 1e-6, f"pair {n + 1} split: {a} vs {b} Hz"


def test_residuals_and_mass_orthonormality(cylinder):
    assert np.all(cylinder.modes.residuals < 1e-8)
    assert cylinder.modes.orthonormality_error < 1e-8
    # and independently of the solver's own bookkeeping:
    X, M = cylinder.modes.shapes, cylinder.system.M
    assert np.max(np.abs(X.T @ (M @ X) - np.eye(X.shape[1]))) < 1e-8


def test_p1_is_stiffer_than_p2(cylinder):
    """Linear tets lock: at the same mesh P1 frequencies sit well above P2's."""
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    p1 = run_modes(with_mesh(cylinder.scene, order=1))
    L, R, E, nu, rho = _props(cylinder)
    ft = torsion_hz(1, L, E, nu, rho)
    f1 = p1.modes.frequencies[p1.modes.kinds.index("torsion")]
    assert f1 / ft - 1 > 10 * abs(
        cylinder.modes.frequencies[cylinder.modes.kinds.index("torsion")] / ft - 1)
    assert p1.modes.n_rigid == 6


# --------------------------------------------------------------------------
# Cubic elements (order 3) on the same curved quadratic geometry


def test_cubic_elements_are_conforming_and_exact_for_cubic_fields():
    """On a straight-sided mesh whose cells list their vertices in any order, the cubic
    element interpolates a cubic field exactly across element faces: its energy
    int |grad u|^2 over the unit cube is exact (a swapped edge node between two
    neighbours would change it)."""
    from skfem import Basis, BilinearForm, MeshTet1, MeshTet2
    from skfem.helpers import dot, grad

    from shaftfem.cad.tetrahedra import EDGES, lagrange_cubic, sorted_cells

    m = MeshTet1().refined(2)
    t = m.t.T.copy()
    rng = np.random.default_rng(1)
    for row in t:
        rng.shuffle(row)                      # as gmsh lists them: no order
    points, mid = list(m.p.T), {}
    cells = []
    for c in t:
        for a, b in EDGES:
            mid.setdefault(tuple(sorted((c[a], c[b]))), len(points) + len(mid))
        cells.append(list(c) + [mid[tuple(sorted((c[a], c[b])))] for a, b in EDGES])
    points += [(m.p[:, a] + m.p[:, b]) / 2 for a, b in sorted(mid, key=mid.get)]
    mesh = MeshTet2(np.array(points).T, sorted_cells(np.array(cells)).T)
    basis = Basis(mesh, lagrange_cubic()(), intorder=6)
    K = BilinearForm(lambda u, v, _: dot(grad(u), grad(v))).assemble(basis)
    x, y, z = basis.doflocs
    u = x**3 + x * y * z
    exact = 9 / 5 + 6 / 12 + 3 / 9     # int (3x^2 + yz)^2 + (xz)^2 + (xy)^2
    assert abs(u @ K @ u - exact) < 1e-12


def test_cubic_elements_converge_faster_and_lie_below_quadratic_ones(cylinder):
    """P3 on the same mesh: a space containing P2's, so every frequency is at or below
    P2's (min-max); the torsion mode comes within 2e-5 of c_t / 2L, where P2 is 6e-4
    off; K takes the six rigid motions to zero and the solver finds them."""
    from shaftfem.fem.supports import rigid_body_modes
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    p2 = run_modes(with_mesh(cylinder.scene, 16.0))
    p3 = run_modes(with_mesh(cylinder.scene, 16.0, order=3))
    assert p3.mesh.n_elements == p2.mesh.n_elements and p3.modes.n_dofs > 3 * p2.modes.n_dofs
    assert np.all(p3.modes.frequencies <= p2.modes.frequencies * (1 + 1e-12))
    m = cylinder.scene.material
    ct = np.sqrt(m.shear_modulus / m.density) / (2 * cylinder.scene.shaft.length)
    err = [abs(r.modes.frequencies[r.modes.kinds.index("torsion")] / ct - 1) for r in (p2, p3)]
    assert err[1] < 2e-5 < 4e-4 < err[0], err
    R = rigid_body_modes(p3.system.nodes, constant=p3.system.constant)
    KR = p3.system.K @ R
    K_max = abs(p3.system.K).max()
    assert np.max(np.linalg.norm(KR, axis=0) / (K_max * np.linalg.norm(R, axis=0))) < 1e-12
    assert p3.modes.n_rigid == 6 and p3.modes.residuals.max() < 1e-8
    # the mode shapes at the mesh's points (export, pictures) are the P3 fields there
    u = p3.shapes_at_points()
    assert u.shape == (p3.modes.count, p3.mesh.points.shape[0], 3) and np.all(np.isfinite(u))
