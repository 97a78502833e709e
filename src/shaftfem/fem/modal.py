"""Natural frequencies and mode shapes: (K - w^2 M) x = 0.

K of a free body is singular (six rigid-body modes at 0 Hz), so the pencil is
solved with shift-invert Lanczos (SciPy `eigsh`) about a small negative shift
sigma, where K - sigma M is positive definite, factorised by MKL PARDISO,
CHOLMOD or SuperLU. The six rigid-body modes must come out near 0 Hz; anything
else is reported as an error with its cause. An installed shaft (shaftfem.fem.supports)
is solved the same way on its reduced pencil, with the rigid motions its supports
leave free in place of the six.
"""

from __future__ import annotations

import math
import time
from concurrent.futures import Future
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.linalg import eigh
from scipy.sparse.linalg import eigsh
from scipy.sparse.linalg import norm as spnorm

from shaftfem.errors import SolverError
from shaftfem.fem.factor import Pencil, ShiftedFactor, uses_pardiso
from shaftfem.fem.supports import Installed, n_bodies, rigid_body_modes
from shaftfem.scene.schema import DEFAULT_MODE_COUNT, MAX_MODE_COUNT

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
# Davidson correction step (solve_modes).
RESIDUAL_TARGET = 3e-9
# ARPACK's start vector is fixed, so that runs differ only by the round-off of MKL's
# threads (a random start moved the paper shaft's frequencies by up to 6e-12).
START_SEED = 2018
# Ritz pairs computed beyond the wanted ones, to find a gap above them where the
# inertia count is taken; two eigenvalues closer than INERTIA_GAP (relative) are
# counted together. A skipped mode is retried INERTIA_RETRIES times with a larger
# Krylov space.
EXTRA_RITZ = 2
INERTIA_GAP = 1e-6
INERTIA_RETRIES = 1
# ARPACK's tolerance: its Ritz values need not be final, the subspace and Davidson
# steps after it bring the residuals to ~1e-9 (tolerance 0 took 7 more solves on
# the paper's shaft for the same final residuals; 1e-4 left 6e-8).
ARPACK_TOL = 1e-6
# A Ritz pair with a larger relative residual than this is taken for a failed solve
# (the pairs the solver returns reach ~1e-9).
ACCEPT_RESIDUAL = 1e-6
# With a shift hint (solve_modes), the one factorisation at the hint both counts and
# solves: Lanczos then seeks the eigenvalues below it, the most negative of
# 1 / (w^2 - s). Those converge a little slower than the lowest ones about sigma < 0,
# so ARPACK's tolerance is tighter and its space larger (paper's shaft, 86k DOFs:
# 37 solves, residuals 9e-10 straight from Rayleigh-Ritz); a hint with more than
# SLICE_SLACK extra modes below it costs more than the second factorisation it saves.
SLICE_TOL = 1e-8
SLICE_SLACK = 4
# ARPACK's restarts below a hint (it needs 1-3 there); one that does not converge by
# then falls back to the ordinary search.
SLICE_RESTARTS = 10


# With a frequency limit instead of a count, the Krylov space grows (twice the
# modes each time) until a mode above the limit is found, up to MAX_MODES modes.
MAX_MODES = MAX_MODE_COUNT


@dataclass(frozen=True)
class Modes:
    """The first elastic modes of a free body, lowest first.

    frequencies in Hz; shapes (n_dofs, n) mass-normalised (x^T M x = 1, in
    m / sqrt(kg)); residuals ||K x - w^2 M x|| / ||K x||; backward_errors the
    same residual over (||K|| + w^2 ||M||) ||x|| (1-norms); kinds 'bending',
    'torsion', 'axial' or 'mixed'; energy (n, 3): kinetic-energy fractions in
    axial, radial and tangential (about the shaft axis) motion.
    """

    frequencies: np.ndarray
    shapes: np.ndarray
    residuals: np.ndarray
    backward_errors: np.ndarray
    kinds: list[str]
    energy: np.ndarray
    rigid_frequencies: np.ndarray
    orthonormality_error: float
    shift: float
    n_dofs: int
    factorizer: str
    factorisation_seconds: float
    eigensolve_seconds: float
    # The inertia of K - s M counted `inertia_count` eigenvalues (rigid ones included)
    # below s = inertia_shift (rad^2/s^2), as many as the solver found: none was skipped.
    inertia_count: int = 0
    inertia_shift: float = 0.0

    @property
    def inertia_shift_hz(self) -> float:
        """The counting shift as a frequency, Hz."""
        return math.sqrt(self.inertia_shift) / (2 * math.pi)

    @property
    def n_rigid(self) -> int:
        return len(self.rigid_frequencies)

    @property
    def count(self) -> int:
        return len(self.frequencies)


