"""The space one order down, on the same mesh: order p's functions of degree below p.

Hierarchical spaces are nested (fem.elements): order p - 1's space is spanned by order
p's functions of degree p - 1 or less, so its K and M are order p's restricted to them,
on the same quadrature, with no new mesh or assembly. By the min-max principle none of
its frequencies lies below order p's: f_(p-1) - f_p is a guaranteed lower bound of
f_(p-1)'s error, and the two solutions give the bound of f_p (fem.estimate.combine).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from shaftfem.fem.assembly import System


def lower_order(system: System) -> tuple[System, np.ndarray]:
    """Order p - 1's system inside a hierarchical order-p `system`, and which of its
    scalar DOFs it keeps (indices, ascending)."""
    if system.degrees is None or system.constant is None or system.point_values is None:
        raise ValueError("only a hierarchical system (order 3 and up) has a lower order inside")
    keep = np.flatnonzero(system.degrees < system.order)
    dofs = (3 * keep[:, None] + np.arange(3)).ravel()
    return replace(system, K=system.K[dofs][:, dofs].tocsr(), M=system.M[dofs][:, dofs].tocsr(),
                   mass_scalar=system.mass_scalar[keep][:, keep].tocsr(),
                   nodes=system.nodes[keep], order=system.order - 1,
                   point_values=system.point_values[:, keep].tocsr(),
                   constant=system.constant[keep], degrees=system.degrees[keep]), keep


def raised(shapes: np.ndarray, keep: np.ndarray, n_nodes: int) -> np.ndarray:
    """Mode shapes (3 len(keep), m) of the lower order as vectors of order p's space (the
    same functions: zero on the functions of degree p)."""
    out = np.zeros((3 * n_nodes, shapes.shape[1]))
    out[(3 * keep[:, None] + np.arange(3)).ravel()] = shapes
    return out
