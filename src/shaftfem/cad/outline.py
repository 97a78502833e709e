"""A stepped shaft's axial half-section, and the volumes its solid must have: geometry
without CAD.

The outline is a closed polygon of lines and quarter arcs in the (z, r) half-plane:
along the outer contour from the left end to the right, with the fillets in the
concave corners of the steps and the chamfers on the convex ones, then back along the
bore (or the axis). Revolved about the axis it is the shaft; its area and centroid
give the solid's volume by Pappus's theorem, which the CAD solid is checked against.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaftfem.scene.model import Keyway, Shaft


@dataclass(frozen=True)
class Piece:
    """One piece of the outline from `a` to `b`, points (z, r) in m: a line, or an arc
    about `centre`."""

    a: tuple[float, float]
    b: tuple[float, float]
    centre: tuple[float, float] | None = None


def outline(shaft: Shaft) -> list[Piece]:
    """The closed half-section of a profiled shaft, counter-clockwise in (z, r)."""
    prof = shaft.profile
    bounds = shaft.section_bounds()
    c = shaft.end_chamfer
    pts: list[tuple[tuple[float, float], tuple[float, float] | None]] = []  # (point, arc centre)

    def to(p: tuple[float, float], centre: tuple[float, float] | None = None) -> None:
        pts.append((p, centre))

    r0 = prof[0].diameter_start / 2
    to((0.0, prof[0].bore / 2))
    to((0.0, r0 - c))
    if c:
        to((c, r0))
    for i, (s, (_, z1)) in enumerate(zip(prof, bounds)):
        if i + 1 == len(prof):
            break
        nxt = prof[i + 1]
        ra, rb = s.diameter_end / 2, nxt.diameter_start / 2
        rho, ch = s.fillet, s.chamfer
        if ra < rb:        # a step up: the concave corner first, on this section
            to((z1 - rho, ra))
            if rho:
                to((z1, ra + rho), (z1 - rho, ra + rho))
            to((z1, rb - ch))
            if ch:
                to((z1 + ch, rb))
        elif ra > rb:      # a step down: the convex corner first
            to((z1 - ch, ra))
            if ch:
                to((z1, ra - ch))
            to((z1, rb + rho))
            if rho:
                to((z1 + rho, rb), (z1 + rho, rb + rho))
        else:
            to((z1, ra))
    L = shaft.length
    rn = prof[-1].diameter_end / 2
    if c:
        to((L - c, rn))
    to((L, rn - c))
    # back along the bore (or the axis), from the right end, a point only where it steps
    for i in reversed(range(len(prof))):
        (z0, z1), bore = bounds[i], prof[i].bore
        if pts[-1][0][1] != bore / 2:
            to((z1, bore / 2))
        if i == 0 or bore != prof[i - 1].bore:
            to((z0, bore / 2))
    pieces: list[Piece] = []
    closed = pts + [pts[0]]
    for (p, _), (q, centre) in zip(closed, closed[1:]):
        if math.dist(p, q) > 1e-12:
            pieces.append(Piece(p, q, centre))
    return pieces


def revolved_volume(pieces: list[Piece]) -> float:
    """The volume swept by the closed outline about the axis (m^3): 2 pi times the
    first moment of its area about the axis, by Green's theorem over the polygon of its
    chords, each arc's circular segment then added or taken away exactly."""
    area = sum(p.a[0] * p.b[1] - p.b[0] * p.a[1] for p in pieces) / 2
    turn = 1.0 if area > 0 else -1.0   # +1: counter-clockwise in (z, r)
    moment = -turn * sum((p.b[0] - p.a[0]) * (p.a[1] ** 2 + p.a[1] * p.b[1] + p.b[1] ** 2)
                         for p in pieces) / 6
    for p in pieces:
        if p.centre is not None:
            moment += _segment_moment(p, turn)
    return 2 * math.pi * moment


