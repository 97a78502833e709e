"""A vertex field read at points of the solid: linear in the tetrahedron holding each
point (its barycentric coordinates). The mesh's tetrahedra have straight sides, while
the solid's surface is curved: a point between a surface chord and the true surface
lies a hair outside every tetrahedron, and is read by the nearest one's linear field
extended that far (REACH of its own size at most); a point farther out is not read.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import sparse

# candidate tetrahedra per point (the nearest centroids), and how far outside its
# nearest tetrahedron a point may lie and still be read from it (the least barycentric
# coordinate): a chord's sagitta is a few percent of the element
CANDIDATES = 12
REACH = 0.25


@dataclass(frozen=True)
class Probe:
    """Reading at points: the interpolation matrix (points, vertices) and which points
    were read (the rows of the others are empty)."""

    matrix: sparse.csr_matrix
    found: np.ndarray

    def tensors(self, stress: np.ndarray) -> np.ndarray:
        """Each case's tensor (k, cases, 3, 3) at the points read, of fields (cases, n,
        3, 3) at the mesh's vertices."""
        cases, n = stress.shape[:2]
        flat = np.moveaxis(stress, 0, 1).reshape(n, cases * 9)
        return np.asarray(self.matrix @ flat).reshape(-1, cases, 3, 3)


def probe(vertices: np.ndarray, tets: np.ndarray, points: np.ndarray, tree=None) -> Probe:
    """The linear interpolation of a field at the mesh's `vertices` (n, 3) over `tets`
    (m, 4) to `points` (k, 3); `tree`, a cKDTree of the tets' centroids (built if not
    given)."""
    from scipy.spatial import cKDTree

    if tree is None:
        tree = cKDTree(vertices[tets].mean(axis=1))
    k = min(CANDIDATES, len(tets))
    _, near = tree.query(points, k)
    near = near.reshape(len(points), k)
    corners = vertices[tets[near]]                       # (k_pts, cand, 4, 3)
    J = np.transpose(corners[..., 1:, :] - corners[..., :1, :], (0, 1, 3, 2))
    rhs = points[:, None, :] - corners[..., 0, :]
    lam = np.linalg.solve(J, rhs[..., None])[..., 0]     # (k_pts, cand, 3)
    bary = np.concatenate([1 - lam.sum(-1, keepdims=True), lam], axis=-1)
    best = np.argmax(bary.min(-1), axis=1)
    rows = np.arange(len(points))
    b = bary[rows, best]
    found = b.min(-1) >= -REACH
    cells = tets[near[rows, best]]
    data = np.where(found[:, None], b, 0.0)
    matrix = sparse.csr_matrix((data.ravel(), (np.repeat(rows, 4), cells.ravel())),
                               shape=(len(points), len(vertices)))
    return Probe(matrix=matrix, found=found)
