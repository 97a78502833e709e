"""Free-free natural frequencies and mode shapes: (K - w^2 M) x = 0.

K of a free body is singular (six rigid-body modes at 0 Hz), so the pencil is
solved with shift-invert Lanczos (SciPy `eigsh`) about a small negative shift
sigma, where K - sigma M is positive definite, factorised by MKL PARDISO,
CHOLMOD or SuperLU. The six rigid-body modes must come out near 0 Hz; anything
else is reported as an error with its cause.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp
from scipy.linalg import eigh
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import eigsh
from scipy.sparse.linalg import norm as spnorm

from .errors import SolverError
from .schema import DEFAULT_MODE_COUNT, MAX_MODE_COUNT

RIGID_BODY_MODES = 6
# sigma = -SHIFT_FACTOR * median(diag K / diag M): scale-free, so frequencies scale
# exactly with sqrt(E / rho) and do not depend on the unit system.
SHIFT_FACTOR = 1e-8
# A mode counts as rigid below this fraction of the same scale (f ~ 1e-5 f_scale).
RIGID_FACTOR = 1e-10
# Relative residual ||K x - w^2 M x|| / ||K x|| above which an elastic mode gets a
# Davidson correction step (solve_modes).
RESIDUAL_TARGET = 3e-9
# ARPACK's start vector: fixed, so that a run is repeatable to the last bit (a random
# start moved the paper shaft's frequencies by up to 6e-12 between runs).
START_SEED = 2018


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

    @property
    def n_rigid(self) -> int:
        return len(self.rigid_frequencies)

    @property
    def count(self) -> int:
        return len(self.frequencies)


@dataclass(frozen=True)
class EigenSolution:
    """The lowest eigenpairs of (K, M): w^2 (rad^2/s^2) and M-normalised vectors."""

    eigenvalues: np.ndarray
    vectors: np.ndarray
    scale: float          # median of diag K / diag M, rad^2/s^2
    factorizer: str
    factorisation_seconds: float
    eigensolve_seconds: float


def _n_bodies(K: sp.csr_matrix) -> int:
    graph = K[::3, ::3] if K.shape[0] % 3 == 0 else K
    n, _ = connected_components(graph, directed=False)
    return n


FACTORIZERS = ("pardiso", "cholmod", "superlu")
# 'auto' takes SuperLU below this many DOFs: there its solves give residuals of
# 1e-10..1e-12 and the factorisation is a small part of the time, while PARDISO's
# residuals reached 1e-7 on the plain cylinder (28k DOFs). Above it factorisation
# dominates and PARDISO is 7x faster (benchmarks/).
AUTO_SUPERLU_BELOW = 60_000


def available_factorizers() -> list[str]:
    """The factorisation back-ends importable here, fastest first (SuperLU always)."""
    import importlib.util

    out = [name for name, mod in (("pardiso", "pypardiso"), ("cholmod", "cholespy"))
           if importlib.util.find_spec(mod) is not None]
    return out + ["superlu"]


def factorize(A: sp.spmatrix, backend: str = "auto"):
    """A solve function x = A^-1 b for the SPD matrix A = K - sigma M.

    'pardiso' (Intel MKL PARDISO via pypardiso, SPD mode), 'cholmod' (CHOLMOD via
    cholespy), 'superlu' (SciPy, COLAMD ordering: the pure-SciPy path), or 'auto'
    (SuperLU for small systems, else the fastest installed). All give the same
    frequencies (a test checks 1e-8).
    """
    if backend == "auto":
        backend = "superlu" if A.shape[0] < AUTO_SUPERLU_BELOW else available_factorizers()[0]
    if backend == "pardiso":
        import pypardiso

        solver = pypardiso.PyPardisoSolver(mtype=2)  # real symmetric positive definite
        upper = sp.triu(A, format="csr")
        upper.sort_indices()
        solver.factorize(upper)

        def solve(b):
            return solver.solve(upper, np.asarray(b, dtype=float))
        return solve, backend
    if backend == "cholmod":
        from cholespy import CholeskySolverD, MatrixType

        C = sp.csc_matrix(A)
        C.sort_indices()
        chol = CholeskySolverD(C.shape[0], C.indptr.astype(np.int32),
                               C.indices.astype(np.int32), C.data, MatrixType.CSC)

        def solve(b):
            b = np.ascontiguousarray(b, dtype=float)
            x = np.zeros_like(b)
            chol.solve(b, x)
            return x
        return solve, backend
    if backend == "superlu":
        from scipy.sparse.linalg import splu

        return splu(sp.csc_matrix(A)).solve, backend
    raise SolverError(f"unknown factoriser {backend!r}; choose one of {', '.join(FACTORIZERS)}")


def solve_modes(K: sp.csr_matrix, M: sp.csr_matrix, n_modes: int = DEFAULT_MODE_COUNT,
                tol: float = 0.0, factorizer: str = "auto",
                max_frequency: float | None = None) -> EigenSolution:
    """The lowest n_modes + 6 eigenpairs; with `max_frequency` (Hz), more until one
    lies above it (the factorisation is reused)."""
    scale = float(np.median(K.diagonal() / M.diagonal()))
    sigma = -SHIFT_FACTOR * scale
    t0 = time.perf_counter()
    A = (K - sigma * M).tocsr()
    try:
        solve, used = factorize(A, factorizer)
    except SolverError:
        raise
    except MemoryError:
        raise SolverError(f"not enough memory to factorise K - sigma M ({A.shape[0]} DOFs); "
                          "use a coarser mesh or a smaller DOF budget (--max-dofs)") from None
    except Exception as exc:  # SuperLU, PARDISO and CHOLMOD each raise their own kind
        raise SolverError(f"factorising K - sigma M ({A.shape[0]} DOFs) failed: "
                          f"{type(exc).__name__}: {exc}; a degenerate element or a "
                          "material of absurd stiffness can cause it") from None
    t1 = time.perf_counter()
    k = n_modes + RIGID_BODY_MODES
    while True:
        lam, X = _lanczos(K, M, k, sigma, scale, solve, tol)
        if max_frequency is None or lam[-1] > (2 * math.pi * max_frequency) ** 2:
            break
        if k >= MAX_MODES + RIGID_BODY_MODES:
            raise SolverError(f"more than {MAX_MODES} modes lie below {max_frequency:g} Hz; "
                              "lower the frequency limit")
        k = min(2 * k, MAX_MODES + RIGID_BODY_MODES)
    return EigenSolution(eigenvalues=lam, vectors=X, scale=scale, factorizer=used,
                         factorisation_seconds=t1 - t0,
                         eigensolve_seconds=time.perf_counter() - t1)


def _lanczos(K: sp.csr_matrix, M: sp.csr_matrix, k: int, sigma: float, scale: float,
             solve: Callable[[np.ndarray], np.ndarray], tol: float
             ) -> tuple[np.ndarray, np.ndarray]:
    """k eigenpairs nearest sigma by shift-invert Lanczos through `solve` = (K - sigma M)^-1,
    refined by one subspace step and, where needed, one Davidson step."""
    n_dofs = K.shape[0]
    if n_dofs <= k + 2:
        raise SolverError(f"the mesh has only {n_dofs} DOFs; {k} modes need more")
    op = sp.linalg.LinearOperator(K.shape, matvec=solve, matmat=solve, dtype=float)
    try:
        v0 = np.random.default_rng(START_SEED).standard_normal(n_dofs)
        lam, X = eigsh(K, k=k, M=M, sigma=sigma, which="LM", OPinv=op, tol=tol,
                       ncv=min(n_dofs, max(2 * k + 1, 40)), v0=v0)
    except sp.linalg.ArpackNoConvergence as exc:
        raise SolverError(f"the eigen solver did not converge: {exc}") from None
    except sp.linalg.ArpackError as exc:
        raise SolverError(f"the eigen solver (ARPACK) failed: {exc}") from None
    # One step of subspace iteration with the same factors, then Rayleigh-Ritz:
    # it takes ARPACK's vectors (residuals ~1e-6) down to ~1e-9 and splits
    # near-repeated pairs cleanly.
    Y = solve(np.asarray(M @ X))
    lam, X = _rayleigh_ritz(K, M, Y, k)
    # The highest wanted mode improves least in that step when the next mode is
    # close above it (its residual came out anywhere from 2e-9 to 1.5e-8 on the
    # paper's shaft, depending on ARPACK's start). One Davidson step - the
    # residuals through the same factors, added to the basis - is taken for every
    # elastic mode above RESIDUAL_TARGET: over 16 repeated runs the largest residual
    # left was 6.7e-9 (0.3 s at 86k DOFs, only when needed).
    R, r, kx, _ = _residuals(K, M, X, lam)
    poor = (lam > RIGID_FACTOR * scale) & (r > RESIDUAL_TARGET * kx)
    if poor.any():
        Z = solve(R[:, poor])
        for _ in range(2):  # M-orthogonal to X and M-normalised: a well-conditioned basis
            Z -= X @ (X.T @ (M @ Z))
            Z /= np.sqrt(np.einsum("ij,ij->j", Z, M @ Z))
        try:
            lam, X = _rayleigh_ritz(K, M, np.hstack([X, Z]), k)
        except np.linalg.LinAlgError:
            pass  # corrections that are (nearly) dependent: keep the step before
    return lam, X


def _residuals(K: sp.spmatrix, M: sp.spmatrix, X: np.ndarray, lam: np.ndarray):
    """R = K X - M X diag(lam), its column norms, those of K X, and M X."""
    KX, MX = K @ X, M @ X
    R = KX - MX * lam
    return R, np.linalg.norm(R, axis=0), np.linalg.norm(KX, axis=0), MX


def _rayleigh_ritz(K: sp.spmatrix, M: sp.spmatrix, V: np.ndarray, k: int
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The k lowest Ritz pairs of (K, M) in the span of V's columns."""
    lam, Q = eigh(V.T @ (K @ V), V.T @ (M @ V))
    return lam[:k], V @ Q[:, :k]


