"""The groove's profile and the volume it removes: geometry without CAD.

The profile is given in the axial section, as screw-thread profiles are:
width along the axis, depth radially, a root fillet at each floor corner. The
analytic groove volume is what the CAD solid's removed volume is checked
against (never another CAD volume: OpenCASCADE's volumes of one shape have
been seen to differ by 0.8 % between tools).
"""

from __future__ import annotations

import math

import numpy as np

from shaftfem.scene.model import Grooves

TOOL_OVERSHOOT = 1e-3           # the cutting tool reaches 1 mm above the surface
FILLET_POINTS = 9               # spline points on each mapped root fillet
# the root fillet meets the floor at acos(1 - FILLET_CROSSING) = 4.4 degrees, not
# tangentially (no boolean meets two tangent surfaces): a re-entrant kink, whose stress
# has no limit but grows only as r^-0.047 (Williams), so a crossing's converges as
# refined to 0.03 mm (178.3 MPa where 14 degrees rose to 222 MPa and on:
# benchmarks/groove_root_kink.py)
FILLET_CROSSING = 0.003


# a runout's floor ends this far above the surface, so that it crosses the surface, not
# touches it
RUNOUT_CLEARANCE = 0.5e-3
RUNOUT_FORM = "parabola, tangent to the floor"   # in the cache's keys


def runout_lift(g: Grooves, radius: float, beyond: np.ndarray) -> np.ndarray:
    """How far a groove's floor has risen (m) at `beyond` m along the axis past the end of
    the grooved zone: a parabola leaving the floor tangentially (a crease there, 4.4
    degrees at first, rose with every refinement: 163 MPa and on at 4 um elements on the
    paper's shaft) and rising out through the surface at the runout's end."""
    u = np.clip(np.asarray(beyond, dtype=float) / g.runout, 0.0, 1.0)
    return (g.depth + RUNOUT_CLEARANCE) * u**2


def _sharp_dip(g: Grooves, radius: float) -> float:
    """How far a sharp-cornered groove's tool reaches below its floor (m)."""
    return min(0.5e-3, 0.5 * (radius - g.depth))


def _sharp_tool_floor(g: Grooves, radius: float, lift: float) -> float:
    """A sharp-cornered groove's tool's floor (m above the groove's: below it, -dip, at
    full depth) in a runout where the lift is `lift`, rising to the runout's same top."""
    dip, rise = _sharp_dip(g, radius), g.depth + RUNOUT_CLEARANCE
    return lift * (rise + dip) / rise - dip


def _sharp_lift(g: Grooves, radius: float, lift: float) -> float:
    """A sharp-cornered groove's floor (m above the groove's) in a runout where the lift
    is `lift`: its tool's floor, or the groove's where the tool reaches below it."""
    return max(0.0, _sharp_tool_floor(g, radius, lift))


def axial_width(g: Grooves, radius: float, r: np.ndarray, lift: float = 0.0) -> np.ndarray:
    """Width of the groove along the axis (m) at radius r, for r in [R-d, R], its floor
    risen by `lift` (m, in a runout)."""
    r = np.asarray(r, dtype=float)
    floor = radius - g.depth + (lift if g.root_radius > 0 else _sharp_lift(g, radius, lift))
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
    z = np.linspace(0.0, g.length, nz)
    volume = _swept(g, radius, r, z, np.zeros_like(z))
    if g.runout > 0:   # each runout, its floor risen by runout_lift
        beyond = np.linspace(0.0, g.runout, nz // 4 + 1)
        lift = runout_lift(g, radius, beyond)
        volume += _swept(g, radius, r, -beyond, lift) + _swept(g, radius, r,
                                                                g.length + beyond, lift)
    return volume


def _swept(g: Grooves, radius: float, r: np.ndarray, z: np.ndarray, lift: np.ndarray
           ) -> float:
    """The grooves' volume between the transverse sections at z (m from the zone's start,
    increasing or decreasing), their floors risen by `lift` there."""
    phi = np.array([2 * math.pi * axial_width(g, radius, r, h) / g.pitch for h in lift])
    if len(g.hands) == 1:
        return abs(float(np.trapezoid(np.trapezoid(phi * r[None, :], r, axis=1), z)))
    # right-hand centre at pi/2 + 2 pi z/P, left-hand at -(pi/2 + 2 pi z/P)
    diff = np.mod(math.pi + 4 * math.pi * z / g.pitch, 2 * math.pi)
    gap = np.minimum(diff, 2 * math.pi - diff)
    overlap = np.maximum(0.0, phi - gap[:, None])
    area = np.trapezoid((2 * phi - overlap) * r[None, :], r, axis=1)
    return abs(float(np.trapezoid(area, z)))


def profile_outline(g: Grooves, radius: float, lift: float = 0.0, top: float | None = None
                    ) -> list[tuple[str, list[tuple[float, float]]]]:
    """The cutting tool's closed outline in the axial section, as (kind, [(s, r), ...]).

    s is the axial offset from the groove's centre line, r the radius (m). Kinds:
    'radial' (s constant), 'arc' (r constant), 'spline' (a mapped root fillet).
    The tool reaches below the floor so that the ring intersection, not the tool,
    makes the floor. In a runout the floor has risen by `lift` (m); the tool reaches
    to radius `top` (default TOOL_OVERSHOOT above the surface).
    """
    a = g.width / 2
    floor = radius - g.depth + lift
    top = radius + TOOL_OVERSHOOT if top is None else top
    rf = g.root_radius
    if rf == 0:
        # the tool's floor reaches below the groove's; in a runout it rises from there
        # to the runout's top
        bottom = radius - g.depth + _sharp_tool_floor(g, radius, lift)
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
