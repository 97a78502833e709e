"""How a run is carried out, set in one place: thread pools and RunOptions.

MKL PARDISO's threads do the heavy work of the eigensolve. NumPy's OpenBLAS
pool, started beside them, fights MKL's for the cores: on 2 cores it doubled
the paper shaft's eigensolve (5.4 s against 2.8 s, benchmarks/end_to_end.py).
OpenBLAS reads its thread count once, when NumPy loads, and a later runtime
limit did not have the same effect, so `configure_threads()` must run before
NumPy is imported. The CLI, the sweep workers, the tests and the benchmarks
call it first; a library user does the same:

    import shaftfem.runtime
    shaftfem.runtime.configure_threads()   # before numpy / scipy / shaftfem.workflows.pipeline

A user's own OPENBLAS_NUM_THREADS wins.
"""

from __future__ import annotations

import os
import sys
import warnings
from collections.abc import Callable
from dataclasses import dataclass

BLAS_THREADS = 1


def configure_threads() -> None:
    """One OpenBLAS thread (unless the user set one), before NumPy loads."""
    if "numpy" in sys.modules and "OPENBLAS_NUM_THREADS" not in os.environ:
        warnings.warn("shaftfem.runtime.configure_threads() ran after NumPy was imported: "
                      "OpenBLAS keeps its own thread pool and the eigensolve may be slower",
                      RuntimeWarning, stacklevel=2)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", str(BLAS_THREADS))


def cores() -> int:
    """One thread per core, at most 8."""
    return max(1, min(os.cpu_count() or 1, 8))


def assembly_threads(requested: int | None = None) -> int:
    """Threads for assembling K and M: `requested`, else one per core (at most 8)."""
    if requested is not None:
        return max(1, int(requested))
    return cores()


def worker_env() -> dict[str, str]:
    """Environment for worker processes that share the cores with their siblings."""
    return {"OPENBLAS_NUM_THREADS": str(BLAS_THREADS)}


@dataclass(frozen=True)
class RunOptions:
    """How a run is carried out, never what it computes: whether the cache is read and
    written, whether each solve keeps its mode shapes there for a re-run of the design
    (sweeps and calibrations, which solve each design once, do not: 7 MB a design at
    the default mesh), the factoriser ('auto', 'pardiso', 'cholmod', 'superlu'), the
    assembly threads (None: one per core) and where progress lines go (None: nowhere)."""

    use_cache: bool = True
    keep_solves: bool = True
    factoriser: str = "auto"
    threads: int | None = None
    progress: Callable[[str], None] | None = None

    def say(self, message: str) -> None:
        """One progress line."""
        if self.progress is not None:
            self.progress(message)
