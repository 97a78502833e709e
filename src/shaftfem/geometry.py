"""The shaft's solid: a cylinder with helical grooves, built with gmsh on OpenCASCADE.

Construction (why it is done this way is in the comments):

* A groove of one hand is invariant under the screw motion (rotate by 2*pi*dz/P,
  translate by dz), so each of its cross-sections perpendicular to the axis is a
  rotated copy of one planar section: the axial-section profile mapped to angles
  by theta = 2*pi*s/P. Straight groove walls become radial lines, the floor and
  top become circular arcs, the root fillets short splines.
* A right- and a left-hand groove of the same pitch together repeat every half
  pitch, turned by 180 degrees. So one "cell" (half a pitch long) is built with
  booleans and then copied; the cells and the plain ends are glued with one
  fragment. The grooves cross once inside each cell, never on a cell face.
* Each groove piece is a loft (ThruSections) through exact sections that start
  and end exactly on the cell faces, so neighbouring cells meet on identical
  edges. The piece is cut oversized (from below the floor to above the surface)
  and intersected with the ring R-d <= r <= R+1 mm, so that every groove floor
  is the same exact cylinder and two crossing floors never meet as two slightly
  different surfaces (a trial showed full-length swept tubes failing there).

`build_shape` returns the path of a BREP file, cached by the shape's parameters.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import tempfile
import time
from contextlib import contextmanager
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from .errors import GeometryError
from .scene import Grooves, Shaft

# Bump when the construction changes, so old cached shapes are not reused.
CONSTRUCTION_VERSION = 3
SECTIONS_PER_CELL = 13          # exact sections per half turn (15 degree steps)
FILLET_POINTS = 9               # spline points on each mapped root fillet
TOOL_OVERSHOOT = 1e-3           # the cutting tool reaches 1 mm above the surface
FILLET_CROSSING = 0.03          # fillet meets the floor at acos(1 - 0.03) = 14 degrees
VOLUME_TOLERANCE = 0.01         # removed volume vs analytic groove volume


@dataclass(frozen=True)
class ShaftShape:
    """A built solid: its BREP file and the volumes that checked it (m^3)."""

    brep: Path
    volume: float
    groove_volume_analytic: float
    groove_volume_cad: float
    n_volumes: int
    build_seconds: float
    from_cache: bool

    @property
    def groove_volume_error(self) -> float:
        """Relative difference of the removed volume against the analytic one."""
        if self.groove_volume_analytic == 0:
            return 0.0
        return self.groove_volume_cad / self.groove_volume_analytic - 1.0


# --------------------------------------------------------------------------
# The groove profile and its analytic volume (no CAD involved).


def axial_width(g: Grooves, radius: float, r: np.ndarray) -> np.ndarray:
    """Width of the groove along the axis (m) at radius r, for r in [R-d, R]."""
    r = np.asarray(r, dtype=float)
    floor = radius - g.depth
    w = np.full_like(r, g.width)
    if g.root_radius > 0:
        rf = g.root_radius
        delta = FILLET_CROSSING * rf
        rc = floor + rf - delta
        inside = r < rc
        dr = np.clip(rc - r[inside], 0.0, rf)
        w[inside] = 2 * (g.width / 2 - rf) + 2 * np.sqrt(rf**2 - dr**2)
    return np.where(r >= floor, w, 0.0)


def groove_volume(g: Grooves, radius: float, nz: int = 4001, nr: int = 801) -> float:
    """Volume removed by the grooves (m^3), integrated over transverse sections.

    At height z each groove occupies, at radius r, an arc of angle
    phi(r) = 2 pi W(r) / P around its centre; two grooves overlap by
    max(0, phi - gap), with gap the angle between their centres.
    """
    r = np.linspace(radius - g.depth, radius, nr)
    phi = 2 * math.pi * axial_width(g, radius, r) / g.pitch
    if len(g.hands) == 1:
        return g.length * np.trapezoid(phi * r, r)
    z = np.linspace(0.0, g.length, nz)
    # right-hand centre at pi/2 + 2 pi z/P, left-hand at -(pi/2 + 2 pi z/P)
    diff = np.mod(math.pi + 4 * math.pi * z / g.pitch, 2 * math.pi)
    gap = np.minimum(diff, 2 * math.pi - diff)
    overlap = np.maximum(0.0, phi[None, :] - gap[:, None])
    area = np.trapezoid((2 * phi[None, :] - overlap) * r[None, :], r, axis=1)
    return float(np.trapezoid(area, z))


def profile_outline(g: Grooves, radius: float) -> list[tuple[str, list[tuple[float, float]]]]:
    """The cutting tool's closed outline in the axial section, as (kind, [(s, r), ...]).

    s is the axial offset from the groove's centre line, r the radius (m). Kinds:
    'radial' (s constant), 'arc' (r constant), 'spline' (a mapped root fillet).
    The tool reaches below the floor so that the ring intersection, not the tool,
    makes the floor.
    """
    a = g.width / 2
    floor = radius - g.depth
    top = radius + TOOL_OVERSHOOT
    rf = g.root_radius
    if rf == 0:
        bottom = floor - min(0.5e-3, 0.5 * floor)
        return [
            ("arc", [(-a, bottom), (a, bottom)]),
            ("radial", [(a, bottom), (a, top)]),
            ("arc", [(a, top), (-a, top)]),
            ("radial", [(-a, top), (-a, bottom)]),
        ]
    delta = FILLET_CROSSING * rf
    rc = floor + rf - delta
    bottom = rc - rf
    sc = a - rf
    t = np.linspace(0.0, 0.5 * math.pi, FILLET_POINTS)
    right = [(sc + rf * math.sin(u), rc - rf * math.cos(u)) for u in t]
    left = [(-sc - rf * math.sin(u), rc - rf * math.cos(u)) for u in t[::-1]]
    out = []
    if sc > 1e-9:
        out.append(("arc", [(-sc, bottom), (sc, bottom)]))
    out += [
        ("spline", right),
        ("radial", [(a, rc), (a, top)]),
        ("arc", [(a, top), (-a, top)]),
        ("radial", [(-a, top), (-a, rc)]),
        ("spline", left),
    ]
    return out


# --------------------------------------------------------------------------
# gmsh plumbing


@contextmanager
def gmsh_session(verbose: bool = False):
    """Initialise gmsh for one job and always finalise it (gmsh state is global)."""
    import gmsh

    if gmsh.isInitialized():
        gmsh.finalize()
    gmsh.initialize(readConfigFiles=False, interruptible=False)
    gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
    try:
        yield gmsh
    finally:
        gmsh.finalize()


@contextmanager
def _stdout_to_devnull():
    """Silence C-level prints on stdout (OpenCASCADE's STEP writer talks there)."""
    import sys

    sys.stdout.flush()
    saved = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)