def modal_analysis(K: sp.csr_matrix, M: sp.csr_matrix, nodes: np.ndarray,
                   mass_scalar: sp.csr_matrix, n_modes: int = DEFAULT_MODE_COUNT,
                   factorizer: str = "auto", max_frequency: float | None = None) -> Modes:
    """Solve, separate the six rigid-body modes, check and classify the elastic ones:
    the lowest `n_modes`, or with `max_frequency` (Hz) every one below it (at least one)."""
    n_bodies = _n_bodies(K)
    if n_bodies != 1:
        raise SolverError(
            f"the mesh has {n_bodies} disconnected parts; a free body must be one piece "
            f"(it would have {RIGID_BODY_MODES * n_bodies} rigid-body modes)"
        )
    sol = solve_modes(K, M, n_modes, factorizer=factorizer, max_frequency=max_frequency)
    lam, X, scale = sol.eigenvalues, sol.vectors, sol.scale
    rigid_limit = RIGID_FACTOR * scale
    if lam[0] < -rigid_limit:
        raise SolverError(
            f"a negative eigenvalue w^2 = {lam[0]:.3g} rad^2/s^2: K is not positive "
            "semi-definite (an inverted element or a bad material)"
        )
    is_rigid = lam < rigid_limit
    n_rigid = int(is_rigid.sum())
    f_limit = math.sqrt(rigid_limit) / (2 * math.pi)
    if n_rigid != RIGID_BODY_MODES:
        why = ("a mechanism or a nearly disconnected part" if n_rigid > RIGID_BODY_MODES
               else "the shift-invert solve missed some (bad shift or a failed factorisation)")
        raise SolverError(
            f"found {n_rigid} modes below {f_limit:.3g} Hz where one free body has "
            f"{RIGID_BODY_MODES} rigid-body modes: {why}"
        )
    if max_frequency is not None:
        n_modes = max(1, int(np.sum(lam[~is_rigid] < (2 * math.pi * max_frequency) ** 2)))
    lam_e, X_e = lam[~is_rigid][:n_modes], X[:, ~is_rigid][:, :n_modes]
    # M-normalise explicitly (ARPACK's vectors are, up to round-off)
    X_e = X_e / np.sqrt(np.einsum("ij,ij->j", X_e, M @ X_e))
    _, R, kx, MX = _residuals(K, M, X_e, lam_e)
    residuals = R / kx
    # Normwise backward error ||r|| / ((||K|| + w^2 ||M||) ||x||): the relative residual
    # above has a round-off floor of about eps * w_max^2 / w^2, which slender shafts
    # (low modes, fine meshes) reach; the backward error has none.
    nx = np.linalg.norm(X_e, axis=0)
    backward = R / ((spnorm(K, 1) + lam_e * spnorm(M, 1)) * nx)
    ortho = float(np.max(np.abs(X_e.T @ MX - np.eye(X_e.shape[1]))))
    energy = energy_split(X_e, nodes, mass_scalar)
    freqs = np.sqrt(lam_e) / (2 * math.pi)
    rigid = np.sqrt(np.abs(lam[is_rigid])) / (2 * math.pi)
    return Modes(frequencies=freqs, shapes=X_e, residuals=residuals, backward_errors=backward,
                 kinds=[classify(e) for e in energy], energy=energy,
                 rigid_frequencies=rigid, orthonormality_error=ortho,
                 shift=-SHIFT_FACTOR * scale, n_dofs=K.shape[0], factorizer=sol.factorizer,
                 factorisation_seconds=sol.factorisation_seconds,
                 eigensolve_seconds=sol.eigensolve_seconds)


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
