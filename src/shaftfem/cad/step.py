"""The user's own solid from a STEP file: imported through gmsh's OpenCASCADE, checked to
be one solid, and placed with its axis along z from z = 0, in m.

What the import finds is said to the user (`StepImport.summary`): the axis, the length,
the volume and the outer radius's range, so that a file in the wrong unit or with the
wrong axis is seen at once.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shaftfem.cad.session import session, stdout_to_devnull, translated
from shaftfem.errors import SceneError
from shaftfem.scene.model import StepSolid


@dataclass(frozen=True)
class StepImport:
    """What a STEP import found, in m: the axis (two points in the file's coordinates),
    the solid's length along it, its volume (m^3), its largest and smallest outer radius
    (over its length) and its smallest radius anywhere (a bore, a keyway's floor)."""

    axis: tuple[tuple[float, float, float], tuple[float, float, float]]
    length: float
    volume: float
    outer_max: float
    outer_min: float
    inner_min: float

    def summary(self, name: str) -> str:
        a, b = (", ".join(f"{v * 1e3:.4g}" for v in p) for p in self.axis)
        return (f"{name}: one solid, axis from ({a}) to ({b}) mm, {self.length * 1e3:.5g} mm "
                f"long, {self.volume * 1e9:.6g} mm^3, outer radius {self.outer_min * 1e3:.4g} "
                f"to {self.outer_max * 1e3:.4g} mm")


def import_step(step: StepSolid, where: str, brep: Path | None = None) -> StepImport:
    """Import the STEP file, check it is one solid, find its axis and place it along z
    from z = 0 (written to `brep` when given). `where` names the scene key for errors
    (SceneError, exit 2: the file is the user's input)."""
    with session("step") as s, stdout_to_devnull(), \
            translated(SceneError, f"{where} = {step.path!r}: OpenCASCADE could not read it"):
        gmsh = s.gmsh
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        try:
            gmsh.model.occ.importShapes(step.path)
        finally:
            gmsh.option.setString("Geometry.OCCTargetUnit", "")
        gmsh.model.occ.synchronize()
        vols = gmsh.model.getEntities(3)
        if len(vols) != 1:
            raise SceneError(
                f"{where} = {step.path!r}: holds {len(vols)} solids; shaftfem takes one closed "
                "solid (fuse the parts in CAD, or export the shaft alone)"
                if vols else f"{where} = {step.path!r}: holds no solid (only surfaces or "
                "curves): export the shaft as a closed solid")
        volume = gmsh.model.occ.getMass(3, vols[0][1])
        if not volume > 0:
            raise SceneError(f"{where} = {step.path!r}: the solid has no volume ({volume:g} "
                             "m^3): it is not closed")
        axis = step.axis or _bounding_box_axis(gmsh, where, step.path)
        gmsh.model.occ.affineTransform(vols, _placing(gmsh, axis))
        gmsh.model.occ.synchronize()
        xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(-1, -1)
        gmsh.model.occ.translate(vols, 0, 0, -zmin)
        gmsh.model.occ.synchronize()
        length = zmax - zmin
        radii = _radii(gmsh, length)
        if brep is not None:
            gmsh.write(str(brep))
    return StepImport(axis=axis, length=length, volume=volume, outer_max=radii[0],
                      outer_min=radii[1], inner_min=radii[2])


def _bounding_box_axis(gmsh, where: str, path: str
                       ) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """The z direction through the middle of the solid's bounding box (in x and y); a
    solid longer across than along z has its axis elsewhere, and is refused."""
    xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(-1, -1)
    across = max(xmax - xmin, ymax - ymin)
    if zmax - zmin < across:
        raise SceneError(
            f"{where} = {path!r}: the solid is {across * 1e3:.4g} mm across but only "
            f"{(zmax - zmin) * 1e3:.4g} mm along z, so its axis is not along z: give it with "
            "[shaft] axis_from_mm and axis_to_mm")
    x, y = (xmin + xmax) / 2, (ymin + ymax) / 2
    return (x, y, zmin), (x, y, zmax)


def _placing(gmsh, axis) -> list[float]:
    """The rigid motion (row-major 3x4) taking the axis onto z through the origin."""
    a, b = np.asarray(axis[0], float), np.asarray(axis[1], float)
    u = (b - a) / np.linalg.norm(b - a)
    # an orthonormal frame (e1, e2, u): e1 from the coordinate axis least along u
    helper = np.eye(3)[int(np.argmin(np.abs(u)))]
    e1 = np.cross(helper, u)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u, e1)
    R = np.vstack([e1, e2, u])
    t = -R @ a
    return [*R[0], t[0], *R[1], t[1], *R[2], t[2]]


def _radii(gmsh, length: float) -> tuple[float, float, float]:
    """(largest outer radius, smallest outer radius, smallest radius) of the placed solid,
    from a coarse surface mesh: the outer radius of each of 100 slices along z is its
    largest node radius."""
    xmin, ymin, _, xmax, ymax, _ = gmsh.model.getBoundingBox(-1, -1)
    size = max(xmax - xmin, ymax - ymin, length) / 40
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", size / 4)
    gmsh.model.mesh.generate(2)
    _, xyz, _ = gmsh.model.mesh.getNodes()
    xyz = np.asarray(xyz).reshape(-1, 3)
    gmsh.model.mesh.clear()
    r = np.hypot(xyz[:, 0], xyz[:, 1])
    bins = np.minimum((xyz[:, 2] / max(length, 1e-300) * 100).astype(int), 99)
    outer = np.full(100, -np.inf)
    np.maximum.at(outer, bins, r)
    outer = outer[np.isfinite(outer)]
    return float(outer.max()), float(outer.min()), float(r.min())
