"""The lowest eigenpairs of (K - w^2 M) x = 0, proven complete.

K of a free body is singular (six rigid-body modes at 0 Hz), so the pencil is
solved with shift-invert Lanczos (SciPy `eigsh`) about a small negative shift
sigma, where K - sigma M is positive definite, factorised by MKL PARDISO,
CHOLMOD or SuperLU (shaftfem.fem.factor). Two strategies, one proof
(shaftfem.fem.inertia):

* `search`: Lanczos about sigma, then the inertia at a gap above the pairs found
  counts the eigenvalues below it; a skipped mode makes the count larger and the
  search is repeated with a larger Krylov space;
* `slice_below`: with a shift hint s from an earlier solve, K - s M is factorised
  once: its inertia counts the eigenvalues below s and Lanczos finds them through
  the same factor, saving the second factorisation;
* `refine_below`: with a hint and a start basis that already holds the pairs below
  it (an earlier solve of the same space), Rayleigh-Ritz on the basis and Davidson
  steps through the same factor replace Lanczos.
"""

from __future__ import annotations

import math
from concurrent.futures import Future
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import eigsh

from shaftfem.errors import SolverError
from shaftfem.fem.factor import Pencil, ShiftedFactor, uses_pardiso
from shaftfem.fem.inertia import (
    ACCEPT_RESIDUAL,
    INERTIA_GAP,
    count_below,
    unproven,
    verified_gap,
)
from shaftfem.fem.ritz import Ritz, rayleigh_ritz
from shaftfem.scene.model import ModeRequest
from shaftfem.scene.schema import MAX_MODE_COUNT

RIGID_BODY_MODES = 6
# sigma = -SHIFT_FACTOR * median(diag K / diag M): scale-free, so frequencies scale
# exactly with sqrt(E / rho) and do not depend on the unit system.
SHIFT_FACTOR = 1e-8
# Rigid pairs (the free motions given to the solver) have |w^2| below this fraction of
# the same scale, their round-off; below it an eigenvalue counts as zero in the checks.
RIGID_FACTOR = 1e-10
# The rigid motions are given (a free body's six, or those its seats leave free), and
# every other mode is elastic, however low (soft bearings, heavy parts). An elastic
# w^2 below this fraction of the scale (f ~ 1e-7 f_scale, 0.01 Hz on a steel shaft's
# 8 mm mesh) is a motion K does not resist beyond those: a mechanism.
MECHANISM_FACTOR = 1e-14
# Relative residual ||K x - w^2 M x|| / ||K x|| above which an elastic mode gets a
# Davidson correction step.
RESIDUAL_TARGET = 3e-9
SLICE_DAVIDSON = 4           # Davidson steps at most below a shift hint
# ARPACK's start vector is fixed, so that runs differ only by the round-off of MKL's
# threads (a random start moved the paper shaft's frequencies by up to 6e-12).
START_SEED = 2018
# Ritz pairs computed beyond the wanted ones, to find a gap above them where the
# inertia count is taken. A skipped mode is retried INERTIA_RETRIES times with a
# larger Krylov space.
EXTRA_RITZ = 2
INERTIA_RETRIES = 2
# ARPACK's tolerance: its Ritz values need not be final, the subspace and Davidson
# steps after it bring the residuals to ~1e-9 (tolerance 0 took 7 more solves on
# the paper's shaft for the same final residuals; 1e-4 left 6e-8).
ARPACK_TOL = 1e-6
# With a shift hint, the one factorisation at the hint both counts and solves:
# Lanczos then seeks the eigenvalues below it, the most negative of 1 / (w^2 - s).
# Those converge a little slower than the lowest ones about sigma < 0, so ARPACK's
# tolerance is tighter and its space larger (paper's shaft, 86k DOFs: 37 solves,
# residuals 9e-10 straight from Rayleigh-Ritz); a hint with more than SLICE_SLACK
# extra modes below it costs more than the second factorisation it saves.
SLICE_TOL = 1e-8
SLICE_SLACK = 4
# ARPACK's restarts below a hint (it needs 1-3 there); one that does not converge by
# then falls back to the search.
SLICE_RESTARTS = 10
# Davidson steps at most from a start basis below a hint; a basis that is the space's
# own eigenvectors needs none or one, and one that is not falls back to Lanczos.
REFINE_DAVIDSON = 2
# With a frequency limit instead of a count, the Krylov space grows (twice the
# modes each time) until a mode above the limit is found, up to MAX_MODES modes.
MAX_MODES = MAX_MODE_COUNT


