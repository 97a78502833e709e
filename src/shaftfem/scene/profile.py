"""The shaft's form from a scene file, in file units, checked: a plain bar, a stepped
profile of [[section]] tables with its [[keyway]] tables, or a STEP file.

Every rule a profile must keep so that its solid can be built is checked here, each
failure naming the key, its value and what is allowed; the CAD kernel never sees a
profile it cannot make.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

from shaftfem.errors import SceneError
from shaftfem.scene.keyway_sizes import keyway_size
from shaftfem.scene.model import MM, Keyway, Section, Shaft, StepSolid
from shaftfem.scene.schema import SCHEMA
from shaftfem.scene.toml_reading import entry, validate_table, where


def shaft_from_tables(source: str, shaft_t: dict, sections: list, keyways: list,
                      folder: Path | None) -> Shaft:
    """The scene's shaft (SI) from its [shaft] table, its [[section]] and [[keyway]]
    entries (raw) and the scene file's folder (a STEP file is named relative to it)."""
    plain = shaft_t["length_mm"] is not None or shaft_t["diameter_mm"] is not None
    step = shaft_t["step_file"] is not None
    if sum((plain, bool(sections), step)) != 1:
        raise SceneError(
            f"{source}: [shaft]: give the shaft one way: length_mm and diameter_mm (a plain "
            "bar), [[section]] tables (a stepped profile), or step_file (your own solid)"
            + ("; the file gives more than one" if plain + bool(sections) + step > 1 else ""))
    if step:
        if keyways:
            raise SceneError(f"{where(source, 'keyway[1]', 'position_mm')}: a keyway beside "
                             "step_file: draw it in the CAD model instead")
        if shaft_t["end_chamfer_mm"]:
            raise SceneError(f"{where(source, 'shaft', 'end_chamfer_mm')}: beside step_file: "
                             "draw it in the CAD model instead")
        return _step_shaft(source, shaft_t, folder)
    if plain:
        for key in ("length_mm", "diameter_mm"):
            if shaft_t[key] is None:
                raise SceneError(f"{where(source, 'shaft', key)}: missing (a plain bar needs "
                                 "length_mm and diameter_mm)")
        d = shaft_t["diameter_mm"]
        profile: tuple[Section, ...] = (Section(shaft_t["length_mm"] * MM, d * MM, d * MM),)
    else:
        profile = tuple(_section(source, i, e) for i, e in enumerate(sections))
    _check_steps(source, profile)
    chamfer = shaft_t["end_chamfer_mm"] * MM
    _check_end_chamfer(source, profile, chamfer)
    shaft = Shaft(length=sum(s.length for s in profile),
                  diameter=max(max(s.diameter_start, s.diameter_end) for s in profile),
                  sections=profile if len(profile) > 1 or _not_bar(profile[0]) else (),
                  end_chamfer=chamfer)
    cuts = tuple(_keyway(source, i, e, shaft) for i, e in enumerate(keyways))
    return Shaft(length=shaft.length, diameter=shaft.diameter, sections=shaft.sections,
                 keyways=cuts, end_chamfer=chamfer) if cuts else shaft


def _not_bar(s: Section) -> bool:
    return s.conical or s.bore > 0


def _section(source: str, i: int, raw: object) -> Section:
    table = entry("section", i)
    t = validate_table(source, table, raw, SCHEMA["section"])
    cone = (t["diameter_start_mm"], t["diameter_end_mm"])
    if t["diameter_mm"] is not None:
        if any(c is not None for c in cone):
            raise SceneError(f"{where(source, table, 'diameter_mm')}: give diameter_mm (a "
                             "cylinder) or diameter_start_mm and diameter_end_mm (a cone), "
                             "not both")
        cone = (t["diameter_mm"], t["diameter_mm"])
    elif any(c is None for c in cone):
        missing = "diameter_start_mm" if cone[0] is None else "diameter_end_mm"
        raise SceneError(f"{where(source, table, missing)}: missing (a section needs "
                         "diameter_mm, or diameter_start_mm and diameter_end_mm for a cone)")
    if t["bore_mm"] >= min(cone):
        raise SceneError(f"{where(source, table, 'bore_mm')} = {t['bore_mm']:g}: must be "
                         f"smaller than the section's outer diameter ({min(cone):g} mm)")
    return Section(length=t["length_mm"] * MM, diameter_start=cone[0] * MM,
                   diameter_end=cone[1] * MM, bore=t["bore_mm"] * MM,
                   fillet=t["fillet_mm"] * MM, chamfer=t["chamfer_mm"] * MM)


