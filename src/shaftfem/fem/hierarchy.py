"""Spaces inside a hierarchical space, on the same mesh: lower orders and orders that
vary from element to element.

Hierarchical spaces are nested (fem.elements): order p - 1's space is spanned by order
p's functions of degree p - 1 or less, so its K and M are order p's restricted to them,
on the same quadrature, with no new mesh or assembly. By the min-max principle none of
its frequencies lies below order p's: f_(p-1) - f_p is a guaranteed lower bound of
f_(p-1)'s error, and the two solutions give the bound of f_p (fem.estimate.combine).

Any set of the global functions spans a conforming space (each is continuous across
the elements that share its vertex, edge or face), so an order per element is a choice
of functions: an edge's or face's functions of degree k are kept when any element
holding it has order k or more (the maximum rule of p-element codes). Raising one
element's order adds functions and so lowers every frequency or leaves it.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from shaftfem.fem.assembly import System


def restricted(system: System, keep: np.ndarray, order: int) -> System:
    """The system of the hierarchical `system`'s scalar functions `keep` (indices,
    ascending; every vertex function among them), whose highest degree is `order`."""
    if system.degrees is None or system.constant is None or system.point_values is None:
        raise ValueError("only a hierarchical system (order 3 and up) has spaces inside")
    dofs = (3 * keep[:, None] + np.arange(3)).ravel()
    return replace(system, K=system.K[dofs][:, dofs].tocsr(), M=system.M[dofs][:, dofs].tocsr(),
                   mass_scalar=system.mass_scalar[keep][:, keep].tocsr(),
                   nodes=system.nodes[keep], order=order,
                   point_values=system.point_values[:, keep].tocsr(),
                   constant=system.constant[keep], degrees=system.degrees[keep],
                   element_dofs=None)


def lower_order(system: System) -> tuple[System, np.ndarray]:
    """Order p - 1's system inside a hierarchical order-p `system`, and which of its
    scalar DOFs it keeps (indices, ascending)."""
    if system.degrees is None:
        raise ValueError("only a hierarchical system (order 3 and up) has a lower order inside")
    keep = np.flatnonzero(system.degrees < system.order)
    return restricted(system, keep, system.order - 1), keep


def spanned(system: System, element_orders: np.ndarray) -> np.ndarray:
    """The scalar functions (indices, ascending) of the space with order
    `element_orders[e]` on element e of the hierarchical `system` (at most its order),
    by the maximum rule: a function is kept when an element holding it has its degree."""
    if system.degrees is None or system.element_dofs is None:
        raise ValueError("only a full hierarchical system has orders per element")
    return _spanned(system.degrees, system.element_dofs, element_orders)


def _spanned(degrees: np.ndarray, element_dofs: np.ndarray,
             element_orders: np.ndarray) -> np.ndarray:
    reach = np.zeros(degrees.size, dtype=np.int64)
    np.maximum.at(reach, element_dofs.ravel(),
                  np.broadcast_to(element_orders, element_dofs.shape).ravel())
    return np.flatnonzero(degrees <= reach)


def assemble_space(mesh, material, element_orders: np.ndarray,
                   threads: int | None = None) -> tuple[System, np.ndarray]:
    """The system of the space with order `element_orders[e]` on element e of a
    mesh.ShaftMesh (the mesh's order the highest), assembled directly: the same K and M
    as `restricted(assemble(mesh), spanned(...))` without the whole space's, and which
    of the whole space's scalar functions it keeps (a mask)."""
    from shaftfem.fem.assembly import (
        MASS_INTORDER,
        Pattern,
        hierarchical_degrees_of,
        hierarchical_system,
        scalar_basis,
        stiffness_and_mass,
    )
    from shaftfem.runtime import assembly_threads

    basis = scalar_basis(mesh)
    keep = _spanned(hierarchical_degrees_of(basis), basis.element_dofs, element_orders)
    number = np.full(basis.N, -1, dtype=np.int64)
    number[keep] = np.arange(keep.size)
    local = number[basis.element_dofs]
    kept = local >= 0
    # every element's kernel is on all its local functions (batched alike; the copies
    # that grouping elements by the degrees they keep takes cost more than it saves);
    # the pairs of functions outside the space are dropped in the sum
    pattern = Pattern.of(np.where(kept, local, 0), keep.size, kept)
    K, Ms = stiffness_and_mass(basis, pattern, material, MASS_INTORDER[mesh.order],
                               assembly_threads(threads))
    return (hierarchical_system(mesh, basis, K, Ms, keep, int(element_orders.max())),
            number >= 0)


def raise_indicators(system: System, keep: np.ndarray, element_orders: np.ndarray,
                     shapes: np.ndarray, eigenvalues: np.ndarray) -> np.ndarray:
    """How much raising each element's order by one would lower the frequencies: per
    element (E,), the largest over the modes of the relative frequency drops that its
    new functions would give one at a time.

    For a mode (lambda, u) of the space `keep` and a function phi outside it, the
    Rayleigh quotient on span(u, phi) falls by about r^2 / (k - lambda m), with
    r = phi^T (K - lambda M) u, k = phi^T K phi, m = phi^T M phi (the hierarchical
    surplus estimate); df / f = dlambda / (2 lambda). `shapes` (3 len(keep), m) are
    M-normalised; `eigenvalues` (m,) in rad^2/s^2."""
    if system.degrees is None or system.element_dofs is None:
        raise ValueError("only a full hierarchical system has orders per element")
    from shaftfem.fem.elements import hierarchical_degrees

    n = system.degrees.size
    U = raised(shapes, keep, n)
    R = system.K @ U - (system.M @ U) * eigenvalues
    k, m = system.K.diagonal()[:, None], system.M.diagonal()[:, None]
    drop = R**2 / np.maximum(k - eigenvalues * m, 1e-3 * k) / (2 * eigenvalues)
    drop = drop.reshape(n, 3, -1).sum(axis=1)
    drop[keep] = 0.0
    new = hierarchical_degrees(system.order)[:, None] == element_orders[None, :] + 1
    per_element = np.einsum("le,lem->em", new, drop[system.element_dofs])
    return per_element.max(axis=1)


def raised(shapes: np.ndarray, keep: np.ndarray, n_nodes: int) -> np.ndarray:
    """Mode shapes (3 len(keep), m) of a space inside as vectors of the whole space (the
    same functions: zero on the functions it does not keep)."""
    out = np.zeros((3 * n_nodes, shapes.shape[1]))
    out[(3 * keep[:, None] + np.arange(3)).ravel()] = shapes
    return out
