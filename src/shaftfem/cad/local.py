"""A slice of the shaft's solid between two planes across the axis, meshed finer round
one point: the local model of a hot spot (fem.submodel drives it by the whole shaft's
displacements on its two cut faces).

The slice is the solid's volumes that reach into z0..z1, each cut there by a plane (a
disk wider than the shaft), as the mesher cuts seat bands (cad.mesher): OpenCASCADE
then intersects the helical and B-spline faces with planes only, 0.2 s where one
intersection of the three cells with a cylinder took 6 s. Its elements are `size`
within `reach` of the point, growing by `grading` of the distance beyond, and elsewhere
as the scene's mesh settings make the whole's (its features' and grooves' faces finer):
a notch's fillet all round the shaft meshed coarsely away from the spot stiffens the
section wrongly alike in every round, which no two rounds' difference shows (a 40/32 mm
shoulder's 1.6 mm fillet read 0.9 % low, its bound 0.13 %).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.cad.session import session, translated
from shaftfem.errors import MeshError
from shaftfem.scene.model import Grooves, MeshSettings, Shaft

if TYPE_CHECKING:
    from shaftfem.cad.mesh import ShaftMesh

# gmsh's Delaunay refinement can fail to settle on a notch's small sizes (the pump
# shaft's 0.6 mm keyway corners kept it inserting and removing points for minutes, as on
# the whole, cad.mesh): a slice's mesh is made in a process of its own, given this long
# (a slice's usual mesh takes 1 to 3 s), and past that by gmsh's HXT, as are that
# slice's later meshes in this run (they refine the same place further)
DELAUNAY_SECONDS = 30.0
_UNSETTLED: set[tuple[str, float, float]] = set()


def slice_mesh(brep: Path, z0: float, z1: float, radius: float, centre: np.ndarray,
               size: float, reach: float, grading: float, shaft: Shaft,
               grooves: Grooves | None, settings: MeshSettings,
               hubs: tuple[tuple[float, float], ...]) -> ShaftMesh:
    """The checked mesh (cad.mesh.checked_mesh) of the solid in `brep` between z0 and z1
    (m), whose largest radius is below `radius` (m):
    `size` (m) within `reach` of `centre` (3,), graded by `grading` to the sizes the
    scene's mesh settings give (its features', grooves' and hubs', cad.mesher), which
    rule beyond. By gmsh's Delaunay within DELAUNAY_SECONDS, else by its HXT."""
    from shaftfem.aside import Aside
    from shaftfem.cad.mesh import _aside, checked_mesh

    given = (brep, z0, z1, radius, centre, size, reach, grading, shaft, grooves, settings,
             hubs)
    which = (str(brep), round(z0, 9), round(z1, 9))
    hxt = which in _UNSETTLED
    if not hxt:
        try:
            points, cells = _aside(Aside(_slice_mesh, *given), DELAUNAY_SECONDS, "Delaunay")
        except TimeoutError:
            _UNSETTLED.add(which)
            hxt = True
    if hxt:
        points, cells = _aside(Aside(_slice_mesh, *given, True), None, "HXT")
    return checked_mesh(points, cells, settings, hxt)


def _slice_mesh(brep: Path, z0: float, z1: float, radius: float, centre: np.ndarray,
                size: float, reach: float, grading: float, shaft: Shaft,
                grooves: Grooves | None, settings: MeshSettings,
                hubs: tuple[tuple[float, float], ...], hxt: bool = False
                ) -> tuple[np.ndarray, np.ndarray]:
    """slice_mesh's one try, by Delaunay or (`hxt`) by HXT on one thread."""
    from shaftfem.cad.mesher import mesh_options, read_tetrahedra, scene_fields

    with session("local") as s, translated(MeshError, "gmsh could not mesh a hot spot's "
                                                      "local model"):
        gmsh = s.gmsh
        occ = gmsh.model.occ
        occ.importShapes(str(brep))
        occ.synchronize()
        for _, v in gmsh.model.getEntities(3):
            lo, hi = occ.getBoundingBox(3, v)[2::3]
            if hi <= z0 + 1e-9 or lo >= z1 - 1e-9:
                occ.remove([(3, v)], recursive=True)
                continue
            # each volume cut by its own planes alone (a disk each): its faces that the
            # planes miss stay the ones it shares with its neighbours
            disks = [(2, occ.addDisk(0, 0, z, 2 * radius, 2 * radius))
                     for z in (z0, z1) if lo + 1e-9 < z < hi - 1e-9]
            if disks:
                occ.fragment([(3, v)], disks)
        occ.synchronize()
        outside = [(3, v) for _, v in gmsh.model.getEntities(3)
                   if not z0 < occ.getCenterOfMass(3, v)[2] < z1]
        occ.remove(outside, recursive=True)
        occ.synchronize()
        # the disks' parts outside the shaft bound no volume
        stray = [(2, t) for _, t in gmsh.model.getEntities(2)
                 if len(gmsh.model.getAdjacencies(2, t)[0]) == 0]
        occ.remove(stray, recursive=True)
        occ.synchronize()
        volumes = gmsh.model.getEntities(3)
        if not volumes:
            raise MeshError(f"the solid has nothing between {z0 * 1e3:g} and {z1 * 1e3:g} mm")
        shared = sum(len(gmsh.model.getAdjacencies(2, t)[0]) == 2
                     for _, t in gmsh.model.getEntities(2))
        if shared < len(volumes) - 1:
            raise MeshError(f"the slice between {z0 * 1e3:g} and {z1 * 1e3:g} mm fell apart "
                            f"into {len(volumes)} volumes sharing {shared} faces")
        point = occ.addPoint(*map(float, centre))
        occ.synchronize()
        f = gmsh.model.mesh.field
        d = f.add("Distance")
        f.setNumbers(d, "PointsList", [point])
        t = f.add("Threshold")
        f.setNumber(t, "InField", d)
        far = settings.size
        f.setNumber(t, "SizeMin", size)
        f.setNumber(t, "SizeMax", far)
        f.setNumber(t, "DistMin", reach)
        f.setNumber(t, "DistMax", reach + (far - size) / grading)
        fields, smallest = scene_fields(gmsh, shaft, grooves, settings, hubs)
        m = f.add("Min")
        f.setNumbers(m, "FieldsList", [t, *fields])
        f.setAsBackgroundMesh(m)
        # as the whole's options (a STEP solid's features sized by their curvature too:
        # away from the spot the slice is meshed as the whole is)
        mesh_options(s, shaft, far, min(size, smallest), hxt)
        gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], 1, "slice")
        gmsh.model.mesh.generate(3)
        if settings.order >= 2:
            gmsh.model.mesh.setOrder(2)
        return read_tetrahedra(gmsh, settings.order, "a hot spot's local model")
