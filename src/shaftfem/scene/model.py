"""The scene as the solver sees it: frozen dataclasses in SI units (m, Pa, kg/m^3, W,
rad/s, Hz), made from a scene file by shaftfem.scene.load."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

from shaftfem.scene.schema import (
    DEFAULT_DAMPING_PERCENT,
    DEFAULT_MARGIN_PERCENT,
    DEFAULT_MAX_DOFS,
    DEFAULT_MODE_COUNT,
    STANDARD_GRAVITY,
)

MM = 1e-3  # m per mm: scene files are in mm

# --------------------------------------------------------------------------
# The SI dataclasses the rest of the pipeline takes.


@dataclass(frozen=True)
class Section:
    """One stretch of a stepped shaft's profile, all in m: its length, its outer
    diameter at its start and at its end (a cone where they differ), its bore (0:
    solid), and at the step to the next section the fillet radius in the concave corner
    and the chamfer (45 degrees, its leg) on the convex one."""

    length: float
    diameter_start: float
    diameter_end: float
    bore: float = 0.0
    fillet: float = 0.0
    chamfer: float = 0.0

    @property
    def conical(self) -> bool:
        return self.diameter_start != self.diameter_end


@dataclass(frozen=True)
class Keyway:
    """A keyway milled into the shaft, all in m and rad: from z = `start` over `length`
    along the axis, `width` across, its flat floor `depth` below the surface at its
    centre line, centred at `angle` about the axis (0: towards +x). `form` "rounded":
    end-milled, round ends (DIN 6885 form A); "sled": disc-cut, the ends running out
    along the cutter's radius `cutter_radius`. `corner_radius`: the floor's corners."""

    start: float
    length: float
    width: float
    depth: float
    angle: float = 0.0
    form: str = "rounded"
    corner_radius: float = 0.0
    cutter_radius: float = 0.0

    @property
    def end(self) -> float:
        return self.start + self.length


@dataclass(frozen=True)
class StepSolid:
    """The user's own solid from a STEP file, in the unit the file states: its path, the
    checksum of its content (the cache key), and the shaft axis as two points in the
    file's coordinates, m (None: the z direction through the middle of the solid's
    bounding box)."""

    path: str
    sha256: str
    axis: tuple[tuple[float, float, float], tuple[float, float, float]] | None = None
    summary: str = ""   # what its import found (cad.step.StepImport.summary)


@dataclass(frozen=True)
class Shaft:
    """The shaft, in m: its overall length and largest outer diameter, and its form.

    With no `sections`, keyways or chamfer it is a solid round bar of that diameter (the
    shorthand `[shaft] length_mm, diameter_mm`); else its profile is `sections` from the
    left end, with `keyways` cut into it and `end_chamfer` at both ends. A `step` shaft
    is the user's own solid, its axis along z from z = 0 once imported."""

    length: float
    diameter: float
    sections: tuple[Section, ...] = ()
    keyways: tuple[Keyway, ...] = ()
    end_chamfer: float = 0.0
    step: StepSolid | None = None

    @property
    def radius(self) -> float:
        """The largest outer radius, m."""
        return 0.5 * self.diameter

    def unplaced(self) -> Shaft:
        """A STEP shaft as its scene gives it, before its import measured it (length and
        diameter 0, no summary); any other shaft as it is."""
        if self.step is None:
            return self
        return replace(self, length=0.0, diameter=0.0, step=replace(self.step, summary=""))

    @property
    def plain(self) -> bool:
        """A solid round bar (grooved or not): no steps, bore, keyway, chamfer or STEP."""
        return not (self.sections or self.keyways or self.end_chamfer or self.step)

    @property
    def profile(self) -> tuple[Section, ...]:
        """The sections from the left end (a plain bar is one; a STEP shaft has none)."""
        if self.step is not None:
            return ()
        return self.sections or (Section(self.length, self.diameter, self.diameter),)

    def section_bounds(self) -> list[tuple[float, float]]:
        """(z0, z1) of each section, m."""
        out, z = [], 0.0
        for s in self.profile:
            out.append((z, z + s.length))
            z += s.length
        return out

    def step_positions(self) -> tuple[float, ...]:
        """z (m) of each change of section: the shoulders and the ends of cones."""
        return tuple(z1 for _, z1 in self.section_bounds()[:-1])

    def plain_span(self, i: int) -> tuple[float, float]:
        """(z0, z1) of section i less what the fillets and chamfers at its ends take, m:
        at a step the fillet lies on the smaller section, the chamfer on the larger."""
        prof, (z0, z1) = self.profile, self.section_bounds()[i]
        left = right = self.end_chamfer
        if i > 0:
            step = prof[i - 1]
            left = step.chamfer if step.diameter_end < prof[i].diameter_start else step.fillet
        if i < len(prof) - 1:
            step = prof[i]
            right = step.fillet if step.diameter_end < prof[i + 1].diameter_start else step.chamfer
        return z0 + left, z1 - right

    def section_at(self, z: float) -> int | None:
        """The index of the section holding z (the left one at a step; None for STEP)."""
        for i, (z0, z1) in enumerate(self.section_bounds()):
            if z <= z1 + 1e-12:
                return i if z >= z0 - 1e-12 else None
        return None

    def radius_at(self, z: float) -> float | None:
        """The outer radius at z, m (None where the profile is not known: a STEP shaft)."""
        i = self.section_at(z)
        if i is None:
            return None
        s, (z0, z1) = self.profile[i], self.section_bounds()[i]
        t = 0.0 if z1 == z0 else min(max((z - z0) / (z1 - z0), 0.0), 1.0)
        return 0.5 * (s.diameter_start + t * (s.diameter_end - s.diameter_start))