@dataclass(frozen=True)
class EigenSolution:
    """The lowest eigenpairs of (K, M): w^2 (rad^2/s^2) and M-normalised vectors."""

    pairs: Ritz
    scale: float          # median of diag K / diag M, rad^2/s^2
    factorizer: str
    factorisation_seconds: float
    eigensolve_seconds: float
    inertia_count: int    # eigenvalues below inertia_shift, by the inertia of K - s M
    inertia_shift: float  # rad^2/s^2

    @property
    def eigenvalues(self) -> np.ndarray:
        return self.pairs.lam

    @property
    def vectors(self) -> np.ndarray:
        return self.pairs.X


def solve_modes(K: sp.csr_matrix, M: sp.csr_matrix, n_modes: int = DEFAULT_MODE_COUNT,
                tol: float = ARPACK_TOL, factorizer: str = "auto",
                max_frequency: float | None = None, ncv: int | None = None,
                rigid: np.ndarray | None = None,
                analysis: Future | None = None,
                shift_hint: float | None = None) -> EigenSolution:
    """The lowest n_modes + 6 eigenpairs; with `max_frequency` (Hz), more until one
    lies above it (the factorisation is reused).

    Shift-invert Lanczos about sigma < 0 finds them; then the inertia of K - s M,
    with s in the gap above the highest one found, counts the eigenvalues below s.
    A mode the Krylov space skipped makes that count larger: the solve is then
    repeated from another start with a Krylov space twice as large, and refused if
    the count still differs.
    `rigid` (n_dofs, r): the body's rigid motions (K R = 0), kept out of the Krylov
    space and returned as the r lowest pairs, so that it holds only elastic modes.
    `ncv`: the Krylov space's size (default max(2k + 1, 20), k the pairs sought).
    `analysis`: PARDISO's analysis of the sparsity, started beforehand (factor.py).
    `shift_hint` (rad^2/s^2): where an earlier solve of a pencil like this one found a
    gap above its wanted modes (PARDISO only). K - s M is factorised there once: its
    inertia counts the eigenvalues below s, Lanczos finds them through the same
    factor, and the second factorisation is saved. A hint with too few or too many
    modes below it falls back to the search above."""
    scale = float(np.median(K.diagonal() / M.diagonal()))
    sigma = -SHIFT_FACTOR * scale
    t0 = time.perf_counter()
    pencil = Pencil(K, M)
    fixed = _rigid_pairs(K, M, rigid) if rigid is not None and rigid.shape[1] else None
    r = 0 if fixed is None else fixed.lam.size
    k = n_modes + (RIGID_BODY_MODES if rigid is None else 0)
    k_max = MAX_MODES + (RIGID_BODY_MODES if rigid is None else 0)
    zero = _zero_limit(scale, fixed)
    if shift_hint is not None and max_frequency is None and uses_pardiso(factorizer, pencil.n):
        factor = _factorise(pencil, shift_hint, factorizer, analysis)
        t1 = time.perf_counter()
        sliced = _slice_below(K, M, factor, shift_hint, r, k, scale, ncv, fixed)
        if sliced is not None:
            pairs, counted = sliced
            return EigenSolution(pairs=pairs.first(r + k), scale=scale,
                                 factorizer=factor.backend, factorisation_seconds=t1 - t0,
                                 eigensolve_seconds=time.perf_counter() - t1,
                                 inertia_count=counted, inertia_shift=shift_hint)
        factor.shift_to(sigma)
    else:
        factor = _factorise(pencil, sigma, factorizer, analysis)
        t1 = time.perf_counter()
    for attempt in range(INERTIA_RETRIES + 1):
        while True:
            pairs, ncv_used = _lanczos(K, M, k + EXTRA_RITZ, sigma, scale, factor, tol, ncv,
                                       None if fixed is None else fixed.X, attempt)
            if fixed is not None:
                pairs = fixed.join(pairs)
            lam = pairs.lam
            if max_frequency is None or lam[r + k - 1] > (2 * math.pi * max_frequency) ** 2:
                break
            if k >= k_max:
                raise SolverError(f"more than {MAX_MODES} modes lie below {max_frequency:g} Hz; "
                                  "lower the frequency limit")
            k = min(2 * k, k_max)
        # The proof that these are the lowest eigenvalues: the pairs up to a gap are
        # eigenpairs to their residuals, and the inertia counts as many below it.
        good, found, s_top = _verified_gap(pairs, r + k, zero, r)
        counted = _counted(factor, s_top) if found else 0
        if counted == found >= r + k:
            pairs = good
            break
        ncv = min(K.shape[0] - r - 1, 2 * ncv_used)
        factor.shift_to(sigma)
    else:
        raise SolverError(_unproven(pairs, found, counted, s_top, r, ncv_used, zero))
    return EigenSolution(pairs=pairs.first(r + k), scale=scale,
                         factorizer=factor.backend, factorisation_seconds=t1 - t0,
                         eigensolve_seconds=time.perf_counter() - t1,
                         inertia_count=counted, inertia_shift=s_top)


