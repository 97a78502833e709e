"""Will the shaft hold: its duty solved on the solid, its hot spots found, bounded and
judged by the FKM guideline (checks.fkm), and its slopes and deflections at the seats
and parts against their limits.

The hot spots are the local maxima of the equivalent stress amplitude and of the peak
equivalent stress on the surface, away from where loads and reactions enter (a bearing
seat's or a hub's band, whose stresses depend on the fit, not on the shaft). Each one's
stress is bounded as each frequency is: the same scene solved on a mesh COARSER times
coarser, the bound the difference between the two meshes' peaks at the spot, and at
least CURVATURE_ERROR (h / rho)^2 in a notch of radius rho (two meshes can agree by
chance; P2's surface stress there is off by up to about that, either way), plus the
spot's scatter (a spot is the largest of its vertices, and P2's vertex-averaged stress
scatters from vertex to vertex by a percent or so: the spot's value stands that far off
a smooth fit of its neighbours', and is read high by it). While a
bound exceeds the target ([strength] target_error_percent), the mesh is refined around
those spots only (a gmsh size field: the elements within a few sizes of the spot shrink
by at least COARSER, by as much as P2 stresses' h^2 convergence asks for AIM times the
target; every earlier round's refinement kept, none coarser than the scene's own
mesh), and the spots are bounded again against the mesh before. A spot whose stress
keeps growing as the mesh refines where the surface turns concavely within an element is a
sharp re-entrant corner of the geometry (a singular stress): it is reported as such,
without a number to trust. A convex edge (a land's corner where two grooves' root fillets
meet) has a bounded stress, and is bounded as any notch is.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from itertools import chain
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from shaftfem.errors import BudgetError, MeshError, SceneError, SolverError
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Keyway, PointForce, Scene, Torque

if TYPE_CHECKING:
    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.checks.fkm import PointAssessment

COARSER = 1.5
# a bound needs its coarse mesh this many times coarser at the spot than its fine one
MIN_RATIO = 1.3
MAX_REFINEMENTS = 3
# a refinement aims each spot's bound at this share of the target, shrinking its
# elements by at most SHRINK_MAX per round, over REACH spot sizes or a tenth of the
# local radius, whichever is larger, the elements growing by GRADING of the distance
# beyond
AIM = 0.5
SHRINK_MAX = 4.0
REACH = 2.0
GRADING = 0.4
# a round whose mesh would exceed the DOF budget is asked this many times more, its
# sizes enlarged (at most ENLARGE_MAX times) until its estimate is BUDGET_AIM of the budget
BUDGET_TRIES = 3
ENLARGE_MAX = 8.0
BUDGET_AIM = 0.95
HOOP_REACH = 4.0
# each round refines around the few spots still above the target that may be the worst
# (the largest utilisation at the top of their intervals, at least half the worst: the
# others do not decide the verdict)
REFINED = 3
# a spot rising as refined where the surface's normal turns concavely by more than this
# within an element (rad) is a sharp (re-entrant) edge
SHARP = math.radians(30.0)
# ... and a mesh whose normal turns concavely by more than this within an element at a
# spot does not resolve the notch there: both meshes of a bound miss its peak alike
RESOLVED = math.radians(20.0)
# a P2 mesh's surface stress at a notch of radius rho is off by up to about 1.7 (h /
# rho)^2, either way (h its longest surface edge there: measured on shoulder fillets in
# bending, tension and torsion against an axisymmetric solution converged to 1e-5,
# benchmarks/notch_factors.py); a bound is at least this times (h / rho)^2
CURVATURE_ERROR = 2.0
# a spot's scatter: the quadratic fitted over the surface points within this many of its
# element sizes (P2's surface stress is smooth to O(h^3) over them), from at least
# SCATTER_POINTS of them
SCATTER_REACH = 2.0
SCATTER_POINTS = 10
# travelling loads: screened places whose worst utilisations lie within this share of
# each other are taken as alike (the first is bounded)
PLACES_ALIKE = 0.005
# hot spots: at most this many, each the largest within SPACING local radii, and at least
# this share of the largest
MAX_SPOTS = 8
SPACING = 0.25
SHARE = 0.3
# on a standing shaft of revolution, a stress this close to the same all round a circle
# is taken as round (a torque's, an axial force's): its spot follows the refined place
ROUND = 0.05
# slope limits by bearing kind (rad), common practice: Budynas & Nisbett, Shigley's
# Mechanical Engineering Design, 10th ed., table 7-2 (the low ends of the ranges:
# deep-groove ball 0.001-0.003, cylindrical roller 0.0008-0.0012); springs and
# coefficients are taken as a ball bearing's; a journal, a seal and a rigid seat are not
# judged
SLOPE_LIMITS = {"ball": 1.0e-3, "roller": 0.8e-3, "springs": 1.0e-3, "bearing": 1.0e-3}
SLOPE_SOURCE = "Shigley, table 7-2"
# a notch's K_t under a load is given where that load's nominal stress is at least this
# share of the spot's peak (below it the ratio says little), beside the table's
NOMINAL = 0.05
_TURN = np.linspace(0.0, 2 * np.pi, 72, endpoint=False)


@dataclass(frozen=True)
class NotchFactor:
    """A notch's stress concentration under one load ("bending", "torsion", "tension"):
    K_t from the solid (largest principal stress, or largest shear in torsion, at the
    spot over the nominal stress of the notch's smaller section, from what that section
    carries) beside the table's (None outside its range), and the notch's size (m)."""

    load: str
    computed: float
    table: float | None
    large: float
    small: float
    radius: float


@dataclass(frozen=True)
class HotSpot:
    """A hot spot: where (m, rad), its stresses over a turn (Pa; the mean signed), the
    bound on them (fraction; None when not known), whether they converge, the relative
    stress gradient (1/m), the shaft's diameter there (m), what it is and FKM's verdict."""

    z: float
    angle: float
    radius: float
    feature: str
    amplitude: float
    mean: float
    peak: float
    bound: float | None
    converging: bool
    gradient: float
    diameter: float
    fkm: PointAssessment
    size: float = 0.0     # the mesh's element size at the spot, m
    # whether the mesh follows the notch's curvature at the spot (its normal turns
    # concavely by less than RESOLVED within an element): a two-mesh bound means
    # nothing before
    resolved: bool = True
    # whether the spot rose as a sharp edge's would at this round (a sharp edge once more
    # and it is one: a notch not yet resolved rises so once, then refines into a smooth one)
    rising: bool = False
    # the error the next refinement aims from (fraction): the bound, or where the coarser
    # mesh did not resolve the notch (its difference overstates the finer mesh's error)
    # the notch's curvature term and the spot's scatter
    aim: float | None = None
    # the two meshes' difference alone (fraction; None when not known): the bound is it
    # or the notch's curvature term, whichever is larger
    difference: float | None = None
    # at a shoulder fillet the tables cover: its K_t under each load it carries
    factors: tuple[NotchFactor, ...] = ()
    # the DOFs of the local model that bounded it (_localised); 0: read on the whole
    local_dofs: int = 0


@dataclass(frozen=True)
class SeatCheck:
    """The shaft's slope (rad) and deflection (m) at a seat or part, and its limits
    (None: not judged)."""

    name: str
    position: float
    slope: float
    deflection: float
    slope_limit: float | None
    deflection_limit: float | None
    source: str

    @property
    def ok(self) -> bool:
        return ((self.slope_limit is None or self.slope <= self.slope_limit)
                and (self.deflection_limit is None or self.deflection <= self.deflection_limit))


@dataclass(frozen=True)
class StressSurface:
    """The finest mesh's surface: points (n, 3) m and triangles (m, 3), and at each point
    the equivalent stress amplitude over a turn, the signed mean and the peak (Pa), the
    relative stress gradient (1/m) and FKM's degrees of utilisation, fatigue a_BK and
    yield a_SK (NaN where a load or a reaction enters: the fit's stress, not judged)."""

    points: np.ndarray
    facets: np.ndarray
    amplitude: np.ndarray
    mean: np.ndarray
    peak: np.ndarray
    gradient: np.ndarray
    fatigue_utilisation: np.ndarray
    yield_utilisation: np.ndarray


@dataclass(frozen=True)
class Travel:
    """One place of the travelling loads' screening on the coarser mesh: where they
    stood (m, the first travelling load's z), the worst hot spot's utilisation there
    (the larger of fatigue and yield) and its z (m)."""

    position: float
    utilisation: float
    spot: float = math.nan


@dataclass(frozen=True)
class StrengthResult:
    """`shaftfem strength`: the hot spots (worst fatigue first), the seats' checks, the
    meshes solved (DOFs) and the scene."""

    scene: Scene
    spots: tuple[HotSpot, ...]
    seats: tuple[SeatCheck, ...]
    dofs: tuple[int, ...]
    target: float
    # the finest mesh's surface with its stresses and utilisations: the hot-spot picture's
    # field and the VTK file's
    surface: StressSurface | None = field(default=None, compare=False, repr=False)
    notes: tuple[str, ...] = ()   # why the refinement stopped short, and a mesh HXT made
    # a travelling load's screening (Travel), the scene's loads at the worst place,
    # and which of them was bounded (its index, _worst_place)
    travel: tuple[Travel, ...] = ()
    worst_place: int = 0

    @property
    def sharp(self) -> tuple[HotSpot, ...]:
        """The spots whose stress rises as the mesh refines: sharp edges, whose elastic
        stress has no limit (no number to judge)."""
        return tuple(s for s in self.spots if not s.converging)

    @property
    def fatigue_ok(self) -> bool:
        return all(s.fkm.fatigue_utilisation <= 1 for s in self.spots if s.converging)

    @property
    def yield_ok(self) -> bool:
        return all(s.fkm.yield_utilisation <= 1 for s in self.spots if s.converging)

    @property
    def deflection_ok(self) -> bool:
        return all(s.ok for s in self.seats)

    @property
    def bounded(self) -> bool:
        """Whether every hot spot's bound meets the target."""
        return all(s.bound is not None and s.bound <= self.target and s.converging
                   and s.resolved for s in self.spots)

    @property
    def ok(self) -> bool:
        """Every check passed, and no hot spot is a sharp edge (which none can pass)."""
        return self.fatigue_ok and self.yield_ok and self.deflection_ok and not self.sharp

    def as_dict(self) -> dict:
        """The JSON of `shaftfem strength`."""
        from shaftfem.checks.notch_tables import SOURCE

        st = self.scene.strength
        assert st is not None
        return {
            "passed": self.ok, "fatigue_ok": self.fatigue_ok, "yield_ok": self.yield_ok,
            "deflection_ok": self.deflection_ok, "bounded": self.bounded,
            "sharp_edges": len(self.sharp),
            "target_error_percent": self.target * 100, "dofs": list(self.dofs),
            "notes": list(self.notes),
            "travel": [{"position_mm": t.position * 1e3, "utilisation": t.utilisation,
                        "worst_z_mm": t.spot * 1e3} for t in self.travel],
            "material": {"tensile_strength_mpa": st.tensile_strength / 1e6,
                         "yield_strength_mpa": st.yield_strength / 1e6,
                         "source": st.source},
            "hot_spots": [{
                "z_mm": s.z * 1e3, "angle_deg": math.degrees(s.angle) % 360,
                "radius_mm": s.radius * 1e3, "feature": s.feature,
                "amplitude_mpa": s.amplitude / 1e6, "mean_mpa": s.mean / 1e6,
                "peak_mpa": s.peak / 1e6,
                "bound_percent": None if s.bound is None else s.bound * 100,
                "converging": s.converging, "resolved": s.resolved,
                "local_model_dofs": s.local_dofs or None,
                "gradient_per_mm": s.gradient * 1e-3,
                "diameter_mm": s.diameter * 1e3,
                "stress_concentration": [{
                    "load": k.load, "kt": k.computed, "kt_table": k.table,
                    "table": SOURCE, "large_diameter_mm": k.large * 1e3,
                    "small_diameter_mm": k.small * 1e3, "fillet_radius_mm": k.radius * 1e3}
                    for k in s.factors],
                "fkm": {k: float(v) for k, v in vars(s.fkm).items()}} for s in self.spots],
            "seats": [{"name": c.name, "position_mm": c.position * 1e3,
                       "slope_mrad": c.slope * 1e3, "deflection_um": c.deflection * 1e6,
                       "slope_limit_mrad": None if c.slope_limit is None
                       else c.slope_limit * 1e3,
                       "deflection_limit_um": None if c.deflection_limit is None
                       else c.deflection_limit * 1e6,
                       "source": c.source, "ok": c.ok} for c in self.seats]}


@dataclass(frozen=True)
class _Field:
    """One mesh's solution: the surface's stress cycle and the deflection line."""

    points: np.ndarray
    normals: np.ndarray
    edge: np.ndarray
    stress: np.ndarray
    amplitude: np.ndarray
    mean: np.ndarray
    peak: np.ndarray
    all_stress: np.ndarray
    vertices: np.ndarray   # the mesh's vertices (N, 3) and tetrahedra (m, 4), to read
    tets: np.ndarray       # all_stress inside the solid
    facets: np.ndarray
    allowed: np.ndarray   # the surface points outside the load and seat bands
    line: tuple[np.ndarray, np.ndarray, np.ndarray]
    dofs: int
    tree: Any = None   # a cKDTree of the tetrahedra's centroids, to read the field inside
    # the mesh (points (N, 3), cells (E, 10)) and its displacements at the points (cases,
    # N, 3), m, to drive local models (fem.submodel); None on a local model's own field
    mesh_points: np.ndarray | None = None
    mesh_cells: np.ndarray | None = None
    point_u: np.ndarray | None = None
    # its scalar nodes (n, 3) and the nodal forces K u there (cases, n, 3), N: what a
    # section carries (fem.submodel.carried)
    node_xyz: np.ndarray | None = None
    node_force: np.ndarray | None = None
    key: str = ""      # the solution's cache key

    def read(self, points: np.ndarray):
        """The vertex fields' reading at points (k, 3) inside the solid (fem.probe)."""
        from shaftfem.fem.probe import probe

        return probe(self.vertices, self.tets, points, self.tree)


def run_strength(scene: Scene, options: RunOptions = RunOptions()) -> StrengthResult:
    """The scene's strength: its hot spots bounded to [strength] target_error_percent
    (or as near as MAX_REFINEMENTS refinements get), judged by FKM, and its seats."""
    from shaftfem.workflows.pipeline import with_mesh

    if scene.strength is None:
        raise SceneError(f"{scene.source}: no [strength] table: strength is not checked "
                         "(add [strength] with the duty in [[force]] and [[torque]])")
    if not scene.held:
        raise SceneError(f"{scene.source}: no [[support]] holds the shaft: its duty has "
                         "nothing to react it")
    target = scene.strength.target_error
    stations = _stations(scene)
    travel: list[Travel] = []
    worst_seats: dict[str, SeatCheck] = {}
    bounded = 0
    if len(stations) > 1:
        for where, station in stations:
            # screened on the coarser mesh alone: the places are compared, not bounded
            coarse = _solve(with_mesh(station, station.mesh.size * 1e3 * COARSER),
                            options)[0]
            spots = _spots(station, coarse, coarse, None)
            top = max(spots, key=_utilisation, default=None)
            travel.append(Travel(where, 0.0 if top is None else _utilisation(top),
                                 math.nan if top is None else top.z))
            options.say(f"travelling loads at {where * 1e3:.1f} mm: worst utilisation "
                        f"{travel[-1].utilisation:.3f}")
            for c in _seats(station, coarse):
                if c.name not in worst_seats or _seat_use(c) > _seat_use(worst_seats[c.name]):
                    worst_seats[c.name] = c
        # the worst place is bounded: its coarser mesh again (from the cache), then finer
        bounded = _worst_place([t.utilisation for t in travel])
        scene = stations[bounded][1]
    coarse = _solve(with_mesh(scene, scene.mesh.size * 1e3 * COARSER), options)[0]
    first = coarse
    fine, mesh, built = _solve(scene, options)
    spots = _spots(scene, fine, coarse, None)
    dofs = [coarse.dofs, fine.dofs]
    notes: list[str] = []
    requests: list[_Request] = []
    history: list[list[HotSpot]] = []   # the earlier rounds' spots, the newest first
    for _ in range(MAX_REFINEMENTS):
        worst = max((_utilisation(s) for s in spots), default=0.0)
        # the spots that may be the worst first: an unresolved notch reads low (a keyway
        # end's floor fillet at 1 mm elements, K_t 1.6 +-127 %, where its truth is 2.2,
        # above the mantle's bounded 2.1 beside it)
        open_ = sorted((s for s in spots if s.converging and _upper(s) >= 0.5 * worst
                        and (s.bound is None or s.bound > target or not s.resolved)),
                       key=_upper, reverse=True)[:REFINED]
        if not open_:
            break
        options.say(f"hot spot(s) {', '.join(str(spots.index(s) + 1) for s in open_)} bounded "
                    f"above {target:.1%}: refining around them")
        asked = _requested(open_, target)
        try:
            refined, asked = _within_budget(built, mesh, requests, asked, scene, options)
            if refined.hxt:
                from shaftfem.cad.mesh import mesh_dofs

                made_by = (f"round {len(dofs) - 1}'s mesh ({mesh_dofs(refined):,} DOFs) was "
                           "made by gmsh's HXT: its Delaunay did not finish in its time "
                           "(a mesh of the same sizes, another of the same solid)")
                options.say(made_by)
                notes.append(made_by)
            requests += asked
            coarse, (fine, mesh, built) = fine, _solve(scene, options, (built, refined))
        except (BudgetError, MeshError) as e:
            # the DOF budget, or a refined mesh the mesher left with a bad element: the
            # spots keep the last mesh's values and bounds, and the reader is told why
            done = len(dofs) - 2
            when = f"after {done} round(s)" if done else "at its first round"
            stopped = f"refining stopped {when}: {e}"
            options.say(stopped)
            notes.append(stopped)
            break
        dofs.append(fine.dofs)
        history.insert(0, spots)
        spots = _spots(scene, fine, coarse, spots, history[1:])
    spots = _localise(scene, spots, fine, first, built, target, options, notes)
    runouts = _runouts(scene)
    if runouts:
        notes.append(runouts)
    notes += _keyed(scene)
    seats = _seats(scene, fine)
    if worst_seats:
        # each seat at the place of the travel that bends it most
        seats = tuple(worst_seats.get(c.name, c) for c in seats)
    return StrengthResult(scene=scene, spots=tuple(spots), seats=seats,
                          dofs=tuple(dofs), target=target, surface=_surface(scene, fine),
                          notes=tuple(notes), travel=tuple(travel), worst_place=bounded)


def _worst_place(utilisations: list[float]) -> int:
    """The worst of the screened places: the first within PLACES_ALIKE of the largest
    utilisation (places the screening's mesh does not tell apart load the spots alike,
    and the last digit of a solve must not choose among them)."""
    top = max(utilisations)
    return next(i for i, u in enumerate(utilisations) if u >= top * (1 - PLACES_ALIKE))


def _travelling(scene: Scene) -> list[PointForce | Torque]:
    """The scene's travelling loads ([[force]] and [[torque]] with travel_to_mm)."""
    loads: list[PointForce | Torque] = [*scene.forces, *scene.torques]
    return [q for q in loads if q.travel is not None]


_Load = TypeVar("_Load", PointForce, Torque)


def _stations(scene: Scene) -> list[tuple[float, Scene]]:
    """The scene with its travelling loads at each of [strength] travel_positions places
    along their ways, ends included (each load from its position to its travel's end),
    with where the first of them stands (m); the scene itself when no load travels."""
    moving = _travelling(scene)
    if not moving:
        return [(0.0, scene)]
    assert scene.strength is not None

    def at(q: _Load, t: float) -> _Load:
        # it keeps its travel: the mesh leaves out the planes of travelling loads
        if q.travel is None:
            return q
        return replace(q, position=q.position + t * (q.travel - q.position))

    first = moving[0]
    assert first.travel is not None
    return [(first.position + t * (first.travel - first.position),
             replace(scene, forces=tuple(at(f, t) for f in scene.forces),
                     torques=tuple(at(q, t) for q in scene.torques)))
            for t in np.linspace(0.0, 1.0, scene.strength.travel_positions)]


def _seat_use(c: SeatCheck) -> float:
    """How near a seat is to its limits (its slope where it has none: a larger one is
    worse)."""
    uses = [v / limit for v, limit in ((c.slope, c.slope_limit),
                                       (c.deflection, c.deflection_limit)) if limit]
    return max(uses) if uses else c.slope


def _surface(scene: Scene, field: _Field) -> StressSurface:
    """The field's surface with FKM judged at every point (outside the load bands)."""
    from shaftfem.checks.fkm import assess_many

    st = scene.strength
    assert st is not None
    gradient = _gradients(field, np.arange(len(field.points)), st.speed > 0)
    fkm = assess_many(field.amplitude, field.mean, field.peak, gradient,
                      2 * _outer_radii(field), st)
    return StressSurface(
        points=field.points, facets=field.facets, amplitude=field.amplitude,
        mean=field.mean, peak=field.peak, gradient=gradient,
        fatigue_utilisation=np.where(field.allowed, fkm["fatigue_utilisation"], np.nan),
        yield_utilisation=np.where(field.allowed, fkm["yield_utilisation"], np.nan))


def _runouts(scene: Scene) -> str | None:
    """What the check leaves out at the grooves' ends where they have no runouts: flat
    walls, each meeting the floor at a right-angled re-entrant edge, whose elastic stress
    has no limit (checks.singular); None without grooves or with runouts."""
    from shaftfem.checks.singular import wedge_exponent

    g = scene.grooves
    if g is None or g.runout > 0:
        return None
    power = wedge_exponent(1.5 * math.pi) - 1
    return (f"not judged: the grooves' ends at {g.start * 1e3:g} and "
            f"{(g.start + g.length) * 1e3:g} mm, flat walls meeting the floor at a right "
            f"angle, sharp re-entrant edges whose stress has no limit (it grows as "
            f"r^{power:.3f} towards them); [grooves] runout_mm models the floor rising out "
            "as the cutter lifts")


def _keyed(scene: Scene) -> list[str]:
    """How each keyed torque is taken to enter: through its key's pressure on the flank
    it drives (fem.stress.key_loads), a model whose contact the stress below it reads."""
    from shaftfem.fem.stress import key_bearings

    out = []
    for kb in key_bearings(scene):
        k, q = kb.keyway, scene.torques[kb.source]
        floor = (scene.shaft.radius_at(0.5 * (k.start + k.end)) or 0.0) - k.depth
        out.append(f"the torque '{q.name}' ({kb.torque:+.1f} N m) enters through the key in "
                   f"the keyway at {k.start * 1e3:g}-{k.end * 1e3:g} mm, "
                   f"{math.degrees(k.angle) % 360:g} deg: a uniform pressure on "
                   f"the flank it drives, from {kb.z0 * 1e3:g} to {kb.z1 * 1e3:g} mm and from "
                   f"{(kb.foot - floor) * 1e3:.2g} mm above the floor (the key's chamfer) to "
                   "the surface, the hub's bore taking its net force (DIN 6892's uniform "
                   "pressure); not judged: the keyway's half on that side (the flank, the "
                   "floor's corner below it, that half of each end), whose stress is the "
                   "contact's (the key's fit and tilt decide it)")
    return out


def _utilisation(s: HotSpot) -> float:
    """A spot's larger degree of utilisation, fatigue or yield."""
    return max(s.fkm.fatigue_utilisation, s.fkm.yield_utilisation)


def _upper(s: HotSpot) -> float:
    """A spot's utilisation at the top of its interval: times 1 + its bound (or the error
    its next refinement aims from, where that is larger: a notch the mesh did not
    resolve)."""
    return _utilisation(s) * (1 + max(s.bound or 0.0, s.aim or 0.0))


@dataclass(frozen=True)
class _Request:
    """A refinement asked around a hot spot: elements of `size` (m) within `reach` (m),
    growing by GRADING of the distance beyond. Kept over the rounds: a round refines
    around its spots and keeps every earlier round's refinement."""

    spot: HotSpot
    size: float
    reach: float


def _requested(spots: list[HotSpot], target: float) -> list[_Request]:
    """Around each spot whose bound is above the target: its element size shrunk by
    (bound / (AIM target))^(1/2) (P2 stresses converge as h^2), at least COARSER and at
    most SHRINK_MAX, within REACH of its sizes (or a tenth of the local radius)."""
    out = []
    for s in spots:
        error = s.bound if s.aim is None else s.aim
        shrink = SHRINK_MAX if not s.resolved else COARSER if error is None else float(np.clip(
            math.sqrt(error / (AIM * target)), COARSER, SHRINK_MAX))
        out.append(_Request(s, s.size / shrink, _reach(s.size, s.radius)))
    return out


def _reach(size: float, radius: float) -> float:
    """How far round a spot a round refines (m): REACH of its element sizes, or a tenth
    of the local radius, whichever is larger."""
    return max(REACH * size, 0.1 * radius)


def _refined_sizes(mesh, requests: list[_Request], round_: bool, largest: float
                   ) -> np.ndarray:
    """Element sizes at the mesh's points for the next mesh: the smallest any request
    asks there, `largest` where none does (the scene's own sizes then rule: the mesher
    takes the smaller of these and its own). On a shaft of revolution too, only around
    the spot (not all round its circle), but HOOP_REACH times as far round the circle as
    along the axis: the spot found on a coarse mesh sits where a vertex happened to be,
    some degrees off the load's plane, where the finer mesh finds the peak."""
    new = np.full(mesh.points.shape[0], largest)
    for q in requests:
        d = _distance(mesh.points, q.spot, round_)
        new = np.minimum(new, q.size + GRADING * np.maximum(d - q.reach, 0.0))
    return new


def _within_budget(built, mesh, requests: list[_Request], asked: list[_Request],
                   scene: Scene, options: RunOptions) -> tuple[ShaftMesh, list[_Request]]:
    """The next mesh, with this round's refinement `asked` on top of the rounds' before,
    within the DOF budget: a round refines as far as the budget lets it, not stops.
    Before a mesh is made its DOFs are estimated from the size field
    (cad.mesh.refined_elements), scaled by what gmsh made of the last field it was given
    (it stops short of a notch's finest sizes: the pump shaft's keyway, 395,505 DOFs made
    where 800,000 were estimated); where that is above the budget, this round's sizes are
    enlarged until it is not, so that no mesh of millions of DOFs is made only to be
    refused. A mesh still above the budget, counted, rescales the estimate, and the round
    is asked again (BUDGET_TRIES times at most)."""
    from shaftfem.cad.mesh import DOFS_PER_ELEMENT, check_mesh_budget, mesh_dofs, refined_elements

    placed = built[0]
    budget = placed.max_dofs

    def estimate(requests: list[_Request]) -> float:
        sizes = _refined_sizes(mesh, requests, scene.axisymmetric, scene.mesh.size)
        return (DOFS_PER_ELEMENT[placed.mesh.order]
                * refined_elements((mesh.points, mesh.cells[:, :4], sizes)))

    def grown(g: float) -> list[_Request]:
        return [replace(q, size=q.size * g) for q in asked]

    made_of = float(np.clip(mesh_dofs(mesh) / estimate(requests), 0.25, 4.0))
    for tries in range(BUDGET_TRIES + 1):
        guess = made_of * estimate(requests + asked)
        if guess > budget:
            # the least enlargement whose estimate is within BUDGET_AIM of the budget
            if made_of * estimate(requests + grown(ENLARGE_MAX)) > BUDGET_AIM * budget:
                raise BudgetError(
                    f"the refined mesh would have about {guess:,.0f} DOFs, above the budget "
                    f"of {budget:,} however far this round's elements are enlarged (the "
                    "mesh outside this round's refinement needs that many); raise the "
                    "budget ([mesh] max_dofs or --max-dofs)")
            lo, hi = 1.0, ENLARGE_MAX
            while hi / lo > 1.01:
                mid = math.sqrt(lo * hi)
                lo, hi = (lo, mid) if made_of * estimate(requests + grown(mid)) <= \
                    BUDGET_AIM * budget else (mid, hi)
            options.say(f"the refined mesh would have about {guess:,.0f} DOFs, above the "
                        f"budget of {budget:,}: this round's elements {hi:.2f} times larger")
            asked = grown(hi)
        made = _remeshed(built, mesh, _refined_sizes(mesh, requests + asked,
                                                     scene.axisymmetric, scene.mesh.size))
        n = mesh_dofs(made)
        if n <= budget or tries == BUDGET_TRIES:
            break
        made_of = n / estimate(requests + asked)
        options.say(f"the refined mesh has {n:,} DOFs, above the budget of {budget:,}: "
                    "asked again with its estimate scaled to it")
    check_mesh_budget(made, placed.mesh, budget)
    return made, asked


def _distance(points: np.ndarray, s: HotSpot, round_: bool) -> np.ndarray:
    """How far points (n, 3) lie from a hot spot (m); on a shaft of revolution their
    distance round the circle counts HOOP_REACH times less."""
    if not round_:
        return np.linalg.norm(points - _xyz(s), axis=1)
    r = np.hypot(points[:, 0], points[:, 1])
    turn = np.angle(np.exp(1j * (np.arctan2(points[:, 1], points[:, 0]) - s.angle)))
    return np.sqrt((points[:, 2] - s.z) ** 2 + (r - s.radius) ** 2
                   + (s.radius * turn / HOOP_REACH) ** 2)


def _remeshed(built, mesh, sizes: np.ndarray) -> ShaftMesh:
    """The placed scene's solid meshed to `sizes` (at the mesh's points), from the cache
    where it holds that mesh (its DOF budget checked by the caller)."""
    import hashlib

    from shaftfem.cad.mesh import (
        MESH_ARRAYS,
        generate_mesh,
        mesh_arrays,
        mesh_from_arrays,
    )
    from shaftfem.store import cache_dir, content_key, discard, load_arrays, save_arrays
    from shaftfem.workflows.stages import mesh_key

    placed, shape = built
    digest = hashlib.sha256(np.ascontiguousarray(mesh.points).tobytes()
                            + np.round(sizes, 12).tobytes()).hexdigest()
    key = content_key({"version": 3, "mesh": mesh_key(shape, placed.shaft, placed.grooves,
                                                      placed.mesh, placed.seat_cuts(),
                                                      placed.hubs()),
                       "sizes": digest})
    path = cache_dir() / "strength" / f"{key}.npz"
    # which mesher made it is kept with it: a warm run reports what the cold one did
    fields, why = (load_arrays(path, MESH_ARRAYS + ("hxt",)) if path.exists()
                   else (None, ""))
    if fields is None and why:
        discard(f"refined mesh {path.stem}", why, path)
    if fields is not None:
        made = replace(mesh_from_arrays(fields), order=placed.mesh.order,
                       hxt=bool(fields["hxt"]))
    else:
        # refined, never coarser than the scene's own mesh: a size read from the mean
        # of a vertex's elements exceeds a notch surface's own, and a notch's far side
        # coarsened round after round shifts its load onto the refined spot (a 64/32 mm
        # shoulder in tension read 1.3 % high with its bound at 0.2 %)
        made = generate_mesh(shape, placed.shaft, placed.grooves, placed.mesh,
                             (mesh.points, mesh.cells[:, :4], sizes), placed.seat_cuts(),
                             placed.hubs(), refine=True)
        save_arrays(path, dict(mesh_arrays(made), hxt=np.bool_(made.hxt)))
    return made


def _solve(scene: Scene, options: RunOptions, given=None) -> tuple[_Field, object, tuple]:
    """The duty's four cases on the scene's mesh (or on `given`: (placed scene and its
    solid, a mesh of it)): the surface's stress cycle and the deflection line of the
    standing loads; the mesh, and the placed scene with its solid."""
    from scipy.spatial import cKDTree

    from shaftfem.fem.stress import cycle
    from shaftfem.store import discard, load_arrays, save_arrays
    from shaftfem.workflows.equip import with_parts
    from shaftfem.workflows.pipeline import built

    if given is None:
        held = replace(scene, supports=tuple(
            replace(s, kind="rigid-radial", bearing=None, journal=None, tolerance=None)
            if s.kind == "journal" else s for s in scene.supports))
        placed, shape, mesh = built(with_parts(held), options)
    else:
        (placed, shape), mesh = given
    path = _field_path(placed, mesh)
    fields, why = load_arrays(path, FIELD_ARRAYS) if path.exists() else (None, "")
    if fields is None and why:
        discard(f"solved duty {path.stem}", why, path)
    if fields is None:
        fields = _solved(placed, mesh, options)
        save_arrays(path, fields)
    turning = scene.strength is not None and scene.strength.speed > 0
    amplitude, mean, peak = cycle(fields["stress"], turning)
    vertices, tets = fields["vertices"], fields["tets"]
    return _Field(points=fields["points"], normals=fields["normals"], edge=fields["edge"],
                  stress=fields["stress"], amplitude=amplitude, mean=mean, peak=peak,
                  all_stress=fields["all_stress"], vertices=vertices, tets=tets,
                  facets=fields["facets"], allowed=~_excluded(scene, fields["points"]),
                  line=(fields["line_z"], fields["line_x"], fields["line_y"]),
                  dofs=int(fields["dofs"]), tree=cKDTree(vertices[tets].mean(axis=1)),
                  mesh_points=fields["mesh_points"], mesh_cells=fields["mesh_cells"],
                  point_u=fields["point_u"], node_xyz=fields["node_xyz"],
                  node_force=fields["node_force"], key=path.stem), mesh, (placed, shape)


# a mesh's solved duty, kept in the cache: warm runs (the same scene again, or its
# refinement rounds) read it instead of solving again
SURFACE_ARRAYS = ("points", "normals", "edge", "stress", "all_stress", "vertices", "tets",
                  "facets", "dofs")
FIELD_ARRAYS = SURFACE_ARRAYS + ("line_z", "line_x", "line_y", "mesh_points", "mesh_cells",
                                 "point_u", "node_xyz", "node_force")


def _field_path(placed: Scene, mesh) -> Path:
    """Where a mesh's solved duty is kept: keyed by the mesh itself (its nodes and
    cells) and everything the four cases' solution depends on (material, seats, parts,
    loads, gravity)."""
    from dataclasses import asdict

    from shaftfem.store import cache_dir, content_key

    digest = _mesh_digest(mesh)
    # version 3: a keyed part's torque enters through its key (fem.stress.key_loads);
    # 5: the mesh, its displacements and nodal forces kept, to drive local models
    key = content_key({"version": 5, "nodes": digest, "order": placed.mesh.order,
                       "material": asdict(placed.material),
                       "supports": [asdict(s) for s in placed.supports],
                       "attachments": [asdict(a) for a in placed.attachments],
                       "forces": [asdict(f) for f in placed.forces],
                       "torques": [asdict(t) for t in placed.torques],
                       "gravity": list(placed.gravity)})
    return cache_dir() / "strength" / "fields" / f"{key}.npz"


def _mesh_digest(mesh) -> str:
    """A hash of a mesh's nodes and cells, for the cache keys of what is solved on it."""
    import hashlib

    return hashlib.sha256(np.ascontiguousarray(mesh.points).tobytes()
                          + np.ascontiguousarray(mesh.cells).tobytes()).hexdigest()


def _solved(placed: Scene, mesh, options: RunOptions) -> dict[str, np.ndarray]:
    """The four cases solved on the mesh: the surface's and the vertices' stresses, the
    surface's geometry and the standing loads' deflection line, as FIELD_ARRAYS."""
    from shaftfem.fem.assembly import _element, assemble
    from shaftfem.fem.installation import install
    from shaftfem.fem.static import line
    from shaftfem.fem.stress import duty_loads, solve_cases, surface_stress

    system = assemble(mesh, placed.material, threads=options.threads)
    options.say(f"solving the duty on {system.n_dofs:,} DOFs")
    skmesh = mesh.to_skfem()
    inst = install(placed, system.K, system.M, system.nodes, skmesh, system.order)
    element = _element(system.order)
    F, resultants = duty_loads(placed, system, inst, skmesh, element)
    U = solve_cases(placed, system, inst, F, resultants)
    surface = surface_stress(skmesh, element, placed.material.lame, U)
    z, x, y = line(system, U[:, 0])
    return {**_surface_arrays(surface, system.n_dofs), "line_z": z, "line_x": x, "line_y": y,
            "mesh_points": mesh.points,
            "mesh_cells": mesh.cells, "point_u": system.at_points(U),
            "node_xyz": system.nodes,
            "node_force": np.moveaxis((system.K @ U).reshape(-1, 3, U.shape[1]), 2, 0)}


def _excluded(scene: Scene, points: np.ndarray) -> np.ndarray:
    """The surface points in a band where a load or a reaction enters (a seat, a hub, a
    load's slice, a keyed part's keyway), widened by a quarter of the local radius: their
    stress is the fit's; less the keyways' pockets (_pockets)."""
    out = np.zeros(len(points), dtype=bool)
    for z0, z1 in _bands(scene, points):
        out |= (points[:, 2] >= z0) & (points[:, 2] <= z1)
    # a keyway's pocket touches no hub (the hub bears on the mantle): judged, but for
    # the flank its key bears on
    return out & ~_pockets(scene, points)


def _bands(scene: Scene, points: np.ndarray) -> list[tuple[float, float]]:
    """Where a load or a reaction enters (z0, z1), m: a seat, a hub, a load's slice, a
    keyed part's keyway, each widened by a quarter of the local radius (read from the
    surface points near it)."""
    seats, loads = _band_kinds(scene, points)
    return seats + loads


def _band_kinds(scene: Scene, points: np.ndarray
                ) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """_bands as the seats' (where the supports react) and the loads' (the parts' hubs,
    the forces' and torques' slices, the keyed parts' keyways)."""
    from shaftfem.fem.stress import key_bearings, load_band

    r = np.hypot(points[:, 0], points[:, 1])
    seats = [s.seat for s in scene.held if s.kind != "seal"]
    loads = [a.seat for a in scene.attachments]
    for position, width in ([(f.position, f.width) for f in scene.forces]
                            + [(q.position, q.width) for q in scene.torques]):
        b = load_band(position, width, points)
        loads.append((b.z0, b.z1))
    # a keyed part's hub covers its key at least (a coupling given by its position)
    loads += [(kb.keyway.start, kb.keyway.end) for kb in key_bearings(scene)]

    def widened(bands: list[tuple[float, float]]) -> list[tuple[float, float]]:
        out = []
        for z0, z1 in bands:
            near = (points[:, 2] > z0 - 0.02) & (points[:, 2] < z1 + 0.02)
            margin = 0.25 * (float(r[near].max()) if near.any() else 0.0)
            out.append((z0 - margin, z1 + margin))
        return out

    return widened(seats), widened(loads)


def _pockets(scene: Scene, points: np.ndarray) -> np.ndarray:
    """The surface points inside a keyway's pocket (below the surface by 5 % of its
    depth), less the half of a keyway a key drives on the side it drives, where the
    stress is the contact's: the pressure's edge at the key's chamfer, 0.5 mm above a 0.4
    mm corner, raised the paper shaft's corner below it to 25 times the nominal stress,
    and the corner 2.5 mm round the end beyond the pressure's end to 10 times; the key's
    fit and tilt decide it."""
    from shaftfem.fem.stress import key_bearings

    out = np.zeros(len(points), dtype=bool)
    bearing = key_bearings(scene)
    for k, yk, inside in _keyway_pockets(scene, points):
        for kb in bearing:
            if kb.keyway == k:
                # the half the key drives: its flank, the floor's corner below it and
                # that half of each end (the contact's own stress)
                inside &= ~(kb.side * yk > 0)
        out |= inside
    return out


def _keyway_pockets(scene: Scene, points: np.ndarray
                    ) -> list[tuple[Keyway, np.ndarray, np.ndarray]]:
    """Each keyway, the points' place across it (cad.outline.keyway_frame) and which of
    them lie inside its pocket (below the surface by 5 % of its depth); none on a STEP
    solid."""
    from shaftfem.cad.outline import keyway_frame

    if scene.shaft.step is not None:
        return []
    r, z = np.hypot(points[:, 0], points[:, 1]), points[:, 2]
    out = []
    for k in scene.shaft.keyways:
        radius = scene.shaft.radius_at(0.5 * (k.start + k.end))
        if radius is None:
            continue
        xk, yk = keyway_frame(k, points[:, 0], points[:, 1])
        tol = 0.02 * k.width
        out.append((k, yk, (z > k.start - tol) & (z < k.end + tol) & (xk > 0)
                    & (np.abs(yk) < k.width / 2 + tol) & (r < radius - 0.05 * k.depth)))
    return out


def _owned(scene: Scene, points: np.ndarray) -> list[np.ndarray]:
    """The places a designer names and asks about, each judged by its own worst point
    however far below the shaft's worst it lies: each keyway's two halves along the axis
    (its ends: a whole mesh coarser than their corners puts its worst at either), each
    groove runout (between the grooved zone's end and the runout's, below the surface by
    5 % of the depth)."""
    z = points[:, 2]
    out = []
    for k, _, inside in _keyway_pockets(scene, points):
        mid = 0.5 * (k.start + k.end)
        out += [inside & (z < mid), inside & (z >= mid)]
    g = scene.grooves
    radius = None if g is None else scene.shaft.radius_at(g.start + 0.5 * g.length)
    if g is not None and radius is not None:
        below = np.hypot(points[:, 0], points[:, 1]) < radius - 0.05 * g.depth
        out += [below & (z > z0) & (z < z1) for z0, z1 in g.runouts]
    return out


def _maxima(field: _Field, values: np.ndarray, allowed: np.ndarray,
            round_: np.ndarray) -> list[int]:
    """Local maxima of `values` on the surface, largest first: points with no larger
    value within SPACING local radii (along the axis where the shaft is of revolution
    about them, `round_`: there the turning cycle is the same all round), down to SHARE
    of the largest."""
    from scipy.spatial import cKDTree

    idx = np.flatnonzero(allowed)
    if idx.size == 0:
        return []
    pts = field.points[idx]
    # along the axis alone where round: (z, 0, 0); elsewhere in space
    off = (~round_[idx]).astype(float)
    where = np.column_stack([pts[:, 2], pts[:, 0] * off, pts[:, 1] * off])
    tree = cKDTree(where)
    r = np.hypot(pts[:, 0], pts[:, 1])
    v = values[idx]
    top = float(v.max())
    taken: list[int] = []
    for k in np.argsort(-v):
        if v[k] < SHARE * top or len(taken) >= MAX_SPOTS:
            break
        near = tree.query_ball_point(where[k], SPACING * max(float(r[k]), 1e-3))
        i = int(idx[k])
        if v[near].max() <= v[k] and _clear_of(field, i, taken, round_):
            taken.append(i)
    return taken


def _locally_round(scene: Scene, points: np.ndarray) -> np.ndarray:
    """Whether the shaft is of revolution about each surface point: everywhere on a
    shaft of revolution; on a keyed or grooved one, farther along the axis than a
    keyway's or groove's width from it; nowhere on a STEP solid."""
    if scene.axisymmetric:
        return np.ones(len(points), dtype=bool)
    if scene.shaft.step is not None:
        return np.zeros(len(points), dtype=bool)
    z = points[:, 2]
    spans = [(k.start - k.width, k.end + k.width) for k in scene.shaft.keyways]
    g = scene.grooves
    if g is not None:
        spans.append((g.cut[0] - g.width, g.cut[1] + g.width))
    out = np.ones(len(points), dtype=bool)
    for z0, z1 in spans:
        out &= (z < z0) | (z > z1)
    return out


def _apart(p: np.ndarray, q: np.ndarray, round_: bool) -> float:
    """How far apart two surface points are (m): along the axis where the shaft is of
    revolution about both, else in space."""
    return float(abs(p[2] - q[2])) if round_ else float(np.linalg.norm(p - q))


def _clear_of(field: _Field, i: int, taken: list[int], round_: np.ndarray) -> bool:
    """Whether surface point i lies more than SPACING local radii from every point
    taken (along the axis where the shaft is of revolution about both)."""
    p = field.points[i]
    gap = SPACING * float(np.hypot(p[0], p[1]))
    return all(_apart(p, field.points[j], bool(round_[i] and round_[j])) > gap
               for j in taken)


def _spots(scene: Scene, fine: _Field, coarse: _Field, before: list[HotSpot] | None,
           earlier: Sequence[list[HotSpot]] = ()) -> list[HotSpot]:
    """The fine mesh's hot spots, each bounded against the coarse mesh and judged;
    before: the last round's spots, earlier: the rounds' before it (the newest first)."""
    st = scene.strength
    assert st is not None
    allowed = fine.allowed
    turning = st.speed > 0
    round_ = scene.axisymmetric
    local = _locally_round(scene, fine.points)
    picks = _maxima(fine, fine.amplitude if turning else fine.peak, allowed, local)
    for i in _maxima(fine, fine.peak, allowed, local):
        if _clear_of(fine, i, picks, local):
            picks.append(i)
    # every keyway's end and groove runout is judged, however far below the worst spots
    # it lies: its own worst
    owned = [np.flatnonzero(inside & allowed) for inside in _owned(scene, fine.points)]
    for values in ((fine.amplitude, fine.peak) if turning else (fine.peak,)):
        for own in (o for o in owned if o.size):
            i = int(own[np.argmax(values[own])])
            if _clear_of(fine, i, picks, local):
                picks.append(i)
    # a pick taken round its circle to the last round's spot there: that spot
    followed: dict[int, HotSpot] = {}
    if round_ and before:
        # taken round their circles, two picks may land on one spot: each spot once
        moved: list[int] = []
        governing = fine.amplitude if turning else fine.peak
        # (a shaft of revolution is round about every point: `local` is all True)
        for i, old in (_round_the_circle(before, fine, i, governing, turning) for i in picks):
            if _clear_of(fine, i, moved, local):
                moved.append(i)
                if old is not None:
                    followed[i] = old
        picks = moved
    spots = []
    for i in picks:
        # the stress that governs the spot: its amplitude on a turning shaft, unless the
        # steady stress dwarfs it (a torsion-only span), then its peak
        cyclic = turning and fine.amplitude[i] >= 0.1 * fine.peak[i]
        value = fine.amplitude if cyclic else fine.peak
        difference, bound, aim = _two_meshes(fine, coarse, i, cyclic)
        converging, rising = True, False
        turn = _edge_turn(fine, i)
        old = followed.get(i) or _same_spot(before or [], fine, i, round_)
        was = 0.0 if old is None else (old.amplitude if cyclic else old.peak)
        if old is not None and old.difference is not None:
            # P2 stresses at a smooth notch converge as h^2: refined s times, the change
            # shrinks s^2 times; at a sharp edge the stress grows as h^-0.46 (a
            # right-angled re-entrant corner, Williams), the change shrinking by less
            # than s: rising with an apparent order below 1 where the surface turns
            # concavely by more than SHARP within an element ...
            change, before_change = value[i] - was, old.difference * was
            s_ = max(old.size / max(float(fine.edge[i]), 1e-12), 1.0)
            rising = (change > 0 and difference is not None
                      and change > before_change / s_ and turn > SHARP)
            # ... at two rounds running: a notch the last mesh did not resolve turns and
            # rises so too, once, and then refines into a smooth one
            converging = old.converging and not (rising and old.rising)
        if bound is None and value[i] > 0:
            # the mesh here is as before (this round refined elsewhere): the truth lies
            # within the old bound of the old value, so within this of the new one; the
            # spot's own last round first, else the newest earlier round that bounded it
            # (a spot hopping between a groove's two like fillets, round after round)
            # (lazily: the earlier rounds are searched only while none has lent a bound)
            lenders = chain([old], (_earlier_spot(e, fine, i, value, turning, round_)
                                    for e in earlier))
            for spot in lenders:
                if spot is not None and spot.bound is not None:
                    then = spot.amplitude if cyclic else spot.peak
                    bound = float((abs(value[i] - then) + spot.bound * then) / value[i])
                    break
        spots.append(_hot_spot(scene, fine, i, bound=bound, difference=difference,
                               converging=converging, resolved=turn <= RESOLVED,
                               rising=rising, aim=aim))
    spots.sort(key=lambda s: -_utilisation(s))
    return _per_circle(spots)


def _two_meshes(fine: _Field, coarse: _Field, i: int, cyclic: bool
                ) -> tuple[float | None, float | None, float | None]:
    """At the fine mesh's surface point i, for the stress that governs it (the amplitude,
    `cyclic`, else the peak): the two meshes' difference (_bound), the bound and the
    error the next refinement aims from (HotSpot's `difference`, `bound`, `aim`)."""
    value = fine.amplitude if cyclic else fine.peak
    # how far each of the coarser mesh's surface points lies from the spot (m)
    d_coarse = np.linalg.norm(coarse.points - fine.points[i], axis=1)
    difference = _bound(fine, coarse, i, value, coarse.amplitude if cyclic else coarse.peak,
                        d_coarse)
    # two meshes can agree by chance (the peak falls between vertices differently on
    # each): P2's surface stress in a notch of radius rho is off by up to about 1.7
    # (h / rho)^2 (benchmarks/notch_factors.py), so the bound is at least
    # CURVATURE_ERROR (h / rho)^2
    curvature = CURVATURE_ERROR * (float(fine.edge[i]) * _concave(fine, i)) ** 2
    # ... and the spot's vertex scatter on top: both meshes' spots are read high by
    # their own (a stress the same all round a fillet's circle: its largest vertex)
    scatter = _scatter(fine, i, value)
    bound = None if difference is None else max(difference, curvature) + scatter
    aim = (curvature + scatter if _edge_turn(coarse, int(np.argmin(d_coarse))) > RESOLVED
           else None)
    return difference, bound, aim


def _hot_spot(scene: Scene, field: _Field, i: int, **state: Any) -> HotSpot:
    """Surface point i of a field as a hot spot, judged by FKM; `state`: its bound and
    how its refinement stands (HotSpot's fields from `bound` on)."""
    from shaftfem.checks.fkm import assess

    st = scene.strength
    assert st is not None
    p = field.points[i]
    gradient = _gradient(field, i, st.speed > 0)
    diameter = 2 * _outer_radius(field, p[2])
    feature, step = _feature(scene, p, diameter / 2)
    fkm = assess(float(field.amplitude[i]), float(field.mean[i]), float(field.peak[i]),
                 gradient, diameter, st)
    return HotSpot(z=float(p[2]), angle=float(math.atan2(p[1], p[0])),
                   radius=float(np.hypot(p[0], p[1])), feature=feature,
                   amplitude=float(field.amplitude[i]), mean=float(field.mean[i]),
                   peak=float(field.peak[i]), gradient=gradient, diameter=diameter, fkm=fkm,
                   size=float(field.edge[i]), factors=_notch_factors(scene, field, i, step),
                   **state)


# spots kept on one circle about the axis where the shaft is not of revolution about it
# (a keyway within a width of a shoulder, a STEP solid): each vertex round a fillet's
# circle may be a local maximum there
PER_CIRCLE = 2
# two spots of one feature lie on one circle within this share of their radius (along
# the axis and across it)
SAME_CIRCLE = 0.02


def _per_circle(spots: list[HotSpot]) -> list[HotSpot]:
    """The spots (worst first) with at most PER_CIRCLE of one feature on each circle
    about the axis: a hollow keyed shaft's shoulder 10 mm from its keyways' ends listed
    eight round its fillet (60 to 64 MPa), a STEP shaft's shoulder eight (101 to 103
    MPa)."""
    kept: list[tuple[HotSpot, int]] = []   # each kept spot, and how many its circle holds
    out = []
    for s in spots:
        tol = SAME_CIRCLE * s.radius
        for j, (k, n) in enumerate(kept):
            if (k.feature == s.feature and abs(k.z - s.z) < tol
                    and abs(k.radius - s.radius) < tol):
                kept[j] = (k, n + 1)
                if n + 1 > PER_CIRCLE:
                    break
                out.append(s)
                break
        else:
            kept.append((s, 1))
            out.append(s)
    return out


def _round_the_circle(before: list[HotSpot], fine: _Field, i: int, value: np.ndarray,
                      turning: bool) -> tuple[int, HotSpot | None]:
    """On a turning shaft of revolution the cycle is the same all round a circle, and
    its largest value falls where a vertex happens to be: point i taken back round its
    circle to where the last round's spot at its z was (and refined), the largest there.
    So too on a standing one where the stress is the same all round (a torque, an axial
    force: the value there within ROUND of point i's); not where it is not (a standing
    bending load's peak is in its plane). Returns the point and the last round's spot it
    was taken to (None where it was not)."""
    p = fine.points[i]
    r = float(np.hypot(p[0], p[1]))
    old = min(before, key=lambda s: abs(s.z - p[2]) + abs(s.radius - r))
    if abs(old.z - p[2]) + abs(old.radius - r) > max(2 * old.size, 0.05 * r):
        return i, None
    # the largest over the place the last round refined (a bending stress's peak lies in
    # its load's plane, a few degrees from where a coarser vertex found it: read at the
    # old spot's own angle, the spot stayed low by 1 - cos of that)
    # ... but on a turning shaft, where the cycle is the same all round, at the old spot
    # itself (within its own element size, in space): its mesh before is the one its
    # round refined for it, so the two meshes are compared where both are fine, not at
    # the refined place's rim, where the mesh before is coarser than its spot's
    d = _distance(fine.points, replace(old, radius=r), not turning)
    reach = max(old.size if turning else _reach(old.size, r), 2 * float(fine.edge[i]))
    near = np.flatnonzero((d <= reach) & fine.allowed)
    if not near.size:
        return i, None
    j = int(near[np.argmax(value[near])])
    # the point found there is the old spot, however far round it lies within its place
    # (the next round's mesh, refined elsewhere, puts its vertices elsewhere round it)
    return (j, old) if turning or value[j] >= (1 - ROUND) * value[i] else (i, None)


def _earlier_spot(spots: list[HotSpot], fine: _Field, i: int, value: np.ndarray,
                  turning: bool, round_: bool) -> HotSpot | None:
    """An earlier round's spot that surface point i is: taken round its circle on a
    shaft of revolution (_round_the_circle), else the same spot (_same_spot)."""
    if round_ and spots:
        found = _round_the_circle(spots, fine, i, value, turning)[1]
        if found is not None:
            return found
    return _same_spot(spots, fine, i, round_)


def _same_spot(before: list[HotSpot], fine: _Field, i: int, round_: bool
               ) -> HotSpot | None:
    """The last round's hot spot that surface point i is (a spot moves as the mesh
    refines: the same one within two of its old sizes, or a twentieth of the radius;
    on a shaft of revolution, HOOP_REACH times that round the circle), or None."""
    if not before:
        return None
    p = fine.points[i]
    far = [float(_distance(p[None, :], s, round_)[0]) for s in before]
    k = int(np.argmin(far))
    near = max(2 * before[k].size, 0.05 * float(np.hypot(p[0], p[1])))
    return before[k] if far[k] < near else None


def _offsets(field: _Field, i: int) -> tuple[np.ndarray, np.ndarray]:
    """Every surface point's offset from surface point i (m) and its square length."""
    d = field.points - field.points[i]
    return d, np.einsum("ij,ij->i", d, d)


def _edge_turn(field: _Field, i: int) -> float:
    """How far the surface's normal turns (rad) from surface point i to the points within
    1.5 of its element sizes where the surface bends concavely towards them: about 1.5 h /
    rho on a notch of radius rho, half a right angle at a re-entrant edge however fine the
    mesh; nothing on the plain mantle or across a convex edge (two grooves' root fillets
    meeting at a land's corner), whose stress is bounded."""
    d, dist2 = _offsets(field, i)
    near = (dist2 > 0) & (dist2 <= (1.5 * field.edge[i]) ** 2)
    if not near.any():
        return 0.0
    # -(n_j - n_i).(p_j - p_i) > 0 where the surface bends concavely from i towards j
    concave = np.einsum("ij,ij->i", field.normals[near] - field.normals[i], d[near]) < 0
    cos = np.clip(field.normals[near][concave] @ field.normals[i], -1.0, 1.0)
    return float(np.arccos(cos).max()) if concave.any() else 0.0


def _concave(field: _Field, i: int) -> float:
    """The surface's largest concave curvature at surface point i (1/m): a notch's 1 /
    rho, 0 on a plain mantle (convex) and at a convex edge. From the normals' turn
    towards the points within 1.5 element sizes: -(n_j - n_i).(p_j - p_i) / |p_j - p_i|^2
    is the normal curvature along p_j - p_i, positive where the surface is concave."""
    d, dist2 = _offsets(field, i)
    near = (dist2 > 0) & (dist2 <= (1.5 * field.edge[i]) ** 2)
    if not near.any():
        return 0.0
    k = -np.einsum("ij,ij->i", field.normals[near] - field.normals[i], d[near]) / dist2[near]
    return max(float(k.max()), 0.0)


def _scatter(field: _Field, i: int, value: np.ndarray) -> float:
    """How far surface point i's value stands off a smooth fit of its neighbourhood's
    (fraction of it): a quadratic in the surface's tangent coordinates at i, fitted by
    least squares to the values at the surface points within SCATTER_REACH element
    sizes (away from the load bands), |v_i - fit(i)| / v_i; 0 where too few points."""
    if value[i] <= 0:
        return 0.0
    d, dist2 = _offsets(field, i)
    near = np.flatnonzero((dist2 <= (SCATTER_REACH * float(field.edge[i])) ** 2)
                          & field.allowed)
    if near.size < SCATTER_POINTS:
        return 0.0
    n = field.normals[i]
    t1 = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
    t1 /= np.linalg.norm(t1)
    u, v = d[near] @ t1, d[near] @ np.cross(n, t1)
    fit = np.column_stack([np.ones_like(u), u, v, u * u, u * v, v * v])
    c = np.linalg.lstsq(fit, value[near], rcond=None)[0]
    return float(abs(value[i] - c[0]) / value[i])


def _xyz(s: HotSpot) -> np.ndarray:
    return np.array([s.radius * math.cos(s.angle), s.radius * math.sin(s.angle), s.z])


def _bound(fine: _Field, coarse: _Field, i: int, value: np.ndarray,
           coarse_value: np.ndarray, d_coarse: np.ndarray) -> float | None:
    """|sigma_fine - sigma_coarse| / sigma_fine at hot spot i: each mesh's largest value
    near the spot (within twice the larger of the two meshes' element sizes there, away
    from the load bands), the hot spot as each mesh sees it; None where the coarse mesh
    is not MIN_RATIO times coarser there. d_coarse: the coarse mesh's points' distances
    from the spot (m)."""
    if value[i] <= 0:
        return None
    d_fine = np.linalg.norm(fine.points - fine.points[i], axis=1)
    h_coarse = float(coarse.edge[np.argmin(d_coarse)])
    if h_coarse < MIN_RATIO * float(fine.edge[i]):
        # the two meshes are alike here (the spot moved to where the last round did not
        # refine): their agreement says nothing
        return None
    reach = 2 * max(float(fine.edge[i]), h_coarse)
    near_fine = (d_fine <= reach) & fine.allowed
    near_coarse = (d_coarse <= reach) & coarse.allowed
    if not near_coarse.any():
        return None
    here = max(float(value[near_fine].max()), float(value[i]))
    return float(abs(here - coarse_value[near_coarse].max()) / here)


def _gradient(field: _Field, i: int, turning: bool) -> float:
    """FKM's relative stress gradient at surface point i (1/m) (_gradients)."""
    return float(_gradients(field, np.array([i]), turning)[0])


def _gradients(field: _Field, idx: np.ndarray, turning: bool) -> np.ndarray:
    """FKM's relative stress gradient at surface points idx (1/m): the drop of the
    equivalent stress (amplitude; peak on a standing shaft) a quarter element inward,
    over that depth and the surface value; 0 where it cannot be read (no support, on the
    safe side)."""
    from shaftfem.fem.stress import cycle

    k = len(idx)
    depth = 0.25 * field.edge[idx]
    inward = depth[:, None] * field.normals[idx]
    at = field.read(np.vstack([field.points[idx] - 1e-3 * inward, field.points[idx] - inward]))
    tensors = np.moveaxis(at.tensors(field.all_stress), 1, 0)
    amplitude, _, peak = cycle(tensors, turning)
    v = amplitude if turning else peak
    v0, v1 = v[:k], v[k:]
    ok = at.found[:k] & at.found[k:] & (v0 > 0)
    g = (v0 - v1) / (depth * (1 - 1e-3) * np.where(ok, v0, 1.0))
    return np.where(ok, np.maximum(g, 0.0), 0.0)


def _outer_radii(field: _Field) -> np.ndarray:
    """_outer_radius at every surface point (m), read from the largest radius in 0.5 mm
    slices of the axis (within 1 mm, as _outer_radius)."""
    z, r = field.points[:, 2], np.hypot(field.points[:, 0], field.points[:, 1])
    slices = np.floor((z - z.min()) / 0.5e-3).astype(int)
    top = np.zeros(slices.max() + 1)
    np.maximum.at(top, slices, r)
    padded = np.pad(top, 2)
    near = np.max([padded[2 + k: 2 + k + top.size] for k in range(-2, 3)], axis=0)
    return near[slices]


def _outer_radius(field: _Field, z: float) -> float:
    """The shaft's outer radius near z (m): the largest surface radius within 1 mm."""
    near = np.abs(field.points[:, 2] - z) < 1e-3
    return float(np.hypot(field.points[near, 0], field.points[near, 1]).max())


def _feature(scene: Scene, p: np.ndarray, outer: float) -> tuple[str, int | None]:
    """What a hot spot sits on, in a designer's words; and the step it is at (the index
    of the section the step ends), if it sits on a shoulder."""
    r = float(np.hypot(p[0], p[1]))
    z = float(p[2])
    below = outer - r
    g = scene.grooves
    if g is not None and g.cut[0] <= z <= g.cut[1] and below > 0.05 * g.depth:
        if not g.start <= z <= g.start + g.length:
            return "groove runout", None
        return ("groove root" if below > 0.5 * g.depth else "groove flank"), None
    for k in scene.shaft.keyways:
        if not k.start - 1e-3 <= z <= k.start + k.length + 1e-3:
            continue
        end = min(abs(z - k.start), abs(z - k.start - k.length)) < k.width
        if below > 0.05 * k.depth:
            return ("keyway end" if end else "keyway"), None
        # on the mantle at the keyway's rim (where its walls meet the surface, a convex
        # edge whose stress rises beside the end in bending): the keyway's too
        across = abs(-p[0] * math.sin(k.angle) + p[1] * math.cos(k.angle))
        facing = p[0] * math.cos(k.angle) + p[1] * math.sin(k.angle) > 0
        if facing and across <= 0.6 * k.width:
            return ("keyway end, at its rim" if end else "keyway, at its rim"), None
    step = _shoulder(scene, z, outer)
    if step is not None:
        return f"shoulder at {scene.shaft.section_bounds()[step][1] * 1e3:g} mm", step
    return "plain surface", None


def _shoulder(scene: Scene, z: float, outer: float) -> int | None:
    """The step (the index of the section it ends) whose fillet, or a quarter of the
    local radius beyond it, holds z, or None: a large fillet's peak lies near its far
    tangent (a 64/32 mm step's r 5 mm fillet in torsion: 4.1 mm from the step's face)."""
    bounds = scene.shaft.section_bounds() if scene.shaft.profile else []
    profile = scene.shaft.profile
    for k, (_, z1) in enumerate(bounds[:-1]):
        if abs(z - z1) < 0.25 * outer + profile[k].fillet:
            return k
    return None


def _groove_section(scene: Scene, j: int) -> bool:
    """Whether section j is a groove turned into the shaft (a relief groove): larger
    sections on both sides and shorter than its diameter. Peterson's shoulder chart,
    whose smaller shaft runs on, does not hold at its fillets (a 40/35 mm relief groove 4
    mm wide read 2.25 in bending against the shoulder chart's 1.96)."""
    prof = scene.shaft.profile
    if j == 0 or j == len(prof) - 1:
        return False
    s = prof[j]
    return (prof[j - 1].diameter_end > s.diameter_start and prof[j + 1].diameter_start
            > s.diameter_end and s.length < s.diameter_start)


def _notch_factors(scene: Scene, field: _Field, i: int, k: int | None
                   ) -> tuple[NotchFactor, ...]:
    """At a hot spot on a shoulder fillet of a solid shaft (no bore, no keyway or groove
    there), K_t under each load its section carries (a nominal stress at least NOMINAL of
    the spot's peak), beside Peterson's (k: the step's index, None off a shoulder):
    bending from the rotating cases' largest principal stress over the turn, torsion
    from the torque's largest shear, tension from the axial case's largest principal;
    each over the nominal stress of the smaller diameter d from what the section through
    the spot carries."""
    from shaftfem.checks.notch_tables import shoulder_fillet
    from shaftfem.fem.section import resultants

    if k is None:
        return ()
    p = field.points[i]
    prof = scene.shaft.profile
    a, b = prof[k], prof[k + 1]
    if a.bore or b.bore or a.conical or b.conical or a.diameter_end == b.diameter_start:
        return ()
    D, d = max(a.diameter_end, b.diameter_start), min(a.diameter_end, b.diameter_start)
    r = a.fillet
    if r <= 0 or _groove_section(scene, k if a.diameter_end < b.diameter_start else k + 1):
        return ()
    carried = resultants(field.read, field.all_stress, float(p[2]),
                         float(np.hypot(p[0], p[1])))
    if carried is None:
        return ()
    A, B, T, Z = field.stress[:, i]
    c, s = np.cos(_TURN), np.sin(_TURN)
    moment = np.hypot(c * carried[0, 1] - s * carried[1, 1], c * carried[0, 2] - s * carried[1, 2])
    out = []
    nominal = {"bending": 32 * float(moment.max()) / (math.pi * d**3),
               "torsion": 16 * abs(float(carried[2, 3])) / (math.pi * d**3),
               "tension": 4 * abs(float(carried[3, 0])) / (math.pi * d**2)}
    local = {"bending": max(float(np.linalg.eigvalsh(ci * A - si * B)[-1])
                            for ci, si in zip(c, s)),
             "torsion": float(np.ptp(np.linalg.eigvalsh(T))) / 2,
             "tension": float(np.abs(np.linalg.eigvalsh(Z)).max())}
    for load in ("bending", "torsion", "tension"):
        if nominal[load] >= NOMINAL * float(field.peak[i]) and nominal[load] > 0:
            out.append(NotchFactor(load, local[load] / nominal[load],
                                   shoulder_fillet(D, d, r, load), D, d, r))
    return tuple(out)


# --------------------------------------------------------------------------
# Local models. A spot the whole shaft's meshes leave above the target (a notch far
# finer than the elements the whole can afford: the paper shaft's 1 mm root fillets
# where its grooves cross, under 4 mm elements) is bounded in a slice of the solid round
# it, driven by the whole's displacements on its cut faces (fem.submodel) and refined
# there alone, round after round, as a designer refines a submodel in ANSYS. Its bound
# is the two last local meshes' difference, the finer driven by the whole's finest
# mesh and the coarser by its first, coarser one: it holds the cut faces' error too.

# the slice reaches LOCAL_HALF of the whole's elements at the spot to either side, and
# at least LOCAL_RADII of the shaft's radius: the whole's error in how its cut faces
# deform (a self-equilibrated pattern, the faces' resultants being exact) decays along a
# round bar over about its radius (Saint-Venant): on the paper's shaft the crossings'
# bounds were 1.3 to 2.2 % with slices reaching 12 mm to either side, 1.0 to 1.5 % with
# 24 mm (1.5 R). At least LOCAL_LEAST of the whole's elements, clear of every load band,
# else the spot keeps the whole's reading. Its first mesh is LOCAL_FIRST times finer than
# the whole's over LOCAL_SEARCH of the whole's elements round the spot, where its peak is
# looked for; each next mesh is finer round the last one's peak, LOCAL_ROUNDS at most
LOCAL_HALF = 3.0
LOCAL_RADII = 1.5
LOCAL_LEAST = 1.5
LOCAL_FIRST = 4.0
LOCAL_SEARCH = 1.0
LOCAL_ROUNDS = 5
# a cut face's prescribed displacements are the whole's: surface points nearer a cut
# face than this share of the spot's distance from the nearer one are not read
LOCAL_GUARD = 0.5
# at most this many spots get local models, those that may be the worst first
LOCAL_SPOTS = 16


def _localise(scene: Scene, spots: list[HotSpot], fine: _Field, first: _Field, built,
              target: float, options: RunOptions, notes: list[str]) -> list[HotSpot]:
    """The spots, those the whole's meshes leave above the target bounded in local
    models (_localised), the likely worst first; a spot two local models found alike
    once."""
    open_ = [s for s in spots if s.converging
             and (s.bound is None or s.bound > target or not s.resolved)]
    open_ = sorted(open_, key=_upper, reverse=True)[:LOCAL_SPOTS]
    if not open_ or fine.mesh_cells is None or fine.mesh_cells.shape[1] != 10:
        return spots
    options.say(f"hot spot(s) {', '.join(str(spots.index(s) + 1) for s in open_)} bounded "
                f"above {target:.1%} on the whole shaft: bounding them in local models")
    out = []
    for s in spots:
        if s in open_:
            try:
                s = _localised(scene, s, fine, first, built, target, options, notes)
            except (BudgetError, MeshError, SolverError) as e:
                why = f"the local model at {s.z * 1e3:.1f} mm stopped: {e}"
                options.say(why)
                notes.append(why)
        out.append(s)
    out.sort(key=lambda s: -_utilisation(s))
    kept: list[HotSpot] = []
    for s in out:   # two spots whose local models found one peak: that peak once
        if all(np.linalg.norm(_xyz(s) - _xyz(k)) > SPACING * s.radius for k in kept):
            kept.append(s)
    return kept


def _localised(scene: Scene, spot: HotSpot, fine: _Field, first: _Field, built,
               target: float, options: RunOptions, notes: list[str] | None = None
               ) -> HotSpot:
    """The spot bounded in a slice of the solid round it (see LOCAL_HALF), or as it was
    where no slice fits between the load bands (said in `notes`)."""
    placed, shape = built
    st = scene.strength
    assert st is not None
    if shape.brep is None:
        return spot
    # the whole's own element size there (its first mesh is the scene's, COARSER times
    # coarser, never refined), and where it refined, its finest at the spot
    H = float(first.edge[np.argmin(np.linalg.norm(first.points - _xyz(spot), axis=1))]
              ) / COARSER
    h = min(spot.size, H)
    span = _local_span(scene, spot, fine, H)
    if span is None:
        why = (f"no local model for the spot at {spot.z * 1e3:.1f} mm: no slice of the solid "
               "round it fits short of the seats beside it (a slice stops short of every "
               "seat and holds every load band whole); its bound is the whole shaft's, "
               "which a larger [mesh] max_dofs or finer sizes there tighten")
        options.say(why)
        if notes is not None:
            notes.append(why)
        return spot
    z0, z1 = span
    guard = LOCAL_GUARD * min(spot.z - z0, z1 - spot.z)
    radius = float(np.hypot(fine.points[:, 0], fine.points[:, 1]).max())
    cyclic = st.speed > 0 and spot.amplitude >= 0.1 * spot.peak
    centre, size, reach = _xyz(spot), h / LOCAL_FIRST, LOCAL_SEARCH * h
    was, was_size = (spot.amplitude if cyclic else spot.peak), h
    last_change: float | None = None
    last_rising = False
    out = spot
    for _ in range(LOCAL_ROUNDS):
        # a pair of meshes each round, as the whole's: the slice as the scene's settings
        # mesh it, finer round the spot, driven by the whole's finest mesh; and all of
        # it COARSER times coarser, driven by the whole's first
        here, coarser = (_local_field(scene, placed, _local_mesh(
            shape.brep, (z0, z1), radius, centre, size * k, reach, placed, k), (z0, z1),
            driver, guard) for k, driver in ((1.0, fine), (COARSER, first)))
        value = here.amplitude if cyclic else here.peak
        # the peak within the place this round refined (the first round's: one of the
        # whole's elements round its spot): where a stress is the same all round a
        # fillet's circle, the largest vertex elsewhere on it lies where the mesh is
        # coarser, and refining there would only move it round again
        near = np.flatnonzero(here.allowed & (np.linalg.norm(here.points - centre, axis=1)
                                              <= reach))
        if near.size == 0:
            break
        i = int(near[np.argmax(value[near])])
        p = here.points[i]
        difference, bound, aim = _two_meshes(here, coarser, i, cyclic)
        if bound is not None and out.local_dofs:
            # at least as far as the spot moved since the last round: the pump's keyway
            # corner, meshed anew by HXT each round, read 36.3, 34.3 and 36.2 MPa, the
            # last pair of meshes agreeing to 0.2 %
            bound = max(bound, abs(float(value[i]) - was) / float(value[i]))
        turn = _edge_turn(here, i)
        # a sharp edge rises as refined, with an apparent order below 1 (as in _spots)
        change = float(value[i]) - was
        rising = (last_change is not None and change > 0 and turn > SHARP
                  and change > last_change / max(was_size / float(here.edge[i]), 1.0))
        converging = not (rising and last_rising)
        out = _hot_spot(scene, here, i, bound=bound, difference=difference,
                        converging=converging, resolved=turn <= RESOLVED, rising=rising,
                        aim=aim, local_dofs=here.dofs)
        options.say(f"local model at {p[2] * 1e3:.1f} mm ({here.dofs:,} DOFs, "
                    f"{here.edge[i] * 1e3:.3g} mm at the spot): {value[i] / 1e6:.1f} MPa, "
                    + ("bound unknown" if bound is None else f"+-{bound:.1%}"))
        if not converging or (bound is not None and bound <= target and out.resolved):
            break
        error = bound if aim is None else aim
        shrink = SHRINK_MAX if not out.resolved else COARSER if error is None else float(
            np.clip(math.sqrt(error / (AIM * target)), COARSER, SHRINK_MAX))
        was, was_size = float(value[i]), float(here.edge[i])
        last_change, last_rising = change, rising
        centre, size, reach = p, float(here.edge[i]) / shrink, REACH * float(here.edge[i])
    return out


def _local_span(scene: Scene, spot: HotSpot, fine: _Field, H: float
                ) -> tuple[float, float] | None:
    """The slice round a spot (z0, z1), m: LOCAL_HALF of the whole's elements H (m) and
    LOCAL_RADII of its radius to either side, grown to hold whole every load band it
    reaches (a hub, a load's slice, a keyed part's keyway: their loads are applied in
    it as in the whole) and every groove runout, with H to spare, and cut H short of
    every seat's band (where its reaction, the whole's, unknown to the slice, enters; not
    the band widened against the fit's stresses, in which no spot is judged: a shoulder's
    fillet beside a bearing lies there); None where no slice of at least LOCAL_LEAST of H
    either side fits so."""
    seats, loads = _band_kinds(scene, fine.points)
    if scene.grooves is not None:
        # a runout is held whole too: a cut face through it, beside the small faces where
        # it leaves the groove's floor, meshed with facets crossing each other
        loads = loads + list(scene.grooves.runouts)
    z = spot.z
    if any(b0 <= z <= b1 for b0, b1 in seats):
        return None
    half = max(LOCAL_HALF * H, LOCAL_RADII * 0.5 * spot.diameter)
    lo, hi = z - half, z + half
    grown = True
    while grown:
        grown = False
        for b0, b1 in loads:
            if b1 > lo and b0 < hi and (b0 - H < lo or b1 + H > hi):
                lo, hi, grown = min(lo, b0 - H), max(hi, b1 + H), True
    for b0, b1 in (s.seat for s in scene.held if s.kind != "seal"):
        # one of the whole's elements short of it: a cut face on the band's edge would
        # take the whole's nodes there, whose reactions are the seat's, as the section's
        if b1 < z:
            lo = max(lo, b1 + H)
        else:
            hi = min(hi, b0 - H)
    lo, hi = max(lo, 0.0), min(hi, scene.shaft.length)
    if any(b1 > lo and b0 < hi and (b0 < lo or b1 > hi) for b0, b1 in loads):
        return None    # a seat too near a hub: the slice would cut through its band
    if min(z - lo, hi - z) < LOCAL_LEAST * H:
        return None
    return lo, hi


def _local_mesh(brep: Path, span: tuple[float, float], radius: float, centre: np.ndarray,
                size: float, reach: float, placed: Scene, scale: float) -> ShaftMesh:
    """A slice's mesh (cad.local), its elsewhere sizes the scene's times `scale`, from
    the cache where it holds it; refused above the scene's DOF budget."""
    from shaftfem.cad.local import slice_mesh
    from shaftfem.cad.mesh import MESH_ARRAYS, check_mesh_budget, mesh_arrays, mesh_from_arrays
    from shaftfem.store import cache_dir, content_key, discard, load_arrays, save_arrays

    m = placed.mesh
    settings = replace(m, size=m.size * scale, groove_size=m.groove_size * scale,
                       edge_size=m.edge_size * scale)
    key = content_key({"version": 4, "solid": brep.stem, "span": list(span),
                       "radius": radius, "centre": [float(c) for c in centre], "size": size,
                       "reach": reach, "grading": GRADING, "settings": vars(settings),
                       "hubs": [list(b) for b in placed.hubs()]})
    path = cache_dir() / "strength" / "local" / f"{key}.npz"
    fields, why = load_arrays(path, MESH_ARRAYS) if path.exists() else (None, "")
    if fields is None and why:
        discard(f"local mesh {path.stem}", why, path)
    if fields is not None:
        mesh = mesh_from_arrays(fields)
    else:
        mesh = slice_mesh(brep, span[0], span[1], radius, centre, size, reach, GRADING,
                          placed.shaft, placed.grooves, settings, placed.hubs())
        save_arrays(path, mesh_arrays(mesh))
    check_mesh_budget(mesh, placed.mesh, placed.max_dofs)
    return mesh


def _local_field(scene: Scene, placed: Scene, mesh: ShaftMesh, span: tuple[float, float],
                 driver: _Field, guard: float) -> _Field:
    """A slice's duty driven on its cut faces by the whole's solution `driver`, from the
    cache where it holds it; the surface points within `guard` (m) of a cut face, and
    in the bands where loads enter, not read."""

    from scipy.spatial import cKDTree

    from shaftfem.fem.stress import cycle
    from shaftfem.store import cache_dir, content_key, discard, load_arrays, save_arrays

    key = content_key({"version": 6, "mesh": _mesh_digest(mesh), "driver": driver.key,
                       "span": list(span)})
    path = cache_dir() / "strength" / "local" / f"{key}.fields.npz"
    fields, why = load_arrays(path, SURFACE_ARRAYS) if path.exists() else (None, "")
    if fields is None and why:
        discard(f"local duty {path.stem}", why, path)
    if fields is None:
        fields = _local_solved(placed, mesh, span, driver)
        save_arrays(path, fields)
    z = fields["points"][:, 2]
    length = placed.shaft.length
    allowed = (((z >= span[0] + guard) | (span[0] <= 1e-9))
               & ((z <= span[1] - guard) | (span[1] >= length - 1e-9))
               & ~_excluded(scene, fields["points"]))
    assert scene.strength is not None
    amplitude, mean, peak = cycle(fields["stress"], scene.strength.speed > 0)
    empty = np.zeros(0)
    return _Field(points=fields["points"], normals=fields["normals"], edge=fields["edge"],
                  stress=fields["stress"], amplitude=amplitude, mean=mean, peak=peak,
                  all_stress=fields["all_stress"], vertices=fields["vertices"],
                  tets=fields["tets"], facets=fields["facets"], allowed=allowed,
                  line=(empty, empty, empty), dofs=int(fields["dofs"]),
                  tree=cKDTree(fields["vertices"][fields["tets"]].mean(axis=1)))


# the slice's held face reacts as the whole carries across it, within this share of the
# largest force and moment the whole carries there (the whole's sum at its nodes beyond
# the plane leaves out gravity on an element's share: 0.4 % of the weight's 3 N on the
# paper's crossings; a band's load the slice missed would be all of it)
BALANCE = 1e-2


def _check_balance(K, F: np.ndarray, q: np.ndarray, dofs: np.ndarray, points: np.ndarray,
                   z: float, driver: _Field, beyond: bool, other: np.ndarray) -> None:
    """The held face's reaction on the slice (force, moment about (0, 0, z); the slice
    `beyond` z or before it) against what the whole (`driver`) carries across it, in
    each case: a slice whose own loads are
    not the whole's there is refused (SolverError)."""
    from shaftfem.fem.submodel import carried

    r = (K @ q - F)[dofs]                      # (3 k, cases): the face's nodal reactions
    cases = r.shape[1]
    arm = points - np.array([0.0, 0.0, z])
    assert driver.node_xyz is not None and driver.node_force is not None
    # what the whole beyond z exerts on the part before it; on the slice, if it lies
    # beyond z, the opposite
    want = carried(driver.node_xyz, driver.node_force, z) * (-1.0 if beyond else 1.0)
    fr = r.T.reshape(cases, -1, 3)
    got = np.concatenate([fr.sum(axis=1), np.cross(arm, fr).sum(axis=1)], axis=1)
    # a force against the forces and the moments over the face's radius (a span in pure
    # bending carries no shear), a moment against both the other way; at both faces
    # (`other`: what the whole carries across the slice's other end, if it has one): a
    # face the whole loads with little but gravity (a coupling's free end) reads that
    # little against the slice's own loads
    radius = float(np.hypot(arm[:, 0], arm[:, 1]).max())
    both = np.vstack([want, other])
    force, moment = float(np.abs(both[:, :3]).max()), float(np.abs(both[:, 3:]).max())
    for part, scale in ((slice(0, 3), max(force, moment / radius, 1e-9)),
                        (slice(3, 6), max(moment, force * radius, 1e-9))):
        off = float(np.abs(got[:, part] - want[:, part]).max())
        if off > BALANCE * scale:
            what = "force" if part.start == 0 else "moment"
            raise SolverError(f"a local model at {z * 1e3:.1f} mm does not balance as the "
                              f"whole shaft does: its cut face's {what} is off by "
                              f"{off / scale:.1%} of what the whole carries there")


def _dof_columns(u: np.ndarray) -> np.ndarray:
    """Displacements (cases, k, 3) as DOF columns (3 k, cases)."""
    return np.moveaxis(u, 0, -1).reshape(-1, u.shape[0])


def _local_solved(placed: Scene, mesh: ShaftMesh, span: tuple[float, float],
                  driver: _Field) -> dict[str, np.ndarray]:
    """The slice's four cases, its cut faces driven by the whole's solution `driver`."""
    from shaftfem.fem.assembly import _element, assemble
    from shaftfem.fem.installation import install
    from shaftfem.fem.stress import duty_loads, load_band, surface_stress
    from shaftfem.fem.submodel import (
        carried,
        driven_solve,
        read_displacements,
        reduced_dofs,
        rigid_motions,
    )

    d = driver
    assert (d.mesh_points is not None and d.mesh_cells is not None and d.point_u is not None
            and d.node_xyz is not None and d.node_force is not None)
    system = assemble(mesh, placed.material)
    nodes = system.nodes
    skmesh = mesh.to_skfem()
    element = _element(system.order)
    length = placed.shaft.length
    # the slice's own loads (those whose bands it holds, _local_span) and parts, as the
    # whole applies them; no seat
    inside = [(f.position, f.width) for f in placed.forces] + [
        (q.position, q.width) for q in placed.torques]
    bands = [load_band(z, w, nodes) for z, w in inside]
    within = [span[0] < 0.5 * (b.z0 + b.z1) < span[1] for b in bands]
    n_f = len(placed.forces)
    own = replace(placed, supports=(),
                  forces=tuple(f for f, w in zip(placed.forces, within[:n_f]) if w),
                  torques=tuple(q for q, w in zip(placed.torques, within[n_f:]) if w),
                  attachments=tuple(a for a in placed.attachments
                                    if span[0] < 0.5 * (a.seat[0] + a.seat[1]) < span[1]))
    inst = install(own, system.K, system.M, nodes, skmesh, system.order)
    F, _ = duty_loads(own, system, inst, skmesh, element)
    faces = [np.abs(nodes[:, 2] - z) < 1e-9 for z, inner in
             ((span[0], span[0] > 1e-9), (span[1], span[1] < length - 1e-9)) if inner]
    # with two cut faces, the first is held as the whole moves it and the second floats
    # with what the whole carries across it (fem.submodel.driven_solve): the slice's
    # bending and twist are then its own, not the whole's mesh's stiffness
    held = faces[0]
    held_dofs = reduced_dofs(inst.T, held)
    # the whole's field read at both faces' nodes at once (one search of its elements)
    at = np.vstack([nodes[f] for f in faces])
    u = read_displacements(d.mesh_points, d.mesh_cells, d.point_u, at)
    k = int(held.sum())
    u_held = _dof_columns(u[:, :k])
    other = np.zeros((F.shape[1], 6))
    if len(faces) == 2:
        floating = faces[1]
        other = carried(d.node_xyz, d.node_force, span[1])
        q = driven_solve(inst.K, F, held_dofs, u_held, reduced_dofs(inst.T, floating),
                         _dof_columns(u[:, k:]),
                         rigid_motions(nodes[floating], np.array([0.0, 0.0, span[1]])),
                         other)
    else:
        q = driven_solve(inst.K, F, held_dofs, u_held)
    # the held face is the slice's first end (the slice beyond it) unless the slice
    # starts at the shaft's end
    first_end = span[0] > 1e-9
    _check_balance(inst.K, F, q, held_dofs, nodes[held], span[0] if first_end else span[1],
                   d, first_end, other)
    return _surface_arrays(surface_stress(skmesh, element, placed.material.lame,
                                          np.asarray(inst.T @ q)), system.n_dofs)


def _surface_arrays(surface, n_dofs: int) -> dict[str, np.ndarray]:
    """A solution's surface stresses (fem.stress.SurfaceStress) and its vertex field's
    mesh as the named arrays of a cache entry (SURFACE_ARRAYS), with its DOFs."""
    p1 = surface.p1_basis.mesh
    return {"points": surface.points, "normals": surface.normals, "edge": surface.edge,
            "stress": surface.stress, "all_stress": surface.all_stress,
            "vertices": np.ascontiguousarray(p1.p.T), "tets": np.ascontiguousarray(p1.t.T),
            "facets": surface.facets, "dofs": np.array(n_dofs)}


def _seats(scene: Scene, field: _Field) -> tuple[SeatCheck, ...]:
    """The slope and deflection of the standing loads' deflection line at each bearing
    seat and at each part with limits."""
    z, x, y = field.line
    sx, sy = np.gradient(x, z), np.gradient(y, z)
    out = []
    for s in scene.held:
        limit = s.slope_limit if s.slope_limit is not None else SLOPE_LIMITS.get(s.kind)
        source = "given" if s.slope_limit is not None else (
            SLOPE_SOURCE if limit is not None else "not judged")
        out.append(SeatCheck(s.name, s.position,
                             float(np.hypot(np.interp(s.position, z, sx),
                                            np.interp(s.position, z, sy))),
                             float(np.hypot(np.interp(s.position, z, x),
                                            np.interp(s.position, z, y))),
                             limit, None, source))
    for a in scene.attachments:
        out.append(SeatCheck(a.name, a.position,
                             float(np.hypot(np.interp(a.position, z, sx),
                                            np.interp(a.position, z, sy))),
                             float(np.hypot(np.interp(a.position, z, x),
                                            np.interp(a.position, z, y))),
                             a.slope_limit, a.deflection_limit,
                             "given" if a.slope_limit or a.deflection_limit else "not judged"))
    return tuple(out)
