"""Scene files: a shaft, its material, its grooves and its mesh, read from TOML.

A scene file is written in the units designers use (mm, MPa, kg/m^3, kW, r/min);
every key names its unit. `load_scene` checks every value and returns a `Scene`
in SI units (m, Pa, kg/m^3, W, rad/s), which is all the solver ever sees.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from .errors import SceneError

GEOMETRY_DIR = Path(__file__).resolve().parents[2] / "geometry"
DEFAULT_SCENE = "paper2018"

MM = 1e-3
MPA = 1e6


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
    required_margin: float = 0.15  # resonance separation margin, fraction
    raw: dict = field(default_factory=dict, repr=False, compare=False)


# --------------------------------------------------------------------------
# The schema: every key, its unit, what it must satisfy.


@dataclass(frozen=True)
class Key:
    kind: type | tuple  # float, int, str, or ("list", str)
    doc: str
    check: Callable[[Any], bool] | None = None
    allowed: str = ""
    default: Any = None
    required: bool = True


def _positive(v: float) -> bool:
    return v > 0


SCHEMA: dict[str, dict[str, Key]] = {
    "": {
        "name": Key(str, "short name of the scene", required=False),
        "description": Key(str, "free text", required=False),
    },
    "shaft": {
        "length_mm": Key(float, "overall shaft length, mm", _positive, "> 0"),
        "diameter_mm": Key(float, "outer diameter, mm", _positive, "> 0"),
    },
    "material": {
        "name": Key(str, "material name", required=False, default="steel"),
        "youngs_modulus_mpa": Key(float, "Young's modulus E, MPa", _positive, "> 0"),
        "poisson_ratio": Key(
            float, "Poisson's ratio", lambda v: -1.0 < v < 0.5, "in (-1, 0.5)"
        ),
        "density_kg_m3": Key(float, "density, kg/m^3", _positive, "> 0"),
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
        "pitch_mm": Key(float, "helix pitch (lead), mm", _positive, "> 0"),
        "width_mm": Key(float, "groove width along the shaft axis, mm", _positive, "> 0"),
        "depth_mm": Key(float, "groove depth, mm", _positive, "> 0"),
        "root_radius_mm": Key(
            float, "fillet radius at the groove's floor corners, mm (0 = sharp)",
            lambda v: v >= 0, ">= 0", default=0.0, required=False,
        ),
        "grooved_length_mm": Key(float, "axial length of the grooved zone, mm", _positive, "> 0"),
        "start_mm": Key(
            float, "distance from the shaft's left end to the grooved zone, mm "
            "(default: the zone is centred)", lambda v: v >= 0, ">= 0", required=False,
        ),
    },
    "excitation": {  # an array of tables: [[excitation]]
        "name": Key(str, "name of the source, e.g. engine"),
        "speed_rpm": Key(float, "speed of the source, r/min (f = n / 60 Hz)", _positive, "> 0"),
        "orders": Key(("list", int), "harmonic orders that excite, e.g. [1, 2]",
                      lambda v: len(v) >= 1 and all(k >= 1 for k in v), "integers >= 1",
                      default=[1], required=False),
    },
    "sizing": {  # the paper's screw sizing, equations (1)-(9); see shaftfem.sizing
        "power_kw": Key(float, "power through the shaft, kW", _positive, "> 0"),
        "speed_rpm": Key(float, "shaft speed n, r/min", _positive, "> 0"),
        "friction_coefficient": Key(float, "friction coefficient f of the groove pair",
                                    lambda v: 0 < v < 1, "in (0, 1)"),
        "lead_angle_deg": Key(float, "helix lead angle lambda, deg", lambda v: 0 < v < 90,
                              "in (0, 90)"),
        "pressure_angle_deg": Key(float, "groove pressure angle alpha, deg",
                                  lambda v: 0 < v < 90, "in (0, 90)"),
        "allowable_pressure_angle_deg": Key(
            float, "largest pressure angle before self-locking, deg", lambda v: 0 < v < 90,
            "in (0, 90)", default=38.0, required=False),
        "allowable_pressure_mpa": Key(float, "allowable bearing pressure P_p, MPa", _positive,
                                      "> 0"),
        "psi": Key(float, "nut-height factor psi", _positive, "> 0"),
        "keyways": Key(int, "keyways in the section: 0, 1 or 2 (180 deg apart)",
                       lambda v: v in (0, 1, 2), "0, 1 or 2", default=0, required=False),
        "rounding_step_mm": Key(float, "the diameter is rounded up to a multiple of this, mm",
                                _positive, "> 0", default=1.0, required=False),
        "crest_clearance_mm": Key(float, "crest clearance a_c, mm", lambda v: v >= 0, ">= 0"),
        "feed_step_mm": Key(float, "box feed step b per pick, mm", _positive, "> 0"),
        "picks_per_row": Key(int, "picks per row n", lambda v: v >= 2, ">= 2"),
        "needle_width_mm": Key(float, "needle width h, mm", lambda v: v >= 0, ">= 0"),
        "drive_teeth": Key(int, "teeth on the driving gear Z_drive", lambda v: v >= 1, ">= 1"),
        "driven_teeth": Key(int, "teeth on the driven gear Z_driven", lambda v: v >= 1, ">= 1"),
    },
    "resonance": {
        "required_margin_percent": Key(
            float, "least separation |f - k f_exc| / (k f_exc) between a mode and an "
            "excitation harmonic, % (default 15)", lambda v: 0 < v < 100, "in (0, 100)",
            default=15.0, required=False),
    },
    "mesh": {
        "element_size_mm": Key(float, "element size away from the grooves, mm", _positive, "> 0"),
        "groove_element_size_mm": Key(
            float, "element size in the grooved zone, mm (default: element_size_mm / 2)",
            _positive, "> 0", required=False,
        ),
        "edge_element_size_mm": Key(
            float, "element size at the groove's inner floor edges, mm "
            "(default: the root radius, or groove size / 3 for sharp corners)",
            _positive, "> 0", required=False,
        ),
        "order": Key(int, "element order: 1 (P1) or 2 (P2)", lambda v: v in (1, 2), "1 or 2",
                     default=2, required=False),
    },
}



def _where(source: str, table: str, key: str) -> str:
    return f"{source}: {table + '.' if table else ''}{key}"


def _coerce(source: str, table: str, key: str, spec: Key, value: Any) -> Any:
    where = _where(source, table, key)
    if spec.kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SceneError(f"{where} = {value!r}: expected a number ({spec.doc})")
        value = float(value)
        if not math.isfinite(value):
            raise SceneError(f"{where} = {value!r}: expected a finite number ({spec.doc})")
    elif spec.kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise SceneError(f"{where} = {value!r}: expected an integer ({spec.doc})")
    elif spec.kind is str:
        if not isinstance(value, str):
            raise SceneError(f"{where} = {value!r}: expected a string ({spec.doc})")
    elif isinstance(spec.kind, tuple) and spec.kind[0] == "list":
        if not isinstance(value, list) or not all(isinstance(v, spec.kind[1]) for v in value):
            raise SceneError(f"{where} = {value!r}: expected a list ({spec.doc})")
    if spec.check is not None and not spec.check(value):
        raise SceneError(f"{where} = {value!r}: must be {spec.allowed} ({spec.doc})")
    return value


def validate_table(source: str, table: str, data: Any, schema: dict[str, Key]) -> dict:
    """Check one table against its schema; return it with defaults filled in."""
    if not isinstance(data, dict):
        raise SceneError(f"{source}: [{table}] must be a table")
    out = {}
    for key, value in data.items():
        if table == "" and key in SCHEMA and key:
            continue  # sub-tables are checked on their own
        if key not in schema:
            raise SceneError(
                f"{_where(source, table, key)}: unknown key; allowed: {', '.join(schema)}"
            )
        out[key] = _coerce(source, table, key, schema[key], value)
    for key, spec in schema.items():
        if key not in out:
            if spec.required:
                raise SceneError(f"{_where(source, table, key)}: missing ({spec.doc})")
            out[key] = spec.default
    return out


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


def read_toml(path: str | Path, what: str = "file") -> dict:
    """A TOML file as a dict; a missing or malformed file is a SceneError naming it."""
    path = Path(path)
    try:
        return tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise SceneError(f"{what} {str(path)!r}: no such file") from None
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{path.name}: not valid TOML: {exc}") from None


def scene_beside(base: str, file: str | Path) -> str:
    """A scene named in another file (sweep, calibration): a relative .toml path is taken
    relative to that file; a bare name stays a name in geometry/."""
    if not Path(base).is_absolute() and Path(base).suffix == ".toml":
        return str(Path(file).parent / base)
    return base


def load_scene(scene: str | Path | None = None, overrides: dict | None = None) -> Scene:
    """Read and check a scene file; `overrides` maps 'table.key' to a value in file units."""
    path = resolve_scene_path(scene)
    data = read_toml(path, "scene")
    for dotted, value in (overrides or {}).items():
        table, key = dotted.split(".")
        data.setdefault(table, {})[key] = value
    return scene_from_dict(data, source=path.name)


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

    exc = data.get("excitation", [])
    if isinstance(exc, dict):
        exc = [exc]
    if not isinstance(exc, list):
        raise SceneError(f"{source}: excitation must be an array of tables ([[excitation]])")
    excitations = []
    for i, e in enumerate(exc):
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
                f"{_where(source, 'mesh', key)} = {value:g}: must not exceed "
                f"element_size_mm = {size:g}"
            )
    if size > shaft_t["length_mm"]:
        raise SceneError(
            f"{_where(source, 'mesh', 'element_size_mm')} = {size:g}: must not exceed the "
            f"shaft length ({shaft_t['length_mm']:g} mm)"
        )
    mesh = MeshSettings(size=size * MM, groove_size=groove_size * MM, edge_size=edge_size * MM,
                        order=mesh_t["order"])
    name = top["name"] or Path(source).stem
    return Scene(name=name, source=source, shaft=shaft, material=material, grooves=grooves,
                 mesh=mesh, excitations=tuple(excitations), sizing=sizing,
                 required_margin=res_t["required_margin_percent"] / 100, raw=data)


def _check_grooves(source: str, g: dict, shaft_t: dict) -> Grooves:
    def fail(key: str, msg: str) -> SceneError:
        return SceneError(f"{_where(source, 'grooves', key)} = {g[key]!r}: {msg}")

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
