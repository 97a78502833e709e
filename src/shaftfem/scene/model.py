"""Scene files: a shaft, its material, its grooves and its mesh, read from TOML.

A scene file is written in the units designers use (mm, MPa, kg/m^3, kW, r/min);
every key names its unit. `load_scene` checks every value and returns a `Scene`
in SI units (m, Pa, kg/m^3, W, rad/s), which is all the solver ever sees.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, replace
from pathlib import Path

from shaftfem.errors import SceneError
from shaftfem.scene.schema import (
    DEFAULT_DAMPING_PERCENT,
    DEFAULT_MARGIN_PERCENT,
    DEFAULT_MAX_DOFS,
    DEFAULT_MODE_COUNT,
    SCHEMA,
    read_toml,
    split_parameter,
    validate_table,
    where,
)

# The scenes shipped with shaftfem: the repository's geometry/ folder, which an
# installed package carries as shaftfem/scenes (pyproject.toml maps one onto the other).
_PACKAGED = Path(__file__).resolve().parents[1] / "scenes"
GEOMETRY_DIR = _PACKAGED if _PACKAGED.is_dir() else Path(__file__).resolve().parents[3] / "geometry"
DEFAULT_SCENE = "paper2018"

MM = 1e-3
MPA = 1e6
# A seat's band must be meshable and mean something: at least SEAT_MIN wide (no bearing
# or hub is narrower) and 1/16 of the element size (the band's faces need elements of
# about its width), and at least SEAT_MIN from another seat, a shaft end or the grooved
# zone, or exactly at it (nearer, the cut leaves a sliver the mesher cannot fill).
SEAT_MIN = 1e-3  # m
SEAT_PER_ELEMENT = 1 / 16


# --------------------------------------------------------------------------
# The SI dataclasses the rest of the pipeline takes.


@dataclass(frozen=True)
class Shaft:
    """A solid round shaft: length and diameter in m."""

    length: float
    diameter: float

    @property
    def radius(self) -> float:
        return 0.5 * self.diameter


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
    The grooves run from z = `start` to z = `start + length`.
    """

    hands: tuple[int, ...]
    pitch: float
    width: float
    depth: float
    root_radius: float
    length: float
    start: float


def cell_type(order: int) -> str:
    """meshio's name of the element: 10-node (P2) or 4-node (P1) tetrahedra."""
    return "tetra10" if order == 2 else "tetra"


@dataclass(frozen=True)
class MeshSettings:
    """Element sizes in m; `order` 1 (P1, linear) or 2 (P2, quadratic)."""

    size: float
    groove_size: float
    edge_size: float
    order: int


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

    @property
    def seat(self) -> tuple[float, float]:
        return self.position - self.width / 2, self.position + self.width / 2


@dataclass(frozen=True)
class Attachment:
    """A rigid part (gear, pulley) fixed on the band z = position -+ width / 2 (m): its
    mass (kg) and its moments of inertia about the axis and a diameter (kg m^2), with
    its centre of mass on the axis at `position`."""

    name: str
    position: float
    width: float
    mass: float
    polar_inertia: float
    diametral_inertia: float

    @property
    def seat(self) -> tuple[float, float]:
        return self.position - self.width / 2, self.position + self.width / 2


@dataclass(frozen=True)
class Scene:
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
    # the supports left off (free-free), their seats kept in the mesh
    hanging_free: bool = False

    @property
    def held(self) -> tuple[Support, ...]:
        """The supports that hold the shaft (none when it hangs free)."""
        return () if self.hanging_free else self.supports

    @property
    def installed(self) -> bool:
        """Whether anything holds the shaft or sits on it (else: free-free, bare)."""
        return bool(self.held or self.attachments)

    def seat_cuts(self) -> tuple[float, ...]:
        """The axial positions (m) where a seat band begins or ends: the mesh follows them."""
        zs = {z for part in self.supports + self.attachments for z in part.seat}
        return tuple(sorted(z for z in zs if 0.0 < z < self.shaft.length))

    def free(self) -> Scene:
        """The same shaft hanging free, on the same mesh: its supports left off (the
        attached parts stay on)."""
        return replace(self, hanging_free=True)


def resolve_scene_path(scene: str | Path | None) -> Path:
    """A scene argument is a path to a .toml file or the name of one in geometry/."""
    if scene is None:
        scene = DEFAULT_SCENE
    p = Path(scene)
    if p.suffix != ".toml" and not p.exists():
        p = GEOMETRY_DIR / f"{scene}.toml"
    if not p.is_file():
        names = sorted(q.stem for q in GEOMETRY_DIR.glob("*.toml"))
        raise SceneError(f"scene {str(scene)!r}: no such file (scenes in geometry/: {', '.join(names)})")
    return p