@dataclass(frozen=True)
class SolverSettings:
    """How the pencil is solved: the factoriser ('auto', 'pardiso', 'cholmod',
    'superlu'), ARPACK's tolerance, the Krylov space's size (None: max(2k + 1, 20)),
    and PARDISO's analysis of the sparsity when started beforehand (factor.py)."""

    factoriser: str = "auto"
    tol: float = ARPACK_TOL
    ncv: int | None = None
    analysis: Future | None = None


@dataclass(frozen=True)
class EigenSolution:
    """The lowest eigenpairs of (K, M), w^2 in rad^2/s^2, M-normalised vectors, and
    their proof: the inertia of K - s M counted `inertia_count` eigenvalues below
    s = inertia_shift, as many as were found."""

    pairs: Ritz
    scale: float          # median of diag K / diag M, rad^2/s^2
    factoriser: str
    inertia_count: int
    inertia_shift: float  # rad^2/s^2
    # the further pairs' vectors proven below inertia_shift (n_dofs, inertia_count -
    # given rigid - wanted): with the pairs', a start from which the next solve of the
    # pencil refines every pair below that shift (refine_below)
    beyond: np.ndarray | None = None

    @property
    def eigenvalues(self) -> np.ndarray:
        return self.pairs.lam


@dataclass(frozen=True)
class Problem:
    """The pencil with what every strategy needs: its scale, the given rigid pairs
    (`fixed`, None: the solver finds a free body's six) and how many pairs are sought."""

    K: sp.csr_matrix
    M: sp.csr_matrix
    scale: float
    fixed: Ritz | None
    k: int        # pairs sought beyond the given rigid ones
    k_max: int

    @property
    def r(self) -> int:
        return 0 if self.fixed is None else self.fixed.lam.size

    @property
    def sigma(self) -> float:
        return -SHIFT_FACTOR * self.scale

    @property
    def zero(self) -> float:
        """|w^2| below which an eigenvalue is zero: the solver's own rigid pairs, or with
        the rigid motions given, a mechanism's, which modal_analysis refuses."""
        return (RIGID_FACTOR if self.fixed is None else MECHANISM_FACTOR) * self.scale


def solve_modes(K: sp.csr_matrix, M: sp.csr_matrix, wanted: ModeRequest = ModeRequest(),
                rigid: np.ndarray | None = None, settings: SolverSettings = SolverSettings(),
                shift_hint: float | None = None, start: np.ndarray | None = None,
                ceiling: tuple[float, int] | None = None) -> EigenSolution:
    """The lowest pairs: the rigid ones and the `wanted` elastic ones above them (the
    lowest count, or every one below max_frequency, Hz), proven complete.

    `rigid` (n_dofs, r): the body's rigid motions (K R = 0), kept out of the Krylov
    space and returned as the r lowest pairs (None: six are found among the pairs).
    `shift_hint` (rad^2/s^2): where an earlier solve of a pencil like this one proved
    its modes complete (PARDISO only); a hint that does not serve falls back to the
    search. `start` (n_dofs, m): vectors spanning (nearly) the elastic pairs below the
    hint, tried before Lanczos. `ceiling` (s, n): at most n eigenvalues lie below s, as
    in a subspace of a space whose count that was (see search)."""
    scale = float(np.median(K.diagonal() / M.diagonal()))
    extra = RIGID_BODY_MODES if rigid is None else 0
    fixed = _rigid_pairs(K, M, rigid) if rigid is not None and rigid.shape[1] else None
    p = Problem(K, M, scale, fixed, wanted.count + extra, MAX_MODES + extra)
    pencil = Pencil(K, M)
    if (shift_hint is not None and wanted.max_frequency is None
            and uses_pardiso(settings.factoriser, pencil.n, K.nnz)):
        factor = shifted_factor(pencil, shift_hint, settings)
        sliced = None if start is None else refine_below(p, factor, shift_hint, start)
        if sliced is None:
            sliced = slice_below(p, factor, shift_hint, settings.ncv)
        if sliced is not None:
            return sliced
        factor.shift_to(p.sigma)
    else:
        factor = shifted_factor(pencil, p.sigma, settings)
    return search(p, factor, wanted.max_frequency, settings, ceiling)


