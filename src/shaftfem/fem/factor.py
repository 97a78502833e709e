"""Sparse symmetric factorisations: x = A^-1 b for A = K - sigma M, and A's inertia.

MKL PARDISO is called directly (pypardiso finds the library; its own `solve`
re-checks and re-copies the matrix on every call and leaves MKL's default of
two refinement steps on, which together made each solve three times slower).
PARDISO factorises A = L D L^T (symmetric indefinite), so the same analysis
also gives the inertia of another shift of the same pencil: the number of
negative pivots of K - s M is the number of eigenvalues below s (Sylvester's
law), which is how `modal` proves that no mode was skipped.
CHOLMOD (cholespy) and SuperLU (SciPy) are the other back-ends.
"""

from __future__ import annotations

import ctypes
import functools
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor

import numpy as np
import scipy.sparse as sp

from shaftfem.errors import SolverError

FACTORISERS = ("pardiso", "cholmod", "superlu")
# 'auto' takes SuperLU below this many DOFs, where it is as fast as PARDISO (3k DOFs:
# 0.15-0.19 s against 0.11-0.21 s); from 6.7k DOFs on PARDISO is faster, and 3.6x
# at 49k (the bound's coarser mesh of the paper's shaft: 2.3-3.1 s against 10 s).
# A denser matrix (P3: 132 nonzeros a row against P2's 75) makes SuperLU slow
# sooner: above DENSE_ROW nonzeros a row, 'auto' is always the fastest installed.
AUTO_SUPERLU_BELOW = 5_000
DENSE_ROW = 100

# PARDISO's settings (iparm, 1-based as in MKL's manual): our own values, parallel METIS
# nested dissection, pivots perturbed below 1e-8 (counted, see `perturbed`), no
# iterative refinement (the residuals are 1e-11 without it, and modal refines the
# eigenpairs itself), 1-based indices.
_IPARM = {1: 1, 2: 3, 8: 0, 10: 8, 35: 0}
_SYMMETRIC_INDEFINITE = -2


def available_factorisers() -> list[str]:
    """The factorisation back-ends usable here, fastest first (SuperLU always): PARDISO
    where MKL's library loads, CHOLMOD where cholespy imports."""
    import importlib.util

    out = ["pardiso"] if _mkl_pardiso() is not None else []
    if importlib.util.find_spec("cholespy") is not None:
        out.append("cholmod")
    return out + ["superlu"]


@functools.cache
def _mkl_pardiso():
    """MKL's `pardiso` entry point, or None where MKL is not found: from the lib folder
    of this environment or of one whose site-packages is on the path (where pip's
    `mkl` puts it), else from wherever pypardiso finds it (a slower search).

    MKL is asked for conditional numerical reproducibility (MKL_CBWR=AUTO, unless the
    user set it), read when its library loads: without it the threaded factorisation
    gives results that differ between runs by about 1e-14, and the same scene would not
    give the same frequencies to the last bit twice."""
    import os
    import sys
    from pathlib import Path

    os.environ.setdefault("MKL_CBWR", "AUTO")

    prefixes = [Path(sys.prefix)] + [Path(p).parents[2] for p in sys.path
                                     if p.endswith("site-packages") and len(Path(p).parts) > 3]
    found = [lib for prefix in prefixes for lib in sorted(prefix.glob("lib/libmkl_rt.so*"))]
    try:
        if found:
            lib = ctypes.CDLL(str(found[0]))
        else:
            import pypardiso

            lib = pypardiso.PyPardisoSolver().libmkl
    except (ImportError, OSError):  # pypardiso without MKL's library
        return None
    fn = lib.pardiso
    i32 = ctypes.POINTER(ctypes.c_int32)
    fn.argtypes = [ctypes.POINTER(ctypes.c_int64), i32, i32, i32, i32, i32, ctypes.c_void_p,
                   i32, i32, i32, i32, i32, i32, ctypes.c_void_p, ctypes.c_void_p, i32]
    fn.restype = None
    return fn


