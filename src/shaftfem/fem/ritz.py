"""Ritz pairs of the pencil (K, M): approximate eigenpairs with K X and M X kept.

Rayleigh-Ritz on a basis V solves the small dense problem V^T K V q = w^2 V^T M V q;
its pairs are the best the span of V holds, and their residuals K x - w^2 M x say
how good they are.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.linalg import eigh


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

    def rotated(self, Q: np.ndarray) -> Ritz:
        """The vectors X Q, Q orthogonal and mixing only pairs of one eigenvalue (within
        the solver's tolerance): the eigenvalues stay."""
        return Ritz(self.lam, self.X @ Q, self.KX @ Q, self.MX @ Q)

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