@dataclass(frozen=True)
class Material:
    """Isotropic linear elastic material: E in Pa, density in kg/m^3."""

    name: str
    youngs_modulus: float
    poisson_ratio: float
    density: float

    @property
    def shear_modulus(self) -> float:
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def lame(self) -> tuple[float, float]:
        """Lame parameters (lambda, mu) in Pa."""
        E, nu = self.youngs_modulus, self.poisson_ratio
        return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


@dataclass(frozen=True)
class Grooves:
    """Helical grooves of one pitch, all in m.

    The profile is given in the axial section (as screw-thread profiles are):
    `width` along the shaft axis, `depth` radially, `root_radius` the fillet at
    the two floor corners. Each hand (+1 right, -1 left) is one groove.
    The grooves run at full depth from z = `start` to z = `start + length`; beyond
    each end each floor rises out to the surface over `runout` along the axis (as the
    cutter lifts out), or, with `runout` 0, each groove ends in a flat wall.
    """

    hands: tuple[int, ...]
    pitch: float
    width: float
    depth: float
    root_radius: float
    length: float
    start: float
    runout: float = 0.0

    @property
    def cut(self) -> tuple[float, float]:
        """Where the grooves cut the shaft (m): the grooved zone and its runouts."""
        return self.start - self.runout, self.start + self.length + self.runout

    @property
    def runouts(self) -> tuple[tuple[float, float], ...]:
        """The runouts' spans (z0, z1), m: none where the grooves end flat."""
        if not self.runout:
            return ()
        lo, hi = self.cut
        return (lo, self.start), (self.start + self.length, hi)


def cell_type(order: int) -> str:
    """meshio's name of the mesh's cells for an element order: 10-node tetrahedra (curved,
    for P2 and P3) or 4-node ones (P1)."""
    return "tetra10" if order >= 2 else "tetra"


@dataclass(frozen=True)
class MeshSettings:
    """Element sizes in m; `order` 1 (P1, linear), 2 (P2, quadratic), or 3 to 5
    (hierarchical); `geometry_order` 2 (elements curved quadratically onto the CAD
    surfaces, as P2's) or 3 (cubically, for orders 3 to 5)."""

    size: float
    groove_size: float
    edge_size: float
    order: int
    geometry_order: int = 2


@dataclass(frozen=True)
class Excitation:
    """A source of periodic forcing: its base frequency (Hz) and the harmonic orders that count."""

    name: str
    frequency: float
    orders: tuple[int, ...]


@dataclass(frozen=True)
class ModeRequest:
    """Which elastic modes to compute: the lowest `count`, or every one below
    `max_frequency` (Hz) when that is set."""

    count: int = DEFAULT_MODE_COUNT
    max_frequency: float | None = None


# a pad whose film's row is below this share of the bearing's largest entry floats (read
# between a table's rows, a pad that lifts off leaves a film of round-off: kept, its
# tilt would be a root of that film's own tiny damping, far off the rotor's)
FLOATING = 1e-8


def coupled(Z) -> list[int]:
    """The coordinates past the seat's two that a film matrix couples to the others
    beyond FLOATING of its largest entry: a floating pad's tilt and radial motion (its
    pivot's spring alone on its diagonal) are not."""
    import numpy as np

    off = np.abs(Z - np.diag(np.diag(Z)))
    scale = FLOATING * max(float(np.abs(Z).max()), 1e-300)
    return [i for i in range(2, Z.shape[0]) if off[i].max() > scale]