def search(p: Problem, factor: ShiftedFactor, max_frequency: float | None,
           settings: SolverSettings, ceiling: tuple[float, int] | None = None
           ) -> EigenSolution:
    """Lanczos about sigma < 0, proven by the inertia at a gap above the pairs found;
    repeated from another start with a Krylov space twice as large if a mode was
    skipped, and refused if the count still differs.

    With a `ceiling` (s, n), at most n eigenvalues lie below s: a subspace's i-th
    eigenvalue is never below the whole space's (min-max), so a lower order inside a
    hierarchical space has no more below s than the space's own proven count. n Ritz
    values below s then mean at least n eigenvalues there (the i-th Ritz value is
    never below the i-th eigenvalue), so exactly n, and the pairs, eigenpairs to their
    residuals, are all of them: no inertia count, no second factorisation."""
    k, ncv, extra = p.k, settings.ncv, EXTRA_RITZ
    for attempt in range(INERTIA_RETRIES + 1):
        pairs, k, ncv_used = _enough_pairs(p, factor, k, max_frequency, settings.tol, ncv,
                                           attempt, extra)
        good, found, s_top = verified_gap(pairs, p.r + k, p.zero, p.r)
        if ceiling is not None and _under_ceiling(pairs, good, ceiling, p.r + k):
            s, n = ceiling
            return _proven(p, good, p.r + k, factor, n, s)
        counted = count_below(factor, s_top) if found else 0
        if counted == found >= p.r + k:
            return _proven(p, good, p.r + k, factor, counted, s_top)
        # a skipped mode is most often the partner of a repeated frequency (a bending
        # pair, exactly repeated on a symmetric mesh): a wider search asks for more pairs
        # as well as a larger space
        extra += max(counted - found, 1) + EXTRA_RITZ
        ncv = min(p.K.shape[0] - p.r - 1, max(2 * ncv_used, 2 * (p.r + k + extra) + 1))
        factor.shift_to(p.sigma)
    raise SolverError(unproven(pairs, found, counted, s_top, p.r, ncv_used, p.zero))


def _under_ceiling(pairs: Ritz, good: Ritz, ceiling: tuple[float, int], wanted: int) -> bool:
    """Whether the Ritz pairs prove the count under a ceiling (s, n) (see search): n of
    them below s, each an eigenpair to its residual, and no fewer than wanted. A margin
    of INERTIA_GAP below s keeps round-off of the Ritz values out of the count."""
    s, n = ceiling
    below = int(np.sum(pairs.lam < s * (1 - INERTIA_GAP)))
    return below == n == int(np.sum(good.lam < s * (1 - INERTIA_GAP))) and n >= wanted


def _enough_pairs(p: Problem, factor: ShiftedFactor, k: int, max_frequency: float | None,
                  tol: float, ncv: int | None, attempt: int, extra: int = EXTRA_RITZ
                  ) -> tuple[Ritz, int, int]:
    """The k lowest pairs and `extra` more (and k, the Krylov space's size); with a
    frequency limit, k doubled until a pair lies above it."""
    while True:
        pairs, ncv_used = _lanczos(p, factor, k + extra, p.sigma, tol, ncv, attempt)
        if max_frequency is None or pairs.lam[p.r + k - 1] > (2 * math.pi * max_frequency) ** 2:
            return pairs, k, ncv_used
        if k >= p.k_max:
            raise SolverError(f"more than {MAX_MODES} modes lie below {max_frequency:g} Hz; "
                              "lower the frequency limit")
        k = min(2 * k, p.k_max)


def slice_below(p: Problem, factor: ShiftedFactor, s: float, ncv: int | None
                ) -> EigenSolution | None:
    """Every eigenpair below s, through the factor of K - s M, proven by its inertia;
    None where the hint does not serve (s on an eigenvalue, fewer than the k wanted
    or more than k + SLICE_SLACK below it, or Lanczos finding fewer than counted,
    even with a larger space)."""
    try:
        counted = count_below(factor, s)
    except SolverError:
        return None  # pivots perturbed: s lies (nearly) on an eigenvalue
    m = counted - p.r
    if not p.k <= m <= p.k + SLICE_SLACK:
        return None
    ncv = ncv or max(2 * m + 5, 20)
    for attempt in range(INERTIA_RETRIES + 1):
        try:
            pairs, ncv_used = _lanczos(p, factor, m, s, SLICE_TOL, ncv, attempt, below=True)
        except SolverError:  # ARPACK did not converge within SLICE_RESTARTS
            return None
        if (pairs.verified(p.zero, ACCEPT_RESIDUAL, p.r).all()
                and int(np.sum(pairs.lam < s)) == counted):
            return _proven(p, pairs, p.r + p.k, factor, counted, s)
        ncv = min(p.K.shape[0] - p.r - 1, 2 * ncv_used)
    return None