def _section_wire(occ, outline, z: float, theta: float, pitch: float) -> int:
    """One transverse section of a groove tool at height z, centred at angle theta."""
    k = 2 * math.pi / pitch

    def xy(s: float, r: float) -> tuple[float, float, float]:
        ang = theta + k * s
        return r * math.cos(ang), r * math.sin(ang), z

    points: dict[tuple[float, float], int] = {}

    def pt(s: float, r: float) -> int:
        key = (round(s, 12), round(r, 12))
        if key not in points:
            points[key] = occ.addPoint(*xy(s, r))
        return points[key]

    centre = None
    curves = []
    for kind, pts in outline:
        if kind == "radial":
            curves.append(occ.addLine(pt(*pts[0]), pt(*pts[1])))
        elif kind == "arc":
            if centre is None:
                centre = occ.addPoint(0.0, 0.0, z)
            curves.append(occ.addCircleArc(pt(*pts[0]), centre, pt(*pts[-1])))
        else:
            tags = [pt(*pts[0])] + [occ.addPoint(*xy(*p)) for p in pts[1:-1]] + [pt(*pts[-1])]
            curves.append(occ.addSpline(tags))
    return occ.addWire(curves)


def _groove_piece(occ, g: Grooves, radius: float, outline, hand: int,
                  z0: float, length: float, theta0: float) -> int:
    """A groove tool over [z0, z0 + length] whose centre starts at angle theta0."""
    n = max(3, math.ceil((SECTIONS_PER_CELL - 1) * length / (g.pitch / 2)) + 1)
    wires = []
    for z in np.linspace(z0, z0 + length, n):
        theta = theta0 + hand * 2 * math.pi * (z - z0) / g.pitch
        wires.append(_section_wire(occ, outline, float(z), theta, g.pitch))
    out = occ.addThruSections(wires, makeSolid=True, makeRuled=False)
    vols = [t for d, t in out if d == 3]
    if len(vols) != 1:
        raise GeometryError(f"groove loft gave {len(vols)} solids instead of 1")
    return vols[0]