def condensed(Z):
    """The journal's 2x2 block of a film matrix on (x, y, tilts...) (stiffness, or a
    dynamic stiffness K + i w C - w^2 M at a whirl) with the tilts condensed out: Z_jj -
    Z_jp Z_pp^-1 Z_pj."""
    import numpy as np

    # a pad whose film carries nothing (the journal pulled away from it: its film
    # diverges all over, whatever its tilt) floats: it adds nothing, and is left out
    loaded = coupled(Z)
    if not loaded:
        return Z[:2, :2]
    p = np.array(loaded)
    return Z[:2, :2] - Z[:2, p] @ np.linalg.solve(Z[np.ix_(p, p)], Z[p, :2])


@dataclass(frozen=True)
class TiltingFilm:
    """A tilting-pad bearing's film on the seat's (q_x, q_y) and its pads' tilts, per
    speed of its BearingCoefficients: K (N/m) and C (N s/m), (speeds, size, size)
    flattened, and the mass on each coordinate past the seat's two (kg; empty: none): a
    pad's inertia about its pivot over R^2 on its tilt, its mass on its pivot's radial
    motion."""

    size: int
    stiffness: tuple[float, ...]
    damping: tuple[float, ...]
    masses: tuple[float, ...] = ()

    @property
    def mass(self):
        """The film's coordinates' mass matrix (size, size): the pads' inertias on their
        tilts, kg (zero on the seat's motion: the shaft's own mass is the rotor's)."""
        import numpy as np

        return np.diag([0.0, 0.0, *(self.masses or (0.0,) * (self.size - 2))])