def refine_below(p: Problem, factor: ShiftedFactor, s: float, start: np.ndarray
                 ) -> EigenSolution | None:
    """Every eigenpair below s from a basis `start` that holds as many vectors as there
    are elastic eigenvalues below s (a cached solve of this pencil): Rayleigh-Ritz on it
    and up to REFINE_DAVIDSON Davidson steps through the factor of K - s M, proven by
    its inertia like Lanczos' pairs; None where the basis does not serve."""
    try:
        counted = count_below(factor, s)
    except SolverError:
        return None
    m = counted - p.r
    if start.shape != (p.K.shape[0], m) or m < p.k:
        return None
    solve, project = _operators(p, factor)
    try:
        pairs = rayleigh_ritz(p.K, p.M, project(start), m)
    except np.linalg.LinAlgError:  # a (nearly) dependent basis
        return None
    for _ in range(REFINE_DAVIDSON):
        pairs = _davidson(p, pairs, solve)
    if p.fixed is not None:
        pairs = p.fixed.join(pairs)
    if not (pairs.verified(p.zero, ACCEPT_RESIDUAL, p.r).all()
            and int(np.sum(pairs.lam < s)) == counted):
        return None
    return _proven(p, pairs, p.r + p.k, factor, counted, s)


def _proven(p: Problem, pairs: Ritz, n: int, factor: ShiftedFactor, counted: int, s: float
            ) -> EigenSolution:
    """The first n of the pairs, proven by `counted` eigenvalues below s, with the
    vectors of the rest of those below s (EigenSolution.beyond)."""
    rest = pairs.X[:, n:counted] if counted > n and pairs.X.shape[1] >= counted else None
    return EigenSolution(pairs=pairs.first(n), scale=p.scale, factoriser=factor.backend,
                         inertia_count=counted, inertia_shift=s, beyond=rest)


def one_norm(A: sp.csr_matrix) -> float:
    """||A||_1 of a symmetric CSR matrix: its largest row sum of |a_ij| (= column sum),
    without the copy of A that abs(A) makes (0.3 s a call at order 5's 74M entries)."""
    data = np.abs(A.data)
    if not data.size:
        return 0.0
    sums = np.add.reduceat(data, A.indptr[:-1])
    sums[np.diff(A.indptr) == 0] = 0.0  # reduceat gives an empty row its next entry
    return float(sums.max())


def _rigid_pairs(K: sp.csr_matrix, M: sp.csr_matrix, R: np.ndarray) -> Ritz:
    """Rayleigh-Ritz pairs of (K, M) on the rigid motions R, which K must not resist."""
    pairs = rayleigh_ritz(K, M, R, R.shape[1])
    strain = np.linalg.norm(pairs.KX, axis=0) / (one_norm(K) * np.linalg.norm(pairs.X, axis=0))
    if np.any(strain > 1e-9):
        raise SolverError(f"K resists a rigid motion (|K r| / |K| |r| = {strain.max():.2g}): "
                          "the stiffness is wrong or the body is not free")
    return pairs


def shifted_factor(pencil: Pencil, sigma: float, settings: SolverSettings) -> ShiftedFactor:
    """K - sigma M factorised, the back-ends' failures translated (the cause kept)."""
    try:
        return ShiftedFactor(pencil, sigma, settings.factoriser, settings.analysis)
    except SolverError:
        raise
    except MemoryError as exc:
        raise SolverError(f"not enough memory to factorise K - sigma M ({pencil.n} DOFs); "
                          "use a coarser mesh or a smaller DOF budget (--max-dofs)") from exc
    except Exception as exc:  # SuperLU, PARDISO and CHOLMOD each raise their own kind
        raise SolverError(f"factorising K - sigma M ({pencil.n} DOFs) failed: "
                          f"{type(exc).__name__}: {exc}; a degenerate element or a "
                          "material of absurd stiffness can cause it") from exc


def _operators(p: Problem, factor: ShiftedFactor):
    """(solve, project): the factor's solve and the projection off the given rigid
    motions R (M-orthonormal), x - R R^T M x; plain without R."""
    if p.fixed is None:
        return factor.solve, (lambda x: x)
    R = p.fixed.X
    MR = np.asarray(p.M @ R)

    def project(x):
        return x - R @ (MR.T @ x)

    def solve(b):
        # b's rigid part removed first, the result's again: the rigid modes' huge
        # shift-inverted eigenvalue would otherwise grow any round-off along them.
        return project(factor.solve(b - MR @ (R.T @ b)))
    return solve, project