def _cell(occ, g: Grooves, radius: float, outline, z0: float, length: float,
          turn: float) -> int:
    """A grooved stretch [z0, z0 + length]: cylinder minus each hand's groove piece.

    `turn` is the angle of the right-hand groove's centre at z0 minus pi/2.
    """
    floor = radius - g.depth
    body = occ.addCylinder(0, 0, z0, 0, 0, length, radius)
    for hand in g.hands:
        theta0 = hand * (math.pi / 2 + turn)
        tool = _groove_piece(occ, g, radius, outline, hand, z0, length, theta0)
        outer = occ.addCylinder(0, 0, z0 - 1e-3, 0, 0, length + 2e-3, radius + 2 * TOOL_OVERSHOOT)
        inner = occ.addCylinder(0, 0, z0 - 2e-3, 0, 0, length + 4e-3, floor)
        ring, _ = occ.cut([(3, outer)], [(3, inner)])
        piece, _ = occ.intersect([(3, tool)], ring)
        if not piece:
            raise GeometryError("a groove piece does not meet the ring R-d..R+1 mm")
        cut, _ = occ.cut([(3, body)], piece)
        if len(cut) != 1:
            raise GeometryError(f"cutting a groove piece left {len(cut)} solids instead of 1")
        body = cut[0][1]
    return body


def _build(gmsh, shaft: Shaft, grooves: Grooves | None) -> None:
    """Create the shaft in the current gmsh model (not yet synchronised)."""
    occ = gmsh.model.occ
    R, L = shaft.radius, shaft.length
    if grooves is None:
        occ.addCylinder(0, 0, 0, 0, 0, L, R)
        return
    g = grooves
    outline = profile_outline(g, R)
    half = g.pitch / 2
    n_full = int(math.floor(g.length / half + 1e-9))
    rest = g.length - n_full * half
    pieces = []
    if g.start > 1e-9:
        pieces.append((3, occ.addCylinder(0, 0, 0, 0, 0, g.start, R)))
    if n_full:
        cell = _cell(occ, g, R, outline, g.start, half, 0.0)
        pieces.append((3, cell))
        for k in range(1, n_full):
            copy = occ.copy([(3, cell)])
            if k % 2:
                occ.rotate(copy, 0, 0, 0, 0, 0, 1, math.pi)
            occ.translate(copy, 0, 0, k * half)
            pieces += copy
    if rest > 1e-9:
        pieces.append((3, _cell(occ, g, R, outline, g.start + n_full * half, rest,
                                n_full * math.pi)))
    end = g.start + g.length
    if L - end > 1e-9:
        pieces.append((3, occ.addCylinder(0, 0, end, 0, 0, L - end, R)))
    if len(pieces) > 1:
        occ.fragment(pieces[:1], pieces[1:])