@dataclass(frozen=True)
class BearingCoefficients:
    """A rotor bearing's or seal's stiffness (N/m), damping (N s/m) and added mass (kg)
    coefficients on the seat's mean radial motion (q_x, q_y), as rotor engineers give
    them: the force on the shaft is -[[kxx, kxy], [kyx, kyy]] q - [[cxx, cxy], [cyx,
    cyy]] dq/dt - diag(mxx, myy) d^2q/dt^2 (no mass: empty mxx, myy). Each coefficient
    holds one value per speed of `speeds` (rad/s, ascending), or one value when
    `speeds` is empty; between speeds interpolated linearly, outside them the nearest
    end's value."""

    speeds: tuple[float, ...]
    kxx: tuple[float, ...]
    kxy: tuple[float, ...]
    kyx: tuple[float, ...]
    kyy: tuple[float, ...]
    cxx: tuple[float, ...]
    cxy: tuple[float, ...]
    cyx: tuple[float, ...]
    cyy: tuple[float, ...]
    reference: float = 0.0   # rad/s: the speed whose kxx, kyy the standstill modes hold
    mxx: tuple[float, ...] = ()
    myy: tuple[float, ...] = ()
    # a bearing of tilting pads: its film on the seat and on each pad's tilt, per speed
    # (None: the 2x2 coefficients are the whole bearing)
    pads: TiltingFilm | None = None

    @functools.cached_property
    def _table(self):
        """The speeds and the ten coefficients as arrays, (n,) and (10, n): read at every
        speed of a run, thousands of times."""
        import numpy as np

        n = max(len(self.speeds), 1)
        rows = [self.kxx, self.kxy, self.kyx, self.kyy, self.cxx, self.cxy, self.cyx, self.cyy,
                self.mxx or (0.0,), self.myy or (0.0,)]
        return (np.asarray(self.speeds, dtype=float),
                np.array([v * n if len(v) == 1 else v for v in rows], dtype=float))

    def _values(self, omega: float) -> list[float]:
        speeds, table = self._table
        if speeds.size <= 1:
            return [float(v) for v in table[:, 0]]
        i = int(min(max(speeds.searchsorted(omega), 1), speeds.size - 1))
        t = min(max((omega - speeds[i - 1]) / (speeds[i] - speeds[i - 1]), 0.0), 1.0)
        return [float(v) for v in (1 - t) * table[:, i - 1] + t * table[:, i]]

    def stiffness(self, omega: float) -> tuple[tuple[float, float], tuple[float, float]]:
        """[[kxx, kxy], [kyx, kyy]] at the speed omega (rad/s), N/m."""
        if self.pads is not None:
            return self._synchronous(omega)[0]
        kxx, kxy, kyx, kyy = self._values(omega)[:4]
        return ((kxx, kxy), (kyx, kyy))

    def damping(self, omega: float) -> tuple[tuple[float, float], tuple[float, float]]:
        """[[cxx, cxy], [cyx, cyy]] at the speed omega (rad/s), N s/m."""
        if self.pads is not None:
            return self._synchronous(omega)[1]
        cxx, cxy, cyx, cyy = self._values(omega)[4:8]
        return ((cxx, cxy), (cyx, cyy))

    def at_whirl(self, omega: float, whirl: float):
        """A tilting pads' bearing's 2x2 (K, C) (N/m, N s/m) at the spin omega for a whirl
        at `whirl` (rad/s): its tilts condensed out there (the synchronous ones at whirl =
        omega); None without pads."""
        if self.pads is None:
            return None
        K, C = self.pad_film(omega)
        Z = condensed(K + 1j * whirl * C - whirl**2 * self.pads.mass)
        return Z.real, Z.imag / whirl

    @functools.cached_property
    def _reduced(self) -> dict:
        return {}

    def _synchronous(self, omega: float):
        """A tilting pads' bearing's 2x2 (K, C) at the speed omega: its film on the seat
        and the tilts (pad_film) with the tilts condensed out at a whirl at omega (its
        table's kxx... are these at its speeds)."""
        if omega not in self._reduced:
            K, C = self.at_whirl(omega, max(omega, 1e-12))
            self._reduced[omega] = (tuple(map(tuple, K.tolist())), tuple(map(tuple, C.tolist())))
        return self._reduced[omega]

    def mass(self, omega: float) -> tuple[tuple[float, float], tuple[float, float]]:
        """[[mxx, 0], [0, myy]] at the speed omega (rad/s), kg."""
        mxx, myy = self._values(omega)[8:]
        return ((mxx, 0.0), (0.0, myy))

    @functools.cached_property
    def _pad_arrays(self):
        """The speeds and the pads' film (n, size, size) as arrays: read at every speed."""
        import numpy as np

        assert self.pads is not None
        n = self.pads.size
        return (np.asarray(self.speeds, dtype=float),
                np.asarray(self.pads.stiffness).reshape(-1, n, n),
                np.asarray(self.pads.damping).reshape(-1, n, n))

    def pad_film(self, omega: float):
        """The bearing's (K, C) on (q_x, q_y, R phi_1, ..., R phi_P) at the speed omega
        (rad/s): N/m and N s/m, each tilt phi (rad) as the motion R phi it gives the pad's
        surface; linear between speeds as the 2x2 ones. None without pads."""
        if self.pads is None:
            return None
        speeds, K, C = self._pad_arrays
        if speeds.size <= 1:
            return K[0], C[0]
        i = min(max(int(speeds.searchsorted(omega)), 1), speeds.size - 1)
        t = min(max((omega - speeds[i - 1]) / (speeds[i] - speeds[i - 1]), 0.0), 1.0)
        return (1 - t) * K[i - 1] + t * K[i], (1 - t) * C[i - 1] + t * C[i]

    @property
    def has_mass(self) -> bool:
        return any(self.mxx) or any(self.myy)

    @property
    def isotropic(self) -> bool:
        """Whether the bearing looks the same from every angle about the axis (kxx = kyy,
        kxy = -kyx, and so for damping) at every speed: what a rotating frame needs."""
        return (self.kxx == self.kyy and self.cxx == self.cyy and self.mxx == self.myy
                and all(a == -b for a, b in zip(self.kxy, self.kyx))
                and all(a == -b for a, b in zip(self.cxy, self.cyx)))


@dataclass(frozen=True)
class Rotor:
    """The shaft turning about its axis: its operating speeds and the end of the
    Campbell diagram (rad/s), the frame its motion is written in ("auto",
    "stationary", "rotating"), the Campbell diagram's number of speeds, and how many
    standstill modes the whirl is solved on (0: the default)."""

    speeds: tuple[float, ...]
    max_speed: float
    frame: str = "auto"
    points: int = 31
    basis_modes: int = 0
    probes: tuple[float, ...] = ()   # z (m) of points whose unbalance response is shown
    ranges: tuple[tuple[float, float], ...] = ()   # operating speed ranges (rad/s)
    min_log_dec: float | None = None   # None: 0, or API 684's 0.1 with criterion "api684"
    tolerance_cases: str = "extremes"   # or "corners": all four of clearance and oil
    log_dec_modes: str = "forward"   # the modes min_log_dec holds for: "forward",
                                     # "first_forward" or "all" (a growing mode always fails)
    amplitude_limit: float | None = None   # m, 0-peak, at any probe
    level1: bool = False   # check and design screen it by API 684's Level I
    level1_qa: float | None = None   # its Q_A, N/m (None: the stages' Wachel estimates)
    runup: float | None = None   # design runs it up at this acceleration, rad/s^2
    rated: float = 0.0   # rad/s: where seals' pressure drops and stages' powers are given

    @property
    def spans(self) -> tuple[tuple[float, float], ...]:
        """Where the shaft runs (rad/s): each range, and each operating speed outside
        them as a range of one speed."""
        alone = [(w, w) for w in self.speeds
                 if not any(lo <= w <= hi for lo, hi in self.ranges)]
        return tuple(sorted([*self.ranges, *alone]))

    @property
    def top_speed(self) -> float:
        """The highest operating speed (rad/s)."""
        return max(hi for _, hi in self.spans)