def _slice_below(K: sp.csr_matrix, M: sp.csr_matrix, factor: ShiftedFactor, s: float,
                 r: int, k: int, scale: float, ncv: int | None, fixed: Ritz | None
                 ) -> tuple[Ritz, int] | None:
    """Every eigenpair below s, through the factor of K - s M, and how many its inertia
    counts; None where the hint does not serve (s on an eigenvalue, fewer than the k
    wanted or more than k + SLICE_SLACK below it, or Lanczos finding fewer than
    counted, even with a larger space)."""
    try:
        counted = _counted(factor, s)
    except SolverError:
        return None  # pivots perturbed: s lies (nearly) on an eigenvalue
    m = counted - r
    if not k <= m <= k + SLICE_SLACK:
        return None
    ncv = ncv or max(2 * m + 5, 20)
    for attempt in range(INERTIA_RETRIES + 1):
        try:
            pairs, ncv_used = _lanczos(K, M, m, s, scale, factor, SLICE_TOL, ncv,
                                       None if fixed is None else fixed.X, attempt, below=True)
        except SolverError:  # ARPACK did not converge within SLICE_RESTARTS
            return None
        if fixed is not None:
            pairs = fixed.join(pairs)
        if (pairs.verified(_zero_limit(scale, fixed), ACCEPT_RESIDUAL, r).all()
                and int(np.sum(pairs.lam < s)) == counted):
            return pairs, counted
        ncv = min(K.shape[0] - r - 1, 2 * ncv_used)
    return None


def _zero_limit(scale: float, fixed: Ritz | None) -> float:
    """|w^2| below which an eigenvalue is zero: the solver's own rigid pairs, or with
    the rigid motions given (`fixed`), a mechanism's, which modal_analysis refuses."""
    return (RIGID_FACTOR if fixed is None else MECHANISM_FACTOR) * scale


def _rigid_pairs(K: sp.csr_matrix, M: sp.csr_matrix, R: np.ndarray) -> Ritz:
    """Rayleigh-Ritz pairs of (K, M) on the rigid motions R, which K must not resist."""
    pairs = rayleigh_ritz(K, M, R, R.shape[1])
    strain = np.linalg.norm(pairs.KX, axis=0) / (spnorm(K, 1) * np.linalg.norm(pairs.X, axis=0))
    if np.any(strain > 1e-9):
        raise SolverError(f"K resists a rigid motion (|K r| / |K| |r| = {strain.max():.2g}): "
                          "the stiffness is wrong or the body is not free")
    return pairs


