"""The proof that an eigensolver found the lowest eigenvalues, none skipped.

Sylvester's law of inertia: the number of negative pivots of K - s M (L D L^T)
equals the number of eigenvalues of (K, M) below s. If the pairs found up to a
clear gap are eigenpairs to their residuals, and the inertia at a shift s in that
gap counts exactly as many, no eigenvalue below s was missed.
"""

from __future__ import annotations

import math

import numpy as np

from shaftfem.errors import SolverError
from shaftfem.fem.factor import ShiftedFactor
from shaftfem.fem.ritz import Ritz

# Two eigenvalues closer than INERTIA_GAP (relative) are counted together.
INERTIA_GAP = 1e-6
# A Ritz pair with a larger relative residual than this is taken for a failed solve
# (the pairs the solver returns reach ~1e-9).
ACCEPT_RESIDUAL = 1e-6


def count_below(factor: ShiftedFactor, s: float) -> int:
    """The eigenvalues below s (rad^2/s^2), by the inertia of K - s M."""
    try:
        return factor.count_below(s)
    except SolverError:
        raise
    except Exception as exc:
        raise SolverError(f"counting the eigenvalues below a shift failed: "
                          f"{type(exc).__name__}: {exc}") from exc


def _split(low: float, high: float) -> float:
    """A shift between two eigenvalues: their geometric mean (the middle if low <= 0)."""
    return math.sqrt(low * high) if low > 0 else 0.5 * (low + high)


def gap_above(lam: np.ndarray, k: int) -> tuple[int, float]:
    """(j, s): the first j >= k with a clear gap between lam[j - 1] and lam[j], and s
    in that gap; the inertia count below s must then be j."""
    for j in range(k, len(lam)):
        if lam[j] > lam[j - 1] * (1 + INERTIA_GAP):
            return j, _split(lam[j - 1], lam[j])
    raise SolverError(f"the {len(lam) - k + 1} highest eigenvalues found are equal to within "
                      f"{INERTIA_GAP:g}: no gap to count them in; ask for more modes")


def verified_gap(pairs: Ritz, k: int, zero: float, r: int) -> tuple[Ritz, int, float]:
    """The pairs that are eigenpairs to their residuals (poor ones dropped), and (j, s):
    a clear gap above the first j of them at s, j >= k where at least k + 1 are,
    else the highest gap there is (j = 0: none). The inertia count below s must then
    be j; a larger count means the solver skipped modes below s."""
    good = pairs.select(pairs.verified(zero, ACCEPT_RESIDUAL, r))
    lam = good.lam
    if len(lam) > k:
        j, s = gap_above(lam, k)
        return good, j, s
    for j in range(len(lam) - 1, 0, -1):
        if lam[j] > lam[j - 1] * (1 + INERTIA_GAP):
            return good, j, _split(lam[j - 1], lam[j])
    return good, 0, 0.0


def unproven(pairs: Ritz, found: int, counted: int, s: float, r: int, ncv: int,
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
