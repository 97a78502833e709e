"""Checks across a scene's tables, in file units: grooves that fit the shaft, and seats
that can be meshed and mean something."""

from __future__ import annotations

from shaftfem.errors import SceneError
from shaftfem.scene.model import MM, Attachment, Grooves, MeshSettings, Shaft, Support
from shaftfem.scene.toml_reading import entry, where

# A seat's band must be meshable and mean something: at least SEAT_MIN wide (no bearing
# or hub is narrower) and 1/16 of the element size (the band's faces need elements of
# about its width), and at least SEAT_MIN from another seat, a shaft end or the grooved
# zone, or exactly at it (nearer, the cut leaves a sliver the mesher cannot fill).
SEAT_MIN = 1e-3  # m
SEAT_PER_ELEMENT = 1 / 16


def check_seats(source: str, shaft: Shaft, grooves: Grooves | None,
                 supports: tuple[Support, ...], attachments: tuple[Attachment, ...],
                 mesh: MeshSettings) -> None:
    """Every seat wide enough to mesh, on the shaft, clear of the grooves, and no two
    seats overlapping; none nearer than SEAT_MIN to an edge it does not sit on."""
    seats = ([(entry("support", i, s), s) for i, s in enumerate(supports)]
             + [(entry("attachment", i, a), a) for i, a in enumerate(attachments)])
    L = shaft.length
    narrowest = max(SEAT_MIN, SEAT_PER_ELEMENT * mesh.size)
    edges = [0.0] + ([L] if L else [])  # an unplaced STEP shaft's length is not known yet
    edges += [] if grooves is None else list(grooves.cut)
    edges += list(shaft.step_positions())
    for table, part in seats:
        lo, hi = part.seat
        at = where(source, table, "position_mm")
        if part.width < narrowest - 1e-12:
            raise SceneError(
                f"{where(source, table, 'width_mm')} = {part.width / MM:g}: a seat must be at "
                f"least {narrowest / MM:g} mm wide (1 mm, and 1/16 of the element size "
                f"{mesh.size / MM:g} mm): narrower, it is no bearing or hub seat and its band "
                "cannot be meshed")
        near = [e for e in edges for z in (lo, hi) if 1e-12 < abs(z - e) < SEAT_MIN]
        if near:
            raise SceneError(
                f"{at} = {part.position / MM:g}: the seat {lo / MM:g} to {hi / MM:g} mm ends "
                f"within {SEAT_MIN / MM:g} mm of {near[0] / MM:g} mm (a shaft end, a step or the "
                "grooved zone): put it exactly there or at least 1 mm away")
        if lo < -1e-12 or (hi > L + 1e-12 and shaft.step is None):
            raise SceneError(
                f"{at} = {part.position / MM:g}: the seat {lo / MM:g} to {hi / MM:g} mm "
                f"(width_mm = {part.width / MM:g}) must lie on the shaft, 0 to {L / MM:g} mm")
        steps = [z for z in shaft.step_positions() if lo + 1e-12 < z < hi - 1e-12]
        if steps:
            raise SceneError(
                f"{at} = {part.position / MM:g}: the seat {lo / MM:g} to {hi / MM:g} mm "
                f"crosses the shoulder at {steps[0] / MM:g} mm; a seat lies on one section")
        k = shaft.section_at(part.position)
        if k is not None and shaft.profile[k].conical:
            raise SceneError(
                f"{at} = {part.position / MM:g}: the seat {lo / MM:g} to {hi / MM:g} mm lies on "
                f"section {k + 1}, a cone; seats go on cylindrical sections")
        if grooves is not None and lo < grooves.cut[1] and hi > grooves.cut[0]:
            raise SceneError(
                f"{at} = {part.position / MM:g}: the seat {lo / MM:g} to {hi / MM:g} mm lies "
                f"over the grooved zone ({grooves.cut[0] / MM:g} to {grooves.cut[1] / MM:g} mm"
                f"{', with its runouts' if grooves.runout else ''}); seats must be on plain "
                "shaft")
    ordered = sorted(seats, key=lambda s: s[1].seat[0])
    for (ta, a), (tb, b) in zip(ordered, ordered[1:]):
        # seats that touch would share the nodes of their common edge
        if b.seat[0] < a.seat[1] + SEAT_MIN - 1e-12:
            raise SceneError(
                f"{where(source, tb, 'position_mm')} = {b.position / MM:g}: its seat "
                f"({b.seat[0] / MM:g} to {b.seat[1] / MM:g} mm) overlaps, touches or comes "
                f"within {SEAT_MIN / MM:g} mm of the seat of {ta} ({a.seat[0] / MM:g} to "
                f"{a.seat[1] / MM:g} mm)")


