"""Cubic geometry: gmsh's 20-node tetrahedra as the elements take them.

A cubic map follows the groove faces far closer than a quadratic one: on the paper's
shaft at 16/8/8 mm the mesh holds the solid's volume to 3.5e-5 instead of 4.6e-3, and
order 4 is 0.15 % off instead of 0.53 % on the same DOFs (docs/accuracy.md). gmsh
curves only the boundary (cad.mesher puts its nodes at their parametric places); the
boundary's curving is carried inside by a harmonic extension, and the few elements
still folded (a face across a 1 mm root fillet over an element thinner than the
fillet's sagitta allows) keep what share of their curving leaves them valid.

gmsh's high-order optimisers are not used: on the paper's shaft at 16/12/12 mm they
took 64 s of a 98 s order-5 run, gave a different mesh at each meshing, and left order
5 as far from the reference (0.056-0.072 %) as this route's 0.066 %, with 168
elements partly straightened against their 34-44.

Cells are (E, 20) in the cubic element's node order (cad.tetrahedra.CUBIC_NODES: the vertices,
two nodes per edge from its first vertex, the face centres) with the vertices in
ascending global order, so that neighbours agree on every edge's and face's nodes.
"""

from __future__ import annotations

import numpy as np

from shaftfem.cad.tetrahedra import (
    CUBIC_NODES,
    EDGES,
    FACES,
    barycentric,
    skfem_mesh,
    straight_positions,
    triple_products,
)
from shaftfem.errors import MeshError

OURS = barycentric(CUBIC_NODES)


def ascending(cells: np.ndarray, local: np.ndarray = CUBIC_NODES) -> np.ndarray:
    """Cells (E, 20) whose node k sits at reference point `local[k]` (gmsh's order, or
    ours with the vertices in any order), as ascending-vertex cells in our node order."""
    theirs = barycentric(local)
    perm = np.argsort(cells[:, :4], axis=1)
    out = np.empty_like(cells)
    for key in {tuple(p) for p in perm}:
        rows = np.all(perm == key, axis=1)
        # our node k over the sorted vertices is at barycentrics OURS[k][inverse] over
        # the cell's own vertex order
        mapped = OURS[:, np.argsort(key)]
        pick = [int(np.argmin(np.abs(theirs - m).sum(axis=1))) for m in mapped]
        if len(set(pick)) != 20:
            raise MeshError("gmsh's 20-node tetrahedra do not have the expected nodes")
        out[rows] = cells[rows][:, pick]
    return out


def _boundary_nodes(cells: np.ndarray) -> np.ndarray:
    """The nodes on faces that belong to one cell only."""
    faces = np.concatenate([cells[:, list(f)] for f in FACES])
    _, inverse, counts = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True,
                                   return_counts=True)
    local = [list(f) + [4 + 2 * k + j for k, e in enumerate(EDGES) if set(e) <= set(f)
                        for j in (0, 1)] + [16 + n] for n, f in enumerate(FACES)]
    nodes = np.concatenate([cells[:, n] for n in local])
    return np.unique(nodes[counts[inverse.ravel()] == 1])


def curve_inside(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Inner edge and face nodes moved from their straight positions by the harmonic
    extension (weighted by 1 / det J, so small elements deform least) of the boundary
    nodes' displacement from theirs."""
    import scipy.sparse.linalg as sla
    from skfem import Basis, BilinearForm
    from skfem.helpers import dot, grad

    straight = points.copy()
    straight[cells[:, 4:]] = straight_positions(points, cells)
    mesh = skfem_mesh(straight, cells)
    basis = Basis(mesh, mesh.elem(), intorder=4)
    dof = np.empty(points.shape[0], dtype=np.int64)
    dof[cells.T] = basis.element_dofs
    w = 1.0 / np.abs(basis.mapping.detDF(basis.X))
    L = BilinearForm(lambda u, v, p: dot(grad(u), grad(v)) * p.w).assemble(basis, w=w)
    fixed = np.union1d(dof[_boundary_nodes(cells)], basis.element_dofs[:4].ravel())
    free = np.setdiff1d(np.arange(basis.N), fixed)
    d = np.zeros((basis.N, 3))
    d[dof] = points - straight
    if free.size:
        d[free] = sla.splu(L[free][:, free].tocsc()).solve(-(L[free][:, fixed] @ d[fixed]))
    return straight + d[dof]


# Other programs' 20-node tetrahedra: each node's reference coordinates, times 3 (tests
# check both tables against gmsh's getElementProperties and VTK's vtkLagrangeTetra).
GMSH_NODES = np.array([
    [0, 0, 0], [3, 0, 0], [0, 3, 0], [0, 0, 3], [1, 0, 0], [2, 0, 0], [2, 1, 0], [1, 2, 0],
    [0, 2, 0], [0, 1, 0], [0, 0, 2], [0, 0, 1], [0, 1, 2], [0, 2, 1], [1, 0, 2], [2, 0, 1],
    [1, 1, 0], [1, 0, 1], [0, 1, 1], [1, 1, 1]]) / 3.0
VTK_NODES = np.array([
    [0, 0, 0], [3, 0, 0], [0, 3, 0], [0, 0, 3], [1, 0, 0], [2, 0, 0], [2, 1, 0], [1, 2, 0],
    [0, 2, 0], [0, 1, 0], [0, 0, 1], [0, 0, 2], [2, 0, 1], [1, 0, 2], [0, 2, 1], [0, 1, 2],
    [1, 0, 1], [1, 1, 1], [0, 1, 1], [1, 1, 0]]) / 3.0


def in_node_order(points: np.ndarray, cells: np.ndarray, local: np.ndarray) -> np.ndarray:
    """Cells (E, 20, ours) as another program's 20-node tetrahedra, node k at reference
    point `local[k]`, every element positively oriented (vertices 1 and 2 swapped where
    the ascending order turned it)."""
    turned = triple_products(points, cells) < 0
    target = barycentric(local)
    out = np.empty_like(cells)
    for flip in (False, True):
        rows = turned == flip
        order = [0, 2, 1, 3] if flip else [0, 1, 2, 3]
        # node k sits at barycentrics target[k] over the vertices in `order`
        over_ours = np.zeros_like(target)
        over_ours[:, order] = target
        pick = [int(np.argmin(np.abs(OURS - b).sum(axis=1))) for b in over_ours]
        out[rows] = cells[rows][:, pick]
    return out