def upper_triangle(A: sp.spmatrix) -> sp.csr_matrix:
    """The upper triangle (diagonal included) of a CSR matrix with sorted indices."""
    A = sp.csr_matrix(A)
    A.sort_indices()
    rows = np.repeat(np.arange(A.shape[0], dtype=np.int32), np.diff(A.indptr))
    keep = A.indices >= rows
    indptr = np.zeros(A.shape[0] + 1, dtype=A.indptr.dtype)
    np.cumsum(np.bincount(rows[keep], minlength=A.shape[0]), out=indptr[1:])
    return sp.csr_matrix((A.data[keep], A.indices[keep], indptr), shape=A.shape)


class Pencil:
    """K and M on one sparsity (their upper triangles), so that any shift K - s M is
    one vector operation on the stored values."""

    def __init__(self, K: sp.spmatrix, M: sp.spmatrix):
        Ku, Mu = upper_triangle(K), upper_triangle(M)
        keys, m_keys = _keys(Ku), _keys(Mu)
        at = np.minimum(np.searchsorted(keys, m_keys), len(keys) - 1)
        if not np.array_equal(keys[at], m_keys):  # M has entries where K has none
            union = upper_triangle(abs(Ku) + abs(Mu))
            keys = _keys(union)
            Ku = sp.csr_matrix((_placed(len(keys), np.searchsorted(keys, _keys(Ku)), Ku.data),
                                union.indices, union.indptr), shape=union.shape)
            at = np.searchsorted(keys, m_keys)
        self.indptr, self.indices = Ku.indptr, Ku.indices
        self.k_data = Ku.data.astype(np.float64)
        self.m_data = _placed(len(keys), at, Mu.data)
        self.K, self.M = K, M
        self.n = K.shape[0]

    def upper(self, s: float) -> sp.csr_matrix:
        """The upper triangle of K - s M."""
        return sp.csr_matrix((self.k_data - s * self.m_data, self.indices, self.indptr),
                             shape=(self.n, self.n))

    def full(self, s: float) -> sp.csr_matrix:
        """K - s M, both triangles."""
        return (self.K - s * self.M).tocsr()


def _keys(A: sp.csr_matrix) -> np.ndarray:
    rows = np.repeat(np.arange(A.shape[0], dtype=np.int64), np.diff(A.indptr))
    return rows * A.shape[1] + A.indices


def _placed(size: int, at: np.ndarray, values: np.ndarray) -> np.ndarray:
    """`values` at positions `at` of an array of `size` zeros."""
    out = np.zeros(size)
    out[at] = values
    return out