def _factorise(pencil: Pencil, sigma: float, factorizer: str,
               analysis: Future | None = None) -> ShiftedFactor:
    """K - sigma M factorised, the back-ends' failures translated."""
    try:
        return ShiftedFactor(pencil, sigma, factorizer, analysis)
    except SolverError:
        raise
    except MemoryError:
        raise SolverError(f"not enough memory to factorise K - sigma M ({pencil.n} DOFs); "
                          "use a coarser mesh or a smaller DOF budget (--max-dofs)") from None
    except Exception as exc:  # SuperLU, PARDISO and CHOLMOD each raise their own kind
        raise SolverError(f"factorising K - sigma M ({pencil.n} DOFs) failed: "
                          f"{type(exc).__name__}: {exc}; a degenerate element or a "
                          "material of absurd stiffness can cause it") from None


def _counted(factor: ShiftedFactor, s: float) -> int:
    try:
        return factor.count_below(s)
    except SolverError:
        raise
    except Exception as exc:
        raise SolverError(f"counting the eigenvalues below a shift failed: "
                          f"{type(exc).__name__}: {exc}") from None


def _gap_above(lam: np.ndarray, k: int) -> tuple[int, float]:
    """(j, s): the first j >= k with a clear gap between lam[j - 1] and lam[j], and s
    in that gap; the inertia count below s must then be j."""
    for j in range(k, len(lam)):
        if lam[j] > lam[j - 1] * (1 + INERTIA_GAP):
            low = lam[j - 1]
            return j, math.sqrt(low * lam[j]) if low > 0 else 0.5 * (low + lam[j])
    raise SolverError(f"the {len(lam) - k + 1} highest eigenvalues found are equal to within "
                      f"{INERTIA_GAP:g}: no gap to count them in; ask for more modes")


def _verified_gap(pairs: Ritz, k: int, zero: float, r: int) -> tuple[Ritz, int, float]:
    """The pairs that are eigenpairs to their residuals (poor ones dropped), and (j, s):
    a clear gap above the first j of them at s, j >= k where at least k + 1 are,
    else the highest gap there is (j = 0: none). The inertia count below s must then
    be j; a larger count means the solver skipped modes below s."""
    good = pairs.select(pairs.verified(zero, ACCEPT_RESIDUAL, r))
    lam = good.lam
    if len(lam) > k:
        j, s = _gap_above(lam, k)
        return good, j, s
    for j in range(len(lam) - 1, 0, -1):
        if lam[j] > lam[j - 1] * (1 + INERTIA_GAP):
            low = lam[j - 1]
            return good, j, math.sqrt(low * lam[j]) if low > 0 else 0.5 * (low + lam[j])
    return good, 0, 0.0


def _unproven(pairs: Ritz, found: int, counted: int, s: float, r: int, ncv: int,
              zero: float) -> str:
    """Why the solve is refused: modes below s that the solver skipped, or too few
    pairs that are eigenpairs (the lowest poor one named: w^2 < 0 or a large residual)."""
    space = f"even with a Krylov space of {ncv} vectors"
    below = (f"the eigen solver found {found} eigenvalues below "
             f"{math.sqrt(max(s, 0.0)) / 2 / math.pi:.6g} Hz where the inertia of K - s M "
             f"counts {counted}")
    if counted > found:
        return f"{below}: a mode was skipped ({counted - found} missing), {space}"
    if counted < found:
        return f"{below}: some pairs found are no distinct eigenpairs, {space}"
    j = int(np.argmin(pairs.verified(zero, ACCEPT_RESIDUAL, r)))
    lam, res = pairs.lam[j], pairs.relative_residuals()[j]
    what = (f"w^2 = {lam:.3g} rad^2/s^2 < 0" if lam < 0
            else f"{math.sqrt(lam) / 2 / math.pi:.6g} Hz, relative residual {res:.2g}")
    return (f"the eigen solver returned a pair that is no eigenpair: number {j + 1 - r} "
            f"above the rigid ones ({what}), {space}")


