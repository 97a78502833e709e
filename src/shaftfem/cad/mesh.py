"""Tetrahedral meshes of the shaft's solid (cad.mesher meshes; this module checks them).

Second-order elements are curved onto the CAD surfaces; every element's
Jacobian determinant is checked and a mesh with an inverted or degenerate
element is refused. A shaft without grooves is meshed as a 90-degree periodic
sector and copied four times, so the mesh has the shaft's 4-fold symmetry and
bending pairs come out exactly degenerate.

A mesh is a function of the solid, the shaft and groove parameters and the
settings; workflows.stages keeps it in the cache under a key of those (and the
meshing constants and gmsh's version), so a re-run of an unchanged scene skips
meshing and gets the very same nodes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from shaftfem.cad.solid import ShaftShape
from shaftfem.cad.tetrahedra import (
    MIN_JACOBIAN_RATIO,
    jacobian_ratio,
    skfem_mesh,
    sorted_cells,
    straighten_folded,
    triple_products,
)
from shaftfem.errors import BudgetError, MeshError
from shaftfem.scene.model import Grooves, MeshSettings, Shaft, cell_type

# Bump when the meshing or what is kept of a mesh changes, so that meshes made before are
# not reused (workflows.stages keys them with it)
# (2: entries carry checksums; 3: the checksum covers the arrays in name order; 4: they
# keep the points from before the straightening; 5: cubic meshes without gmsh's
# high-order optimiser; 6: quadratic meshes' folds keep a share of their curving too).
MESH_VERSION = 6


@dataclass(frozen=True)
class ShaftMesh:
    """A tetrahedral mesh in m: points (N, 3), cells (E, 4 or 10) in VTK/meshio node
    order, or (E, 20) for cubic geometry, in the cubic element's order (cad.cubic)."""

    points: np.ndarray
    cells: np.ndarray
    order: int
    min_jacobian_ratio: float
    straightened: int  # curved elements made straight-sided to stay valid
    from_cache: bool = False
    # the points before the straightening (None where no element was straightened):
    # there the straightened elements' faces followed the CAD surfaces
    unfolded: np.ndarray | None = None
    # made by gmsh's HXT where its Delaunay did not end within its time (_refined): a
    # different mesh of the same sizes, which the run reports
    hxt: bool = False

    @property
    def n_elements(self) -> int:
        return self.cells.shape[0]

    @property
    def geometry_order(self) -> int:
        """The degree of the map from the reference element: 1, 2 or 3."""
        return {4: 1, 10: 2, 20: 3}[self.cells.shape[1]]

    @property
    def cell_type(self) -> str:
        """meshio's name of the cells."""
        return "tetra20" if self.geometry_order == 3 else cell_type(self.order)

    @property
    def element_cells(self) -> np.ndarray:
        """The cells as the elements take them: for orders 3 to 5, vertices in ascending
        order (sorted_cells), so that neighbours agree on their edges' nodes."""
        if self.order < 3 or self.geometry_order == 3:  # cubic cells come ascending
            return self.cells
        return sorted_cells(self.cells)

    def to_skfem(self):
        """The same mesh as a scikit-fem MeshTet1/MeshTet2, its cells as `element_cells`
        (made once: its faces and edges take a tenth of a second on the default mesh,
        and the assembly, the recovery and the bound each ask for it)."""
        made = self.__dict__.get("_skfem")
        if made is None:
            made = skfem_mesh(self.points, self.element_cells)
            object.__setattr__(self, "_skfem", made)
        return made


# Tetrahedra gmsh makes per h^3 of volume (a regular tetrahedron fills h^3 / 8.5; gmsh's
# are less regular), those its surface layer adds per h^2 of a profile's surface, and
# DOFs per element of a P2 / P1 mesh; fitted on the shipped scenes and examples (within
# 40 %, enough to refuse a size that is off by orders of magnitude: the mesh's own count
# is checked again before assembly).
ELEMENTS_PER_H3 = 6.0
ELEMENTS_PER_H2 = 1.1
DOFS_PER_ELEMENT = {1: 0.6, 2: 5.5, 3: 17.0, 4: 40.0, 5: 74.0}
BYTES_PER_DOF = 11e3   # peak memory of a modal run per DOF (docs/performance.md)


