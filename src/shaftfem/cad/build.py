"""The shaft's solid on OpenCASCADE (through gmsh), written as BREP or STEP.

The solid (why it is built this way is in the comments):

* A groove of one hand is invariant under the screw motion (rotate by 2*pi*dz/P,
  translate by dz), so each of its cross-sections perpendicular to the axis is a
  rotated copy of one planar section: the axial-section profile mapped to angles
  by theta = 2*pi*s/P. Straight groove walls become radial lines, the floor and
  top become circular arcs, the root fillets short splines.
* A right- and a left-hand groove of the same pitch together repeat every half
  pitch, turned by 180 degrees. So one "cell" (half a pitch long) is built with
  booleans and then copied. The grooves cross once inside each cell, never on a
  cell face. Each plain end is joined to its cell alone, and then all of them are
  glued in OpenCASCADE's glue mode, which takes shared faces as they are: a general
  fragment of the whole, intersecting every helical face with every other, took
  ten times as long as building the solid.
* Each groove piece is a loft (ThruSections) through exact sections that start
  and end exactly on the cell faces, so neighbouring cells meet on identical
  edges. The piece is cut oversized (from below the floor to above the surface)
  and intersected with the ring R-d <= r <= R+1 mm, so that every groove floor
  is the same exact cylinder and two crossing floors never meet as two slightly
  different surfaces (a trial showed full-length swept tubes failing there).
* Where the grooves run out, the end cells are built apart, each groove's tool the
  cell's loft fused to a loft of its own along the runout (its floor rising,
  cad.profile.runout_lift): their face towards the next cell has that cell's exact
  section, so glue joins them as it joins the copies.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from shaftfem.cad.outline import outline as half_section
from shaftfem.cad.outline import runout, surface_radius
from shaftfem.cad.profile import RUNOUT_CLEARANCE, TOOL_OVERSHOOT, profile_outline, runout_lift
from shaftfem.cad.session import session, stdout_to_devnull, translated
from shaftfem.errors import GeometryError
from shaftfem.scene.model import Grooves, Keyway, Shaft

SECTIONS_PER_CELL = 13          # exact sections per half turn (15 degree steps)
RUNOUT_SECTIONS = 7            # exact sections along each runout
STEP_SUFFIXES = (".step", ".stp")


# --------------------------------------------------------------------------
# The solid


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


def _groove_piece(occ, g: Grooves, hand: int, zs: np.ndarray, outlines: list, z0: float,
                  theta0: float) -> int:
    """A groove tool lofted through its sections at heights `zs` (their outlines in the
    axial section), its centre at angle theta0 at z0."""
    wires = []
    for z, outline in zip(zs, outlines):
        theta = theta0 + hand * 2 * math.pi * (z - z0) / g.pitch
        wires.append(_section_wire(occ, outline, float(z), theta, g.pitch))
    out = occ.addThruSections(wires, makeSolid=True, makeRuled=False)
    vols = [t for d, t in out if d == 3]
    if len(vols) != 1:
        raise GeometryError(f"groove loft gave {len(vols)} solids instead of 1")
    return vols[0]


def _cell(occ, g: Grooves, radius: float, z0: float, length: float, turn: float,
          bore: float = 0.0, runouts: tuple[bool, bool] = (False, False)) -> int:
    """A grooved stretch [z0, z0 + length]: cylinder (less its bore of radius `bore`)
    minus each hand's groove piece; with `runouts` (before, after), the stretch
    reaches g.runout further on that side, where the grooves' floors rise out.

    `turn` is the angle of the right-hand groove's centre at z0 minus pi/2.
    """
    floor = radius - g.depth
    before, after = (g.runout if r else 0.0 for r in runouts)
    n = max(3, math.ceil((SECTIONS_PER_CELL - 1) * length / (g.pitch / 2)) + 1)
    # the tool stands high enough for a risen floor and its root fillets
    top = radius + TOOL_OVERSHOOT + (RUNOUT_CLEARANCE + g.root_radius
                                     if before or after else 0.0)
    plain = profile_outline(g, radius, 0.0, top)
    lofts = [(np.linspace(z0, z0 + length, n), [plain] * n)]
    for z, run in ((z0, -before), (z0 + length, after)):
        if run:   # its own loft (one loft through both took ten times as long to cut)
            zs = np.linspace(z, z + run, RUNOUT_SECTIONS)
            lofts.append((zs, [profile_outline(g, radius, float(h), top)
                               for h in runout_lift(g, radius, np.abs(zs - z))]))
    lo, span = z0 - before, before + length + after
    body = occ.addCylinder(0, 0, lo, 0, 0, span, radius)
    if bore > 0:
        hole = occ.addCylinder(0, 0, lo, 0, 0, span, bore)
        body = occ.cut([(3, body)], [(3, hole)])[0][0][1]
    for hand in g.hands:
        theta0 = hand * (math.pi / 2 + turn)
        tools = [_groove_piece(occ, g, hand, zs, out, z0, theta0) for zs, out in lofts]
        tool = tools[0]
        if len(tools) > 1:
            tool = occ.fuse([(3, tool)], [(3, t) for t in tools[1:]])[0][0][1]
        outer = occ.addCylinder(0, 0, lo - 1e-3, 0, 0, span + 2e-3, top + TOOL_OVERSHOOT)
        inner = occ.addCylinder(0, 0, lo - 2e-3, 0, 0, span + 4e-3, floor)
        ring, _ = occ.cut([(3, outer)], [(3, inner)])
        piece, _ = occ.intersect([(3, tool)], ring)
        if not piece:
            raise GeometryError("a groove piece does not meet the ring R-d..R+1 mm")
        cut, _ = occ.cut([(3, body)], piece)
        if len(cut) != 1:
            raise GeometryError(f"cutting a groove piece left {len(cut)} solids instead of 1")
        body = cut[0][1]
    return body


def glue(gmsh, first: int, rest: list[int]) -> None:
    """Join solids that touch only on faces they have in full (the cells, once each end
    is joined to its neighbour): OpenCASCADE's glue mode skips the face-face
    intersections that make a general fragment of helical B-spline faces slow."""
    glue = gmsh.option.getNumber("Geometry.OCCBooleanGlue")
    gmsh.option.setNumber("Geometry.OCCBooleanGlue", 2)   # full: coinciding faces only
    try:
        gmsh.model.occ.fragment([(3, first)], [(3, t) for t in rest])
    finally:
        gmsh.option.setNumber("Geometry.OCCBooleanGlue", glue)


def _join(occ, a: int, b: int) -> tuple[int, int]:
    """Fragment two touching solids; their tags afterwards (each must stay one solid)."""
    _, parts = occ.fragment([(3, a)], [(3, b)])
    if any(len(p) != 1 for p in parts):
        raise GeometryError("joining two stretches of the shaft split one of them")
    return parts[0][0][1], parts[1][0][1]


def _build(gmsh, shaft: Shaft, grooves: Grooves | None) -> None:
    """Create the shaft in the current gmsh model (not yet synchronised)."""
    occ = gmsh.model.occ
    R, L = shaft.radius, shaft.length
    if not shaft.plain:
        body = _profile_body(occ, shaft)
        if grooves is not None:
            _grooved(gmsh, shaft, grooves, lambda z0, z1: _slice(occ, body, z0, z1, R))
            occ.remove([(3, body)], recursive=True)
        return
    if grooves is None:
        occ.addCylinder(0, 0, 0, 0, 0, L, R)
        return
    _grooved(gmsh, shaft, grooves, lambda z0, z1: occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, R))


def _profile_body(occ, shaft: Shaft) -> int:
    """A stepped shaft: its half-section (cad.outline) revolved about the axis, the
    keyways cut from it."""
    curves = []
    for piece in half_section(shaft):
        a = occ.addPoint(piece.a[1], 0.0, piece.a[0])
        b = occ.addPoint(piece.b[1], 0.0, piece.b[0])
        if piece.centre is None:
            curves.append(occ.addLine(a, b))
        else:
            c = occ.addPoint(piece.centre[1], 0.0, piece.centre[0])
            curves.append(occ.addCircleArc(a, c, b))
    face = occ.addPlaneSurface([occ.addCurveLoop(curves)])
    out = occ.revolve([(2, face)], 0, 0, 0, 0, 0, 1, 2 * math.pi)
    vols = [t for d, t in out if d == 3]
    if len(vols) != 1:
        raise GeometryError(f"revolving the profile gave {len(vols)} solids instead of 1")
    body = vols[0]
    for k in shaft.keyways:
        radius = shaft.radius_at(k.start + k.length / 2)
        assert radius is not None
        # the cutter reaches above the surface over its whole length (a keyway running
        # into a fillet: the fillet's rise)
        high = float(np.max(surface_radius(shaft, np.linspace(k.start, k.end, 201))))
        cut, _ = occ.cut([(3, body)], [(3, _keyway_tool(occ, k, radius, high))])
        if len(cut) != 1:
            raise GeometryError(f"cutting the keyway at {k.start * 1e3:g} mm left {len(cut)} "
                                "solids instead of 1")
        body = cut[0][1]
    return body


def _keyway_tool(occ, k: Keyway, radius: float, high: float | None = None) -> int:
    """The cutter's path as a solid: the keyway's plan (form "rounded": a slot with round
    ends; "sled": straight, its ends rising along the disc cutter) from the floor to
    above the surface (whose highest radius over the keyway is `high`, m), turned to the
    keyway's angle."""
    floor, top = radius - k.depth, max(radius, high or 0.0) + TOOL_OVERSHOOT
    w = k.width
    if k.form == "rounded":   # a slot: round ends of the cutter's radius w / 2
        a = w / 2
        ends = _ends(k.start + a, k.end - a)   # one, where the keyway is a round hole
        parts = [occ.addCylinder(floor, 0, z, top - floor, 0, 0, a) for z in ends]
    else:                     # the disc cutter's path: its ends run out at its radius
        run, rc = runout(k, radius), k.cutter_radius
        ends = _ends(k.start + run, k.end - run)
        parts = [occ.addCylinder(floor + rc, -w / 2, z, 0, w, 0, rc) for z in ends]
    if len(ends) == 2:
        parts.append(occ.addBox(floor, -w / 2, ends[0], top - floor, w, ends[1] - ends[0]))
    tag = parts[0]
    if len(parts) > 1:
        tag = occ.fuse([(3, parts[0])], [(3, t) for t in parts[1:]])[0][0][1]
    if k.corner_radius > 0:
        occ.synchronize()
        eps = 1e-7
        edges = [t for _, t in occ.getEntitiesInBoundingBox(
            floor - eps, -w, k.start - eps, floor + eps, w, k.end + eps, dim=1)]
        tag = occ.fillet([tag], edges, [k.corner_radius])[0][1]
    occ.rotate([(3, tag)], 0, 0, 0, 0, 0, 1, k.angle)
    return tag