class Pardiso:
    """L D L^T of a symmetric matrix by MKL PARDISO, from its upper triangle (CSR).

    `refactor(B)` factorises another matrix of the same sparsity (a new shift of
    the same pencil) reusing the analysis; `inertia` counts the signs of D."""

    def __init__(self, upper: sp.csr_matrix, factorise: bool = True):
        """Analyse `upper`'s sparsity (ordering, symbolic factorisation) and, unless
        `factorise` is False, factorise it; the analysis looks at no values."""
        if np.any(np.diff(upper.indptr) == 0):
            raise SolverError("the matrix has an empty row: a DOF no element touches")
        call = _mkl_pardiso()
        if call is None:
            raise SolverError("PARDISO asked for, but MKL's library (libmkl_rt) is not found: "
                              "install the mkl package, or choose another factoriser")
        self._call = call
        self.n = upper.shape[0]
        self._pt = np.zeros(64, dtype=np.int64)
        self._iparm = np.zeros(64, dtype=np.int32)
        for k, v in _IPARM.items():
            self._iparm[k - 1] = v
        self._ia = (upper.indptr + 1).astype(np.int32)
        self._ja = (upper.indices + 1).astype(np.int32)
        self._indptr, self._indices = upper.indptr, upper.indices
        self._run(11, upper.data)
        if factorise:
            self._run(22, upper.data)

    def _run(self, phase: int, data: np.ndarray, b: np.ndarray | None = None) -> np.ndarray:
        if b is None:
            b = np.zeros((self.n, 1))
        b = np.asfortranarray(b, dtype=np.float64)
        x = np.zeros_like(b)
        err = ctypes.c_int32(0)
        i = ctypes.c_int32
        self._data = np.ascontiguousarray(data, dtype=np.float64)  # PARDISO keeps a pointer
        self._call(self._pt.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)),
                   ctypes.byref(i(1)), ctypes.byref(i(1)), ctypes.byref(i(_SYMMETRIC_INDEFINITE)),
                   ctypes.byref(i(phase)), ctypes.byref(i(self.n)), self._data.ctypes.data,
                   self._ia.ctypes.data_as(ctypes.POINTER(i)),
                   self._ja.ctypes.data_as(ctypes.POINTER(i)), None,
                   ctypes.byref(i(1 if b.ndim == 1 else b.shape[1])),
                   self._iparm.ctypes.data_as(ctypes.POINTER(i)), ctypes.byref(i(0)),
                   b.ctypes.data, x.ctypes.data, ctypes.byref(err))
        if err.value != 0:
            raise SolverError(f"MKL PARDISO failed in phase {phase} with error {err.value}"
                              + (" (not enough memory)" if err.value in (-2, -12) else ""))
        return x

    def solve(self, b: np.ndarray) -> np.ndarray:
        """A^-1 b for one vector (n,) or several (n, m) at once."""
        return np.ascontiguousarray(self._run(33, self._data, b))

    @property
    def inertia(self) -> tuple[int, int]:
        """(positive, negative) pivots of the current factorisation."""
        return int(self._iparm[21]), int(self._iparm[22])

    @property
    def perturbed(self) -> int:
        """Pivots PARDISO perturbed in the current factorisation (0 for a clean one)."""
        return int(self._iparm[13])

    def matches(self, upper: sp.csr_matrix) -> bool:
        """Whether `upper` has the analysed sparsity."""
        return (upper.nnz == len(self._indices) and np.array_equal(upper.indptr, self._indptr)
                and np.array_equal(upper.indices, self._indices))

    def refactor(self, upper: sp.csr_matrix) -> None:
        """Factorise another matrix of the analysed sparsity (its upper triangle)."""
        if not self.matches(upper):
            raise SolverError("refactor: the matrix's sparsity differs from the analysed one")
        self._run(22, upper.data)

    def __del__(self):
        try:
            self._run(-1, np.zeros(1))
        except Exception:  # freeing at interpreter exit: nothing left to report to
            pass


def factorise(A: sp.spmatrix, backend: str = "auto"
              ) -> tuple[Callable[[np.ndarray], np.ndarray], str]:
    """A solve function x = A^-1 b for the SPD matrix A, and the back-end used.

    'pardiso' (Intel MKL PARDISO), 'cholmod' (CHOLMOD via cholespy), 'superlu'
    (SciPy, COLAMD ordering: the pure-SciPy path), or 'auto' (SuperLU for small
    systems, else the fastest installed). All give the same frequencies (a test
    checks 1e-8).
    """
    backend = _resolve(backend, A.shape[0], A.nnz)
    if backend == "pardiso":
        return Pardiso(upper_triangle(A)).solve, backend
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
    raise AssertionError(f"_resolve gave {backend!r}")  # it refuses unknown names itself


def _resolve(backend: str, n: int, nnz: int) -> str:
    """The back-end `backend` means for n unknowns and nnz nonzeros (both triangles)."""
    if backend == "auto":
        small = n < AUTO_SUPERLU_BELOW and nnz < DENSE_ROW * n
        return "superlu" if small else available_factorisers()[0]
    if backend not in FACTORISERS:
        raise SolverError(f"unknown factoriser {backend!r}; choose one of {', '.join(FACTORISERS)}")
    return backend