def _segment_moment(p: Piece, turn: float) -> float:
    """The first moment about the axis of the circular segment between an arc of the
    outline and its chord: added where the arc's centre lies inside the outline (the arc
    bulges out of the polygon of chords), taken away where it lies outside (a concave
    fillet)."""
    assert p.centre is not None
    (za, ra), (zb, rb), (zc, rc) = p.a, p.b, p.centre
    rho = math.dist(p.a, p.centre)
    half = 0.5 * math.acos(max(-1.0, min(1.0, ((za - zc) * (zb - zc) + (ra - rc) * (rb - rc))
                                     / (rho * rho))))
    area = 0.5 * rho * rho * (2 * half - math.sin(2 * half))
    mid = np.array([(za + zb) / 2 - zc, (ra + rb) / 2 - rc])
    mid /= np.linalg.norm(mid)
    # a circular segment's centroid lies 4 rho sin^3(a) / (3 (2a - sin 2a)) from the centre
    d = 4 * rho * math.sin(half) ** 3 / (3 * (2 * half - math.sin(2 * half)))
    inside = ((zb - za) * (rc - ra) - (rb - ra) * (zc - za)) * turn > 0  # left of a->b, CCW
    return (1.0 if inside else -1.0) * area * (rc + d * mid[1])


def surface_radius(shaft: Shaft, z: np.ndarray) -> np.ndarray:
    """The outer contour's radius (m) at each z (m) of a profiled shaft: its sections,
    fillets and chamfers (the outline's pieces running along the axis)."""
    z = np.asarray(z, dtype=float)
    out = np.full(z.shape, np.nan)
    for p in outline(shaft):
        (za, ra), (zb, rb) = p.a, p.b
        if zb <= za:          # a step's face, or the way back along the bore
            continue
        on = np.isnan(out) & (z >= za - 1e-12) & (z <= zb + 1e-12)
        if p.centre is None:
            out[on] = ra + (rb - ra) * (z[on] - za) / (zb - za)
        else:
            zc, rc = p.centre
            rho = math.dist(p.a, p.centre)
            root = np.sqrt(np.maximum(rho * rho - (z[on] - zc) ** 2, 0.0))
            # the branch the arc's ends lie on: below its centre (a fillet) or above
            out[on] = rc - root if (ra + rb) / 2 < rc else rc + root
    return out


def keyway_volume(k: Keyway, radius: float, n: int = 600, surface=None) -> float:
    """The volume a keyway removes from a cylinder of `radius` (m^3), integrated over its
    plan: at each point (y across, z along) the depth from the surface sqrt(R^2 - y^2)
    down to the floor (sharp floor corners); `surface`: the surface's radius as a
    function of z where it is not the cylinder's (a keyway running into a fillet)."""
    y = np.linspace(-k.width / 2, k.width / 2, n)
    z = np.linspace(k.start, k.end, 2 * n)
    Y, Z = np.meshgrid(y, z)
    R = radius if surface is None else surface(Z)
    floor = np.full_like(Z, radius - k.depth)
    inside = np.ones_like(Z, dtype=bool)
    if k.form == "rounded":
        a = k.width / 2
        zc = np.clip(Z, k.start + a, k.end - a)
        inside = (Z - zc) ** 2 + Y**2 <= a * a
    else:
        run = runout(k, radius)
        rc = k.cutter_radius
        zc = np.clip(Z, k.start + run, k.end - run)
        dz = np.abs(Z - zc)
        floor = radius - k.depth + rc - np.sqrt(np.maximum(rc * rc - dz * dz, 0.0))
    depth = np.where(inside, np.maximum(np.sqrt(R**2 - Y**2) - floor, 0.0), 0.0)
    return float(np.trapezoid(np.trapezoid(depth, y, axis=1), z))


def runout(k: Keyway, radius: float) -> float:
    """How far a disc-cut keyway's end rises from its floor to the surface, along the
    axis (m): the cutter's chord at the keyway's depth."""
    rc = k.cutter_radius
    return math.sqrt(max(rc * rc - (rc - k.depth) ** 2, 0.0))


