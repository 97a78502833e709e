"""The eigensolver proves it skipped no mode: the inertia of K - s M counts the
eigenvalues below s, and every pair it returns has a small residual."""

import re

import numpy as np
import pytest
import scipy.linalg as la
import scipy.sparse as sp

from shaftfem.errors import SolverError
from shaftfem.fem import eigen
from shaftfem.fem.eigen import SolverSettings
from shaftfem.fem.factor import Pencil, ShiftedFactor, available_factorisers
from shaftfem.fem.modes import modal_analysis
from shaftfem.fem.supports import rigid_body_modes
from shaftfem.scene.model import ModeRequest


def _chain(n=300, cut=None):
    """A free-free spring-mass chain with uneven masses: one rigid mode, distinct
    eigenvalues. `cut`: that spring removed (two bodies)."""
    k = 1.0 + np.random.default_rng(1).random(n - 1)
    if cut is not None:
        k[cut] = 0.0
    K = sp.diags([np.r_[k, 0] + np.r_[0, k], -k, -k], [0, -1, 1], format="csr")
    K.eliminate_zeros()
    M = sp.diags(1.0 + np.random.default_rng(2).random(n), format="csr")
    return K, M


def _consistent_mass_beside_a_cut_spring(n=300):
    """A consistent (tridiagonal) mass and one spring cut: M couples two DOFs that K
    does not, so K - s M has entries K has not."""
    K, _ = _chain(n, cut=n // 2)
    M = sp.diags([np.full(n, 4.0), np.ones(n - 1), np.ones(n - 1)], [0, -1, 1], format="csr") / 6
    return K, M


@pytest.mark.parametrize("pencil", [_chain, _consistent_mass_beside_a_cut_spring])
@pytest.mark.parametrize("backend", available_factorisers())
def test_the_inertia_count_equals_a_dense_eigenvalue_count(backend, pencil):
    K, M = pencil()
    lam = la.eigvalsh(K.toarray(), M.toarray())
    factor = ShiftedFactor(Pencil(K, M), -1e-6, backend)
    for s in (0.5 * (lam[3] + lam[4]), 0.5 * (lam[40] + lam[41]), 1.01 * lam[-1]):
        assert factor.count_below(s) == np.sum(lam < s)


def _blind_to(x, M):
    """A factor wrapper whose results never contain the M-direction x: a Krylov space
    built on it cannot hold that mode, and the solver converges without it."""
    Mx = M @ x

    def wrap(solve):
        def blind(b):
            y = solve(b)
            return y - np.multiply.outer(x, Mx @ y) if y.ndim == 2 else y - x * (Mx @ y)
        return blind
    return wrap


def test_a_krylov_space_blind_to_a_mode_is_caught_by_the_inertia_count(cylinder, monkeypatch):
    s = cylinder.system
    true = cylinder.modes
    torsion = true.kinds.index("torsion")  # a single mode (bending ones come in pairs)
    wrap = _blind_to(true.shapes[:, torsion], s.M)
    real_solve = ShiftedFactor.solve
    monkeypatch.setattr(ShiftedFactor, "solve", lambda self, b: wrap(
        lambda c: real_solve(self, c))(b))
    monkeypatch.setattr(eigen, "INERTIA_RETRIES", 0)
    rigid = rigid_body_modes(s.nodes)
    with pytest.raises(SolverError, match="a mode was skipped") as caught:
        eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid)
    found, counted = map(int, re.search(r"found (\d+) .* counts (\d+)", str(caught.value)).groups())
    assert counted == found + 1  # exactly the one mode it could not see