def _near_layer(small: float, large: float, grading: float, measure) -> float:
    """Elements in the layer a cad.mesher._near field makes: size `small` within small / 2
    of the feature, growing linearly to `large` over `grading` times the difference, with
    `measure(x)` the area (or perimeter) at distance x of the feature."""
    d0, d1 = 0.5 * small, 0.5 * small + grading * (large - small)
    x = np.linspace(0.0, d1, 400)
    h = np.where(x <= d0, small, small + (large - small) * (x - d0) / max(d1 - d0, 1e-12))
    return float(np.trapezoid(measure(x) / h**3, x)) * ELEMENTS_PER_H3


def estimate_dofs(shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
                  hubs: tuple[tuple[float, float], ...] = ()) -> int:
    """About how many DOFs `settings` give on this shaft, without meshing, from the size
    fields cad.mesher sets: each section at its own size (smaller in a thin section, and
    in a bored one at most twice its wall and its bore's radius) with the layer along its surfaces,
    the parts' seats (`hubs`, z0 and z1 in m) finer, a graded layer over the faces of the
    grooves and of the profile's features (fillets, chamfers, keyways), and a tube around
    the grooves' floor edges."""
    from shaftfem.cad.mesher import EDGE_GRADING, FACE_GRADING, HUB_SIZE

    s, order = settings.size, settings.order
    sections = _section_sizes(shaft, s)
    elements = sum(ELEMENTS_PER_H3 * volume / h**3 for volume, area, h in sections)
    if not shaft.plain:   # a plain bar is a sector's mesh, copied: no surface layer to add
        elements += sum(ELEMENTS_PER_H2 * area / h**2 for volume, area, h in sections)
    for z0, z1 in hubs:   # the parts' seats at HUB_SIZE, a radius beyond each end
        box = np.pi * shaft.radius**2 * (z1 - z0 + 2 * shaft.radius)
        elements += ELEMENTS_PER_H3 * box * (1 / (HUB_SIZE * s) ** 3 - 1 / s**3)
    gs = settings.groove_size
    area, rings = _features(shaft)
    if area and gs < s:
        # the graded layer over the faces, and about their edges a tube that grows with
        # the distance (what dominates a feature much smaller than the layer)
        elements += _near_layer(gs, s, FACE_GRADING, lambda x: area + rings * np.pi * x)
    if grooves is not None:
        g, es = grooves, settings.edge_size
        r_mid = shaft.radius - g.depth / 2
        helix = g.length * np.hypot(1.0, 2 * np.pi * r_mid / g.pitch)
        faces = len(g.hands) * helix * (g.width + 2 * g.depth)
        if gs < s:
            elements += _near_layer(gs, s, FACE_GRADING, lambda x: np.full_like(x, faces))
        if es < gs:
            edges = 2 * len(g.hands) * helix
            elements += _near_layer(es, gs, EDGE_GRADING,
                                    lambda x: edges * np.pi * np.maximum(x, 0.5 * es))
    return int(elements * DOFS_PER_ELEMENT[order])


def _section_sizes(shaft: Shaft, size: float) -> list[tuple[float, float, float]]:
    """(volume m^3, surface m^2, element size m) of each section, as
    cad.mesher._profile_fields sizes it; a STEP solid's as its bounding cylinder's."""
    from shaftfem.cad.mesher import section_size

    if shaft.step is not None:
        r, length = shaft.radius, shaft.length
        return [(np.pi * r**2 * length, 2 * np.pi * r * length, size)]
    out = []
    for sec in shaft.profile:
        r0, r1 = sec.diameter_start / 2, sec.diameter_end / 2
        volume = np.pi * sec.length * ((r0 * r0 + r0 * r1 + r1 * r1) / 3 - (sec.bore / 2) ** 2)
        surface = np.pi * sec.length * (r0 + r1 + sec.bore)
        out.append((volume, surface, section_size(shaft, sec, size)))
    return out