def _check_steps(source: str, profile: tuple[Section, ...]) -> None:
    """Neighbouring sections share material across their step; each fillet and chamfer
    fits its step and the sections beside it."""
    # what the step before each section takes of it, as the solid will draw it
    drawn = Shaft(length=sum(s.length for s in profile), diameter=0.0, sections=profile)
    bounds = drawn.section_bounds()
    for i, (a, b) in enumerate(zip(profile, profile[1:] + (None,))):
        table = entry("section", i)
        if b is None:
            for key, value in (("fillet_mm", a.fillet), ("chamfer_mm", a.chamfer)):
                if value:
                    raise SceneError(f"{where(source, table, key)} = {value / MM:g}: the last "
                                     "section has no step after it (the shaft's end takes "
                                     "[shaft] end_chamfer_mm)")
            continue
        inner, outer = max(a.bore, b.bore), min(a.diameter_end, b.diameter_start)
        if inner >= outer:
            raise SceneError(
                f"{where(source, entry('section', i + 1), 'bore_mm')}: sections {i + 1} and "
                f"{i + 2} do not join: at their step the bore ({inner / MM:g} mm) is not "
                f"smaller than the outer diameter ({outer / MM:g} mm)")
        step = abs(a.diameter_end - b.diameter_start) / 2
        small, big = (a, b) if a.diameter_end < b.diameter_start else (b, a)
        for key, value in (("fillet_mm", a.fillet), ("chamfer_mm", a.chamfer)):
            if value and step == 0:
                raise SceneError(f"{where(source, table, key)} = {value / MM:g}: there is no "
                                 f"step between sections {i + 1} and {i + 2} (both "
                                 f"{a.diameter_end / MM:g} mm there)")
        if a.fillet + a.chamfer > step + 1e-12:
            key = "fillet_mm" if a.fillet else "chamfer_mm"
            raise SceneError(f"{where(source, table, key)} = {getattr(a, key[:-3]) / MM:g}: "
                             f"the fillet and chamfer together ({(a.fillet + a.chamfer) / MM:g} "
                             f"mm) must not exceed the step ({step / MM:g} mm, from "
                             f"{min(a.diameter_end, b.diameter_start) / MM:g} to "
                             f"{max(a.diameter_end, b.diameter_start) / MM:g} mm)")
        if a.fillet and (small.conical or a.fillet >= small.length):
            raise SceneError(f"{where(source, table, 'fillet_mm')} = {a.fillet / MM:g}: a "
                             "fillet needs a cylindrical section beside the step, longer than "
                             f"the fillet (the smaller section is {small.length / MM:g} mm"
                             f"{', a cone' if small.conical else ''})")
        if a.chamfer and (big.conical or a.chamfer >= big.length):
            raise SceneError(f"{where(source, table, 'chamfer_mm')} = {a.chamfer / MM:g}: a "
                             "chamfer needs a cylindrical section above the step, longer than "
                             f"the chamfer (that section is {big.length / MM:g} mm"
                             f"{', a cone' if big.conical else ''})")
        if a.fillet and small is a and a.fillet + drawn.plain_span(i)[0] - bounds[i][0] > a.length:
            raise SceneError(f"{where(source, table, 'fillet_mm')} = {a.fillet / MM:g}: the "
                             "fillets and chamfers at both ends of section "
                             f"{i + 1} overlap ({a.length / MM:g} mm long)")


def _check_end_chamfer(source: str, profile: tuple[Section, ...], c: float) -> None:
    if not c:
        return
    for s, d, bore in ((profile[0], profile[0].diameter_start, profile[0].bore),
                       (profile[-1], profile[-1].diameter_end, profile[-1].bore)):
        if s.conical or c >= min(s.length, (d - bore) / 2):
            raise SceneError(
                f"{where(source, 'shaft', 'end_chamfer_mm')} = {c / MM:g}: must be smaller "
                f"than the end section's wall ({(d - bore) / 2 / MM:g} mm) and length "
                f"({s.length / MM:g} mm), on a cylindrical end section")


# a keyway running into a fillet ends at least this far (m) from the step's face: a cutter
# touching the face makes OpenCASCADE meet two tangent surfaces
STEP_CLEARANCE = 0.2 * MM


def _keyway_span(shaft: Shaft, i: int) -> tuple[float, float]:
    """Where a keyway may lie on section i (m): its plain span, and into a fillet at
    either end short of the step by STEP_CLEARANCE (a keyway running out into a
    shoulder's fillet), never into a chamfer."""
    (z0, z1), (p0, p1) = shaft.section_bounds()[i], shaft.plain_span(i)
    prof = shaft.profile
    if i > 0 and prof[i - 1].diameter_end > prof[i].diameter_start and prof[i - 1].fillet:
        p0 = z0 + STEP_CLEARANCE
    if (i < len(prof) - 1 and prof[i].diameter_end < prof[i + 1].diameter_start
            and prof[i].fillet):
        p1 = z1 - STEP_CLEARANCE
    return p0, p1


