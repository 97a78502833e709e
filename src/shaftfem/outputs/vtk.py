"""The mesh as a VTK grid, and VTU files written by VTK's own XML writer.

VTK is the reference implementation of the format ParaView reads: it writes
the field data (a mode's number, frequency and kind code) that meshio's VTU
writer leaves out, and 10-node tetrahedra in the node order meshio and gmsh-through-
meshio already use (VTK's). pyvista wraps the same grid for pictures.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from shaftfem.cad.mesh import ShaftMesh


def grid(mesh: ShaftMesh, scale: float = 1.0):
    """A vtkUnstructuredGrid of the mesh, coordinates times `scale` (1: m, 1e3: mm)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import (
        VTK_LAGRANGE_TETRAHEDRON,
        VTK_QUADRATIC_TETRA,
        VTK_TETRA,
        vtkCellArray,
        vtkUnstructuredGrid,
    )

    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(mesh.points * scale), deep=True))
    n, per = mesh.cells.shape
    connectivity = mesh.cells
    if per == 20:  # cubic geometry: VTK's Lagrange tetrahedron, ParaView draws it curved
        from shaftfem.cad.cubic import VTK_NODES, in_node_order

        connectivity = in_node_order(mesh.points, mesh.cells, VTK_NODES)
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.arange(0, (n + 1) * per, per), deep=True),
                  numpy_to_vtkIdTypeArray(np.ascontiguousarray(connectivity.ravel()), deep=True))
    g = vtkUnstructuredGrid()
    g.SetPoints(points)
    kind = {10: VTK_QUADRATIC_TETRA, 20: VTK_LAGRANGE_TETRAHEDRON}.get(per, VTK_TETRA)
    g.SetCells(kind, cells)
    return g


def _array(name: str, values):
    from vtkmodules.util.numpy_support import numpy_to_vtk

    a = numpy_to_vtk(np.ascontiguousarray(np.atleast_1d(values)), deep=True)
    a.SetName(name)
    return a


def write_vtu(path: str | Path, mesh: ShaftMesh, point_data: dict[str, np.ndarray],
              field_data: dict[str, Any]) -> Path:
    """mesh with point arrays (n_points,) or (n_points, 3) and numeric field arrays,
    as a binary VTU file."""
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

    g = grid(mesh)
    for name, values in point_data.items():
        g.GetPointData().AddArray(_array(name, values))
    for name, values in field_data.items():
        g.GetFieldData().AddArray(_array(name, values))
    w = vtkXMLUnstructuredGridWriter()
    w.SetFileName(str(path))
    w.SetInputData(g)
    w.SetDataModeToBinary()  # inline base64, zlib-compressed: meshio reads it too
    if not w.Write():
        raise OSError(f"VTK could not write {path}")
    return Path(path)


def write_vtp(path: str | Path, points: np.ndarray, triangles: np.ndarray,
              point_data: dict[str, np.ndarray]) -> Path:
    """A triangulated surface (points (n, 3), triangles (m, 3)) with point arrays, as a
    binary VTP file (VTK's polygonal data: ParaView opens it)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=True))
    n = len(triangles)
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.arange(0, 3 * (n + 1), 3), deep=True),
                  numpy_to_vtkIdTypeArray(np.ascontiguousarray(triangles.ravel()), deep=True))
    g = vtkPolyData()
    g.SetPoints(pts)
    g.SetPolys(cells)
    for name, values in point_data.items():
        g.GetPointData().AddArray(_array(name, np.asarray(values, dtype=float)))
    w = vtkXMLPolyDataWriter()
    w.SetFileName(str(path))
    w.SetInputData(g)
    w.SetDataModeToBinary()
    if not w.Write():
        raise OSError(f"VTK could not write {path}")
    return Path(path)