def scene_beside(base: str, file: str | Path) -> str:
    """A scene named in another file (sweep, calibration): a relative .toml path is taken
    relative to that file; a bare name stays a name in geometry/."""
    if not Path(base).is_absolute() and Path(base).suffix == ".toml":
        return str(Path(file).parent / base)
    return base


@dataclass(frozen=True)
class SceneText:
    """A scene file's content and its name: what travels to a worker that cannot see
    the user's files (a sweep on a cluster)."""

    text: str
    source: str


def read_scene_text(scene: str | Path | SceneText | None = None) -> SceneText:
    """The content of a scene file (a path, or the name of a shipped scene), checked."""
    if isinstance(scene, SceneText):
        return scene
    path = resolve_scene_path(scene)
    read_toml(path, "scene")  # a missing or malformed file is named here
    out = SceneText(text=path.read_text(encoding="utf-8-sig"), source=path.name)
    load_scene(out)  # and a bad value too, before anything is sent anywhere
    return out


def load_scene(scene: str | Path | SceneText | None = None,
               overrides: dict | None = None) -> Scene:
    """Read and check a scene (a file, a shipped scene's name, or a SceneText);
    `overrides` maps 'table.key' (or 'table[i].key' for entry i of a repeated table) to
    a value in file units."""
    if isinstance(scene, SceneText):
        data, source = tomllib.loads(scene.text), scene.source
    else:
        path = resolve_scene_path(scene)
        data, source = read_toml(path, "scene"), path.name
    for dotted, value in (overrides or {}).items():
        table, index, key = split_parameter(dotted) or (None, None, None)
        if table is None:
            raise SceneError(f"{source}: {dotted!r}: not a scene key (table.key or "
                             "table[i].key)")
        spec = SCHEMA.get(table, {}).get(key or "")
        if spec is not None and spec.kind is int and isinstance(value, float) and value.is_integer():
            value = int(value)  # sweep axes and calibration grids carry numbers as floats
        if index is None:
            data.setdefault(table, {})[key] = value
            continue
        entries = _entries_with(source, dotted, data, table, index, "the scene", source)
        data[table] = entries
        entries[index][key] = value
    return scene_from_dict(data, source=source)


def check_entries(source: str, base: SceneText, names: list[str]) -> None:
    """Each 'table[i].key' parameter of a sweep or calibration file names an entry the
    base scene has."""
    data = tomllib.loads(base.text)
    for name in names:
        table, index, _ = split_parameter(name) or (None, None, None)
        if table is not None and index is not None:
            _entries_with(source, name, data, table, index, f"the base scene {base.source}",
                          base.source)


def _entries_with(source: str, name: str, data: dict, table: str, index: int, scene: str,
                  scene_source: str) -> list:
    """The [[table]] entries of a parsed scene, which must include entry `index` (named by
    parameter `name` of file `source`)."""
    entries = _array(scene_source, data, table)
    if index >= len(entries):
        raise SceneError(f"{source}: {name}: {scene} has {len(entries)} [[{table}]] "
                         "table(s), numbered from 0")
    return entries


