"""The user's own solid from a STEP file: imported through gmsh's OpenCASCADE, checked to
be one solid, and placed with its axis along z from z = 0, in m.

What the import finds is said to the user (`StepImport.summary`): the axis, the length,
the volume and the outer radius's range, so that a file in the wrong unit or with the
wrong axis is seen at once.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from shaftfem.cad.build import check_connected, glue
from shaftfem.cad.session import session, stdout_to_devnull, translated
from shaftfem.errors import GeometryError, SceneError
from shaftfem.scene.checks import check_seats
from shaftfem.scene.model import Scene, StepSolid
from shaftfem.scene.toml_reading import entry, where


@dataclass(frozen=True)
class StepImport:
    """What a STEP import found, in m: the axis (two points in the file's coordinates),
    the solid's length along it, its volume (m^3), and its largest and smallest outer
    radius (over its length)."""

    axis: tuple[tuple[float, float, float], tuple[float, float, float]]
    length: float
    volume: float
    outer_max: float
    outer_min: float
    # (z, r) of points on the outward-facing surfaces, placed (what seats sit on)
    surface: tuple[tuple[float, float], ...] = ()

    def as_dict(self) -> dict:
        """The findings as JSON values (kept with the solid they were found on)."""
        return {"axis": [list(p) for p in self.axis], "length": self.length,
                "volume": self.volume, "outer_max": self.outer_max, "outer_min": self.outer_min,
                "surface": [list(p) for p in self.surface]}

    @classmethod
    def from_dict(cls, d: dict) -> StepImport:
        a, b = (tuple(float(v) for v in p) for p in d["axis"])
        return cls(axis=(a, b), length=float(d["length"]),  # type: ignore[arg-type]
                   volume=float(d["volume"]), outer_max=float(d["outer_max"]),
                   outer_min=float(d["outer_min"]),
                   surface=tuple((float(z), float(r)) for z, r in d.get("surface", [])))

    def summary(self, name: str) -> str:
        a, b = (", ".join(f"{v * 1e3:.4g}" for v in p) for p in self.axis)
        return (f"{name}: one solid, axis from ({a}) to ({b}) mm, {self.length * 1e3:.5g} mm "
                f"long, {self.volume * 1e9:.6g} mm^3, outer radius {self.outer_min * 1e3:.4g} "
                f"to {self.outer_max * 1e3:.4g} mm")


def import_step(step: StepSolid, key: str, brep: Path | None = None) -> StepImport:
    """Import the STEP file, check it is one solid, find its axis and place it along z
    from z = 0 (written to `brep` when given). `key` names the scene key for errors
    (SceneError, exit 2: the file is the user's input)."""
    with session("step") as s, stdout_to_devnull(), \
            translated(SceneError, f"{key} = {step.path!r}: OpenCASCADE could not read it"):
        gmsh = s.gmsh
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        try:
            gmsh.model.occ.importShapes(step.path)
        finally:
            gmsh.option.setString("Geometry.OCCTargetUnit", "")
        gmsh.model.occ.synchronize()
        vols = gmsh.model.getEntities(3)
        if not vols:
            raise SceneError(f"{key} = {step.path!r}: holds no solid (only surfaces or "
                             "curves): export the shaft as a closed solid")
        if len(vols) > 1:  # a STEP file repeats the faces its solids share: one again
            _refuse_overlaps(gmsh, vols, key, step.path)
            glue(gmsh, vols[0][1], [t for _, t in vols[1:]])
            gmsh.model.occ.synchronize()
            vols = gmsh.model.getEntities(3)
        try:  # solids that share whole faces are one body (as shaftfem's own files are)
            check_connected(gmsh)
        except GeometryError:
            raise SceneError(
                f"{key} = {step.path!r}: holds {len(vols)} solids that are not joined; "
                "shaftfem takes one solid (fuse the parts in CAD, or export the shaft "
                "alone)") from None
        volume = sum(gmsh.model.occ.getMass(3, t) for _, t in vols)
        if not volume > 0:
            raise SceneError(f"{key} = {step.path!r}: the solid has no volume ({volume:g} "
                             "m^3): it is not closed")
        axis = step.axis or _bounding_box_axis(gmsh, key, step.path)
        _place(gmsh, vols, axis)
        gmsh.model.occ.synchronize()
        xyz = _edge_points(gmsh)
        zmin, zmax = xyz[:, 2].min(), xyz[:, 2].max()
        gmsh.model.occ.translate(vols, 0, 0, -zmin)
        gmsh.model.occ.synchronize()
        length = float(zmax - zmin)
        xyz[:, 2] -= zmin
        outer_max, outer_min = _outer_radii(xyz, length)
        surface = _outer_surface(gmsh)
        if brep is not None:
            gmsh.write(str(brep))
    return StepImport(axis=axis, length=length, volume=volume, outer_max=outer_max,
                      outer_min=outer_min, surface=surface)


SURFACE_SAMPLES = 9     # points along each parameter of a face
OUTSIDE_PROBE = 1e-5    # m: a point this far out from an outer face lies outside the solid


def _outer_surface(gmsh) -> tuple[tuple[float, float], ...]:
    """(z, r) of points on the solid's outward-facing surfaces (m): faces that look away
    from the axis with the material inside them (a bore looks away from the axis too, but
    with the material outside). What a seat sits on."""
    vols = [t for _, t in gmsh.model.getEntities(3)]
    out: list[tuple[float, float]] = []
    n = SURFACE_SAMPLES
    for _, tag in gmsh.model.getEntities(2):
        lo, hi = gmsh.model.getParametrizationBounds(2, tag)
        uv = np.array([(a, b) for a in np.linspace(lo[0], hi[0], n)
                       for b in np.linspace(lo[1], hi[1], n)]).ravel()
        xyz = np.asarray(gmsh.model.getValue(2, tag, uv)).reshape(-1, 3)
        normal = np.asarray(gmsh.model.getNormal(tag, uv)).reshape(-1, 3)
        r = np.hypot(xyz[:, 0], xyz[:, 1])
        away = np.column_stack([xyz[:, 0], xyz[:, 1], 0 * r]) / np.maximum(r, 1e-30)[:, None]
        if np.median(np.abs(np.sum(away * normal, axis=1))) < 0.5:
            continue   # an end, a shoulder: faces along the axis carry no seat
        probe = xyz + OUTSIDE_PROBE * away
        if any(gmsh.model.isInside(3, v, list(probe[len(probe) // 2])) for v in vols):
            continue   # the material lies outside: a bore
        out += [(round(float(z), 9), round(float(q), 9)) for z, q in zip(xyz[:, 2], r)]
    return tuple(out)


def check_seats_on_solid(scene: Scene, info: StepImport) -> None:
    """Each bearing seat of a STEP shaft lies on one round, cylindrical stretch of its
    outer surface: no groove, step or flat under it (the rule a profile's shoulders and
    cones follow). Parts' hubs may sit over keyways, as keyed hubs do."""
    if not info.surface:
        return
    zr = np.asarray(info.surface)
    for i, s in enumerate(scene.supports):
        lo, hi = s.seat
        under = zr[(zr[:, 0] > lo + 1e-6) & (zr[:, 0] < hi - 1e-6), 1]
        if under.size and under.max() - under.min() > 1e-6 + 1e-4 * under.max():
            raise SceneError(
                f"{where(scene.source, entry('support', i, s), 'position_mm')} = "
                f"{s.position * 1e3:g}: the seat {lo * 1e3:g} to {hi * 1e3:g} mm lies on no "
                f"single round section: the solid's outer radius under it runs from "
                f"{under.min() * 1e3:.4g} to {under.max() * 1e3:.4g} mm (a groove, a step or "
                "a flat); a bearing seat needs a round, cylindrical stretch of the shaft")


# Solids sharing more volume than this (m^3) overlap; less is OpenCASCADE's tolerance.
OVERLAP = 1e-12


def _refuse_overlaps(gmsh, vols: list[tuple[int, int]], key: str, path: str) -> None:
    """Refuse solids that overlap (a sleeve exported over the shaft, a press fit drawn
    as two bodies): shaftfem meshes one body, and would not know which material is where.
    Says which solids and where, in the file's coordinates."""
    occ = gmsh.model.occ
    for i, (_, a) in enumerate(vols):
        for j, (_, b) in enumerate(vols[i + 1:], start=i + 1):
            common, _ = occ.intersect([(3, a)], [(3, b)], removeObject=False, removeTool=False)
            occ.synchronize()
            shared = sum(occ.getMass(3, t) for d, t in common if d == 3)
            if shared > OVERLAP:
                box = [gmsh.model.getBoundingBox(3, t) for d, t in common if d == 3]
                lo = np.min([bx[:3] for bx in box], axis=0) * 1e3
                hi = np.max([bx[3:] for bx in box], axis=0) * 1e3
                raise SceneError(
                    f"{key} = {path!r}: solids {i + 1} and {j + 1} overlap ({shared * 1e9:.4g} "
                    f"mm^3, within x {lo[0]:.4g} to {hi[0]:.4g}, y {lo[1]:.4g} to "
                    f"{hi[1]:.4g}, z {lo[2]:.4g} to {hi[2]:.4g} mm in the file): shaftfem "
                    "takes one body; export the shaft alone, or fuse the parts in CAD")
            occ.remove(common, recursive=True)
            occ.synchronize()


def _bounding_box_axis(gmsh, key: str, path: str
                       ) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """The z direction through the middle of the solid's bounding box (in x and y); a
    solid longer across than along z has its axis elsewhere, and is refused."""
    xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(-1, -1)
    across = max(xmax - xmin, ymax - ymin)
    if zmax - zmin < across:
        raise SceneError(
            f"{key} = {path!r}: the solid is {across * 1e3:.4g} mm across but only "
            f"{(zmax - zmin) * 1e3:.4g} mm along z, so its axis is not along z: give it with "
            "[shaft] axis_from_mm and axis_to_mm")
    x, y = (xmin + xmax) / 2, (ymin + ymax) / 2
    return (x, y, zmin), (x, y, zmax)


def _place(gmsh, vols, axis) -> None:
    """Move the solid rigidly so that the axis lies on z through the origin: a translation
    and a rotation (exact; an affine map would turn every face into a B-spline)."""
    a, b = np.asarray(axis[0], float), np.asarray(axis[1], float)
    u = (b - a) / np.linalg.norm(b - a)
    occ = gmsh.model.occ
    occ.translate(vols, *(-a))
    turn = np.cross(u, [0.0, 0.0, 1.0])
    angle = float(np.arctan2(np.linalg.norm(turn), u[2]))
    if angle > 1e-12:
        about = turn / np.linalg.norm(turn) if np.linalg.norm(turn) > 1e-12 else np.array(
            [1.0, 0.0, 0.0])   # u along -z: half a turn about x
        occ.rotate(vols, 0, 0, 0, *about, angle)


def _edge_points(gmsh) -> np.ndarray:
    """Points on the solid's edges (n, 3), 24 along each: exact on its boundary (where
    OpenCASCADE's bounding box is widened by its tolerances), and an edge bounds every
    face, so the ends and each step's outer radius are among them."""
    out = []
    for _, tag in gmsh.model.getEntities(1):
        lo, hi = gmsh.model.getParametrizationBounds(1, tag)
        t = np.linspace(lo[0], hi[0], 24)
        out.append(np.asarray(gmsh.model.getValue(1, tag, t)).reshape(-1, 3))
    return np.vstack(out)


def _outer_radii(xyz: np.ndarray, length: float) -> tuple[float, float]:
    """(largest, smallest) outer radius of the placed solid, from points on its edges: the
    outer radius of each of 100 slices along z is its largest point radius."""
    r = np.hypot(xyz[:, 0], xyz[:, 1])
    bins = np.minimum((xyz[:, 2] / max(length, 1e-300) * 100).astype(int), 99)
    outer = np.full(100, -np.inf)
    np.maximum.at(outer, bins, r)
    outer = outer[np.isfinite(outer)]
    return float(outer.max()), float(outer.min())


def placed(scene: Scene, info: StepImport) -> Scene:
    """A scene whose shaft is a STEP file, with the solid's length and largest diameter as
    its import found them (`info`; the summary kept for the run's header), and the checks
    that need them done: the seats and the response point on the shaft, the element size
    not above its length. Any other scene as it is."""
    shaft = scene.shaft
    if shaft.step is None or shaft.length > 0:
        return scene
    step = replace(shaft.step, summary=info.summary(Path(shaft.step.path).name))
    shaft = replace(shaft, length=info.length, diameter=2 * info.outer_max, step=step)
    check_seats(scene.source, shaft, None, scene.supports, scene.attachments, scene.mesh)
    check_seats_on_solid(scene, info)
    if scene.mesh.size > shaft.length:
        raise SceneError(f"{where(scene.source, 'mesh', 'element_size_mm')} = "
                         f"{scene.mesh.size * 1e3:g}: must not exceed the shaft length "
                         f"({shaft.length * 1e3:g} mm, as imported)")
    point = scene.response_point
    if point is not None and point > shaft.length:
        raise SceneError(f"{where(scene.source, 'response', 'point_mm')} = {point * 1e3:g}: "
                         f"must lie on the shaft, 0 to {shaft.length * 1e3:g} mm")
    return replace(scene, shaft=shaft)