@dataclass(frozen=True)
class Unbalance:
    """A residual unbalance: its plane z = position (m), its amount (kg m: mass times
    radius) and its angle about the axis at t = 0 (rad, 0 towards +x)."""

    name: str
    position: float
    amount: float
    phase: float = 0.0


@dataclass(frozen=True)
class PointForce:
    """A static force (fx, fy, fz; N) on the shaft's cross-section at z = position (m),
    through a part's hub of `width` (m; 0: no part), and a bending moment there (mx, my;
    N m, standing: a helical gear's thrust at its pitch radius)."""

    name: str
    position: float
    fx: float
    fy: float
    fz: float = 0.0
    width: float = 0.0
    mx: float = 0.0
    my: float = 0.0
    travel: float | None = None   # where it travels to from `position` (m): a follower


@dataclass(frozen=True)
class Torque:
    """A torque about the shaft axis (N m; positive where power enters) at z = position
    (m), through a part's hub of `width` (m; 0: no part)."""

    name: str
    position: float
    torque: float
    width: float = 0.0
    travel: float | None = None   # where it travels to from `position` (m)


@dataclass(frozen=True)
class Strength:
    """[strength] in SI: the duty's speed (rad/s), the material's R_m and R_p0.2 (Pa) at
    the diameter they hold for (m), the surface's R_z (m), the required safeties, the
    peak factor and the bound wanted on the hot spots' stresses (fraction)."""

    speed: float
    tensile_strength: float
    yield_strength: float
    strength_diameter: float
    roughness: float
    fatigue_safety: float
    yield_safety: float
    peak_factor: float
    target_error: float
    # where R_m and R_p0.2 come from (the material table's source, or "given"), the FKM
    # material group and the size exponents a_d,m and a_d,p (scene.materials)
    source: str = "given"
    fkm_group: str = "Steel"
    size_exponents: tuple[float, float] = (0.3, 0.4)
    travel_positions: int = 9   # the places each travelling load is screened at


# --------------------------------------------------------------------------
# The parts as the scene declares them. Their coefficients come from their physics
# (shaftfem.parts), which the rotor model asks once the static loads are known.

# the journals' length / diameter ratios the film is solved for
JOURNAL_RATIOS = (0.1, 2.0)
# a seal's inlet loss coefficient where the scene gives none
INLET_LOSS = 0.1


@dataclass(frozen=True)
class JournalBore:
    """A journal's bore when it is not one plain circle, set about its load's line:
    "two_axial_groove" (two pads split by axial grooves across the load, the load
    through a pad's middle), "elliptical" (those pads preloaded: a lemon bore) or
    "tilting_pad" (`pads` pads of `arc` each, rad, pivoted `offset` of the arc from
    their leading edges, the load on a pad or `between` two). `preload` m = 1 - c_b /
    c_p; `groove` the axial grooves' arc (rad)."""

    kind: str
    pads: int = 2
    arc: float = math.radians(160.0)
    preload: float = 0.0
    offset: float = 0.5
    between: bool = True
    groove: float = math.radians(20.0)