def _features(shaft: Shaft) -> tuple[float, float]:
    """The area of the profile's feature faces, m^2 (to a few per cent): the fillet and
    chamfer rings at its steps and ends, and each keyway's floor, walls and ends; and the
    length of the rings and keyway rims that bound them, m."""
    area = rings = 0.0
    prof = shaft.profile
    for sec, nxt in zip(prof, prof[1:]):
        small = min(sec.diameter_end, nxt.diameter_start) / 2
        big = max(sec.diameter_end, nxt.diameter_start) / 2
        if sec.fillet:
            area += 2 * np.pi * small * (np.pi / 2) * sec.fillet
            rings += 2 * np.pi * small
        if sec.chamfer:
            area += 2 * np.pi * big * np.sqrt(2) * sec.chamfer
            rings += 2 * np.pi * big
    if prof and shaft.end_chamfer:
        for d in (prof[0].diameter_start, prof[-1].diameter_end):
            area += np.pi * d * np.sqrt(2) * shaft.end_chamfer
            rings += np.pi * d
    for k in shaft.keyways:
        area += k.length * (k.width + 2 * k.depth) + 2 * k.width * k.depth
        rings += 2 * (k.length + k.width)
    return float(area), float(rings)


def _too_big(what: str, n: float, max_dofs: int, settings: MeshSettings) -> BudgetError:
    return BudgetError(
        f"element size {settings.size * 1e3:g} mm (features and grooves "
        f"{settings.groove_size * 1e3:.3g} mm, floor edges {settings.edge_size * 1e3:.3g} mm) "
        f"{what} {n:.3g} DOFs and {n * BYTES_PER_DOF / 1e9:.2g} GB, above the budget of "
        f"{max_dofs} DOFs; use a larger size, or raise the budget ([mesh] max_dofs or "
        "--max-dofs)")


# The estimate's own spread: a mesh estimated within this factor of the budget is made
# and its DOFs counted (check_mesh_budget) before it is refused.
ESTIMATE_SPREAD = 1.4


def check_budget(shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
                 max_dofs: int, hubs: tuple[tuple[float, float], ...] = ()) -> int:
    """Refuse, before meshing, a mesh that would need more than `max_dofs` DOFs by more
    than the estimate's spread (nearer the budget, the mesh's own count decides)."""
    n = estimate_dofs(shaft, grooves, settings, hubs)
    if n > ESTIMATE_SPREAD * max_dofs:
        raise _too_big("would need about", n, max_dofs, settings)
    return n


