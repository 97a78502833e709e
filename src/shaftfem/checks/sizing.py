"""Screw sizing from the shaft's duty: equations (1)-(9) and Table 1 of the paper.

The paper writes these equations in mm, N, N mm, MPa, kW and r/min, and so does
this module; every quantity carries its unit in its record. No mesher is
imported here.

    (1) b  = P Z_drive / Z_driven                 feed step per pick
    (5) T  = 9 549 000 P_kW / n                   torque, N mm
    (4) f' = f / cos(alpha / 2)                   equivalent friction coefficient
    (3) rho' = arctan f'                          equivalent friction angle
    (2) F  = 2 T / (d2 tan(lambda + rho'))        axial load, N
    (6) d2 >= 0.8 sqrt(F / (psi P_p))             wear (bearing pressure) condition
    (7) (2)-(5) in (6): F ~ 1/d2, so the smallest d2 has a closed form:
        d2^3 = 0.64 * 2 T / (tan(lambda + rho') psi P_p)
    Table 1: keyway allowance on the diameter; round up; D0 = D + 2 a_c
    (8) L = b (n_picks - 1)                       box travel
    (9) B = L + h                                 box floor width
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from shaftfem.errors import SceneError
from shaftfem.scene.model import Scene

# Table 1: diameter increase (%) for keyways, by diameter band (mm).
# Bands: d < 30, 30 <= d <= 100, d > 100.
KEYWAY_TABLE = {1: (7.0, 5.0, 3.0), 2: (15.0, 10.0, 7.0)}

@dataclass
class Quantity:
    symbol: str
    name: str
    value: float
    unit: str
    equation: str


@dataclass
class SizingResult:
    quantities: list[Quantity]
    violations: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.violations

    def __getitem__(self, symbol: str) -> float:
        for q in self.quantities:
            if q.symbol == symbol:
                return q.value
        raise KeyError(symbol)

    def as_dict(self) -> dict:
        return {
            "quantities": [q.__dict__ for q in self.quantities],
            "limits_ok": self.ok,
            "violations": self.violations,
        }


def keyway_increase_percent(d_mm: float, keyways: int) -> float:
    """Table 1: the diameter increase (%) for 0, 1 or 2 keyways at diameter d (mm)."""
    if keyways == 0:
        return 0.0
    if keyways not in KEYWAY_TABLE:
        raise ValueError(f"keyways = {keyways}: must be 0, 1 or 2")
    small, mid, large = KEYWAY_TABLE[keyways]
    if d_mm < 30.0:
        return small
    if d_mm <= 100.0:
        return mid
    return large


def torque_nmm(power_kw: float, speed_rpm: float) -> float:
    """Equation (5): shaft torque T in N mm from power (kW) and speed (r/min)."""
    return 9_549_000.0 * power_kw / speed_rpm


def axial_load_n(torque: float, d2_mm: float, lead_deg: float, rho_deg: float) -> float:
    """Equation (2): axial load F (N) on the screw at mean diameter d2 (mm)."""
    return 2.0 * torque / (d2_mm * math.tan(math.radians(lead_deg + rho_deg)))


def min_mean_diameter_mm(torque: float, lead_deg: float, rho_deg: float, psi: float,
                         p_allow_mpa: float) -> float:
    """Equation (7): the smallest d2 (mm) with d2 >= 0.8 sqrt(F(d2) / (psi P_p)).

    F = 2T / (d2 tan(lambda + rho')) falls as 1/d2, so squaring (6) at equality
    gives d2^3 = 0.64 * 2T / (tan(lambda + rho') psi P_p): a closed form.
    """
    return (0.64 * 2.0 * torque / (math.tan(math.radians(lead_deg + rho_deg)) * psi
                                   * p_allow_mpa)) ** (1.0 / 3.0)


def size_screw(s: dict) -> SizingResult:
    """All quantities of equations (1)-(9) from checked [sizing] inputs (file units)."""
    q: list[Quantity] = []
    bad: list[str] = []
    add = lambda *a, **k: q.append(Quantity(*a, **k))  # noqa: E731

    ratio = s["drive_teeth"] / s["driven_teeth"]
    pitch = s["feed_step_mm"] / ratio
    add("P", "groove pitch from feed step and gears, P = b Z_driven / Z_drive", pitch, "mm", "(1)")
    T = torque_nmm(s["power_kw"], s["speed_rpm"])
    add("T", "shaft torque", T, "N mm", "(5)")
    alpha = s["pressure_angle_deg"]
    f_eq = s["friction_coefficient"] / math.cos(math.radians(alpha / 2))
    add("f'", "equivalent friction coefficient", f_eq, "-", "(4)")
    if f_eq >= 1.0:
        bad.append(f"equivalent friction coefficient f' = {f_eq:.3f} >= 1: no screw drive")
    rho = math.degrees(math.atan(f_eq))
    add("rho'", "equivalent friction angle", rho, "deg", "(3)")
    lead = s["lead_angle_deg"]
    if lead + rho >= 90.0:
        raise SceneError(
            f"sizing.lead_angle_deg = {lead:g}: lead angle + friction angle = {lead + rho:.2f} "
            "deg must be below 90 deg for equation (2)"
        )
    d2 = min_mean_diameter_mm(T, lead, rho, s["psi"], s["allowable_pressure_mpa"])
    F = axial_load_n(T, d2, lead, rho)
    add("F", "axial load at the smallest d2", F, "N", "(2)")
    add("d2", "smallest mean diameter meeting the wear condition", d2, "mm", "(6)-(7)")
    pct = keyway_increase_percent(d2, s["keyways"])
    d_key = d2 * (1 + pct / 100)
    add("k", f"keyway allowance for {s['keyways']} keyway(s) (Table 1)", pct, "%", "Table 1")
    add("d_k", "diameter with the keyway allowance", d_key, "mm", "Table 1")
    step = s["rounding_step_mm"]
    D = math.ceil(d_key / step - 1e-9) * step
    add("D", f"shaft diameter, rounded up to {step:g} mm", D, "mm", "Table 1")
    D0 = D + 2 * s["crest_clearance_mm"]
    add("D0", "thread major diameter, D + 2 a_c", D0, "mm", "-")
    L = s["feed_step_mm"] * (s["picks_per_row"] - 1)
    add("L", "box travel", L, "mm", "(8)")
    B = L + s["needle_width_mm"]
    add("B", "box floor width", B, "mm", "(9)")

    if alpha > s["allowable_pressure_angle_deg"]:
        bad.append(f"pressure angle {alpha:g} deg exceeds the allowable "
                   f"{s['allowable_pressure_angle_deg']:g} deg: the follower may self-lock")
    return SizingResult(quantities=q, violations=bad)


def keyways_in_one_section(shaft) -> int:
    """The most keyways that share an axial position (Table 1 counts the keyways of one
    cross-section), at most 2."""
    cuts = shaft.keyways
    most = max((sum(1 for b in cuts if b.start < a.end and a.start < b.end) for a in cuts),
               default=0)
    return min(most, 2)


def sized_diameter(scene: Scene) -> float:
    """The diameter the sizing applies to, m: the grooved section's, else the smallest
    outer diameter of the profile."""
    shaft = scene.shaft
    if scene.grooves is not None and shaft.profile:
        k = shaft.section_at(scene.grooves.start + scene.grooves.length / 2) or 0
        return shaft.profile[k].diameter_start
    if shaft.profile:
        return min(min(s.diameter_start, s.diameter_end) for s in shaft.profile)
    return shaft.diameter


def size_from_scene(scene: Scene) -> SizingResult:
    """The sizing, and whether the scene's shaft and grooves agree with it."""
    if scene.sizing is None:
        raise SceneError(f"{scene.source}: no [sizing] table: `shaftfem size` needs one")
    sizing, drawn = dict(scene.sizing), keyways_in_one_section(scene.shaft)
    if scene.shaft.keyways:   # the geometry's keyways, not the table's count, size the shaft
        sizing["keyways"] = drawn
    r = size_screw(sizing)
    if scene.shaft.keyways and scene.sizing["keyways"] not in (0, drawn):
        r.violations.append(f"[sizing] keyways = {scene.sizing['keyways']} but the shaft has "
                            f"{drawn} in one section ([[keyway]]): sized with {drawn}")
    diameter, need = sized_diameter(scene) * 1e3, r["D"]
    if diameter < need - 1e-9:
        r.violations.append(f"the shaft's diameter {diameter:g} mm (the grooved or smallest "
                            f"section's) is below the D = {need:g} mm the duty needs "
                            "(equations 1-9)")
    if scene.grooves is not None:
        pitch, gears = scene.grooves.pitch * 1e3, r["P"]
        if abs(pitch / gears - 1) > 1e-6:
            r.violations.append(f"[grooves] pitch_mm = {pitch:g} differs from P = b Z_driven / "
                                f"Z_drive = {gears:g} mm of the feed step and gears (eq. 1)")
    return r