@dataclass(frozen=True)
class JournalBearing:
    """An oil-film journal bearing (a plain cylindrical bore, or `bore`): its journal
    diameter, length and radial
    clearance (m), the oil's dynamic viscosity (Pa s; None while the scene gives the oil
    as its ISO VG grade `oil_iso_vg` at the film's mean temperature `oil_temperature`, C,
    which shaftfem.parts.oil turns into one), the static load on the journal (N; 0
    until the static solution gives it) and its direction (a unit vector in the xy
    plane, the load on the journal), the cavitation condition, and the least minimum
    film that is fine (m)."""

    diameter: float
    length: float
    clearance: float
    viscosity: float | None
    load: float
    direction: tuple[float, float] = (0.0, -1.0)
    cavitation: str = "reynolds"
    min_film: float = 10e-6
    oil_iso_vg: int | None = None
    oil_temperature: float | None = None
    bore: JournalBore | None = None     # None: a plain cylindrical bore
    # the oil's supply temperature (C; None: the film at oil_temperature) and flow
    # (m^3/s; None: not given): the film's temperature at each speed from its heat
    # balance (shaftfem.parts.heat)
    oil_supply_temperature: float | None = None
    oil_flow: float | None = None
    pad_limit: float = 120.0   # C: the highest pad temperature allowed (tilting pads)
    pad_inertia: float = 0.0   # kg m^2: each tilting pad's about its pivot (0: massless)
    # N/m: each tilting pad's pivot's radial stiffness (None: rigid), and the pad's mass
    # on it (kg)
    pivot_stiffness: float | None = None
    pad_mass: float = 0.0
    # m: each tilting pad's radial thickness, for its growth with its heat (None: 0.15 of
    # the diameter, parts.pad_heat.THICKNESS)
    pad_thickness: float | None = None

    @property
    def ratio(self) -> float:
        return self.length / self.diameter

    def sommerfeld(self, omega: float) -> float:
        """S = mu N L D / W (R / c)^2, N in rev/s."""
        assert self.viscosity is not None, "the oil's viscosity comes from shaftfem.parts.oil"
        R = self.diameter / 2
        return (self.viscosity * omega / (2 * math.pi) * self.length * self.diameter
                / self.load * (R / self.clearance) ** 2)


@dataclass(frozen=True)
class AnnularSeal:
    """A plain seal, SI: its length, diameter and radial clearance (m), the pressure
    drop across it at the speed `rated` (Pa, rad/s), the fluid's density (kg/m^3) and
    viscosity (Pa s), and the inlet loss coefficient xi."""

    length: float
    diameter: float
    clearance: float
    pressure_drop: float
    rated: float
    density: float
    viscosity: float
    inlet_loss: float = INLET_LOSS


@dataclass(frozen=True)
class RollingBearing:
    """A ball or roller bearing (`kind` "ball" or "roller"): its number of elements, their
    diameter (balls) or length (rollers), m, the contact angle (rad), an angular-contact
    bearing's axial preload (N, or None), and the radial load on it (N) at the angle
    `load_angle` (rad from x towards y)."""

    kind: str
    elements: int
    size: float
    contact_angle: float = 0.0
    preload: float | None = None
    load: float = 0.0
    load_angle: float = 0.0


@dataclass(frozen=True)
class Stage:
    """An impeller or compressor stage on a part: its power (W) at the highest operating
    speed, its diameter and flow width (m), its kind ("centrifugal" or "axial") and the
    ratio of the gas densities across it (Wachel's estimate, API 617)."""

    power: float
    diameter: float
    width: float
    kind: str = "centrifugal"
    density_ratio: float = 1.0


@dataclass(frozen=True)
class Tolerance:
    """A journal's or a seal's tolerance ranges, each (min, nominal, max), None where the
    scene gives one value: its radial clearance (m), its oil's viscosity (Pa s) and the
    oil temperatures (C) the viscosities come from (cold oil is the most viscous). The
    study's tolerance cases (workflows.cases) take their ends."""

    clearance: tuple[float, float, float] | None = None
    viscosity: tuple[float, float, float] | None = None
    temperature: tuple[float, float, float] | None = None


@dataclass(frozen=True)
class Support:
    """A bearing seat: the band of shaft surface from z = position -+ width / 2 (m).

    `kind` "rigid" holds the band's mean radial and axial displacement, "rigid-radial"
    its mean radial displacement, "clamped" every point of it; "springs" resists them
    with `radial`, `axial` (N/m) and `tilting` (N m/rad) (shaftfem.fem.supports)."""

    name: str
    position: float
    width: float
    kind: str
    radial: float = 0.0
    axial: float = 0.0
    tilting: float = 0.0
    coupling: str = "distributing"   # or "rigid": the band moves as a rigid ring
    # its coefficients: kind "bearing" as given; a journal, ball, roller or seal as its
    # physics gives them (None until the parts are asked: workflows.equip)
    bearing: BearingCoefficients | None = None
    journal: JournalBearing | None = None   # kind "journal": the film's bearing
    seal: AnnularSeal | None = None   # kind "seal": the seal its coefficients come from
    rolling: RollingBearing | None = None   # kind "ball", "roller": the bearing's elements
    tolerance: Tolerance | None = None   # a journal's or seal's tolerance ranges
    # the standstill modes hold the bearing's mean of kxx and kyy on both axes: the
    # basis of a rotor solved in the frame turning with it, which every angle sees alike
    mean_seat: bool = False
    # the largest slope the bearing takes, rad (None: its kind's default, workflows.strength)
    slope_limit: float | None = None

    @property
    def awaits_part(self) -> bool:
        """A part declared (journal, ball or roller bearing, seal) whose coefficients are
        not in yet."""
        return self.bearing is None and any(
            p is not None for p in (self.journal, self.seal, self.rolling))

    @property
    def radial_xy(self) -> tuple[float, float]:
        """The radial stiffness along x and y at standstill, N/m (a bearing's kxx and kyy
        at its reference speed, 0 but for a journal, or with `mean_seat` their mean on
        both; the springs' radial stiffness on both)."""
        if self.bearing is not None:
            (kxx, _), (_, kyy) = self.bearing.stiffness(self.bearing.reference)
            if self.mean_seat:
                return 0.5 * (kxx + kyy), 0.5 * (kxx + kyy)
            return kxx, kyy
        return self.radial, self.radial

    @property
    def seat(self) -> tuple[float, float]:
        return self.position - self.width / 2, self.position + self.width / 2