def _lanczos(K: sp.csr_matrix, M: sp.csr_matrix, k: int, sigma: float, scale: float,
             factor: ShiftedFactor, tol: float, ncv: int | None, R: np.ndarray | None = None,
             attempt: int = 0, below: bool = False) -> tuple[Ritz, int]:
    """k eigenpairs nearest sigma (`below`: the k nearest below it) by shift-invert
    Lanczos through the factor of K - sigma M, refined by one subspace step (not
    `below`) and, where needed, one Davidson step; and the Krylov space's size.
    With R (M-orthonormal), in R's M-complement."""
    n_dofs = K.shape[0]
    if n_dofs <= k + 2:
        raise SolverError(f"the mesh has only {n_dofs} DOFs; {k} modes need more")
    if R is None:
        solve, project = factor.solve, (lambda x: x)
    else:
        MR = np.asarray(M @ R)

        def project(x):
            """x without its rigid part: x - R R^T M x."""
            return x - R @ (MR.T @ x)

        def solve(b):
            # b's rigid part removed first, the result's again: the rigid modes' huge
            # shift-inverted eigenvalue would otherwise grow any round-off along them.
            return project(factor.solve(b - MR @ (R.T @ b)))
    ncv = min(n_dofs - 1, ncv or max(2 * k + 1, 20))
    op = sp.linalg.LinearOperator(K.shape, matvec=solve, matmat=solve, dtype=float)
    try:
        lam, X = eigsh(K, k=k, M=M, sigma=sigma, which="SA" if below else "LM", OPinv=op,
                       tol=tol, ncv=ncv, v0=project(start_vector(n_dofs, attempt)),
                       maxiter=SLICE_RESTARTS if below else None)
    except sp.linalg.ArpackNoConvergence as exc:
        raise SolverError(f"the eigen solver did not converge: {exc}") from None
    except sp.linalg.ArpackError as exc:
        raise SolverError(f"the eigen solver (ARPACK) failed: {exc}") from None
    # One step of subspace iteration with the same factors, then Rayleigh-Ritz:
    # it takes ARPACK's vectors (residuals ~1e-6) down to ~1e-9 and splits
    # near-repeated pairs cleanly. Below a shift it would grow most the modes just
    # above the shift, which are not wanted: there Rayleigh-Ritz alone.
    pairs = rayleigh_ritz(K, M, X if below else solve(np.asarray(M @ X)), k)
    # The highest wanted mode improves least in that step when the next mode is
    # close above it (its residual came out anywhere from 2e-9 to 1.5e-8 on the
    # paper's shaft, depending on ARPACK's start). One Davidson step - the
    # residuals through the same factors, added to the basis - is taken for every
    # elastic mode above RESIDUAL_TARGET: over 16 repeated runs the largest residual
    # left was 6.7e-9 (0.3 s at 86k DOFs, only when needed).
    res = pairs.residual_vectors
    # (without R, the rigid pairs are among them: their residuals mean nothing)
    poor = ((pairs.lam > RIGID_FACTOR * scale) if R is None else np.ones(k, bool)) & (
        np.linalg.norm(res, axis=0) > RESIDUAL_TARGET * np.linalg.norm(pairs.KX, axis=0))
    if poor.any():
        X = pairs.X
        Z = solve(res[:, poor])
        for _ in range(2):  # M-orthogonal to X and M-normalised: a well-conditioned basis
            Z -= X @ (pairs.MX.T @ Z)
            Z /= np.sqrt(np.einsum("ij,ij->j", Z, M @ Z))
        try:
            pairs = rayleigh_ritz(K, M, np.hstack([X, Z]), k,
                                  known=(pairs.KX, pairs.MX))
        except np.linalg.LinAlgError:
            pass  # corrections that are (nearly) dependent: keep the step before
    return pairs, ncv


def start_vector(n: int, attempt: int = 0) -> np.ndarray:
    """ARPACK's start vector: fixed, so that a run is repeatable to the last bit; a
    retry after a skipped mode starts elsewhere."""
    return np.random.default_rng(START_SEED + attempt).standard_normal(n)


