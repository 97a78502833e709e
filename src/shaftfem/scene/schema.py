"""The scene file's schema: every key, its unit, what it must satisfy.

Declarative on purpose: `scene.toml_reading.validate_table` checks any table
against its entry here, so a new key is one line.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

# A flat separation margin of about 15 % between a natural frequency and any
# running-speed harmonic is common machinery practice (see shaftfem.checks.resonance).
DEFAULT_MARGIN_PERCENT = 15.0
DEFAULT_MODE_COUNT = 10
MAX_MODE_COUNT = 200
# An adaptive mesh stops before it needs more DOFs than this (about 6 GB at the peak).
DEFAULT_MAX_DOFS = 400_000
MAX_DOFS_LIMIT = 20_000_000
# element orders (1, 2: Lagrange; 3 on: hierarchical) and degrees of the elements' map
ELEMENT_ORDERS = (1, 2, 3, 4, 5)
GEOMETRY_ORDERS = (2, 3)
SUPPORT_KINDS = ("rigid", "rigid-radial", "clamped", "springs", "bearing", "journal", "ball",
                 "roller", "seal")
CAVITATION = ("reynolds", "gumbel")
# a journal's bores: one cylinder, or pads (shaftfem.parts.pads)
BORES = ("plain", "two_axial_groove", "elliptical", "tilting_pad")
# ISO 3448 viscosity grades shaftfem knows the temperature line of (shaftfem.parts.oil)
ISO_VG = (10, 15, 22, 32, 46, 68, 100, 150, 220, 320, 460, 680)
# A journal bearing's film thinner than this at an operating speed is a warning.
DEFAULT_MIN_FILM_UM = 10.0
ROTOR_FRAMES = ("auto", "stationary", "rotating")
# The Campbell diagram's end when [rotor] does not give one: this much above the
# highest operating speed.
DEFAULT_SPEED_HEADROOM = 1.5
COUPLINGS = ("distributing", "rigid")
KEYWAY_FORMS = ("rounded", "sled")
# The standard acceleration of gravity, m/s^2 (the default [static] gravity_m_s2).
STANDARD_GRAVITY = 9.80665
# Modal damping of a steel shaft in rolling bearings: 1-3 % of critical is usual.
DEFAULT_DAMPING_PERCENT = 2.0


@dataclass(frozen=True)
class Key:
    """One scene key: its type, what it means (with its unit), and what it must satisfy."""

    kind: type | tuple  # float, int, str, bool, or ("list", str)
    doc: str
    check: Callable[[Any], bool] | None = None
    allowed: str = ""
    default: Any = None
    required: bool = True


@dataclass(frozen=True)
class Table:
    """One table of the scene file: what it describes, and whether a scene needs it
    (`required`) or may repeat it as an array of tables, [[name]] (`repeated`)."""

    doc: str
    required: bool = False
    repeated: bool = False


def coupling(why: str, default: str) -> Key:
    """A key naming one of COUPLINGS."""
    return Key(str, why, lambda v: v in COUPLINGS, ", ".join(f'"{c}"' for c in COUPLINGS),
               default=default, required=False)


def upto(high: float, why: str, low: float = 0.0,
         closed_low: bool = False) -> tuple[Callable[[Any], bool], str]:
    """A check and its words: low < v <= high (low <= v with closed_low), and why the cap.

    The caps are far beyond any machine shaft; they keep absurd values (1e300) away
    from the CAD kernel and the solvers, which fail on them without a useful message."""
    def check(v: float) -> bool:
        return (low <= v if closed_low else low < v) and v <= high
    return check, f"in {'[' if closed_low else '('}{low:g}, {high:g}] ({why})"


def coefficient(what: str, direct: bool) -> Key:
    """A bearing coefficient's key: one number, or one per speeds_rpm entry; a direct
    stiffness or damping is not negative."""
    def check(v: list) -> bool:
        return len(v) >= 1 and all(math.isfinite(x) and abs(x) <= 1e12 for x in v) and (
            not direct or all(x >= 0 for x in v))
    return Key(("list", float), f"{what}: one number, or a list with one value per "
               "speeds_rpm entry", check,
               "finite numbers in [0, 1e12]" if direct else "finite numbers in [-1e12, 1e12]",
               required=False)


# the title block's keys at the top of a scene file, with what each names
TITLE_KEYS = {"machine": "the machine the shaft belongs to (its tag or model)",
              "job": "the job or project number", "revision": "the study's revision",
              "date": "the study's date", "engineer": "who made the study"}

SCHEMA: dict[str, dict[str, Key]] = {
    "": {
        "name": Key(str, "short name of the scene; it names the default output folder "
                    "out/NAME", lambda v: re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9._-]*", v) is not None,
                    "letters, digits, '.', '_' and '-', starting with a letter or digit (a "
                    "folder name, not a path)", required=False),
        "description": Key(str, "free text", required=False),
        **{key: Key(str, f"the report's title block: {what}", required=False)
           for key, what in TITLE_KEYS.items()},
    },
    "shaft": {
        "length_mm": Key(float, "overall shaft length, mm (a plain bar; leave out with "
                         "[[section]] or step_file)", *upto(20_000, "a shaft up to 20 m"),
                         required=False),
        "diameter_mm": Key(float, "outer diameter, mm (a plain bar; leave out with "
                           "[[section]] or step_file)", *upto(2_000, "up to 2 m"),
                           required=False),
        "end_chamfer_mm": Key(float, "45-degree chamfer at both shaft ends, its leg, mm",
                              *upto(1_000, "up to 1 m", closed_low=True), default=0.0,
                              required=False),
        "step_file": Key(str, "the shaft's own solid from CAD: a STEP file, relative to the "
                         "scene file, in the unit the file states (no [[section]], "
                         "[grooves] or [[keyway]] beside it)",
                         lambda v: v.strip() != "", "a file name", required=False),
        "axis_from_mm": Key(("list", float), "a point on the shaft axis in the STEP "
                            "file's coordinates, [x, y, z] mm, at the left end's side "
                            "(default: the axis is along z through the middle of the "
                            "solid's bounding box)", lambda v: len(v) == 3,
                            "three numbers", required=False),
        "axis_to_mm": Key(("list", float), "a second point on the axis, towards the "
                          "right end, [x, y, z] mm", lambda v: len(v) == 3, "three numbers",
                          required=False),
    },
    "section": {  # an array of tables: [[section]], the stepped profile from the left end
        "length_mm": Key(float, "length of the section along the axis, mm",
                         *upto(20_000, "up to 20 m")),
        "diameter_mm": Key(float, "outer diameter, mm (or diameter_start_mm and "
                           "diameter_end_mm for a cone)", *upto(2_000, "up to 2 m"),
                           required=False),
        "diameter_start_mm": Key(float, "a cone's outer diameter at its left end, mm",
                                 *upto(2_000, "up to 2 m"), required=False),
        "diameter_end_mm": Key(float, "a cone's outer diameter at its right end, mm",
                               *upto(2_000, "up to 2 m"), required=False),
        "bore_mm": Key(float, "inner diameter, mm (0: solid)",
                       *upto(2_000, "up to 2 m", closed_low=True), default=0.0,
                       required=False),
        "fillet_mm": Key(float, "fillet radius in the concave corner of the step to the "
                         "next section, mm (0: sharp)", *upto(1_000, "up to 1 m",
                                                              closed_low=True),
                         default=0.0, required=False),
        "chamfer_mm": Key(float, "45-degree chamfer on the convex edge of the step to the "
                          "next section, its leg, mm", *upto(1_000, "up to 1 m",
                                                            closed_low=True),
                          default=0.0, required=False),
    },
    "keyway": {  # an array of tables: [[keyway]], a keyway milled into one section
        "position_mm": Key(float, "centre of the keyway from the shaft's left end, mm",
                           *upto(20_000, "up to 20 m", closed_low=True)),
        "length_mm": Key(float, "length of the keyway along the axis, end to end, mm",
                         *upto(20_000, "up to 20 m")),
        "width_mm": Key(float, "width b across the keyway, mm (default: DIN 6885-1 for the "
                        "section's diameter)", *upto(1_000, "up to 1 m"), required=False),
        "depth_mm": Key(float, "depth t1 of the floor below the surface, mm (default: "
                        "DIN 6885-1 for the section's diameter)", *upto(1_000, "up to 1 m"),
                        required=False),
        "angle_deg": Key(float, "angle of the keyway's centre about the axis from +x, deg",
                         lambda v: -360 <= v <= 360, "in [-360, 360]", default=0.0,
                         required=False),
        "form": Key(str, "\"rounded\": end-milled, round ends (DIN 6885 form A); "
                    "\"sled\": disc-cut, the ends running out along the cutter",
                    lambda v: v in KEYWAY_FORMS, ", ".join(f'"{f}"' for f in KEYWAY_FORMS),
                    default="rounded", required=False),
        "corner_radius_mm": Key(float, "radius of the floor's two corners, mm (0: sharp)",
                                *upto(1_000, "up to 1 m", closed_low=True), default=0.0,
                                required=False),
        "cutter_diameter_mm": Key(float, "the disc cutter's diameter, mm (form \"sled\"; "
                                  "default four times the width)", *upto(2_000, "up to 2 m"),
                                  required=False),
    },
    "material": {
        "name": Key(str, "material name", required=False, default="steel"),
        "youngs_modulus_mpa": Key(float, "Young's modulus E, MPa",
                                  *upto(1.2e6, "up to 1200 GPa, above diamond")),
        "poisson_ratio": Key(
            float, "Poisson's ratio", lambda v: -1.0 < v < 0.5, "in (-1, 0.5)"
        ),
        "density_kg_m3": Key(float, "density, kg/m^3", *upto(25_000, "above osmium")),
    },
    "grooves": {
        "hands": Key(
            ("list", str),
            'groove hands, e.g. ["right", "left"]',
            lambda v: 1 <= len(v) <= 2
            and all(h in ("right", "left") for h in v)
            and len(set(v)) == len(v),
            'one or two of "right", "left", each at most once',
        ),
        "pitch_mm": Key(float, "helix pitch (lead), mm", *upto(20_000, "up to 20 m")),
        "width_mm": Key(float, "groove width along the shaft axis, mm",
                         *upto(10_000, "up to 10 m")),
        "depth_mm": Key(float, "groove depth, mm", *upto(1_000, "up to 1 m")),
        "root_radius_mm": Key(
            float, "fillet radius at the groove's floor corners, mm (0 = sharp)",
            *upto(1_000, "up to 1 m", closed_low=True), default=0.0, required=False,
        ),
        "grooved_length_mm": Key(float, "axial length of the grooved zone, mm",
                                  *upto(20_000, "up to 20 m")),
        "start_mm": Key(
            float, "distance from the shaft's left end to the grooved zone, mm "
            "(default: the zone is centred)", *upto(20_000, "up to 20 m", closed_low=True),
            required=False,
        ),
        "runout_mm": Key(
            float, "axial length beyond each end of the grooved zone over which each "
            "groove's floor rises out to the surface, as the cutter lifts out, mm (0 = the "
            "grooves end in flat walls, whose sharp re-entrant edges strength cannot judge)",
            *upto(1_000, "up to 1 m", closed_low=True), default=0.0, required=False,
        ),
    },
    "excitation": {  # an array of tables: [[excitation]]
        "name": Key(str, "name of the source, e.g. engine"),
        "speed_rpm": Key(float, "speed of the source, r/min (f = n / 60 Hz)",
                         *upto(1e6, "up to 10^6 r/min")),
        "orders": Key(("list", int), "harmonic orders that excite, e.g. [1, 2]",
                      lambda v: len(v) >= 1 and all(k >= 1 for k in v), "integers >= 1",
                      default=[1], required=False),
    },
    "support": {  # an array of tables: [[support]], a bearing seat (shaftfem.fem.supports)
        "name": Key(str, "name of the support, e.g. drive-end bearing", required=False),
        "position_mm": Key(float, "centre of the bearing seat from the shaft's left end, mm",
                           *upto(20_000, "up to 20 m", closed_low=True)),
        "width_mm": Key(float, "width of the bearing seat along the axis, mm",
                        *upto(20_000, "up to 20 m")),
        "kind": Key(str, "how the seat is held: \"rigid\" (its mean radial and axial "
                    "displacement), \"rigid-radial\" (radial only: a floating bearing), "
                    "\"clamped\" (every point of it, in every direction), \"springs\" (the "
                    "stiffnesses below), \"bearing\" (a rotor bearing's stiffness and damping "
                    "coefficients kxx ... cyx, constant or against speed), \"journal\" (a plain "
                    "oil-film journal bearing from its clearance, oil and load: its coefficients "
                    "at each speed from Reynolds' equation, docs/journal-bearing.md), \"ball\" "
                    "or \"roller\" (a rolling bearing from its elements and load, Hertz "
                    "contact, docs/rolling-bearing.md), \"seal\" (a plain annular seal from "
                    "its clearance, pressure drop and fluid, docs/seal.md: it carries no static "
                    "load); all but rigid-radial and clamped let the shaft tilt and turn",
                    lambda v: v in SUPPORT_KINDS, ", ".join(f'"{k}"' for k in SUPPORT_KINDS)),
        "kxx_n_per_mm": coefficient(
            "direct stiffness along x, N/mm (kind = \"bearing\")", direct=True),
        "kyy_n_per_mm": coefficient("direct stiffness along y, N/mm (default: kxx)", direct=True),
        "kxy_n_per_mm": coefficient(
            "cross-coupled stiffness, the x force per y displacement, N/mm (default 0)",
            direct=False),
        "kyx_n_per_mm": coefficient(
            "cross-coupled stiffness, the y force per x displacement, N/mm (default 0)",
            direct=False),
        "cxx_n_s_per_mm": coefficient("direct damping along x, N s/mm (default 0)",
                                      direct=True),
        "cyy_n_s_per_mm": coefficient("direct damping along y, N s/mm (default: cxx)",
                                      direct=True),
        "cxy_n_s_per_mm": coefficient("cross-coupled damping, N s/mm (default 0)", direct=False),
        "cyx_n_s_per_mm": coefficient("cross-coupled damping, N s/mm (default 0)", direct=False),
        "speeds_rpm": Key(("list", float), "the speeds, r/min, at which the bearing's "
                          "coefficients are given as lists (kind = \"bearing\"; between them "
                          "interpolated linearly, outside them the nearest end's value)",
                          lambda v: len(v) >= 1 and all(x >= 0 for x in v)
                          and all(b > a for a, b in zip(v, v[1:])),
                          "ascending numbers >= 0", required=False),
        "radial_stiffness_n_per_mm": Key(
            float, "radial stiffness of the bearing, N/mm (kind = \"springs\")",
            *upto(1e12, "up to 10^12 N/mm", closed_low=True), required=False),
        "axial_stiffness_n_per_mm": Key(
            float, "axial stiffness, N/mm (kind = \"springs\"; default 0: free axially)",
            *upto(1e12, "up to 10^12 N/mm", closed_low=True), required=False),
        "tilting_stiffness_nmm_per_rad": Key(
            float, "tilting stiffness, N mm/rad (kind = \"springs\"; default 0: the shaft "
            "tilts freely in the bearing, as in a ball bearing)",
            *upto(1e15, "up to 10^15 N mm/rad: the frequencies stop changing near 10^12; "
                  "far beyond, the solve loses the digits it needs", closed_low=True),
            required=False),
        "radial_clearance_um": Key(
            float, "radial clearance of a journal bearing or a seal (bore radius minus "
            "shaft radius), um (kind = \"journal\", \"seal\"; the length is width_mm); "
            "or its tolerance, [min, max] or [min, nominal, max]: the study runs the ends as "
            "cases (workflows.cases)",
            *upto(10_000, "up to 10 mm"), required=False),
        "diameter_mm": Key(float, "journal or seal diameter, mm (kind = \"journal\", "
                           "\"seal\"; default: the "
                           "shaft's diameter at the seat; needed on a STEP shaft)",
                           *upto(2_000, "up to 2 m"), required=False),
        "viscosity_mpa_s": Key(float, "the oil's dynamic viscosity in the film, mPa s (= cP; "
                               "kind = \"journal\"; or oil_iso_vg and oil_temperature_c; "
                               "a journal's may be a range [min, max]), "
                               "or the sealed fluid's (kind = \"seal\"; water at 20 C: 1.0)",
                               *upto(10_000, "up to 10^4 mPa s"), required=False),
        "oil_iso_vg": Key(int, "the oil's ISO 3448 viscosity grade (a VI-100 mineral oil; "
                          "kind = \"journal\", with oil_temperature_c)",
                          lambda v: v in ISO_VG, ", ".join(str(g) for g in ISO_VG),
                          required=False),
        "oil_temperature_c": Key(float, "the film's mean temperature, C (with oil_iso_vg); "
                                 "or its range, [cold, hot] or [cold, nominal, hot]: the "
                                 "study runs cold oil with the least clearance, hot with the "
                                 "largest",
                                 lambda v: -20 <= v <= 200, "in [-20, 200] C", required=False),
        "oil_supply_temperature_c": Key(
            float, "the oil's supply temperature, C (with oil_iso_vg, in place of "
            "oil_temperature_c): the film's temperature at each speed then comes from its "
            "heat balance (docs/journal-bearing.md); or its range, [cold, hot] or [cold, "
            "nominal, hot], run as tolerance cases as oil_temperature_c's",
            lambda v: -20 <= v <= 150, "in [-20, 150] C", required=False),
        "pad_temperature_limit_c": Key(
            float, "the highest pad temperature allowed, C (bore = \"tilting_pad\" with "
            "oil_supply_temperature_c: the pads' heated film gives the peak; default 120, "
            "a babbitt's limit)", lambda v: 40 <= v <= 300, "in [40, 300] C", default=120.0,
            required=False),
        "oil_flow_l_min": Key(float, "the oil supplied to the bearing, l/min (with "
                              "oil_supply_temperature_c): the report gives the drain's "
                              "temperature, and warns where the film draws more",
                              lambda v: 0 < v <= 1e4, "in (0, 10^4] l/min", required=False),
        "load_n": Key(float, "the static radial load the bearing carries, N (kind = "
                      "\"journal\", \"ball\", \"roller\"; a journal's default: its reaction "
                      "to the static loads, [static] and [[force]])",
                      *upto(1e8, "up to 10^8 N"), required=False),
        "load_angle_deg": Key(float, "direction of that load on the shaft, deg from +x "
                              "towards +y (default -90: along -y, the shaft's weight with y up)",
                              lambda v: -360 <= v <= 360, "in [-360, 360]", default=-90.0,
                              required=False),
        "cavitation": Key(str, "where the oil film ruptures (kind = \"journal\"): "
                          "\"reynolds\" (default: Swift-Stieber, pressure and its gradient "
                          "vanish) or \"gumbel\" (half-Sommerfeld: negative pressures dropped)",
                          lambda v: v in CAVITATION, ", ".join(f'"{c}"' for c in CAVITATION),
                          default="reynolds", required=False),
        "bore": Key(str, "the journal's bore (kind = \"journal\"): \"plain\" (default: one "
                    "cylinder), \"two_axial_groove\" (two pads split by axial grooves across "
                    "the load), \"elliptical\" (those pads preloaded: a lemon bore) or "
                    "\"tilting_pad\" (pads that tilt on pivots); docs/journal-bearing.md",
                    lambda v: v in BORES, ", ".join(f'"{b}"' for b in BORES), default="plain",
                    required=False),
        "pads": Key(int, "the number of tilting pads (bore = \"tilting_pad\")",
                    lambda v: 3 <= v <= 12, "in [3, 12]", required=False),
        "pad_arc_deg": Key(float, "each tilting pad's arc, deg (bore = \"tilting_pad\"; the "
                           "pads' arcs together less than 360)",
                           lambda v: 10 <= v < 180, "in [10, 180)", required=False),
        "preload": Key(float, "the pads' preload m = 1 - c_b / c_p (bore = \"elliptical\", "
                       "\"tilting_pad\"; radial_clearance_um is c_b, the assembled one)",
                       lambda v: 0 <= v < 1, "in [0, 1)", required=False),
        "pivot_offset": Key(float, "each pivot's place along its pad's arc from the leading "
                            "edge (bore = \"tilting_pad\"; default 0.5: centred)",
                            lambda v: 0 < v < 1, "in (0, 1)", default=0.5, required=False),
        "load_between_pads": Key(bool, "whether the load falls between two pads (bore = "
                                 "\"tilting_pad\"; default true) or on a pad's pivot",
                                 lambda v: True, "true or false", default=True,
                                 required=False),
        "pad_inertia_kg_mm2": Key(float, "each tilting pad's moment of inertia about its "
                                  "pivot, kg mm^2 (bore = \"tilting_pad\"; default 0: "
                                  "massless pads, whose tilts are first-order in the rotor "
                                  "model)", *upto(1e9, "up to 10^9 kg mm^2", closed_low=True),
                                  required=False),
        "pivot_stiffness_n_per_mm": Key(float, "each tilting pad's pivot's radial stiffness, "
                                        "N/mm (bore = \"tilting_pad\"; default: rigid). "
                                        "The pad's radial motion on it is then a coordinate "
                                        "of the rotor model, the film and the pivot in "
                                        "series", *upto(1e12, "up to 10^12 N/mm"),
                                        required=False),
        "pad_mass_kg": Key(float, "each tilting pad's mass on its flexible pivot, kg (with "
                           "pivot_stiffness_n_per_mm; default 0)",
                           *upto(1e4, "up to 10^4 kg", closed_low=True), required=False),
        "pad_thickness_mm": Key(float, "each tilting pad's radial thickness, mm (bore = "
                                "\"tilting_pad\" with oil_supply_temperature_c: the pads "
                                "grow with their heat, closing the clearance; default "
                                "0.15 of the journal's diameter)",
                                *upto(1_000, "up to 1 m"), required=False),
        "groove_arc_deg": Key(float, "each axial groove's arc, deg (bore = "
                              "\"two_axial_groove\", \"elliptical\"; default 20)",
                              lambda v: 0 < v < 90, "in (0, 90)", default=20.0,
                              required=False),
        "min_film_um": Key(float, "the thinnest film that is fine at an operating speed, um "
                           f"(kind = \"journal\"; default {DEFAULT_MIN_FILM_UM:g})",
                           *upto(10_000, "up to 10 mm"), required=False),
        "elements": Key(int, "number of balls or rollers (kind = \"ball\", \"roller\")",
                        lambda v: 6 <= v <= 24, "in [6, 24] (where the share across the load "
                        "is known)", required=False),
        "element_diameter_mm": Key(float, "ball diameter, mm (kind = \"ball\")",
                                   *upto(500, "up to 500 mm"), required=False),
        "pitch_diameter_mm": Key(float, "the diameter of the circle through the elements' "
                                 "centres, mm (kind = \"ball\", \"roller\"; optional: checks "
                                 "that the elements fit around the shaft)",
                                 *upto(5_000, "up to 5 m"), required=False),
        "roller_length_mm": Key(float, "effective roller length, mm (kind = \"roller\")",
                                *upto(500, "up to 500 mm"), required=False),
        "contact_angle_deg": Key(float, "contact angle, deg (kind = \"ball\", \"roller\"; "
                                 "0 for a deep-groove or cylindrical roller bearing)",
                                 lambda v: 0 <= v < 60, "in [0, 60)", default=0.0,
                                 required=False),
        "preload_n": Key(float, "the axial preload of an angular-contact ball bearing, N "
                         "(kind = \"ball\", contact_angle_deg > 0): every ball loaded, their "
                         "loads shared ball by ball (Palmgren's contacts; load_n then optional)",
                         *upto(1e7, "up to 10^7 N"), required=False),
        "pressure_drop_mpa": Key(float, "the pressure drop across the seal at the machine's "
                                 "rated speed ([rotor] rated_speed_rpm), MPa (kind = "
                                 "\"seal\"; at other speeds as "
                                 "the square of the speed, as a pump's head)",
                                 *upto(1_000, "up to 1000 MPa"), required=False),
        "fluid_density_kg_m3": Key(float, "the sealed fluid's density, kg/m^3 (kind = "
                                   "\"seal\"; water: 998)", *upto(25_000, "up to 25000 kg/m^3"),
                                   required=False),
        "inlet_loss": Key(float, "the seal's inlet loss coefficient xi (kind = \"seal\"; "
                          "default 0.1)", lambda v: 0 <= v <= 2, "in [0, 2]", required=False),
        "coupling": coupling(
            "how the bearing holds its seat: \"distributing\" (default: the seat band's "
            "mean motion, the section under it free to deform, as a ball bearing on a "
            "slip fit) or \"rigid\" (the band moves as a rigid ring, a shrunk-on inner "
            "ring; the springs or holds act on the ring, and its stiff limit is clamped)",
            "distributing"),
        "slope_limit_mrad": Key(float, "the largest slope of the shaft at the seat its "
                                "bearing takes, mrad (`shaftfem strength`; default by kind: "
                                "docs/strength.md)", *upto(100, "up to 100 mrad"),
                                required=False),
    },
    "attachment": {  # an array of tables: [[attachment]], a part fixed on a seat
        "name": Key(str, "name of the part, e.g. drive gear", required=False),
        "position_mm": Key(float, "centre of the part's seat from the shaft's left end, mm",
                           *upto(20_000, "up to 20 m", closed_low=True)),
        "width_mm": Key(float, "width of the seat (hub length) along the axis, mm",
                        *upto(20_000, "up to 20 m")),
        "mass_kg": Key(float, "mass of the part, kg", *upto(1e6, "up to 1000 t", closed_low=True)),
        "polar_inertia_kg_m2": Key(
            float, "moment of inertia about the shaft axis, kg m^2",
            *upto(1e6, "up to 10^6 kg m^2", closed_low=True), default=0.0, required=False),
        "diametral_inertia_kg_m2": Key(
            float, "moment of inertia about a diameter through its centre, kg m^2",
            *upto(1e6, "up to 10^6 kg m^2", closed_low=True), default=0.0, required=False),
        "stage_power_kw": Key(float, "a compressor or turbine stage's power at the machine's "
                              "rated speed ([rotor] rated_speed_rpm), kW: its aerodynamic "
                              "cross-coupling on the part, Wachel's estimate (API 617; "
                              "docs/cross-coupling.md)",
                              *upto(1e6, "up to 1 GW"), required=False),
        "stage_diameter_mm": Key(float, "the impeller's diameter (an axial stage's pitch "
                                 "diameter), mm (with stage_power_kw)",
                                 *upto(20_000, "up to 20 m"), required=False),
        "stage_width_mm": Key(float, "the narrower of the impeller's discharge width and "
                              "the diffuser's (an axial stage's blade height), mm (with "
                              "stage_power_kw)", *upto(2_000, "up to 2 m"), required=False),
        "stage_kind": Key(str, "\"centrifugal\" (B = 3, default) or \"axial\" (B = 1.5)",
                          lambda v: v in ("centrifugal", "axial"), '"centrifugal", "axial"',
                          default="centrifugal", required=False),
        "density_ratio": Key(float, "the gas's density at discharge over suction (with "
                             "stage_power_kw; default 1)", *upto(100.0, "up to 100"),
                             default=1.0, required=False),
        "coupling_stiffness_nm_per_rad": Key(
            float, "the torsional stiffness of a flexible coupling between this part (its "
            "hub) and another machine's rotor, N m/rad (with coupled_inertia_kg_m2; "
            "docs/coupling.md): the drive train's torsion", *upto(1e12, "up to 10^12 N m/rad"),
            required=False),
        "coupled_inertia_kg_m2": Key(
            float, "the polar moment of inertia of the machine the coupling drives or is "
            "driven by (a motor's rotor with its coupling half), kg m^2", *upto(1e6, "up to "
            "10^6 kg m^2"), required=False),
        "joint": coupling(
            "how the part is joined to its seat: \"rigid\" (a shrink or press fit, the hub "
            "much stiffer than the shaft: the shaft's slice under it moves with the part as "
            "one rigid body) or \"distributing\" (a slip or keyed fit: the part's mass and "
            "inertia act on the mean motion of the shaft's cross-section at the hub's centre, "
            "as a beam model's disk, and add no stiffness). Left out: \"distributing\" where "
            "the hub sits on a keyway, else \"rigid\", and the study runs the other as a "
            "case beside", "rigid"),
        "slope_limit_mrad": Key(float, "the largest slope of the shaft at the part, mrad "
                                "(`shaftfem strength`; a gear's mesh: docs/strength.md)",
                                *upto(100, "up to 100 mrad"), required=False),
        "deflection_limit_um": Key(float, "the largest deflection of the shaft at the part, "
                                   "um (`shaftfem strength`)",
                                   *upto(100_000, "up to 100 mm"), required=False),
    },
    "rotor": {  # the shaft turning: whirl, Campbell diagram, critical speeds (fem.rotor)
        "speed_rpm": Key(("list", float), "operating speed of the shaft, r/min: one number, "
                         "or a list of them (at least 1 r/min apart); may be left out when "
                         "speed_range_rpm is given",
                         lambda v: len(v) >= 1 and all(0 < x <= 1e6 for x in v),
                         "numbers in (0, 10^6]", required=False),
        "max_speed_rpm": Key(float, "end of the Campbell diagram, r/min (default "
                             f"{DEFAULT_SPEED_HEADROOM:g} times the highest operating speed)",
                             *upto(1e6, "up to 10^6 r/min"), required=False),
        "rated_speed_rpm": Key(float, "the machine's rated speed, r/min: where its seals' "
                               "pressure drops and its stages' powers are given (a seal's "
                               "drop goes as the speed squared, a stage's cross-coupling by "
                               "the fan law); needed with a seal or a stage, so that the "
                               "operating speeds change where the machine runs, not what it "
                               "is", *upto(1e6, "up to 10^6 r/min"), required=False),
        "frame": Key(str, "the frame the shaft's motion is written in: \"stationary\" (a "
                     "shaft of revolution: gyroscopic moments; bearings may be anisotropic), "
                     "\"rotating\" (any shaft, turning with it: Coriolis and spin softening; "
                     "bearings must be isotropic), \"auto\" (stationary for a shaft of "
                     "revolution, else rotating)", lambda v: v in ROTOR_FRAMES,
                     ", ".join(f'"{f}"' for f in ROTOR_FRAMES), default="auto", required=False),
        "campbell_points": Key(int, "speeds of the Campbell diagram, from 0 to max_speed_rpm",
                               lambda v: 2 <= v <= 1001, "in [2, 1001]", default=31,
                               required=False),
        "probes_mm": Key(("list", float), "axial positions of the points whose unbalance "
                         "response is plotted, mm (besides the unbalances' planes and the "
                         "bearings)", lambda v: all(0 <= x <= 20_000 for x in v),
                         "numbers in [0, 20000]", default=[], required=False),
        "basis_modes": Key(int, "undamped standstill modes the whirl is solved on (default: "
                           "3 times [modes] count, at least 18)",
                           lambda v: 2 <= v <= MAX_MODE_COUNT, f"in [2, {MAX_MODE_COUNT}]",
                           required=False),
        "speed_range_rpm": Key(("list", float), "operating speed range of a variable-speed "
                               "drive, r/min: [lowest, highest]; a critical speed inside it "
                               "has margin 0, one outside it is measured to the nearer end",
                               lambda v: len(v) == 2 and 0 < v[0] < v[1] <= 1e6,
                               "two numbers, 0 < lowest < highest <= 10^6", required=False),
        "amplitude_limit_um": Key(float, "the largest unbalance response allowed at a probe "
                                  "(0-peak, for example a seal's radial clearance), um: drawn "
                                  "on the Bode plot; an orbit above it at any of its speeds "
                                  "fails the check",
                                  *upto(1e6, "up to 1 m"), required=False),
        "min_log_dec": Key(float, "the least log decrement a whirling mode may have where "
                           "the shaft runs: at its operating speeds and in its ranges, above "
                           "its journals' lift-off (default 0, i.e. no mode may grow; 0.1 "
                           "with [resonance] criterion = \"api684\")",
                           *upto(10.0, "up to 10", closed_low=True), required=False),
        "tolerance_cases": Key(str, "the cases the bearings' tolerance ranges run beside "
                               "the nominal one: \"extremes\" (default: minimum clearance "
                               "with cold oil, maximum clearance with hot oil) or \"corners\" "
                               "(all four corners of clearance and oil temperature)",
                               lambda v: v in ("extremes", "corners"), '"extremes", "corners"',
                               default="extremes", required=False),
        "log_dec_modes": Key(str, "the whirling modes min_log_dec is required of: "
                             "\"forward\" (default: every forward mode; API 684 judges the "
                             "forward modes an unbalance or a stage drives), \"first_forward\" "
                             "(API 684 Level I and II: the first forward mode), \"all\" "
                             "(backward modes too); the others are listed, and a mode that "
                             "grows fails whatever its whirl",
                             lambda v: v in ("forward", "first_forward", "all"),
                             '"forward", "first_forward", "all"', default="forward",
                             required=False),
        "level1": Key(bool, "screen the rotor by API 684's Level I in check and design: a "
                      "failed screening (API 617: Q_0 / Q_A below 2, or a log decrement "
                      "below 0.1 at Q_A) fails the check (docs/rotating.md)", default=False,
                      required=False),
        "level1_qa_n_per_mm": Key(float, "the anticipated cross-coupling Q_A of the Level I "
                                  "screening, N/mm (default: the stages' Wachel estimates)",
                                  *upto(1e10, "up to 10^10 N/mm"), required=False),
        "runup_rpm_per_s": Key(float, "design's report also runs the shaft up from standstill "
                               "to max_speed_rpm at this acceleration, r/min per s, with its "
                               "unbalances (shaftfem runup; docs/rotating.md)",
                               *upto(1e6, "up to 10^6 r/min per s"), required=False),
    },
    "static": {  # the shaft's static loads (shaftfem.fem.static)
        "gravity_m_s2": Key(float, "the acceleration of gravity, m/s^2 (0: no weight)",
                            *upto(1000.0, "up to 100 g", closed_low=True),
                            default=STANDARD_GRAVITY, required=False),
        "gravity_direction": Key(("list", float), "the direction gravity pulls in, [x, y, z] "
                                 "(default [0, -1, 0]: y is up)",
                                 lambda v: len(v) == 3 and any(x != 0 for x in v)
                                 and all(math.isfinite(x) for x in v),
                                 "three finite numbers, not all zero", default=[0.0, -1.0, 0.0],
                                 required=False),
    },
    "force": {  # an array of tables: [[force]], a static radial force on the shaft
        "name": Key(str, "name of the force, e.g. belt pull", required=False),
        "position_mm": Key(float, "axial position of the cross-section it acts on, from the "
                           "shaft's left end, mm (or `part`)",
                           *upto(20_000, "up to 20 m", closed_low=True), required=False),
        "part": Key(str, "the [[attachment]] it acts on, by name: at the part's centre "
                    "(instead of position_mm)", required=False),
        "fx_n": Key(float, "its component along x, N", lambda v: abs(v) <= 1e8,
                    "in [-1e8, 1e8]", default=0.0, required=False),
        "fy_n": Key(float, "its component along y, N", lambda v: abs(v) <= 1e8,
                    "in [-1e8, 1e8]", default=0.0, required=False),
        "fz_n": Key(float, "its component along the shaft axis, N (steady: a helical gear's "
                    "thrust, a follower's push); a supports' axial stiffness takes it",
                    lambda v: abs(v) <= 1e8, "in [-1e8, 1e8]", default=0.0, required=False),
        "travel_to_mm": Key(float, "where the force travels to from position_mm, mm: a "
                            "follower running along a groove; strength screens [strength] "
                            "travel_positions places on the way and bounds the worst (a bare "
                            "position, not a part)", *upto(20_000, "up to 20 m",
                                                            closed_low=True), required=False),
        "gear_pitch_diameter_mm": Key(
            float, "a gear's pitch diameter d, mm: its tooth force from the torque through "
            "the [[torque]] on the same part, F_t = 2 T / d, F_r = F_t tan(alpha_n) / "
            "cos(beta), F_a = F_t tan(beta), with the thrust's moment F_a d / 2 (instead of "
            "fx_n, fy_n, fz_n; needs `part`)", *upto(20_000, "up to 20 m"), required=False),
        "gear_pressure_angle_deg": Key(float, "its normal pressure angle alpha_n, degrees "
                                       "(default 20)", lambda v: 0 < v < 45,
                                       "in (0, 45)", default=20.0, required=False),
        "gear_helix_angle_deg": Key(
            float, "its helix angle beta, degrees (default 0: spur): positive pushes the "
            "shaft towards +z while power enters through the gear, negative towards -z",
            lambda v: abs(v) < 45, "in (-45, 45)", default=0.0, required=False),
        "gear_mesh_angle_deg": Key(
            float, "where its teeth meet the mating gear's, degrees about the axis from +x "
            "towards +y (default 90: the mating gear above)", lambda v: abs(v) <= 360,
            "in [-360, 360]", default=90.0, required=False),
    },
    "torque": {  # an array of tables: [[torque]], where power enters or leaves the shaft
        "name": Key(str, "name of the torque, e.g. coupling", required=False),
        "position_mm": Key(float, "axial position where it enters or leaves, mm from the "
                           "shaft's left end (or `part`)",
                           *upto(20_000, "up to 20 m", closed_low=True), required=False),
        "part": Key(str, "the [[attachment]] it enters or leaves through, by name: over the "
                    "part's hub (instead of position_mm)", required=False),
        "torque_nm": Key(float, "the torque about the shaft axis, N m: positive where power "
                         "enters (a coupling, a driven gear), negative where it leaves; leave "
                         "out torque_nm and power_kw on one torque and it takes the balance",
                         lambda v: abs(v) <= 1e8, "in [-1e8, 1e8]", required=False),
        "power_kw": Key(float, "the power through it instead of torque_nm, kW: positive "
                        "entering, negative leaving (T = P / omega at [strength] speed_rpm)",
                        lambda v: abs(v) <= 1e6, "in [-1e6, 1e6]", required=False),
        "travel_to_mm": Key(float, "where the torque travels to from position_mm, mm, with "
                            "the [[force]] that travels the same way (a follower)",
                            *upto(20_000, "up to 20 m", closed_low=True), required=False),
    },
    "strength": {  # will the shaft hold: workflows.strength, checks.fkm
        "speed_rpm": Key(float, "the running speed the duty is given at, r/min (turns power "
                         "into torque; default: [rotor]'s first speed_rpm, else [sizing]'s)",
                         *upto(1e6, "up to 1e6 r/min"), required=False),
        "tensile_strength_mpa": Key(float, "the material's tensile strength R_m, MPa "
                                    "(default: the [material] name's row in docs/strength.md)",
                                    *upto(5_000, "up to 5000 MPa"), required=False),
        "yield_strength_mpa": Key(float, "its yield strength R_p0.2 (R_e), MPa (default: "
                                  "the [material] name's row)", *upto(5_000, "up to 5000 MPa"),
                                  required=False),
        "strength_diameter_mm": Key(float, "the diameter R_m and R_p0.2 hold for (the test "
                                    "blank's; default: the material row's, else 16 mm)",
                                    *upto(2_000, "up to 2 m"), required=False),
        "roughness_rz_um": Key(float, "the surface's roughness R_z, um (FKM: 1 to 200; "
                               "turned 6.3 to 25, ground 1 to 6.3)",
                               *upto(200, "FKM's roughness factor holds to 200 um", 1.0, True),
                               default=6.3, required=False),
        "required_fatigue_safety": Key(float, "the fatigue safety the shaft must have "
                                       "(FKM's j_D: 1.5 for high consequences of failure, "
                                       "no regular inspection)", *upto(10, "up to 10", 1.0, True),
                                       default=1.5, required=False),
        "required_yield_safety": Key(float, "the safety against yield at the peak load "
                                     "(FKM's j_p: 1.5)", *upto(10, "up to 10", 1.0, True),
                                     default=1.5, required=False),
        "peak_factor": Key(float, "the peak (overload) load over the duty, for the yield "
                           "check (a motor's starting torque: 2 to 3)",
                           *upto(20, "up to 20", 1.0, True), default=1.0, required=False),
        "target_error_percent": Key(float, "the bound wanted on each hot spot's stress, %: "
                                    "the mesh is refined until it is met", *upto(50, "up to 50 %"),
                                    default=2.0, required=False),
        "travel_positions": Key(int, "how many places, ends included, each travelling load "
                                "([[force]] travel_to_mm) is screened at; the worst is bounded "
                                "(default 9)", lambda v: 2 <= v <= 101, "2 to 101", default=9,
                                required=False),
    },
    "unbalance": {  # an array of tables: [[unbalance]], a mass off the axis (workflows.unbalance)
        "name": Key(str, "name of the unbalance, e.g. wheel", required=False),
        "position_mm": Key(float, "axial position of its plane from the shaft's left end, mm "
                           "(or `part`)", *upto(20_000, "up to 20 m", closed_low=True),
                           required=False),
        "part": Key(str, "the [[attachment]] it sits on, by name: its plane is the part's "
                    "centre (instead of position_mm)", required=False),
        "amount_g_mm": Key(float, "the unbalance, mass times its distance from the axis, g mm",
                           *upto(1e9, "up to 10^9 g mm")),
        "phase_deg": Key(float, "its angle about the axis at t = 0, deg (0: towards +x)",
                         lambda v: -360 <= v <= 360, "in [-360, 360]", default=0.0,
                         required=False),
    },
    "response": {  # base excitation at the supports (shaftfem.fem.response)
        "damping_ratio_percent": Key(
            float, f"modal damping ratio zeta, % (default {DEFAULT_DAMPING_PERCENT:g}: "
            "a steel shaft in rolling bearings, 1-3 %)", *upto(50, "up to 50 %"),
            default=DEFAULT_DAMPING_PERCENT, required=False),
        "point_mm": Key(float, "axial position of the point whose response is plotted, mm "
                        "(default: mid-span)", *upto(20_000, "up to 20 m", closed_low=True),
                        required=False),
    },
    "sizing": {  # the paper's screw sizing, equations (1)-(9); see shaftfem.checks.sizing
        "power_kw": Key(float, "power through the shaft, kW", *upto(1e6, "up to 1 GW")),
        "speed_rpm": Key(float, "shaft speed n, r/min", *upto(1e6, "up to 10^6 r/min")),
        "friction_coefficient": Key(float, "friction coefficient f of the groove pair",
                                    lambda v: 0 < v < 1, "in (0, 1)"),
        "lead_angle_deg": Key(float, "helix lead angle lambda, deg", lambda v: 0 < v < 90,
                              "in (0, 90)"),
        "pressure_angle_deg": Key(float, "groove pressure angle alpha, deg",
                                  lambda v: 0 < v < 90, "in (0, 90)"),
        "allowable_pressure_angle_deg": Key(
            float, "largest pressure angle before self-locking, deg", lambda v: 0 < v < 90,
            "in (0, 90)", default=38.0, required=False),
        "allowable_pressure_mpa": Key(float, "allowable bearing pressure P_p, MPa",
                                      *upto(10_000, "up to 10 GPa")),
        "psi": Key(float, "nut-height factor psi", *upto(100, "the usual 1.2-3.5, at most 100")),
        "keyways": Key(int, "keyways in the section: 0, 1 or 2 (180 deg apart)",
                       lambda v: v in (0, 1, 2), "0, 1 or 2", default=0, required=False),
        "rounding_step_mm": Key(float, "the diameter is rounded up to a multiple of this, mm",
                                *upto(100, "up to 100 mm"), default=1.0, required=False),
        "crest_clearance_mm": Key(float, "crest clearance a_c, mm",
                                   *upto(100, "up to 100 mm", closed_low=True)),
        "feed_step_mm": Key(float, "box feed step b per pick, mm", *upto(10_000, "up to 10 m")),
        "picks_per_row": Key(int, "picks per row n",
                             *upto(10_000, "up to 10,000", low=2, closed_low=True)),
        "needle_width_mm": Key(float, "needle width h, mm",
                                *upto(10_000, "up to 10 m", closed_low=True)),
        "drive_teeth": Key(int, "teeth on the driving gear Z_drive",
                           *upto(10_000, "up to 10,000", low=1, closed_low=True)),
        "driven_teeth": Key(int, "teeth on the driven gear Z_driven",
                            *upto(10_000, "up to 10,000", low=1, closed_low=True)),
    },
    "resonance": {
        "required_margin_percent": Key(
            float, "least separation |f - k f_exc| / (k f_exc) between a mode and an "
            f"excitation harmonic, % (default {DEFAULT_MARGIN_PERCENT:g})",
            lambda v: 0 < v < 100, "in (0, 100)", default=DEFAULT_MARGIN_PERCENT,
            required=False),
        "criterion": Key(
            str, "\"flat\": every mode needs required_margin_percent; \"api684\": the "
            "margin follows each mode's amplification factor AF = 1 / (2 zeta) (API 684: "
            "17 (1 - 1 / (AF - 1.5)) %, none below AF = 2.5), zeta from [response]",
            lambda v: v in ("flat", "api684"), '"flat" or "api684"', default="flat",
            required=False),
        "free_free": Key(
            bool, "true: the check is meant on the free-free shaft (a hammer test, a "
            "paper's table), so its PASS exits 0; without it, a PASS of a scene with no "
            "[[support]] exits 4, since in its bearings the shaft's modes lie lower",
            default=False, required=False),
    },
    "modes": {
        "count": Key(int, f"elastic modes to compute (default {DEFAULT_MODE_COUNT})",
                     lambda v: 1 <= v <= MAX_MODE_COUNT, f"in [1, {MAX_MODE_COUNT}]",
                     default=DEFAULT_MODE_COUNT, required=False),
        "max_frequency_hz": Key(
            float, "compute every elastic mode below this frequency, Hz (instead of a count)",
            *upto(1e7, "up to 10 MHz"), required=False),
    },
    "mesh": {
        "element_size_mm": Key(float, "element size away from the grooves, mm",
                               *upto(20_000, "at most the shaft length, up to 20 m")),
        "groove_element_size_mm": Key(
            float, "element size in the grooved zone, mm (default: element_size_mm / 2)",
            *upto(20_000, "at most element_size_mm"), required=False,
        ),
        "edge_element_size_mm": Key(
            float, "element size at the groove's inner floor edges, mm "
            "(default: the root radius, or groove size / 3 for sharp corners)",
            *upto(20_000, "at most element_size_mm"), required=False,
        ),
        "order": Key(int, "element order: 1 (P1), 2 (P2), or 3 to 5 (hierarchical; free "
                     "shafts)", lambda v: v in ELEMENT_ORDERS, "1, 2, 3, 4 or 5",
                     default=2, required=False),
        "geometry_order": Key(int, "how the elements follow the CAD surfaces: 2 (curved "
                              "quadratically) or 3 (cubically: closer on coarse elements; "
                              "element orders 3 to 5; the mesh takes seconds more)",
                              lambda v: v in GEOMETRY_ORDERS, "2 or 3", default=2,
                              required=False),
        "target_error_percent": Key(
            float, "bound wanted on every frequency's discretisation error, %: the mesh is "
            "adapted until it holds (default: the fixed mesh above, with its bound)",
            *upto(50, "up to 50 %"), required=False),
        "max_dofs": Key(int, "DOF budget of an adaptive mesh",
                        lambda v: 1000 <= v <= MAX_DOFS_LIMIT,
                        f"1000 to {MAX_DOFS_LIMIT}", default=DEFAULT_MAX_DOFS, required=False),
    },
}


# What each table is for; the scene file reference (docs/scene-file.md) is generated
# from these and SCHEMA, and a test fails when the page and the schema disagree.
TABLES: dict[str, Table] = {
    "": Table("Keys at the top of the file, before any table."),
    "shaft": Table(
        "The shaft: a plain round bar (`length_mm`, `diameter_mm`), a stepped profile "
        "given by [[section]] tables (then this table may be left out), or the user's own "
        "solid (`step_file`)."),
    "section": Table(
        "One section of a stepped shaft, from the left end: a cylinder or a cone, solid or "
        "bored, with a fillet and a chamfer at the step to the next section. The sections "
        "replace `[shaft] length_mm` and `diameter_mm`.", repeated=True),
    "keyway": Table(
        "A keyway milled into one section (width and depth default to DIN 6885-1 for the "
        "section's diameter); it may run out into a shoulder's fillet, up to 0.2 mm short "
        "of the step's face.", repeated=True),
    "material": Table("An isotropic, linear elastic material.", required=True),
    "grooves": Table(
        "Helical grooves cut into the shaft, one or two hands of the same pitch, profile "
        "given in the axial section (as screw threads are). Leave the table out for a plain "
        "shaft."),
    "excitation": Table(
        "A source that shakes the shaft at its speed and harmonics (an engine, the shaft's "
        "own speed); the resonance check compares every mode with every harmonic. Without "
        "any, a design run reports \"not checked\" and `shaftfem check` refuses the scene.",
        repeated=True),
    "support": Table(
        "A bearing seat: the band of shaft surface the bearing sits on. With supports the "
        "shaft is solved as installed; without, it hangs free.", repeated=True),
    "attachment": Table(
        "A part keyed or shrunk on the shaft (gear, sprocket, pulley), modelled by its mass "
        "and inertias on a joint to the band under its hub.", repeated=True),
    "rotor": Table(
        "The shaft turning: its operating speed(s) and the speed range of the Campbell "
        "diagram. With it, `shaftfem campbell` gives the whirl frequencies against speed "
        "(forward and backward), the critical speeds and the log decrements."),
    "static": Table(
        "The shaft's static loads: its weight and its parts' (gravity), and the [[force]] "
        "tables. `shaftfem static` gives the deflection line and each bearing's reaction; a "
        "journal bearing without load_n carries its reaction."),
    "force": Table(
        "A static force on a cross-section of the shaft or a part (a belt pull, a gear's "
        "mesh force), N: its radial part stands while the shaft turns, its axial part is "
        "steady.", repeated=True),
    "torque": Table(
        "Where power enters or leaves the shaft (a coupling, a gear, a sprocket): a torque, "
        "N m, or a power, kW; the torques balance.", repeated=True),
    "strength": Table(
        "Will the shaft hold: `shaftfem strength` solves the duty ([[force]], [[torque]], "
        "gravity) on the solid, finds its hot spots and judges them for fatigue and yield by "
        "the FKM guideline's local approach, and the slopes and deflections at the seats "
        "and parts against their limits. Leave it out and strength is not checked."),
    "unbalance": Table(
        "A residual unbalance of the turning shaft (needs [rotor]): `shaftfem campbell` gives "
        "the response to it against speed (Bode plot), its peaks, their amplification "
        "factors and separation margins (API 684).", repeated=True),
    "response": Table(
        "Response to harmonic base motion through the supports (installed shafts)."),
    "sizing": Table(
        "Inputs of the paper's screw sizing, equations (1)-(9): `shaftfem size` and the "
        "design report. Leave it out if you do not size a screw shaft."),
    "resonance": Table("How far every mode must stay from every excitation harmonic."),
    "modes": Table("Which elastic modes to compute: a count, or all below a frequency."),
    "mesh": Table(
        "The finite-element mesh and elements. `--mesh-size` on the command line scales all "
        "sizes alike; `--accuracy` asks for an adapted mesh instead.", required=True),
}