@dataclass(frozen=True)
class Attachment:
    """A rigid part (gear, pulley, coupling hub) fixed on the band z = position -+
    width / 2 (m): its mass (kg) and its moments of inertia about the axis and a
    diameter (kg m^2), with its centre of mass on the axis at `position`."""

    name: str
    position: float
    width: float
    mass: float
    polar_inertia: float
    diametral_inertia: float
    joint: str = "rigid"   # or "distributing": on the mean motion of the section at its
                           # centre, no stiffness
    joint_given: bool = True   # False: the scene left it to the default (the study
                               # brackets it, workflows.cases)
    # a stage on the part, and its aerodynamic cross-coupling on the part's motion
    # (Wachel: shaftfem.parts.wachel), N/m against speed
    stage: Stage | None = None
    cross_coupling: BearingCoefficients | None = None
    # a flexible coupling from the part's turn to another machine's rotor: its torsional
    # stiffness (N m/rad) and that rotor's polar inertia (kg m^2); 0: none
    coupling_stiffness: float = 0.0
    coupled_inertia: float = 0.0
    # the largest slope (rad) and deflection (m) the part takes (None: not judged)
    slope_limit: float | None = None
    deflection_limit: float | None = None

    @property
    def seat(self) -> tuple[float, float]:
        return self.position - self.width / 2, self.position + self.width / 2

    @property
    def carried(self) -> bool:
        """On a distributing joint: carried by its section's mean motion (its own
        coordinates kept); any other joint ties it to its slice's rigid motion."""
        return self.joint == "distributing"