def shape_key(shaft: Shaft, grooves: Grooves | None) -> str:
    payload = {
        "version": CONSTRUCTION_VERSION,
        "sections": SECTIONS_PER_CELL,
        "shaft": asdict(shaft),
        "grooves": asdict(grooves) if grooves else None,
    }
    text = json.dumps(payload, sort_keys=True, default=lambda v: round(v, 12))
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def cache_dir() -> Path:
    root = os.environ.get("SHAFTFEM_CACHE") or Path.home() / ".cache" / "shaftfem"
    return Path(root)


def build_shape(shaft: Shaft, grooves: Grooves | None, use_cache: bool = True,
                log=None) -> ShaftShape:
    """Build (or fetch from the cache) the shaft's solid and check its volume."""
    key = shape_key(shaft, grooves)
    folder = cache_dir() / "shapes"
    brep, meta_file = folder / f"{key}.brep", folder / f"{key}.json"
    if use_cache and brep.exists() and meta_file.exists():
        meta = json.loads(meta_file.read_text())
        return ShaftShape(brep=brep, from_cache=True, **meta)

    t0 = time.perf_counter()
    v_grooves = groove_volume(grooves, shaft.radius) if grooves else 0.0
    with gmsh_session() as gmsh:
        gmsh.model.add("shaft")
        _build(gmsh, shaft, grooves)
        gmsh.model.occ.synchronize()
        vols = gmsh.model.getEntities(3)
        volume = sum(gmsh.model.occ.getMass(3, t) for _, t in vols)
        v_full = math.pi * shaft.radius**2 * shaft.length
        removed = v_full - volume
        if grooves is not None:
            err = removed / v_grooves - 1.0
            if abs(err) > VOLUME_TOLERANCE:
                raise GeometryError(
                    f"the grooves removed {removed * 1e9:.1f} mm^3 but the analytic groove "
                    f"volume is {v_grooves * 1e9:.1f} mm^3 ({100 * err:+.2f} %, allowed "
                    f"{100 * VOLUME_TOLERANCE:.0f} %): the CAD booleans went wrong"
                )
        _check_connected(gmsh)
        folder.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(suffix=".brep", dir=folder)
        os.close(fd)
        gmsh.write(tmp)
        os.replace(tmp, brep)
    meta = dict(volume=volume, groove_volume_analytic=v_grooves, groove_volume_cad=removed,
                n_volumes=len(vols), build_seconds=time.perf_counter() - t0)
    fd, tmp = tempfile.mkstemp(suffix=".json", dir=folder)
    with os.fdopen(fd, "w") as f:
        json.dump(meta, f)
    os.replace(tmp, meta_file)
    return ShaftShape(brep=brep, from_cache=False, **meta)


def _check_connected(gmsh) -> None:
    """All volumes must form one body: every volume shares a face with another."""
    vols = [t for _, t in gmsh.model.getEntities(3)]
    if len(vols) < 2:
        return
    faces = {}
    for v in vols:
        _, bnd = gmsh.model.getAdjacencies(3, v)
        for f in bnd:
            faces.setdefault(int(f), []).append(v)
    parent = {v: v for v in vols}

    def find(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for owners in faces.values():
        for a in owners[1:]:
            parent[find(a)] = find(owners[0])
    roots = {find(v) for v in vols}
    if len(roots) != 1:
        raise GeometryError(f"the solid fell apart into {len(roots)} bodies after the booleans")


def export_solid(brep: Path, step: Path, brep_copy: Path | None = None) -> None:
    """Write the cached solid as STEP (for CAD and the workshop) and optionally as BREP."""
    import shutil

    with gmsh_session() as gmsh, _stdout_to_devnull():
        gmsh.model.add("export")
        gmsh.model.occ.importShapes(str(brep))
        gmsh.model.occ.synchronize()
        gmsh.write(str(step))
    if brep_copy is not None:
        shutil.copyfile(brep, brep_copy)