def key_bearing(k: Keyway, radius: float) -> tuple[float, float]:
    """Where a key bears on its keyway's flanks along the axis (m): the straight part
    between the round ends (DIN 6892's bearing length l - b of a round-ended key) or
    between a disc-cut keyway's runouts. Empty (z0 = z1) in a round hole."""
    cut = k.width / 2 if k.form == "rounded" else runout(k, radius)
    z0 = k.start + cut
    return z0, max(k.end - cut, z0)


def feature_faces(shaft: Shaft, samples: dict[int, np.ndarray], tol: float = 1e-6) -> list[int]:
    """The faces (tag -> sampled points (n, 3), m) that lie wholly on a feature of the
    profile: a fillet's or chamfer's ring about its step, or a keyway's pocket."""
    boxes = []  # (z0, z1, r0, r1): rings about a step
    prof, bounds = shaft.profile, shaft.section_bounds()
    for s, nxt, (_, z1) in zip(prof, prof[1:], bounds):
        lo, hi = sorted((s.diameter_end / 2, nxt.diameter_start / 2))
        if s.fillet:
            boxes.append((z1 - s.fillet, z1 + s.fillet, lo, lo + s.fillet))
        if s.chamfer:
            boxes.append((z1 - s.chamfer, z1 + s.chamfer, hi - s.chamfer, hi))
    if shaft.end_chamfer and prof:
        c = shaft.end_chamfer
        boxes.append((0.0, c, prof[0].diameter_start / 2 - c, prof[0].diameter_start / 2))
        boxes.append((shaft.length - c, shaft.length, prof[-1].diameter_end / 2 - c,
                      prof[-1].diameter_end / 2))
    out = []
    for tag, xyz in samples.items():
        r, z = np.hypot(xyz[:, 0], xyz[:, 1]), xyz[:, 2]
        on_ring = any(np.all((z > z0 - tol) & (z < z1 + tol) & (r > r0 - tol) & (r < r1 + tol))
                      for z0, z1, r0, r1 in boxes)
        if on_ring or any(_in_keyway(k, xyz, tol) for k in shaft.keyways):
            out.append(tag)
    return out


def keyway_frame(k: Keyway, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points' (x, y) (m) in the keyway's own frame: along its centre line from the axis,
    and across it (towards +y where the keyway lies on +x)."""
    c, s = math.cos(k.angle), math.sin(k.angle)
    return c * x + s * y, -s * x + c * y


def _in_keyway(k: Keyway, xyz: np.ndarray, tol: float) -> bool:
    """Whether every point lies in the keyway's pocket: along it, and across it within
    half its width on its side of the axis (in the keyway's own frame)."""
    x, y = keyway_frame(k, xyz[:, 0], xyz[:, 1])
    return bool(np.all((xyz[:, 2] > k.start - tol) & (xyz[:, 2] < k.end + tol)
                       & (np.abs(y) < k.width / 2 + tol) & (x > 0)))


def singular_edges(shaft: Shaft, samples: dict[int, np.ndarray], tol: float = 1e-6) -> list[int]:
    """The curves (tag -> sampled points (n, 3), m) along which the stress is singular:
    the concave edges of the profile, where a step has no fillet, and a keyway's floor
    edges (all of its curves below the shaft's surface; its rim's edges are convex)."""
    rings = []  # (z, r) of each sharp concave corner of a step
    prof, bounds = shaft.profile, shaft.section_bounds()
    for s, nxt, (_, z1) in zip(prof, prof[1:], bounds):
        if not s.fillet and s.diameter_end != nxt.diameter_start:
            rings.append((z1, min(s.diameter_end, nxt.diameter_start) / 2))
    out = []
    for tag, xyz in samples.items():
        r, z = np.hypot(xyz[:, 0], xyz[:, 1]), xyz[:, 2]
        if any(np.all((np.abs(z - zc) < tol) & (np.abs(r - rc) < tol)) for zc, rc in rings):
            out.append(tag)
            continue
        for k in shaft.keyways:
            radius = shaft.radius_at(0.5 * (k.start + k.end)) or 0.0
            if _in_keyway(k, xyz, tol) and np.all(r < radius - tol):
                out.append(tag)
                break
    return out