def scene_from_dict(data: dict, source: str = "<scene>") -> Scene:
    """Check a parsed scene (file units) and convert it to SI."""
    known = set(SCHEMA)
    for table, value in data.items():
        is_table = isinstance(value, dict) or (
            isinstance(value, list) and value and all(isinstance(v, dict) for v in value))
        if is_table and table not in known:
            raise SceneError(
                f"{source}: [{table}]: unknown table; allowed: "
                f"{', '.join(sorted(k for k in known if k))}"
            )
    top = validate_table(source, "", data, SCHEMA[""])
    shaft_t = validate_table(source, "shaft", data.get("shaft", {}), SCHEMA["shaft"])
    mat_t = validate_table(source, "material", data.get("material", {}), SCHEMA["material"])
    mesh_t = validate_table(source, "mesh", data.get("mesh", {}), SCHEMA["mesh"])
    res_t = validate_table(source, "resonance", data.get("resonance", {}), SCHEMA["resonance"])
    modes_t = validate_table(source, "modes", data.get("modes", {}), SCHEMA["modes"])
    sizing = None
    if "sizing" in data:
        sizing = validate_table(source, "sizing", data["sizing"], SCHEMA["sizing"])

    shaft = Shaft(length=shaft_t["length_mm"] * MM, diameter=shaft_t["diameter_mm"] * MM)
    material = Material(
        name=mat_t["name"],
        youngs_modulus=mat_t["youngs_modulus_mpa"] * MPA,
        poisson_ratio=mat_t["poisson_ratio"],
        density=mat_t["density_kg_m3"],
    )

    excitations = []
    for i, e in enumerate(_array(source, data, "excitation")):
        e = validate_table(source, f"excitation[{i}]", e, SCHEMA["excitation"])
        excitations.append(Excitation(name=e["name"], frequency=e["speed_rpm"] / 60.0,
                                      orders=tuple(e["orders"])))

    grooves = None
    if "grooves" in data:
        g = validate_table(source, "grooves", data["grooves"], SCHEMA["grooves"])
        grooves = _check_grooves(source, g, shaft_t)

    size = mesh_t["element_size_mm"]
    groove_size = mesh_t["groove_element_size_mm"] or size / 2
    if mesh_t["edge_element_size_mm"] is not None:
        edge_size = mesh_t["edge_element_size_mm"]
    elif grooves is not None and grooves.root_radius > 0:
        edge_size = min(groove_size, grooves.root_radius / MM)
    else:
        edge_size = groove_size / 3
    for key, value in (("groove_element_size_mm", groove_size), ("edge_element_size_mm", edge_size)):
        if value > size:
            raise SceneError(
                f"{where(source, 'mesh', key)} = {value:g}: must not exceed "
                f"element_size_mm = {size:g}"
            )
    if size > shaft_t["length_mm"]:
        raise SceneError(
            f"{where(source, 'mesh', 'element_size_mm')} = {size:g}: must not exceed the "
            f"shaft length ({shaft_t['length_mm']:g} mm)"
        )
    mesh = MeshSettings(size=size * MM, groove_size=groove_size * MM, edge_size=edge_size * MM,
                        order=mesh_t["order"])
    supports = tuple(_support(source, i, t) for i, t in enumerate(_array(source, data, "support")))
    attachments = tuple(_attachment(source, i, t)
                        for i, t in enumerate(_array(source, data, "attachment")))
    _check_seats(source, shaft, grooves, supports, attachments, mesh)
    resp_t = validate_table(source, "response", data.get("response", {}), SCHEMA["response"])
    point = resp_t["point_mm"]
    if point is not None and point > shaft_t["length_mm"]:
        raise SceneError(f"{where(source, 'response', 'point_mm')} = {point:g}: must lie on the "
                         f"shaft, 0 to {shaft_t['length_mm']:g} mm")
    name = top["name"] or Path(source).stem
    return Scene(name=name, source=source, shaft=shaft, material=material, grooves=grooves,
                 mesh=mesh, excitations=tuple(excitations), sizing=sizing,
                 required_margin=res_t["required_margin_percent"] / 100,
                 modes=ModeRequest(count=modes_t["count"],
                                   max_frequency=modes_t["max_frequency_hz"]),
                 target_error=(None if mesh_t["target_error_percent"] is None
                               else mesh_t["target_error_percent"] / 100),
                 max_dofs=mesh_t["max_dofs"], supports=supports, attachments=attachments,
                 damping_ratio=resp_t["damping_ratio_percent"] / 100,
                 response_point=None if point is None else point * MM,
                 criterion=res_t["criterion"])


def _array(source: str, data: dict, table: str) -> list:
    """An array of tables ([[table]]); a single [table] is taken as one entry."""
    items = data.get(table, [])
    if isinstance(items, dict):
        items = [items]
    if not isinstance(items, list):
        raise SceneError(f"{source}: {table} must be an array of tables ([[{table}]])")
    return items


def _support(source: str, i: int, t: dict) -> Support:
    table = f"support[{i}]"
    t = validate_table(source, table, t, SCHEMA["support"])
    springs = ("radial_stiffness_n_per_mm", "axial_stiffness_n_per_mm",
               "tilting_stiffness_nmm_per_rad")
    if t["kind"] == "springs":
        if t["radial_stiffness_n_per_mm"] is None:
            raise SceneError(f"{where(source, table, 'radial_stiffness_n_per_mm')}: missing "
                             "(kind = \"springs\" needs the bearing's radial stiffness, N/mm)")
    else:
        for key in springs:
            if t[key] is not None:
                raise SceneError(f"{where(source, table, key)} = {t[key]:g}: only with kind = "
                                 f"\"springs\" (this support is {t['kind']!r})")
    if t["kind"] == "clamped" and t["coupling"] == "rigid":
        raise SceneError(f"{where(source, table, 'coupling')} = \"rigid\": a clamped seat "
                         "already holds every point of its band; leave coupling out")
    radial = (t["radial_stiffness_n_per_mm"] or 0.0) * 1e3
    width = t["width_mm"] * MM
    return Support(name=t["name"] or f"support {i + 1}", position=t["position_mm"] * MM,
                   width=width, kind=t["kind"], radial=radial,
                   axial=(t["axial_stiffness_n_per_mm"] or 0.0) * 1e3,
                   tilting=(t["tilting_stiffness_nmm_per_rad"] or 0.0) * 1e-3,
                   coupling=t["coupling"])