def _ends(z0: float, z1: float) -> list[float]:
    """The centres of a keyway cutter's two end positions, one where they meet (to 1e-9 m:
    a box between them thinner than that fails in OpenCASCADE)."""
    return [0.5 * (z0 + z1)] if z1 - z0 < 1e-9 else [z0, z1]


def _slice(occ, body: int, z0: float, z1: float, radius: float) -> int:
    """The part z0 <= z <= z1 of the solid `body` (left in place), as a new solid."""
    box = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, 2 * radius)
    part, _ = occ.intersect(occ.copy([(3, body)]), [(3, box)])
    if len(part) != 1:
        raise GeometryError(f"the profile between {z0 * 1e3:g} and {z1 * 1e3:g} mm is "
                            f"{len(part)} solids instead of 1")
    return part[0][1]


def _grooved(gmsh, shaft: Shaft, g: Grooves, plug) -> None:
    """The grooved zone's cells at its section's radius and bore, joined to the plain
    stretches `plug(z0, z1)` makes on either side."""
    occ = gmsh.model.occ
    L = shaft.length
    section = shaft.profile[shaft.section_at(g.start + g.length / 2) or 0]
    R, bore = section.diameter_start / 2, section.bore / 2
    half = g.pitch / 2
    n_full = int(math.floor(g.length / half + 1e-9))
    rest = g.length - n_full * half
    end = g.start + g.length
    run = g.runout
    # Volume tags in axial order (the plain start first): gmsh numbers the imported
    # solid's entities in this order, and the mesh depends on it.
    start_plug = plug(0.0, g.start - run) if g.start - run > 1e-9 else None
    # the cells: full ones copied from the first, turned by pi every other one; a
    # shorter last one, and the end cells where the grooves run out, built apart
    spans = [(g.start + k * half, half, k * math.pi) for k in range(n_full)]
    if rest > 1e-9:
        spans.append((g.start + n_full * half, rest, n_full * math.pi))
    proto, spare = None, False   # the full cell at the start, and whether it is apart
    cells = []
    for k, (z0, length, turn) in enumerate(spans):
        runouts = (bool(run) and k == 0, bool(run) and k == len(spans) - 1)
        if any(runouts) or length < half - 1e-12:
            cells.append(_cell(occ, g, R, z0, length, turn, bore, runouts))
        elif k == 0:
            proto = _cell(occ, g, R, g.start, half, 0.0, bore)
            cells.append(proto)
        else:
            if proto is None:
                proto, spare = _cell(occ, g, R, g.start, half, 0.0, bore), True
            copy = occ.copy([(3, proto)])
            if k % 2:
                occ.rotate(copy, 0, 0, 0, 0, 0, 1, math.pi)
            occ.translate(copy, 0, 0, k * half)
            cells.append(copy[0][1])
    if spare:
        occ.remove([(3, proto)], recursive=True)
    end_plug = plug(end + run, L) if L - end - run > 1e-9 else None
    # A plain end's disk meets a cell's notched face only in part: that one needs a
    # general fragment, of the two solids alone (fast); so does a shorter last cell,
    # whose face is built apart from the copies' (an end cell with runouts is a full
    # one, its face as the copies'). Then every contact is a shared face.
    if start_plug is not None:
        start_plug, cells[0] = _join(occ, start_plug, cells[0])
    if rest > 1e-9 and len(cells) > 1:
        cells[-2], cells[-1] = _join(occ, cells[-2], cells[-1])
    if end_plug is not None:
        cells[-1], end_plug = _join(occ, cells[-1], end_plug)
    solids = ([start_plug] if start_plug is not None else []) + cells + (
        [end_plug] if end_plug is not None else [])
    if len(solids) > 1:
        glue(gmsh, solids[0], solids[1:])