@dataclass(frozen=True)
class Ritz:
    """Approximate eigenpairs (w^2 in rad^2/s^2, vectors) of (K, M), with K X and M X
    kept, so that residuals and further Rayleigh-Ritz steps need no new products."""

    lam: np.ndarray
    X: np.ndarray
    KX: np.ndarray
    MX: np.ndarray

    @property
    def residual_vectors(self) -> np.ndarray:
        """K x - w^2 M x for each pair."""
        return self.KX - self.MX * self.lam

    def relative_residuals(self) -> np.ndarray:
        """||K x - w^2 M x|| / ||K x|| per pair."""
        return (np.linalg.norm(self.residual_vectors, axis=0)
                / np.linalg.norm(self.KX, axis=0))

    def verified(self, zero: float, accept: float, given: int = 0) -> np.ndarray:
        """Per pair: one of the `given` rigid motions (the first pairs), a zero
        eigenvalue (|w^2| <= zero, where the relative residual means nothing), or an
        eigenpair to its residual (<= accept). K is positive semi-definite, so a pair
        with w^2 < -zero is none."""
        given_ = np.arange(self.lam.size) < given
        null = np.abs(self.lam) <= zero
        return given_ | null | ((self.lam > zero) & (self.relative_residuals() <= accept))

    def first(self, n: int) -> Ritz:
        return self.select(slice(n))

    def select(self, keep: np.ndarray | slice) -> Ritz:
        return Ritz(self.lam[keep], self.X[:, keep], self.KX[:, keep], self.MX[:, keep])

    def join(self, other: Ritz) -> Ritz:
        return Ritz(np.concatenate([self.lam, other.lam]), np.hstack([self.X, other.X]),
                    np.hstack([self.KX, other.KX]), np.hstack([self.MX, other.MX]))

    def scaled(self, c: np.ndarray) -> Ritz:
        """The same pairs with vector j scaled by c[j]."""
        return Ritz(self.lam, self.X * c, self.KX * c, self.MX * c)


def rayleigh_ritz(K: sp.spmatrix, M: sp.spmatrix, V: np.ndarray, k: int,
                  known: tuple[np.ndarray, np.ndarray] | None = None) -> Ritz:
    """The k lowest Ritz pairs of (K, M) in the span of V's columns. `known`: K and M
    times V's first columns, when they are at hand."""
    m = 0 if known is None else known[0].shape[1]
    KV, MV = K @ V[:, m:], M @ V[:, m:]
    if known is not None:
        KV, MV = np.hstack([known[0], KV]), np.hstack([known[1], MV])
    lam, Q = eigh(V.T @ KV, V.T @ MV)
    Q = Q[:, :k]
    return Ritz(lam[:k], V @ Q, KV @ Q, MV @ Q)