def uses_pardiso(backend: str, n: int, nnz: int) -> bool:
    """Whether `backend` ('auto' included) means PARDISO for n unknowns and nnz nonzeros."""
    return _resolve(backend, n, nnz) == "pardiso"


def analyse_in_background(upper: sp.csr_matrix) -> Future:
    """PARDISO's analysis of a symmetric matrix's sparsity (`upper`: its upper triangle,
    diagonal included), started in a thread: it needs no values, so it runs while they
    are assembled (ctypes releases the GIL for the call). The future's result is a
    `Pardiso` awaiting `refactor`."""
    pool = ThreadPoolExecutor(1, thread_name_prefix="pardiso-analysis")
    future = pool.submit(Pardiso, upper, False)
    pool.shutdown(wait=False)
    return future


class ShiftedFactor:
    """A factorisation of K - s M for a pencil, that can move to another shift and
    count the pencil's eigenvalues below a shift."""

    def __init__(self, pencil: Pencil, shift: float, backend: str = "auto",
                 analysis: Future | None = None):
        """`analysis`: PARDISO's analysis of the pencil's sparsity, when it was started
        beforehand (analyse_in_background); used if it matches."""
        self.pencil = pencil
        self.backend = _resolve(backend, pencil.n, pencil.K.nnz)
        self._analysis = analysis
        self._pardiso: Pardiso | None = None
        self._solve: Callable[[np.ndarray], np.ndarray] | None = None
        self.shift: float | None = None
        self.shift_to(shift)

    def shift_to(self, s: float) -> None:
        """Factorise K - s M (a no-op if that is the current factor)."""
        if s == self.shift:
            return
        if self.backend == "pardiso":
            upper = self.pencil.upper(s)
            if self._pardiso is None and self._analysis is not None:
                analysed = self._analysis.result()
                if analysed.matches(upper):
                    self._pardiso = analysed
            if self._pardiso is None:
                self._pardiso = Pardiso(upper)
            else:
                self._pardiso.refactor(upper)
            self._solve = self._pardiso.solve
        else:
            self._solve, _ = factorise(self.pencil.full(s), self.backend)
        self.shift = s

    def solve(self, b: np.ndarray) -> np.ndarray:
        """(K - shift M)^-1 b."""
        assert self._solve is not None  # shift_to ran in __init__
        return self._solve(b)

    def count_below(self, s: float) -> int:
        """How many eigenvalues of K x = w^2 M x lie below s (rad^2/s^2): the negative
        pivots of K - s M = L D L^T (Sylvester's law of inertia).

        PARDISO counts them in a factorisation that then stays (the solves are of
        K - s M until `shift_to`); the other back-ends use SuperLU with diagonal pivots."""
        if self.backend == "pardiso":
            self.shift_to(s)
            assert self._pardiso is not None  # shift_to made it
            positive, negative = self._pardiso.inertia
            if positive + negative != self.pencil.n or self._pardiso.perturbed:
                raise SolverError(f"the inertia of K - s M at {_hz(s):.6g} Hz is not clean "
                                  f"({self._pardiso.perturbed} perturbed pivots): s lies on an "
                                  "eigenvalue")
            return negative
        from scipy.sparse.linalg import splu

        lu = splu(sp.csc_matrix(self.pencil.full(s)), permc_spec="MMD_AT_PLUS_A",
                  diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        if not np.array_equal(lu.perm_r, lu.perm_c):
            raise SolverError("counting eigenvalues: SuperLU exchanged rows, so its pivots do "
                              "not give the inertia of K - s M")
        d = lu.U.diagonal()
        if np.any(d == 0):
            raise SolverError(f"K - s M is singular at {_hz(s):.6g} Hz: s lies on an eigenvalue")
        return int(np.sum(d < 0))


def _hz(omega2: float) -> float:
    return float(np.sqrt(max(omega2, 0.0)) / (2 * np.pi))