def _attachment(source: str, i: int, t: dict) -> Attachment:
    t = validate_table(source, f"attachment[{i}]", t, SCHEMA["attachment"])
    polar, diametral = t["polar_inertia_kg_m2"], t["diametral_inertia_kg_m2"]
    if t["mass_kg"] == 0 and polar + diametral > 0:
        raise SceneError(f"{where(source, f'attachment[{i}]', 'mass_kg')} = 0: a part with "
                         "moments of inertia has a mass")
    if diametral < polar / 2 * (1 - 1e-12):
        raise SceneError(
            f"{where(source, f'attachment[{i}]', 'diametral_inertia_kg_m2')} = {diametral:g}: "
            f"a rigid part's moment about a diameter is at least half its polar moment "
            f"({polar / 2:g} kg m^2; a thin disk has exactly half)")
    return Attachment(name=t["name"] or f"attachment {i + 1}", position=t["position_mm"] * MM,
                      width=t["width_mm"] * MM, mass=t["mass_kg"],
                      polar_inertia=t["polar_inertia_kg_m2"],
                      diametral_inertia=t["diametral_inertia_kg_m2"])


def _check_seats(source: str, shaft: Shaft, grooves: Grooves | None,
                 supports: tuple[Support, ...], attachments: tuple[Attachment, ...],
                 mesh: MeshSettings) -> None:
    """Every seat wide enough to mesh, on the shaft, clear of the grooves, and no two
    seats overlapping; none nearer than SEAT_MIN to an edge it does not sit on."""
    seats = ([(f"support[{i}]", s) for i, s in enumerate(supports)]
             + [(f"attachment[{i}]", a) for i, a in enumerate(attachments)])
    L = shaft.length
    narrowest = max(SEAT_MIN, SEAT_PER_ELEMENT * mesh.size)
    edges = [0.0, L] + ([] if grooves is None else [grooves.start, grooves.start + grooves.length])
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
                f"within {SEAT_MIN / MM:g} mm of {near[0] / MM:g} mm (a shaft end or the "
                "grooved zone): put it exactly there or at least 1 mm away")
        if lo < -1e-12 or hi > L + 1e-12:
            raise SceneError(
                f"{at} = {part.position / MM:g}: the seat {lo / MM:g} to {hi / MM:g} mm "
                f"(width_mm = {part.width / MM:g}) must lie on the shaft, 0 to {L / MM:g} mm")
        if grooves is not None and lo < grooves.start + grooves.length and hi > grooves.start:
            raise SceneError(
                f"{at} = {part.position / MM:g}: the seat {lo / MM:g} to {hi / MM:g} mm lies "
                f"over the grooved zone ({grooves.start / MM:g} to "
                f"{(grooves.start + grooves.length) / MM:g} mm); seats must be on plain shaft")
    ordered = sorted(seats, key=lambda s: s[1].seat[0])
    for (ta, a), (tb, b) in zip(ordered, ordered[1:]):
        # seats that touch would share the nodes of their common edge
        if b.seat[0] < a.seat[1] + SEAT_MIN - 1e-12:
            raise SceneError(
                f"{where(source, tb, 'position_mm')} = {b.position / MM:g}: its seat "
                f"({b.seat[0] / MM:g} to {b.seat[1] / MM:g} mm) overlaps, touches or comes "
                f"within {SEAT_MIN / MM:g} mm of the seat of {ta} ({a.seat[0] / MM:g} to "
                f"{a.seat[1] / MM:g} mm)")


def _check_grooves(source: str, g: dict, shaft_t: dict) -> Grooves:
    def fail(key: str, msg: str) -> SceneError:
        return SceneError(f"{where(source, 'grooves', key)} = {g[key]!r}: {msg}")

    radius = shaft_t["diameter_mm"] / 2
    length = shaft_t["length_mm"]
    if g["depth_mm"] >= radius:
        raise fail("depth_mm", f"must be less than the shaft radius ({radius:g} mm)")
    if g["width_mm"] > g["pitch_mm"] / 2:
        raise fail("width_mm", f"must not exceed half the pitch ({g['pitch_mm'] / 2:g} mm)")
    if g["root_radius_mm"] > min(g["depth_mm"], g["width_mm"] / 2):
        raise fail("root_radius_mm", "must not exceed the depth nor half the width "
                   f"({min(g['depth_mm'], g['width_mm'] / 2):g} mm)")
    if g["grooved_length_mm"] > length:
        raise fail("grooved_length_mm", f"must not exceed the shaft length ({length:g} mm)")
    start = g["start_mm"]
    if start is None:
        start = (length - g["grooved_length_mm"]) / 2
    elif start + g["grooved_length_mm"] > length:
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
    )