def modal_analysis(K: sp.csr_matrix, M: sp.csr_matrix, nodes: np.ndarray,
                   mass_scalar: sp.csr_matrix, n_modes: int = DEFAULT_MODE_COUNT,
                   factorizer: str = "auto", max_frequency: float | None = None,
                   analysis: Future | None = None, installed: Installed | None = None,
                   shift_hint: float | None = None) -> Modes:
    """Solve, separate the rigid-body modes, check and classify the elastic ones: the
    lowest `n_modes`, or with `max_frequency` (Hz) every one below it (at least one).

    Free (`installed` None): (K, M) of one free body, six rigid motions. Installed:
    the reduced pencil of `installed` is solved, with the rigid motions its seats leave
    free, and the shapes come back as displacements of every node.
    `shift_hint`: see solve_modes (a Modes' inertia_shift from an earlier solve)."""
    if installed is None:
        bodies = n_bodies(K)
        if bodies != 1:
            raise SolverError(
                f"the mesh has {bodies} disconnected parts; a free body must be one piece "
                f"(it would have {RIGID_BODY_MODES * bodies} rigid-body modes)")
        rigid = rigid_body_modes(nodes)
        what = f"one free body has {RIGID_BODY_MODES} rigid-body modes"
    else:
        K, M, rigid = installed.K, installed.M, installed.rigid
        what = (f"the supports leave {installed.n_rigid} rigid-body modes "
                f"({', '.join(installed.free) or 'none'})")
    expected = rigid.shape[1]
    sol = solve_modes(K, M, n_modes, factorizer=factorizer, max_frequency=max_frequency,
                      rigid=rigid, analysis=analysis, shift_hint=shift_hint)
    lam, scale = sol.eigenvalues, sol.scale
    rigid_limit = RIGID_FACTOR * scale
    if lam[0] < -rigid_limit:
        raise SolverError(
            f"a negative eigenvalue w^2 = {lam[0]:.3g} rad^2/s^2: K is not positive "
            "semi-definite (an inverted element or a bad material)"
        )
    is_rigid = np.arange(lam.size) < expected   # the given motions come first
    zero = ~is_rigid & (lam < MECHANISM_FACTOR * scale)
    if zero.any():
        raise SolverError(
            f"found {int(zero.sum())} zero-frequency modes (below "
            f"{math.sqrt(MECHANISM_FACTOR * scale) / (2 * math.pi):.2g} Hz) beside the "
            f"{expected} rigid-body modes, where {what}: a mechanism, a nearly "
            "disconnected part or a support far too soft")
    if max_frequency is not None:
        n_modes = max(1, int(np.sum(lam[~is_rigid] < (2 * math.pi * max_frequency) ** 2)))
    elastic = sol.pairs.select(~is_rigid).first(n_modes)
    # M-normalise explicitly (the Ritz vectors are, up to round-off)
    elastic = elastic.scaled(1 / np.sqrt(np.einsum("ij,ij->j", elastic.X, elastic.MX)))
    lam_e, X_e, MX = elastic.lam, elastic.X, elastic.MX
    R = np.linalg.norm(elastic.residual_vectors, axis=0)
    residuals = elastic.relative_residuals()
    # Normwise backward error ||r|| / ((||K|| + w^2 ||M||) ||x||): the relative residual
    # above has a round-off floor of about eps * w_max^2 / w^2, which slender shafts
    # (low modes, fine meshes) reach; the backward error has none.
    nx = np.linalg.norm(X_e, axis=0)
    backward = R / ((spnorm(K, 1) + lam_e * spnorm(M, 1)) * nx)
    ortho = float(np.max(np.abs(X_e.T @ MX - np.eye(X_e.shape[1]))))
    shapes = X_e if installed is None else installed.expand(X_e)
    energy = energy_split(shapes, nodes, mass_scalar)
    freqs = np.sqrt(lam_e) / (2 * math.pi)
    rigid = np.sqrt(np.abs(lam[is_rigid])) / (2 * math.pi)
    return Modes(frequencies=freqs, shapes=shapes, residuals=residuals, backward_errors=backward,
                 kinds=[classify(e) for e in energy], energy=energy,
                 rigid_frequencies=rigid, orthonormality_error=ortho,
                 shift=-SHIFT_FACTOR * scale, n_dofs=K.shape[0], factorizer=sol.factorizer,
                 factorisation_seconds=sol.factorisation_seconds,
                 eigensolve_seconds=sol.eigensolve_seconds, inertia_count=sol.inertia_count,
                 inertia_shift=sol.inertia_shift)


def energy_split(X: np.ndarray, nodes: np.ndarray, mass_scalar: sp.csr_matrix) -> np.ndarray:
    """Kinetic-energy fractions of each mode in axial, radial and tangential motion.

    The shaft axis is z. Bending moves sections sideways (radial and tangential
    alike), torsion turns them (tangential only), axial modes stretch (z only).
    """
    r = np.hypot(nodes[:, 0], nodes[:, 1])
    safe = np.where(r > 0, r, 1.0)
    c, s = nodes[:, 0] / safe, nodes[:, 1] / safe
    out = np.empty((X.shape[1], 3))
    for k in range(X.shape[1]):
        ux, uy, uz = X[0::3, k], X[1::3, k], X[2::3, k]
        ur, ut = c * ux + s * uy, -s * ux + c * uy
        e = np.array([uz @ (mass_scalar @ uz), ur @ (mass_scalar @ ur), ut @ (mass_scalar @ ut)])
        out[k] = e / e.sum()
    return out


def classify(energy: np.ndarray) -> str:
    """'axial', 'torsion', 'bending' or 'mixed' from the energy fractions (z, r, t)."""
    axial, radial, tangential = energy
    if axial > 0.6:
        return "axial"
    if tangential > 0.75:
        return "torsion"
    if radial + tangential > 0.5 and radial > 0.2:
        return "bending"
    return "mixed"