def check_grooves(source: str, g: dict, shaft: Shaft) -> Grooves:
    """The grooves in SI: within one cylindrical section, of its radius, clear of its
    bore (file units in `g`)."""
    def fail(key: str, msg: str) -> SceneError:
        return SceneError(f"{where(source, 'grooves', key)} = {g[key]!r}: {msg}")

    length = shaft.length / MM
    start = g["start_mm"]
    if start is None:
        start = (length - g["grooved_length_mm"]) / 2
    run = g["runout_mm"]
    lo, hi = start - run, start + g["grooved_length_mm"] + run
    if run > 0 and (lo <= 0 or hi >= length):
        raise fail("runout_mm", f"the runouts {lo:g} to {start:g} and "
                   f"{start + g['grooved_length_mm']:g} to {hi:g} mm must lie on the shaft, "
                   f"inside 0 to {length:g} mm (a groove that runs off an end has no runout "
                   "there: set runout_mm = 0)")
    k = shaft.section_at((start + g["grooved_length_mm"] / 2) * MM)
    section = shaft.profile[k or 0]
    radius, bore = section.diameter_start / 2 / MM, section.bore / 2 / MM
    if k is not None and not shaft.plain:
        z0, z1 = (z / MM for z in shaft.plain_span(k))
        key = "runout_mm" if run > 0 else "grooved_length_mm"
        if lo < z0 - 1e-9 or hi > z1 + 1e-9 or section.conical:
            raise fail(key, f"the grooved zone {lo:g} to {hi:g} mm"
                       f"{' (with its runouts)' if run > 0 else ''} must lie within one "
                       f"cylindrical section, clear of its fillets and chamfers (section "
                       f"{k + 1}: {z0:g} to {z1:g} mm{', a cone' if section.conical else ''})")
        if any(kw.start < hi * MM and kw.end > lo * MM for kw in shaft.keyways):
            raise fail(key, "a keyway lies over the grooved zone"
                       f"{' or its runouts' if run > 0 else ''}")
    if g["depth_mm"] >= radius - bore:
        raise fail("depth_mm", f"must be less than the wall ({radius - bore:g} mm: the "
                   f"section's radius {radius:g} mm less its bore's)" if bore else
                   f"must be less than the shaft radius ({radius:g} mm)")
    if g["width_mm"] > g["pitch_mm"] / 2:
        raise fail("width_mm", f"must not exceed half the pitch ({g['pitch_mm'] / 2:g} mm)")
    if g["root_radius_mm"] > min(g["depth_mm"], g["width_mm"] / 2):
        raise fail("root_radius_mm", "must not exceed the depth nor half the width "
                   f"({min(g['depth_mm'], g['width_mm'] / 2):g} mm)")
    if g["grooved_length_mm"] > length:
        raise fail("grooved_length_mm", f"must not exceed the shaft length ({length:g} mm)")
    if g["start_mm"] is not None and start + g["grooved_length_mm"] > length:
        raise fail("start_mm", f"start + grooved_length_mm must not exceed the shaft length "
                   f"({length:g} mm)")
    # The groove ends need a little solid beyond them for the CAD to stay one body.
    return Grooves(
        hands=tuple(+1 if h == "right" else -1 for h in g["hands"]),
        pitch=g["pitch_mm"] * MM,
        width=g["width_mm"] * MM,
        depth=g["depth_mm"] * MM,
        root_radius=g["root_radius_mm"] * MM,
        length=g["grooved_length_mm"] * MM,
        start=start * MM,
        runout=run * MM,
    )


# What the tool has been verified on (docs/verification.md): shafts 5 mm to 10 m long,
# length over largest diameter 1 to 100 (tests/test_stability.py), frequencies below 100 kHz.
PLAUSIBLE_LENGTH = (5e-3, 10.0)          # m
VERIFIED_SLENDERNESS = (1.0, 100.0)
PLAUSIBLE_FREQUENCY = 1e5                # Hz


class PlausibilityWarning(UserWarning):
    """A scene that loads but looks like a slip (most often a unit)."""


def implausible(source: str, shaft: Shaft) -> list[str]:
    """What about the shaft's size looks like a slip, each naming the likely one."""
    L, D = shaft.length, shaft.diameter
    if not L:   # a STEP shaft is measured when it is placed
        return []
    out = []
    if not PLAUSIBLE_LENGTH[0] <= L <= PLAUSIBLE_LENGTH[1]:
        out.append(f"{source}: the shaft is {L / MM:g} mm long: lengths are in mm "
                   "(length_mm, diameter_mm), so is this in metres or inches? The tool is "
                   f"meant for shafts {PLAUSIBLE_LENGTH[0] / MM:g} mm to "
                   f"{PLAUSIBLE_LENGTH[1]:g} m long")
    slender = L / D
    if not VERIFIED_SLENDERNESS[0] <= slender <= VERIFIED_SLENDERNESS[1]:
        out.append(f"{source}: length / diameter = {slender:.3g} ({L / MM:g} mm over "
                   f"{D / MM:g} mm): the tool is verified on {VERIFIED_SLENDERNESS[0]:g} to "
                   f"{VERIFIED_SLENDERNESS[1]:g}; check that both are in mm")
    return out


def implausible_frequency(source: str, first_hz: float) -> list[str]:
    """A first frequency no machine shaft has: most often lengths given in metres."""
    if first_hz <= PLAUSIBLE_FREQUENCY:
        return []
    return [f"{source}: the first natural frequency is {first_hz / 1e3:.4g} kHz, above "
            f"{PLAUSIBLE_FREQUENCY / 1e3:g} kHz: lengths are in mm, so is the shaft given "
            "in metres?"]