def check_connected(gmsh) -> None:
    """All volumes must form one body: every volume shares a face with another."""
    vols = [t for _, t in gmsh.model.getEntities(3)]
    if len(vols) < 2:
        return
    faces: dict[int, list[int]] = {}
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

def build_solid(shaft: Shaft, grooves: Grooves | None, brep: Path) -> tuple[float, int]:
    """Build the shaft, check it is one body, write it to `brep`; return its volume
    (m^3) and how many CAD volumes it has."""
    with session("shaft") as s, translated(GeometryError, "OpenCASCADE could not build the "
                                           "shaft's solid (check the groove dimensions)"):
        gmsh = s.gmsh
        _build(gmsh, shaft, grooves)
        gmsh.model.occ.synchronize()
        vols = gmsh.model.getEntities(3)
        volume = sum(gmsh.model.occ.getMass(3, t) for _, t in vols)
        check_connected(gmsh)
        gmsh.write(str(brep))
    return volume, len(vols)


def write_solid(brep: Path | None, shaft: Shaft, paths: list[Path]) -> None:
    """The solid as STEP or BREP files (by suffix; for CAD and the workshop): from its
    BREP, or, for a shaft without grooves, a plain cylinder built on the spot. STEP in
    mm, as it states; BREP, which states no unit, in m."""
    with session("export") as s, stdout_to_devnull(), \
            translated(GeometryError, "the solid could not be written as STEP/BREP"):
        gmsh = s.gmsh
        if brep is None:
            gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, shaft.length, shaft.radius)
        else:
            gmsh.model.occ.importShapes(str(brep))
        gmsh.model.occ.synchronize()
        for path in paths:
            if path.suffix.lower() not in STEP_SUFFIXES:
                gmsh.write(str(path))
        # the model is in m; OpenCASCADE's STEP writer states mm and converts to it from
        # the unit it is told (its setting outlives the option: say it every time)
        steps = [p for p in paths if p.suffix.lower() in STEP_SUFFIXES]
        if steps:
            gmsh.option.setString("Geometry.OCCTargetUnit", "M")
            try:
                for path in steps:
                    gmsh.write(str(path))
            finally:
                gmsh.option.setString("Geometry.OCCTargetUnit", "")