def _lanczos(p: Problem, factor: ShiftedFactor, k: int, sigma: float, tol: float,
             ncv: int | None, attempt: int = 0, below: bool = False) -> tuple[Ritz, int]:
    """The given rigid pairs, then k eigenpairs nearest sigma (`below`: the k nearest
    below it) by shift-invert Lanczos through the factor of K - sigma M, refined by one
    subspace step (not `below`) and, where needed, one Davidson step; and the Krylov
    space's size."""
    K, M = p.K, p.M
    n_dofs = K.shape[0]
    if n_dofs <= k + 2:
        raise SolverError(f"the mesh has only {n_dofs} DOFs; {k} modes need more")
    solve, project = _operators(p, factor)
    ncv = min(n_dofs - 1, ncv or max(2 * k + 1, 20))
    op = sp.linalg.LinearOperator(K.shape, matvec=solve, matmat=solve, dtype=float)
    try:
        lam, X = eigsh(K, k=k, M=M, sigma=sigma, which="SA" if below else "LM", OPinv=op,
                       tol=tol, ncv=ncv, v0=project(start_vector(n_dofs, attempt)),
                       maxiter=SLICE_RESTARTS if below else None)
    except sp.linalg.ArpackNoConvergence as exc:
        raise SolverError(f"the eigen solver did not converge: {exc}") from exc
    except sp.linalg.ArpackError as exc:
        raise SolverError(f"the eigen solver (ARPACK) failed: {exc}") from exc
    # One step of subspace iteration with the same factors, then Rayleigh-Ritz:
    # it takes ARPACK's vectors (residuals ~1e-6) down to ~1e-9 and splits
    # near-repeated pairs cleanly. Below a shift it would grow most the modes just
    # above the shift, which are not wanted: there Rayleigh-Ritz alone.
    pairs = _davidson(p, rayleigh_ritz(K, M, X if below else solve(np.asarray(M @ X)), k), solve)
    for _ in range(SLICE_DAVIDSON - 1 if below else 0):
        # below a shift Rayleigh-Ritz starts from ARPACK's residuals (~1e-6), and one
        # Davidson step can leave the highest mode (its neighbour just above the shift,
        # outside the basis) poor: over 24 start vectors on the cylinder one step left
        # 3 above 1e-8 (8.3e-8 at worst), up to four none (2.8e-9 at worst); a step
        # runs only while a pair is poor
        pairs = _davidson(p, pairs, solve)
    return (pairs if p.fixed is None else p.fixed.join(pairs)), ncv


def _davidson(p: Problem, pairs: Ritz, solve) -> Ritz:
    """One Davidson step for the elastic pairs above RESIDUAL_TARGET: their residuals,
    through the same factor, added to the basis. The highest wanted mode improves least
    in the subspace step when the next mode is close above it (its residual came out
    anywhere from 2e-9 to 1.5e-8 on the paper's shaft, depending on ARPACK's start);
    over 16 repeated runs the largest residual left was 6.7e-9 (0.3 s at 86k DOFs,
    only when needed)."""
    K, M, k = p.K, p.M, pairs.lam.size
    res = pairs.residual_vectors
    # (without given rigid pairs, the solver's are among them: their residuals mean nothing)
    elastic = (pairs.lam > RIGID_FACTOR * p.scale) if p.fixed is None else np.ones(k, bool)
    poor = elastic & (np.linalg.norm(res, axis=0)
                      > RESIDUAL_TARGET * np.linalg.norm(pairs.KX, axis=0))
    if not poor.any():
        return pairs
    X = pairs.X
    Z = solve(res[:, poor])
    for _ in range(2):  # M-orthogonal to X and M-normalised: a well-conditioned basis
        Z -= X @ (pairs.MX.T @ Z)
        Z /= np.sqrt(np.einsum("ij,ij->j", Z, M @ Z))
    try:
        return rayleigh_ritz(K, M, np.hstack([X, Z]), k, known=(pairs.KX, pairs.MX))
    except np.linalg.LinAlgError:
        return pairs  # corrections that are (nearly) dependent: keep the step before


def start_vector(n: int, attempt: int = 0) -> np.ndarray:
    """ARPACK's start vector: fixed, so that a run is repeatable to the last bit; a
    retry after a skipped mode starts elsewhere."""
    return np.random.default_rng(START_SEED + attempt).standard_normal(n)