def test_a_too_small_krylov_space_is_caught_and_retried(cylinder, monkeypatch):
    """A Krylov space of 14 vectors for 12 pairs, a loose tolerance and a start vector
    without the torsion mode: the first solve returns a pair that is no eigenpair.
    Without a retry that is an error; with one (larger space, new start), the
    frequencies equal the full solve's."""
    s = cylinder.system
    true = cylinder.modes
    x = true.shapes[:, true.kinds.index("torsion")]
    start = eigen.start_vector

    def deficient(n, attempt=0):
        v = start(n, attempt)
        return v - x * (x @ (s.M @ v)) if attempt == 0 else v

    monkeypatch.setattr(eigen, "start_vector", deficient)
    rigid = rigid_body_modes(s.nodes)
    monkeypatch.setattr(eigen, "INERTIA_RETRIES", 0)
    with pytest.raises(SolverError, match="no eigenpair|a mode was skipped"):
        eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid, settings=SolverSettings(tol=1e-2, ncv=14))
    monkeypatch.setattr(eigen, "INERTIA_RETRIES", 1)
    sol = eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid, settings=SolverSettings(tol=1e-2, ncv=14))
    f = np.sqrt(sol.eigenvalues[6:16]) / (2 * np.pi)
    assert np.max(np.abs(f / true.frequencies - 1)) < 1e-9
    assert sol.inertia_count == 16


def test_rigid_motions_are_rigid(cylinder):
    """The six rigid motions the solver keeps out of its Krylov space cost no strain
    energy (K R = 0 to round-off) and are what the free body's six zero modes span."""
    s = cylinder.system
    R = rigid_body_modes(s.nodes)
    KR = s.K @ R
    assert np.max(np.linalg.norm(KR, axis=0) / (abs(s.K).max() * np.linalg.norm(R, axis=0))) < 1e-12
    assert np.linalg.matrix_rank(R) == 6


def test_other_start_vectors_give_the_same_modes_with_small_residuals(paper, monkeypatch):
    """The paper's shaft from two other Krylov starts: every elastic residual below 1e-8
    and the same frequencies."""
    s = paper.system
    for seed in (1, 2):
        monkeypatch.setattr(eigen, "START_SEED", 7919 * seed)
        m = modal_analysis(s)
        assert m.residuals.max() < 1e-8
        assert np.max(np.abs(m.frequencies / paper.modes.frequencies - 1)) < 1e-10
        assert m.inertia_count >= 6 + len(m.frequencies)


@pytest.fixture(scope="module")
def plain(cylinder):
    """The cylinder's pencil solved by PARDISO the ordinary way (two factorisations)."""
    if "pardiso" not in available_factorisers():
        pytest.skip("PARDISO is not installed")
    s = cylinder.system
    rigid = rigid_body_modes(s.nodes)
    return s, rigid, eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid,
                                       settings=SolverSettings("pardiso"))


def _factorisations(monkeypatch):
    """A list that grows by one at every factorisation of K - s M."""
    shifts = []
    real = ShiftedFactor.shift_to

    def counted(self, s):
        if s != self.shift:
            shifts.append(s)
        real(self, s)
    monkeypatch.setattr(ShiftedFactor, "shift_to", counted)
    return shifts


def test_a_shift_hint_needs_one_factorisation_and_finds_the_same_modes(plain, monkeypatch):
    """Factorised once at the last solve's counting shift, the same ten modes come out
    (to 1e-9, and to 1e-8 of SuperLU's), each with a residual below 1e-8, the inertia
    there counting all sixteen."""
    s, rigid, sol = plain
    shifts = _factorisations(monkeypatch)
    hinted = eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid, settings=SolverSettings("pardiso"),
                               shift_hint=sol.inertia_shift)
    assert shifts == [sol.inertia_shift]
    assert hinted.inertia_count == 16 and hinted.inertia_shift == sol.inertia_shift
    assert np.max(np.abs(hinted.eigenvalues[6:] / sol.eigenvalues[6:] - 1)) < 2e-9
    assert hinted.pairs.relative_residuals()[6:].max() < 1e-8
    lu = eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid, settings=SolverSettings("superlu"))
    f, f_lu = np.sqrt(hinted.eigenvalues[6:]), np.sqrt(lu.eigenvalues[6:])
    assert np.max(np.abs(f / f_lu - 1)) < 1e-8