def mesh_dofs(mesh: ShaftMesh) -> int:
    """The DOFs of the mesh's elements, counted: three per node of the P1/P2 cells, and for
    orders 3 to 5 three per hierarchical function on its vertices, edges, faces and
    cells."""
    p = mesh.order
    if p <= 2 and mesh.geometry_order <= p:
        return 3 * int(mesh.points.shape[0])
    tets = np.sort(mesh.cells[:, :4], axis=1)
    vertices = np.unique(tets).size
    edges = np.unique(tets[:, [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]]
                      .reshape(-1, 2), axis=0).shape[0]
    if p <= 2:
        return 3 * (vertices + (p - 1) * edges)
    faces = np.unique(tets[:, [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]].reshape(-1, 3),
                      axis=0).shape[0]
    scalar = (vertices + (p - 1) * edges + (p - 1) * (p - 2) // 2 * faces
              + (p - 1) * (p - 2) * (p - 3) // 6 * len(tets))
    return 3 * int(scalar)


def check_mesh_budget(mesh: ShaftMesh, settings: MeshSettings, max_dofs: int) -> int:
    """Refuse, after meshing and before assembly, a mesh whose DOFs, counted, exceed the
    budget (the estimate before meshing can miss a feature's small elements)."""
    n = mesh_dofs(mesh)
    if n > max_dofs:
        raise _too_big(f"meshed to {mesh.n_elements} elements, which have", n, max_dofs,
                       settings)
    return n


def check_memory(n_dofs: int) -> None:
    """Refuse a run whose peak memory (BYTES_PER_DOF a DOF) this machine does not have
    free, before assembly and factorisation fill it."""
    import psutil

    need, free = n_dofs * BYTES_PER_DOF, psutil.virtual_memory().available
    if need > free:
        raise BudgetError(
            f"{n_dofs} DOFs need about {need / 1e9:.3g} GB at the solve's peak, and this "
            f"machine has {free / 1e9:.3g} GB free: use a larger element size (--mesh-size), "
            "a lower order, or a machine with more memory")


MESH_ARRAYS = ("points", "cells", "order", "ratio", "straightened", "unfolded")


def mesh_arrays(mesh: ShaftMesh) -> dict[str, Any]:
    """A mesh as the named arrays of a cache entry."""
    return dict(points=mesh.points, cells=mesh.cells, order=np.int64(mesh.order),
                ratio=np.float64(mesh.min_jacobian_ratio),
                straightened=np.int64(mesh.straightened),
                unfolded=np.zeros((0, 3)) if mesh.unfolded is None else mesh.unfolded)


def mesh_from_arrays(fields: dict) -> ShaftMesh:
    """The mesh of a cache entry's arrays."""
    return ShaftMesh(points=fields["points"], cells=fields["cells"], order=int(fields["order"]),
                     min_jacobian_ratio=float(fields["ratio"]),
                     straightened=int(fields["straightened"]),
                     from_cache=True, unfolded=fields["unfolded"] if len(fields["unfolded"]) else None)


def generate_mesh(shape: ShaftShape, shaft: Shaft, grooves: Grooves | None,
                  settings: MeshSettings, sizes=None, cuts: tuple[float, ...] = (),
                  hubs: tuple[tuple[float, float], ...] = (), refine: bool = False
                  ) -> ShaftMesh:
    """Mesh the solid and check every element's Jacobian. `cuts`: z (m) where the mesh
    must have faces (the edges of seat bands); `hubs`: the parts' seats (z0, z1), meshed
    finer; `sizes`: an element-size field to follow instead of the settings' (points
    (N, 3), tets (E, 4), size at each point, m), or with `refine` only where it is finer
    than the settings'."""
    from shaftfem.cad.mesher import mesh_solid

    hxt = False
    if sizes is None:
        points, cells = mesh_solid(shape.brep, shaft, grooves, settings, None, cuts, hubs)
    else:
        points, cells, hxt = _refined(shape.brep, shaft, grooves, settings, sizes, cuts, hubs,
                                      refine)
    if shape.brep is None:
        points, cells = _four_copies(points, cells)
    return checked_mesh(points, cells, settings, hxt)


def checked_mesh(points: np.ndarray, cells: np.ndarray, settings: MeshSettings,
                 hxt: bool = False) -> ShaftMesh:
    """A mesher's points and cells as a ShaftMesh: the nodes no element uses dropped,
    cubic geometry curved inside, folded curved elements straightened as far as they
    must be, and every element's Jacobian checked."""
    points, cells = _compact(points, cells)
    straightened = 0
    curved = points
    if settings.geometry_order == 3:
        from shaftfem.cad.cubic import ascending, curve_inside

        cells = ascending(cells)   # copies of a sector renumber the vertices
        curved = curve_inside(points, cells)
    if settings.order >= 2:        # curved elements: each fold keeps what curving it can
        points, straightened = straighten_folded(curved, cells)
    ratio = check_jacobians(points, cells)
    return ShaftMesh(points=points, cells=cells, order=settings.order, min_jacobian_ratio=ratio,
                     straightened=straightened, unfolded=curved if straightened else None,
                     hxt=hxt)


# A refined mesh's sizes are set by a run, not by its user, who cannot change them.
# gmsh's Delaunay refinement can fail to settle on them: a pump shaft's keyway, its 0.6 mm
# floor corner asked for 0.36 mm elements, was still inserting and removing points after
# two million steps (for more than 14 minutes; the same solid at 0.8 mm took 5 s). So
# a refined mesh's Delaunay runs in another process, given DELAUNAY_SECONDS plus
# DELAUNAY_PER_ELEMENT (some fifteen times its usual rate) for each element its sizes
# ask; past that, the mesh is made by gmsh's HXT instead (11 s on that keyway), and so
# are the solid's later refinements in this run (they refine the same places further).
DELAUNAY_SECONDS = 30.0
DELAUNAY_PER_ELEMENT = 1.5e-3
_UNSETTLED: set[str] = set()   # the solids (their BREP files) whose Delaunay did not end
# a refined mesh whose surface facets crossed (a message with one of CROSSED) is asked
# again with its sizes these times smaller, in turn
PLC_RETRIES = (0.93, 0.86)
CROSSED = ("PLC Error", "overlapping facets")


def refined_elements(sizes: tuple[np.ndarray, np.ndarray, np.ndarray]) -> float:
    """About how many tetrahedra a size field asks: each of its tetrahedra's volume
    over h^3 at the mean of its vertices' sizes, ELEMENTS_PER_H3 per h^3, at least one."""
    points, tets, h = sizes
    volume = np.abs(triple_products(points, tets)) / 6.0
    return float(np.sum(np.maximum(1.0, ELEMENTS_PER_H3 * volume / h[tets].mean(axis=1) ** 3)))


def _refined(brep, shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
             sizes: tuple[np.ndarray, np.ndarray, np.ndarray], cuts: tuple[float, ...],
             hubs: tuple[tuple[float, float], ...], refine: bool
             ) -> tuple[np.ndarray, np.ndarray, bool]:
    """cad.mesher.mesh_solid by Delaunay within its time (see DELAUNAY_SECONDS), else
    by HXT: the points, the cells and whether HXT made them; asked again a little finer
    (PLC_RETRIES) where the surface mesh's facets crossed."""
    points, tets, h = sizes
    scales = (1.0, *PLC_RETRIES)
    for scale in scales[:-1]:
        try:
            return _refined_once(brep, shaft, grooves, settings, (points, tets, scale * h),
                                 cuts, hubs, refine)
        except MeshError as e:
            # a surface mesh whose facets cross each other (gmsh's boundary recovery:
            # "PLC Error: A segment and a facet intersect", "Invalid boundary mesh
            # (overlapping facets)"; a grooved solid whose 2 mm root fillets span its 2 mm
            # deep grooves) is a matter of where the surface's vertices fell: the same
            # sizes a little smaller put them elsewhere
            if not any(m in str(e) for m in CROSSED):
                raise
    return _refined_once(brep, shaft, grooves, settings, (points, tets, scales[-1] * h),
                         cuts, hubs, refine)


def _refined_once(brep, shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
                  sizes: tuple[np.ndarray, np.ndarray, np.ndarray], cuts: tuple[float, ...],
                  hubs: tuple[tuple[float, float], ...], refine: bool
                  ) -> tuple[np.ndarray, np.ndarray, bool]:
    """_refined's one try: by Delaunay within its time, else by HXT."""
    from shaftfem.aside import Aside
    from shaftfem.cad.mesher import mesh_solid

    given = (brep, shaft, grooves, settings, sizes, cuts, hubs, refine)
    limit = DELAUNAY_SECONDS + DELAUNAY_PER_ELEMENT * refined_elements(sizes)
    if str(brep) not in _UNSETTLED:
        try:
            return (*_aside(Aside(mesh_solid, *given), limit, "Delaunay"), False)
        except TimeoutError:
            _UNSETTLED.add(str(brep))
    # HXT aside too: where it crashed (a keyway running into a shoulder's fillet, its
    # third refinement: "munmap_chunk(): invalid pointer") it took the whole run with it
    return (*_aside(Aside(mesh_solid, *given, True), None, "HXT"), True)


def _aside(job, timeout: float | None, mesher: str):
    """A mesher's answer from its own process; its process dying (gmsh crashing in
    native code) is a MeshError that says so."""
    from shaftfem.aside import AsideStopped

    try:
        return job.result(timeout=timeout)
    except AsideStopped as e:
        raise MeshError(f"gmsh's {mesher} stopped without a mesh ({e})") from None


def _four_copies(points: np.ndarray, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rotate a quarter mesh by 0, 90, 180, 270 degrees and merge the shared nodes."""
    pts, cls = [], []
    p = points.copy()
    for k in range(4):
        pts.append(p)
        cls.append(cells + k * len(points))
        p = np.column_stack([-p[:, 1], p[:, 0], p[:, 2]])  # exact quarter turn
    allp = np.vstack(pts)
    # Copies of a node agree to round-off of the periodic mapping; merge on a 1e-9 m grid.
    _, first, inverse = np.unique(np.round(allp, 9), axis=0, return_index=True,
                                  return_inverse=True)
    return allp[first], inverse.reshape(-1)[np.vstack(cls)]


def _compact(points: np.ndarray, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Drop nodes no element uses (gmsh keeps CAD points as mesh nodes)."""
    used = np.unique(cells)
    remap = np.full(points.shape[0], -1, dtype=np.int64)
    remap[used] = np.arange(used.size)
    return np.ascontiguousarray(points[used]), remap[cells]


def check_jacobians(points: np.ndarray, cells: np.ndarray) -> float:
    """Refuse a mesh with an inverted or degenerate element; return the worst ratio."""
    ratio = jacobian_ratio(points, cells)
    if ratio <= MIN_JACOBIAN_RATIO:
        raise MeshError(
            f"the mesh has an inverted or degenerate element (min/max det J within an "
            f"element = {ratio:.3g}, required > {MIN_JACOBIAN_RATIO}); try a different "
            "element size"
        )
    return ratio