def _keyway(source: str, i: int, raw: object, shaft: Shaft) -> Keyway:
    table = entry("keyway", i)
    t = validate_table(source, table, raw, SCHEMA["keyway"])
    centre, length = t["position_mm"] * MM, t["length_mm"] * MM
    start, end = centre - length / 2, centre + length / 2
    k = shaft.section_at(centre)
    spans = [_keyway_span(shaft, i) for i in range(len(shaft.profile))]
    if k is None or start < spans[k][0] - 1e-12 or end > spans[k][1] + 1e-12:
        raise SceneError(
            f"{where(source, table, 'position_mm')} = {t['position_mm']:g}: the keyway "
            f"{start / MM:g} to {end / MM:g} mm must lie within one section, clear of its "
            "chamfers, and may run into a fillet but not to its step (sections: "
            + ", ".join(f"{a / MM:g}-{b / MM:g}" for a, b in spans) + " mm)")
    s = shaft.profile[k]
    if s.conical:
        raise SceneError(f"{where(source, table, 'position_mm')} = {t['position_mm']:g}: "
                         f"section {k + 1} is a cone; keyways go on cylindrical sections")
    d = s.diameter_start / MM
    din = keyway_size(d)
    width, depth = t["width_mm"], t["depth_mm"]
    if (width is None or depth is None) and din is None:
        raise SceneError(f"{where(source, table, 'width_mm' if width is None else 'depth_mm')}: "
                         f"missing; DIN 6885-1 gives sizes for diameters 6 to 230 mm only "
                         f"(this section is {d:g} mm)")
    if din is not None:
        width = width if width is not None else din[0]
        depth = depth if depth is not None else din[1]
    wall = (d - s.bore / MM) / 2
    if width >= d:
        raise SceneError(f"{where(source, table, 'width_mm')} = {width:g}: must be smaller "
                         f"than the section's diameter ({d:g} mm)")
    if depth >= wall or (s.bore and d / 2 - depth <= s.bore / MM / 2):
        raise SceneError(f"{where(source, table, 'depth_mm')} = {depth:g}: the keyway is "
                         f"deeper than the wall ({wall:g} mm)")
    if t["corner_radius_mm"] > min(depth, width / 2) - 1e-9 and t["corner_radius_mm"] > 0:
        raise SceneError(f"{where(source, table, 'corner_radius_mm')} = "
                         f"{t['corner_radius_mm']:g}: must be smaller than the depth and half "
                         f"the width ({min(depth, width / 2):g} mm)")
    if t["form"] == "rounded" and t["length_mm"] < width:
        raise SceneError(f"{where(source, table, 'length_mm')} = {t['length_mm']:g}: a "
                         f"rounded keyway is at least as long as it is wide ({width:g} mm)")
    cutter = t["cutter_diameter_mm"]
    if t["form"] == "sled":
        cutter = cutter if cutter is not None else 4 * width
        if cutter / 2 <= depth:
            raise SceneError(f"{where(source, table, 'cutter_diameter_mm')} = {cutter:g}: the "
                             f"cutter's radius must exceed the depth ({depth:g} mm)")
        # the cutter's chord at the surface: a disc-cut keyway is at least this long
        chord = 2 * math.sqrt(cutter * depth - depth * depth)
        if t["length_mm"] < chord:
            raise SceneError(f"{where(source, table, 'length_mm')} = {t['length_mm']:g}: a "
                             f"disc-cut keyway {depth:g} mm deep with a {cutter:g} mm cutter is "
                             f"at least {chord:.3g} mm long (the cutter's chord at the surface)")
    elif cutter is not None:
        raise SceneError(f"{where(source, table, 'cutter_diameter_mm')} = {cutter:g}: only "
                         "with form = \"sled\"")
    return Keyway(start=start, length=length, width=width * MM, depth=depth * MM,
                  angle=math.radians(t["angle_deg"]), form=t["form"],
                  corner_radius=t["corner_radius_mm"] * MM,
                  cutter_radius=(cutter or 0.0) * MM / 2)


def _step_shaft(source: str, t: dict, folder: Path | None) -> Shaft:
    """A STEP shaft: the file must exist and be readable; its geometry is checked when
    it is imported (cad.step), where its length and diameter become known."""
    path = Path(t["step_file"]).expanduser()
    if not path.is_absolute() and folder is not None:
        path = folder / path
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise SceneError(f"{where(source, 'shaft', 'step_file')} = {t['step_file']!r}: "
                         f"cannot be read ({exc.strerror or exc}: {path})") from exc
    head = data[:200].lstrip()
    if not head.startswith(b"ISO-10303-21"):
        raise SceneError(f"{where(source, 'shaft', 'step_file')} = {t['step_file']!r}: not a "
                         "STEP file (it does not begin with ISO-10303-21)")
    ends = (t["axis_from_mm"], t["axis_to_mm"])
    if (ends[0] is None) != (ends[1] is None):
        raise SceneError(f"{where(source, 'shaft', 'axis_to_mm' if ends[1] is None else 'axis_from_mm')}: "
                         "missing: the axis takes two points, axis_from_mm and axis_to_mm")
    axis = None
    if ends[0] is not None:
        a, b = ((float(e[0]) * MM, float(e[1]) * MM, float(e[2]) * MM) for e in ends)
        if math.dist(a, b) <= 0:
            raise SceneError(f"{where(source, 'shaft', 'axis_to_mm')} = {ends[1]!r}: the "
                             "axis's two points must differ")
        axis = (a, b)
    step = StepSolid(path=str(path.resolve()), sha256=hashlib.sha256(data).hexdigest(),
                     axis=axis)
    # length and diameter are the solid's: the CAD stage fills them in when it imports
    # the file (cad.step.placed), and checks the seats on them there
    return Shaft(length=0.0, diameter=0.0, step=step)