@dataclass(frozen=True)
class Scene:
    """A checked scene, in SI: lengths in m, E in Pa, density in kg/m^3, stiffnesses in
    N/m and N m/rad, masses in kg, inertias in kg m^2, excitation and mode frequencies
    in Hz, margins and damping as fractions. Made by `load_scene`; frozen, so a changed
    copy comes from `with_mesh`, `with_modes`, `with_accuracy` or `free()`."""

    name: str
    source: str
    shaft: Shaft
    material: Material
    grooves: Grooves | None
    mesh: MeshSettings
    excitations: tuple[Excitation, ...] = ()
    # [sizing] inputs, checked, in the file's units (kW, r/min, deg, MPa, mm):
    # the paper states equations (1)-(9) in these units.
    sizing: dict | None = None
    required_margin: float = DEFAULT_MARGIN_PERCENT / 100  # separation margin, fraction
    modes: ModeRequest = ModeRequest()
    # adaptive meshing: the bound wanted on every frequency (fraction; None: fixed mesh)
    target_error: float | None = None
    max_dofs: int = DEFAULT_MAX_DOFS
    # the installed shaft: bearing seats and parts fixed on it (none: free-free)
    supports: tuple[Support, ...] = ()
    attachments: tuple[Attachment, ...] = ()
    damping_ratio: float = DEFAULT_DAMPING_PERCENT / 100  # modal, fraction of critical
    response_point: float | None = None  # z of the point whose response is shown, m
    criterion: str = "flat"  # resonance margin: "flat" or "api684" (shaftfem.checks.resonance)
    free_free_intended: bool = False  # [resonance] free_free: the check is meant free-free
    # the supports left off (free-free), their seats kept in the mesh
    hanging_free: bool = False
    # planes the mesh follows besides the scene's own: a study's copy with other supports
    # (the critical speed map's) keeps its scene's mesh
    mesh_cuts: tuple[float, ...] = ()
    rotor: Rotor | None = None  # [rotor]: the shaft turns (None: it stands still)
    unbalances: tuple[Unbalance, ...] = ()  # [[unbalance]]: what drives it at 1x
    # the static loads: gravity's acceleration vector (m/s^2) and the [[force]] tables
    gravity: tuple[float, float, float] = (0.0, -STANDARD_GRAVITY, 0.0)
    forces: tuple[PointForce, ...] = ()
    # the duty's torques and what strength is judged against (None: not checked)
    torques: tuple[Torque, ...] = ()
    strength: Strength | None = None
    # the report's title block: (label, text) pairs from the scene's machine, job,
    # revision, date and engineer keys; no bearing on any number
    title_block: tuple[tuple[str, str], ...] = field(default=(), compare=False)
    description: str = field(default="", compare=False)
    # the tables the scene was made from, in the file's units (what to_toml writes), and
    # the scene they made: a copy changed in code since (with_mesh, free) is told apart
    tables: dict | None = field(default=None, compare=False, repr=False)
    made: tuple | None = field(default=None, compare=False, repr=False)

    def with_tables(self, tables: dict) -> Scene:
        """The scene, noting that `tables` (file units) describe it as it is now."""
        return replace(self, tables=tables, made=self._content())

    def _content(self) -> tuple:
        """What the scene says, its name and file aside (a STEP shaft before placing)."""
        return tuple(self.shaft.unplaced() if f.name == "shaft" else getattr(self, f.name)
                     for f in fields(self) if f.compare and f.name not in ("name", "source"))

    def file_tables(self) -> dict:
        """The tables (file units) that make this scene. A scene changed in code since by a
        function that does not keep them (with_mesh, with_modes, free) has none: make such
        a change with shaftfem.vary, which does."""
        if self.tables is None or self.made != self._content():
            from shaftfem.errors import SceneError

            raise SceneError(
                f"{self.source}: this scene was changed in code after it was made (by "
                "with_mesh, with_modes, free or the like), so no scene file describes it; "
                "make the change with shaftfem.vary(scene, ...) instead")
        return self.tables

    def to_toml(self, path: str | Path | None = None) -> str:
        """The scene as a scene file (TOML, file units), written to `path` when given: what
        `shaftfem modes FILE` reads back into this very scene (see file_tables)."""
        import tomli_w

        tables = self.file_tables()
        many = {k for k, v in tables.items()
                if isinstance(v, list) and v and all(isinstance(e, dict) for e in v)}
        top = {k: v for k, v in tables.items() if not isinstance(v, dict) and k not in many}
        # each table under its own header, an array's entries as [[name]] (as people
        # write scene files; tomli_w would put short ones inline)
        chunks = [tomli_w.dumps(top)] if top else []
        for k, v in tables.items():
            if isinstance(v, dict):
                chunks.append(tomli_w.dumps({k: v}))
            elif k in many:
                chunks += [f"[[{k}]]\n" + tomli_w.dumps(e) for e in v]
        text = "\n".join(chunks)
        if path is not None:
            from shaftfem.store import write_text

            write_text(path, text)
        return text

    @property
    def held(self) -> tuple[Support, ...]:
        """The supports that hold the shaft (none when it hangs free)."""
        return () if self.hanging_free else self.supports

    @property
    def axisymmetric(self) -> bool:
        """Whether the shaft is a solid of revolution: a profile without keyways or
        grooves (a STEP solid is not taken as one)."""
        return self.grooves is None and not self.shaft.keyways and self.shaft.step is None

    @property
    def installed(self) -> bool:
        """Whether anything holds the shaft or sits on it (else: free-free, bare)."""
        return bool(self.held or self.attachments)

    def seat_cuts(self) -> tuple[float, ...]:
        """The axial positions (m) where a seat band begins or ends, the centres of parts
        on distributing joints, the planes of unbalances, static forces and the rotor's
        probes (they act on, or read, that cross-section): the mesh follows them."""
        zs = {z for part in self.supports + self.attachments for z in part.seat}
        zs |= {a.position for a in self.attachments if a.carried}
        zs |= {u.position for u in self.unbalances}
        # a travelling load's places share one mesh: their hot spots are compared on it
        zs |= {f.position for f in self.forces if f.travel is None}
        zs |= set(self.rotor.probes if self.rotor is not None else ())
        zs |= set(self.mesh_cuts)
        return tuple(sorted(z for z in zs if 0.0 < z < self.shaft.length))

    def hubs(self) -> tuple[tuple[float, float], ...]:
        """The attached parts' seats (z0, z1 in m): the mesher refines the shaft there."""
        return tuple(sorted(part.seat for part in self.attachments))

    def free(self) -> Scene:
        """The same shaft hanging free, on the same mesh: its supports left off (the
        attached parts stay on)."""
        return replace(self, hanging_free=True)