@pytest.mark.parametrize("where", ["too low", "too high", "below every mode"])
def test_a_hint_that_does_not_serve_falls_back(plain, monkeypatch, where):
    """A hint with fewer than the wanted modes below it, or many more, costs one more
    factorisation and changes nothing in the result."""
    s, rigid, sol = plain
    lam = sol.eigenvalues
    hint = {"too low": np.sqrt(lam[10] * lam[11]), "too high": 4.0 * lam[-1],
            "below every mode": 0.5 * lam[6]}[where]
    shifts = _factorisations(monkeypatch)
    again = eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid, settings=SolverSettings("pardiso"),
                              shift_hint=hint)
    assert len(shifts) == 3 and shifts[0] == hint
    assert again.inertia_shift == pytest.approx(sol.inertia_shift, rel=1e-9)
    assert again.inertia_count == 16
    assert np.max(np.abs(again.eigenvalues[6:] / sol.eigenvalues[6:] - 1)) < 2e-9


@pytest.mark.slow
def test_a_krylov_space_blind_to_a_mode_is_caught_below_a_hint_too(cylinder, plain,
                                                                   monkeypatch):
    """The mode the factor cannot see is missing below the hint: the count there says
    so, the ordinary search after it is as blind, and the solve is refused."""
    s, rigid, sol = plain
    true = cylinder.modes
    wrap = _blind_to(true.shapes[:, true.kinds.index("torsion")], s.M)
    real_solve = ShiftedFactor.solve
    monkeypatch.setattr(ShiftedFactor, "solve", lambda self, b: wrap(
        lambda c: real_solve(self, c))(b))
    with pytest.raises(SolverError, match="a mode was skipped"):
        eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid, settings=SolverSettings("pardiso"),
                          shift_hint=sol.inertia_shift)


def test_a_start_basis_of_the_same_pencil_replaces_lanczos(plain, monkeypatch):
    """Given the space's own elastic vectors, the solve below the hint runs no Lanczos:
    Rayleigh-Ritz on them gives the same ten modes (to 1e-9), residuals below 1e-8,
    proven by the inertia count at the hint."""
    s, rigid, sol = plain
    monkeypatch.setattr(eigen, "eigsh", lambda *a, **k: pytest.fail("Lanczos ran"))
    again = eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid,
                              settings=SolverSettings("pardiso"),
                              shift_hint=sol.inertia_shift, start=sol.pairs.X[:, 6:])
    assert again.inertia_count == 16
    assert np.max(np.abs(again.eigenvalues[6:] / sol.eigenvalues[6:] - 1)) < 2e-9
    assert again.pairs.relative_residuals()[6:].max() < 1e-8


@pytest.mark.parametrize("spoilt", ["a mode replaced by noise", "a mode missing"])
def test_a_start_basis_that_does_not_hold_the_modes_falls_back(plain, spoilt):
    """A start basis lacking a mode never hides it: the pairs come out as Lanczos finds
    them, all sixteen counted below the hint."""
    s, rigid, sol = plain
    X = sol.pairs.X[:, 6:].copy()
    if spoilt == "a mode missing":
        X = X[:, 1:]
    else:
        X[:, 3] = np.random.default_rng(3).standard_normal(X.shape[0])
    again = eigen.solve_modes(s.K, s.M, ModeRequest(10), rigid=rigid,
                              settings=SolverSettings("pardiso"),
                              shift_hint=sol.inertia_shift, start=X)
    assert again.inertia_count == 16
    assert np.max(np.abs(again.eigenvalues[6:] / sol.eigenvalues[6:] - 1)) < 2e-9
    assert again.pairs.relative_residuals()[6:].max() < 1e-8


def test_the_one_norm_of_a_symmetric_matrix_is_scipys(plain):
    """one_norm (no copy of the matrix) gives SciPy's ||A||_1 of K and M, and 0 where an
    empty row would otherwise take its neighbour's entry."""
    from scipy.sparse.linalg import norm as spnorm

    s, _, _ = plain
    for A in (s.K, s.M):
        assert eigen.one_norm(A) == pytest.approx(spnorm(A, 1), rel=1e-12)
    gap = sp.csr_matrix(np.array([[0.0, 0.0], [0.0, -3.0]]))
    assert eigen.one_norm(gap) == 3.0
