"""Scene files: a shaft, its material, its grooves and its mesh, read from TOML.

A scene file is written in the units designers use (mm, MPa, kg/m^3, kW, r/min);
every key names its unit. `load_scene` checks every value and returns a `Scene`
in SI units (m, Pa, kg/m^3, W, rad/s), which is all the solver ever sees.
"""

from __future__ import annotations

import math
import tomllib
import warnings
from dataclasses import dataclass, replace
from pathlib import Path

from shaftfem.errors import SceneError
from shaftfem.scene.checks import PlausibilityWarning, check_grooves, check_seats, implausible
from shaftfem.scene.model import (
    INLET_LOSS,
    JOURNAL_RATIOS,
    MM,
    AnnularSeal,
    Attachment,
    BearingCoefficients,
    Excitation,
    Grooves,
    JournalBearing,
    JournalBore,
    Material,
    MeshSettings,
    ModeRequest,
    PointForce,
    RollingBearing,
    Rotor,
    Scene,
    Shaft,
    Stage,
    Strength,
    Support,
    Tolerance,
    Torque,
    Unbalance,
)
from shaftfem.scene.profile import shaft_from_tables
from shaftfem.scene.schema import DEFAULT_SPEED_HEADROOM, SCHEMA, TITLE_KEYS
from shaftfem.scene.toml_reading import (
    entry,
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

MPA = 1e6
RPM = 2 * math.pi / 60  # rad/s per r/min



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


def load_scene(scene: str | Path | SceneText | dict | None = None,
               overrides: dict | None = None) -> Scene:
    """Read and check a scene (a file, a shipped scene's name, a SceneText, or a dict
    of the file's tables and keys, in its units) and return it in SI. `overrides` maps
    'table.key' (or 'table[i].key' for entry i of a repeated table) to a value in file
    units. A bad value raises SceneError naming the
    file, the key, the value and what is allowed."""
    folder = None
    if isinstance(scene, dict):
        import copy

        data = copy.deepcopy(scene)
        source = f"scene {data['name']!r}" if isinstance(data.get("name"), str) else "<scene>"
    elif isinstance(scene, SceneText):
        data, source = tomllib.loads(scene.text), scene.source
    else:
        path = resolve_scene_path(scene)
        data, source = read_toml(path, "scene"), path.name
        folder = path.resolve().parent
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
    return scene_from_dict(data, source=source, folder=folder)


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


def scene_from_dict(data: dict, source: str = "<scene>", folder: Path | None = None) -> Scene:
    """Check a parsed scene (file units) and convert it to SI (`folder`: the scene
    file's, where a STEP file it names is looked for)."""
    _check_tables(source, data)
    shaft_raw = data.get("shaft", {})
    if isinstance(shaft_raw, dict) and "section" in shaft_raw:
        raise SceneError(f"{source}: [[shaft.section]]: write the sections as [[section]] "
                         "tables (each with length_mm and diameter_mm, from the left end)")
    t = {name: validate_table(source, name, data.get(name, {}), SCHEMA[name])
         for name in ("shaft", "material", "mesh", "resonance", "modes", "response")}
    top = validate_table(source, "", data, SCHEMA[""])
    sizing = (validate_table(source, "sizing", data["sizing"], SCHEMA["sizing"])
              if "sizing" in data else None)
    shaft_t, mat_t, mesh_t, res_t = t["shaft"], t["material"], t["mesh"], t["resonance"]
    shaft = shaft_from_tables(source, shaft_t, _array(source, data, "section"),
                              _array(source, data, "keyway"), folder)
    if shaft.step is not None:
        if "grooves" in data:
            raise SceneError(f"{source}: [grooves] beside [shaft] step_file: cut the grooves "
                             "in the CAD model instead")
    material = Material(name=mat_t["name"], youngs_modulus=mat_t["youngs_modulus_mpa"] * MPA,
                        poisson_ratio=mat_t["poisson_ratio"], density=mat_t["density_kg_m3"])
    grooves = None
    if "grooves" in data:
        g = validate_table(source, "grooves", data["grooves"], SCHEMA["grooves"])
        grooves = check_grooves(source, g, shaft)
    mesh = _mesh_settings(source, mesh_t, shaft, grooves)
    ranged = [_ranges(source, i, e) for i, e in enumerate(_array(source, data, "support"))]
    supports = tuple(_support(source, i, e) for i, (e, _) in enumerate(ranged))
    rotor = _rotor(source, data, shaft)
    physics = {"journal": _journal, "seal": _seal}
    supports = tuple(physics[s.kind](source, i, e, s, shaft, rotor, r) if s.kind in physics
                     else s for i, ((e, r), s) in enumerate(zip(ranged, supports)))
    attachments = tuple(_attachment(source, i, e)
                        for i, e in enumerate(_array(source, data, "attachment")))
    attachments = tuple(_stage(source, i, e, a, rotor) for i, (e, a) in
                        enumerate(zip(_array(source, data, "attachment"), attachments)))
    attachments = tuple(_keyed_default(a, shaft) for a in attachments)
    check_seats(source, shaft, grooves, supports, attachments, mesh)
    if (rotor is not None and rotor.level1 and rotor.level1_qa is None
            and not any(a.stage is not None for a in attachments)):
        raise SceneError(f"{where(source, 'rotor', 'level1')} = true: the Level I screening "
                         "needs the anticipated cross-coupling Q_A: give [rotor] "
                         "level1_qa_n_per_mm, or a stage's stage_power_kw on an [[attachment]] "
                         "(Wachel's estimate)")
    if mesh.order > 2 and (supports or attachments):
        raise SceneError(f"{where(source, 'mesh', 'order')} = {mesh.order}: cubic elements take "
                         "free shafts only for now; use order 2 with [[support]] or "
                         "[[attachment]] tables")
    point = _response_point(source, t["response"], shaft)
    target = mesh_t["target_error_percent"]
    strength = _strength(source, data, material, rotor, sizing)
    torques = _torques(source, data, shaft, attachments, strength)
    for message in implausible(source, shaft):
        warnings.warn(message, PlausibilityWarning, stacklevel=2)
    scene = Scene(name=top["name"] or Path(source).stem, source=source, shaft=shaft,
                  material=material, grooves=grooves, mesh=mesh,
                  excitations=_excitations(source, data), sizing=sizing,
                  required_margin=res_t["required_margin_percent"] / 100,
                  modes=ModeRequest(count=t["modes"]["count"],
                                    max_frequency=t["modes"]["max_frequency_hz"]),
                  target_error=None if target is None else target / 100,
                  max_dofs=mesh_t["max_dofs"], supports=supports, attachments=attachments,
                  damping_ratio=t["response"]["damping_ratio_percent"] / 100,
                  response_point=None if point is None else point * MM,
                  criterion=res_t["criterion"], free_free_intended=res_t["free_free"],
                  rotor=rotor,
                  unbalances=_unbalances(source, data, shaft, attachments),
                  gravity=_static(source, data), forces=_forces(source, data, shaft, attachments,
                                                                torques),
                  torques=torques,
                  strength=strength,
                  title_block=tuple((k, top[k]) for k in TITLE_KEYS if top[k]),
                  description=top["description"] or "")
    return scene.with_tables(_tables(data, shaft))


def _tables(data: dict, shaft: Shaft) -> dict:
    """The scene's tables as they will be written back: a STEP file by its full path, so
    that the file found it from anywhere."""
    import copy

    tables = copy.deepcopy(data)
    if shaft.step is not None:
        tables["shaft"]["step_file"] = str(Path(shaft.step.path).resolve())
    return tables


def _check_tables(source: str, data: dict) -> None:
    """Every table of the file is one the schema knows."""
    known = set(SCHEMA)
    for table, value in data.items():
        is_table = isinstance(value, dict) or (
            isinstance(value, list) and value and all(isinstance(v, dict) for v in value))
        if is_table and table not in known:
            raise SceneError(
                f"{source}: [{table}]: unknown table; allowed: "
                f"{', '.join(sorted(k for k in known if k))}"
            )


def _excitations(source: str, data: dict) -> tuple[Excitation, ...]:
    out = []
    for i, e in enumerate(_array(source, data, "excitation")):
        e = validate_table(source, entry("excitation", i, e), e, SCHEMA["excitation"])
        out.append(Excitation(name=e["name"], frequency=e["speed_rpm"] / 60.0,
                              orders=tuple(e["orders"])))
    return tuple(out)


def _mesh_settings(source: str, mesh_t: dict, shaft: Shaft, grooves: Grooves | None
                   ) -> MeshSettings:
    """The element sizes (defaults: grooves half the size, their edges a third of that or
    the root radius), none above the element size, which is not above the shaft."""
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
    if shaft.step is None and size > shaft.length / MM:
        raise SceneError(
            f"{where(source, 'mesh', 'element_size_mm')} = {size:g}: must not exceed the "
            f"shaft length ({shaft.length / MM:g} mm)"
        )
    return MeshSettings(size=size * MM, groove_size=groove_size * MM, edge_size=edge_size * MM,
                        order=mesh_t["order"], geometry_order=mesh_t["geometry_order"])


def _response_point(source: str, resp_t: dict, shaft: Shaft) -> float | None:
    """The response point, mm, on the shaft (None: the default)."""
    point = resp_t["point_mm"]
    if point is not None and shaft.step is None and point > shaft.length / MM:
        raise SceneError(f"{where(source, 'response', 'point_mm')} = {point:g}: must lie on the "
                         f"shaft, 0 to {shaft.length / MM:g} mm")
    return point


def _array(source: str, data: dict, table: str) -> list:
    """An array of tables ([[table]]); a single [table] is taken as one entry."""
    items = data.get(table, [])
    if isinstance(items, dict):
        items = [items]
    if not isinstance(items, list):
        raise SceneError(f"{source}: {table} must be an array of tables ([[{table}]])")
    return items


BEARING_KEYS = ("kxx_n_per_mm", "kxy_n_per_mm", "kyx_n_per_mm", "kyy_n_per_mm",
                "cxx_n_s_per_mm", "cxy_n_s_per_mm", "cyx_n_s_per_mm", "cyy_n_s_per_mm")


def _as_lists(t: dict, keys: tuple[str, ...]) -> dict:
    """The table with each of `keys` given as one number made a list of it: such keys
    take one number or a list."""
    if not isinstance(t, dict):
        return t
    return {k: [v] if k in keys and isinstance(v, (int, float)) and not isinstance(v, bool)
            else v for k, v in t.items()}


def _bearing(source: str, table: str, t: dict) -> BearingCoefficients:
    """A bearing's coefficients in SI (N/m, N s/m, rad/s), each a constant or one value
    per entry of speeds_rpm."""
    if t["kxx_n_per_mm"] is None:
        raise SceneError(f"{where(source, table, 'kxx_n_per_mm')}: missing (kind = \"bearing\" "
                         "needs at least its direct stiffness kxx, N/mm)")
    speeds = t["speeds_rpm"] or []
    values: dict[str, list[float]] = {}
    for key in BEARING_KEYS:
        v = t[key]
        if v is None:
            default = {"kyy_n_per_mm": "kxx_n_per_mm", "cyy_n_s_per_mm": "cxx_n_s_per_mm"}
            v = values.get(default.get(key, ""))
            v = [0.0] if v is None else v
        elif len(v) != 1 and len(v) != len(speeds):
            raise SceneError(f"{where(source, table, key)} = {v!r}: give one number, or one "
                             f"value for each of the {len(speeds)} speeds of speeds_rpm")
        values[key] = v
    if len(speeds) > 1 and all(len(values[k]) == 1 for k in BEARING_KEYS):
        raise SceneError(f"{where(source, table, 'speeds_rpm')}: no coefficient is a list; "
                         "give lists of values against these speeds, or leave speeds_rpm out")
    if len(speeds) == 1:   # a table of one speed is constant coefficients
        speeds = []
    # a bearing that holds the shaft one way and not the other leaves it free to slide
    # across: no whirl settles on it (a zero typed for a missing number, most often)
    for a, b in (("kxx_n_per_mm", "kyy_n_per_mm"), ("kyy_n_per_mm", "kxx_n_per_mm")):
        free = [i for i, (x, y) in enumerate(zip(
            values[a] * (len(values[b]) if len(values[a]) == 1 else 1),
            values[b] * (len(values[a]) if len(values[b]) == 1 else 1))) if x > 0 and y == 0]
        if free and t[b] is not None:
            given = t[b][0] if len(t[b]) == 1 else t[b]
            raise SceneError(f"{where(source, table, b)} = {given!r}: the bearing holds the "
                             f"shaft along {a[1]} ({a} > 0) but not along {b[1]}: give its "
                             f"stiffness along {b[1]} too, above 0 N/mm (leave {b} out for "
                             f"the same as {a})")
    per_mm = {k: tuple(x * 1e3 for x in v) for k, v in values.items()}
    return BearingCoefficients(
        speeds=tuple(n * RPM for n in speeds), kxx=per_mm["kxx_n_per_mm"],
        kxy=per_mm["kxy_n_per_mm"], kyx=per_mm["kyx_n_per_mm"], kyy=per_mm["kyy_n_per_mm"],
        cxx=per_mm["cxx_n_s_per_mm"], cxy=per_mm["cxy_n_s_per_mm"],
        cyx=per_mm["cyx_n_s_per_mm"], cyy=per_mm["cyy_n_s_per_mm"])


JOURNAL_KEYS = ("radial_clearance_um", "diameter_mm", "viscosity_mpa_s", "oil_iso_vg",
                "oil_temperature_c", "oil_supply_temperature_c", "pad_temperature_limit_c",
                "oil_flow_l_min",
                "cavitation", "min_film_um")
ROLLING_KEYS = ("elements", "element_diameter_mm", "pitch_diameter_mm", "roller_length_mm",
                "contact_angle_deg", "preload_n")
SEAL_KEYS = ("pressure_drop_mpa", "fluid_density_kg_m3", "inlet_loss")
# the keys each kind of bearing or seal from its physics takes
PHYSICS_KEYS = {"journal": (*JOURNAL_KEYS, "load_n", "load_angle_deg"),
                "seal": ("radial_clearance_um", "diameter_mm", "viscosity_mpa_s", *SEAL_KEYS),
                "ball": ("elements", "element_diameter_mm", "pitch_diameter_mm",
                         "contact_angle_deg", "preload_n", "load_n", "load_angle_deg"),
                "roller": ("elements", "roller_length_mm", "pitch_diameter_mm",
                           "contact_angle_deg", "load_n", "load_angle_deg")}


def _rolling(source: str, table: str, t: dict) -> RollingBearing:
    """A ball or roller bearing as declared: its elements, load and contact angle, SI
    (its coefficients: shaftfem.parts.rolling)."""
    size_key = "element_diameter_mm" if t["kind"] == "ball" else "roller_length_mm"
    preload = t["preload_n"]
    for key in ("elements", size_key, *(("load_n",) if preload is None else ())):
        if t[key] is None:
            raise SceneError(f"{where(source, table, key)}: missing (kind = \"{t['kind']}\" "
                             "needs the number of elements, their "
                             + ("diameter" if t["kind"] == "ball" else "length")
                             + ", mm, and the radial load, N, or an angular-contact ball "
                             "bearing's preload_n)")
    if preload is not None and t["contact_angle_deg"] <= 0:
        raise SceneError(f"{where(source, table, 'preload_n')} = {preload:g}: an axial preload "
                         "needs an angular-contact bearing; give its contact_angle_deg (15 to "
                         "40 deg for a spindle bearing)")
    pitch, d, n = t["pitch_diameter_mm"], t["element_diameter_mm"], t["elements"]
    if pitch is not None and d is not None and n * d >= math.pi * pitch:
        raise SceneError(f"{where(source, table, 'elements')} = {n}: {n} balls of {d:g} mm "
                         f"need {n * d:.1f} mm of a pitch circle {math.pi * pitch:.1f} mm round "
                         f"(pitch_diameter_mm = {pitch:g}): they do not fit")
    return RollingBearing(kind=t["kind"], elements=t["elements"], size=t[size_key] * MM,
                          contact_angle=math.radians(t["contact_angle_deg"]), preload=preload,
                          load=t["load_n"] or 0.0,
                          load_angle=math.radians(t["load_angle_deg"]))


# the keys a journal (all three) or a seal (its clearance) takes as a tolerance range
RANGED = {"journal": ("radial_clearance_um", "oil_temperature_c", "oil_supply_temperature_c",
                      "viscosity_mpa_s"),
          "seal": ("radial_clearance_um",)}


def _ranges(source: str, i: int, raw: dict) -> tuple[dict, dict[str, tuple[float, float, float]]]:
    """A [[support]] table with each key it takes as a tolerance range ([min, max] or
    [min, nominal, max], ascending; RANGED) set to its nominal value (the middle of
    [min, max]), and those ranges (min, nominal, max), each end checked as the key is."""
    if not isinstance(raw, dict):
        return raw, {}
    table = entry("support", i, raw)
    out = dict(raw)
    ranges: dict[str, tuple[float, float, float]] = {}
    for key in RANGED.get(raw.get("kind"), ()):   # type: ignore[arg-type]
        v = raw.get(key)
        if not isinstance(v, list):
            continue
        numbers = all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)
        if len(v) not in (2, 3) or not numbers or list(v) != sorted(v) or v[0] == v[-1]:
            raise SceneError(f"{where(source, table, key)} = {v!r}: give one number, or a "
                             "tolerance range [min, max] or [min, nominal, max], ascending "
                             f"({SCHEMA['support'][key].doc})")
        for x in v:
            validate_table(source, table, {key: float(x)}, {key: SCHEMA["support"][key]})
        lo, hi = float(v[0]), float(v[-1])
        ranges[key] = (lo, float(v[1]) if len(v) == 3 else 0.5 * (lo + hi), hi)
        out[key] = ranges[key][1]
    return out, ranges


# the least radial clearance over the diameter the film is solved for: below it the
# Sommerfeld number runs off the film's tables (a clearance in mm typed as um)
MIN_CLEARANCE_RATIO = 1e-4


def _scaled(span: tuple[float, ...], unit: float) -> tuple[float, float, float]:
    lo, nominal, hi = span
    return lo * unit, nominal * unit, hi * unit


def _journal(source: str, i: int, raw: dict, s: Support, shaft: Shaft,
             rotor: Rotor | None, ranges: dict[str, tuple[float, float, float]]) -> Support:
    """A journal bearing's support as declared: its film's bearing (its coefficients:
    shaftfem.parts.journal) at the nominal clearance and oil, and their tolerance
    ranges."""
    from shaftfem.scene.schema import DEFAULT_MIN_FILM_UM

    table = entry("support", i, raw)
    t = validate_table(source, table, _as_lists(raw, BEARING_KEYS), SCHEMA["support"])
    if t["radial_clearance_um"] is None:
        raise SceneError(f"{where(source, table, 'radial_clearance_um')}: missing (kind = "
                         "\"journal\" needs the bearing's radial clearance, um)")
    if rotor is None:
        raise SceneError(f"{where(source, table, 'kind')} = \"journal\": a journal's film "
                         "comes from its speed; add [rotor] with the operating speed")
    if (t["viscosity_mpa_s"] is None) == (t["oil_iso_vg"] is None):
        raise SceneError(f"{where(source, table, 'viscosity_mpa_s')}: give the oil as "
                         "viscosity_mpa_s, or as oil_iso_vg with oil_temperature_c (one of them)")
    viscosity = None
    supply = t["oil_supply_temperature_c"]
    if t["oil_iso_vg"] is not None:
        if (t["oil_temperature_c"] is None) == (supply is None):
            raise SceneError(f"{where(source, table, 'oil_temperature_c')}: with oil_iso_vg, "
                             "give the film's mean temperature oil_temperature_c, or the "
                             "supply's oil_supply_temperature_c for the film to heat (one "
                             "of them)")
    else:
        for key in ("oil_temperature_c", "oil_supply_temperature_c"):
            if t[key] is not None:
                raise SceneError(f"{where(source, table, key)}: only with oil_iso_vg "
                                 "(viscosity_mpa_s is the film's viscosity already)")
        viscosity = t["viscosity_mpa_s"] * 1e-3
    if "pad_temperature_limit_c" in raw and (t["bore"] != "tilting_pad" or supply is None):
        raise SceneError(f"{where(source, table, 'pad_temperature_limit_c')}: only with "
                         "bore = \"tilting_pad\" and oil_supply_temperature_c (the pads' "
                         "heated film gives their temperature)")
    if t["pad_mass_kg"] is not None and t["pivot_stiffness_n_per_mm"] is None:
        raise SceneError(f"{where(source, table, 'pad_mass_kg')}: only with "
                         "pivot_stiffness_n_per_mm (on a rigid pivot the pad does not move "
                         "radially)")
    if t["pad_thickness_mm"] is not None and (t["bore"] != "tilting_pad" or supply is None):
        raise SceneError(f"{where(source, table, 'pad_thickness_mm')}: only with bore = "
                         "\"tilting_pad\" and oil_supply_temperature_c (the pads grow with "
                         "their heated film's temperature)")
    if t["oil_flow_l_min"] is not None and supply is None:
        raise SceneError(f"{where(source, table, 'oil_flow_l_min')}: only with "
                         "oil_supply_temperature_c (the flow the supply heats)")
    diameter = _seat_diameter(source, table, t, shaft, s, "journal")
    clearance = t["radial_clearance_um"] * 1e-6
    widest = ranges.get("radial_clearance_um", (0.0, 0.0, t["radial_clearance_um"]))[2]
    tightest = ranges.get("radial_clearance_um", (t["radial_clearance_um"],))[0]
    if tightest * 1e-6 < MIN_CLEARANCE_RATIO * diameter:
        raise SceneError(f"{where(source, table, 'radial_clearance_um')} = "
                         f"{tightest:g}: {tightest * 1e-6 / diameter:.2g} of the diameter; a "
                         "journal bearing's radial clearance is about 0.0005 to 0.003 of it, "
                         f"and the film is solved from {MIN_CLEARANCE_RATIO:g} (the key is in "
                         "um: 0.05 mm is 50 um)")
    if widest * 1e-6 > 0.05 * diameter:
        raise SceneError(f"{where(source, table, 'radial_clearance_um')} = "
                         f"{widest:g}: {widest * 1e-6 / diameter:.3g} of the "
                         "diameter; a journal bearing's radial clearance is about 0.0005 to "
                         "0.003 of it (the film theory holds below 0.05)")
    ratio = s.width / diameter
    if not JOURNAL_RATIOS[0] <= ratio <= JOURNAL_RATIOS[1]:
        raise SceneError(f"{where(source, table, 'width_mm')} = {s.width / MM:g}: length / "
                         f"diameter {ratio:.3g}; the film is solved for {JOURNAL_RATIOS[0]:g} "
                         f"to {JOURNAL_RATIOS[1]:g}")
    angle = math.radians(t["load_angle_deg"])
    bearing = JournalBearing(
        diameter=diameter, length=s.width, clearance=clearance, viscosity=viscosity,
        load=t["load_n"] or 0.0, direction=(math.cos(angle), math.sin(angle)),
        cavitation=t["cavitation"], bore=_bore(source, table, t),
        min_film=(t["min_film_um"] if t["min_film_um"] is not None else DEFAULT_MIN_FILM_UM)
        * 1e-6, oil_iso_vg=t["oil_iso_vg"], oil_temperature=t["oil_temperature_c"],
        oil_supply_temperature=supply, pad_limit=t["pad_temperature_limit_c"],
        pad_inertia=(t["pad_inertia_kg_mm2"] or 0.0) * 1e-6,
        pivot_stiffness=None if t["pivot_stiffness_n_per_mm"] is None
        else t["pivot_stiffness_n_per_mm"] * 1e3, pad_mass=t["pad_mass_kg"] or 0.0,
        pad_thickness=None if t["pad_thickness_mm"] is None
        else t["pad_thickness_mm"] * MM,
        oil_flow=None if t["oil_flow_l_min"] is None else t["oil_flow_l_min"] / 60e3)
    # an oil given by its grade: the viscosities of its temperature range come from the
    # part (shaftfem.parts.oil), with the film's coefficients
    temperature = ranges.get("oil_temperature_c", ranges.get("oil_supply_temperature_c"))
    spread = _scaled(ranges["viscosity_mpa_s"], 1e-3) if "viscosity_mpa_s" in ranges else None
    tolerance = (Tolerance(clearance=_scaled(ranges["radial_clearance_um"], 1e-6)
                           if "radial_clearance_um" in ranges else None,
                           viscosity=spread, temperature=temperature)
                 if ranges else None)
    return replace(s, tolerance=tolerance, journal=bearing)


def _bore(source: str, table: str, t: dict) -> JournalBore | None:
    """A journal's bore of pads as declared (None: the plain bore), its keys checked
    together: pads that fit round the bore, keys that belong to its kind."""
    kind = t["bore"]
    tilting = ("pads", "pad_arc_deg")
    if kind != "tilting_pad":
        for key in (*tilting, "pad_inertia_kg_mm2", "pivot_stiffness_n_per_mm", "pad_mass_kg"):
            if t[key] is not None:
                raise SceneError(f"{where(source, table, key)}: only with bore = "
                                 "\"tilting_pad\"")
    if kind == "plain":
        if t["preload"] is not None:
            raise SceneError(f"{where(source, table, 'preload')}: a plain bore has none "
                             "(bore = \"elliptical\" or \"tilting_pad\")")
        return None
    if t["cavitation"] != "reynolds":
        raise SceneError(f"{where(source, table, 'cavitation')} = \"{t['cavitation']}\": a "
                         "bore of pads is solved with \"reynolds\" (Swift-Stieber) only")
    groove = math.radians(t["groove_arc_deg"])
    if kind == "two_axial_groove":
        if t["preload"] is not None:
            raise SceneError(f"{where(source, table, 'preload')}: a two-axial-groove bore "
                             "is round (bore = \"elliptical\" for a preloaded one)")
        return JournalBore(kind, arc=math.pi - groove, groove=groove)
    if kind == "elliptical":
        if t["preload"] is None:
            raise SceneError(f"{where(source, table, 'preload')}: missing (an elliptical "
                             "bore's preload, in (0, 1): 0.5 is common)")
        return JournalBore(kind, arc=math.pi - groove, preload=t["preload"], groove=groove)
    for key in tilting:
        if t[key] is None:
            raise SceneError(f"{where(source, table, key)}: missing (bore = "
                             "\"tilting_pad\" needs its pads and their arc)")
    if t["pads"] * t["pad_arc_deg"] >= 360:
        raise SceneError(f"{where(source, table, 'pad_arc_deg')} = {t['pad_arc_deg']:g}: "
                         f"{t['pads']} pads of it overlap (together "
                         f"{t['pads'] * t['pad_arc_deg']:g} deg, less than 360 fit)")
    return JournalBore(kind, pads=t["pads"], arc=math.radians(t["pad_arc_deg"]),
                       preload=t["preload"] or 0.0, offset=t["pivot_offset"],
                       between=t["load_between_pads"])


def _seat_diameter(source: str, table: str, t: dict, shaft: Shaft, s: Support,
                   what: str) -> float:
    """A journal's or seal's diameter (m): diameter_mm, else the shaft's at the seat. A
    journal is the shaft's own surface there (within 1 %: make a sleeve a section of
    the shaft); a seal runs on the shaft or on a larger ring (an impeller's eye), never
    inside the shaft."""
    radius = shaft.radius_at(s.position)
    if t["diameter_mm"] is not None:
        d = t["diameter_mm"] * MM
        if radius is not None:
            shaft_d = 2 * radius
            if what == "journal" and abs(d / shaft_d - 1) > 0.01:
                raise SceneError(f"{where(source, table, 'diameter_mm')} = {t['diameter_mm']:g}: "
                                 f"the shaft is {shaft_d / MM:g} mm at the journal "
                                 f"({s.position / MM:g} mm); a journal's diameter is the "
                                 "shaft's there (within 1 %), or leave diameter_mm out")
            if what == "seal" and d < shaft_d * (1 - 0.01):
                raise SceneError(f"{where(source, table, 'diameter_mm')} = {t['diameter_mm']:g}: "
                                 f"smaller than the shaft ({shaft_d / MM:g} mm at "
                                 f"{s.position / MM:g} mm); a seal runs on the shaft or on a "
                                 "larger ring, or leave diameter_mm out")
        return d
    if radius is None:
        raise SceneError(f"{where(source, table, 'diameter_mm')}: missing (on a STEP shaft "
                         f"give the {what}'s diameter, mm)")
    return 2 * radius


def _seal(source: str, i: int, raw: dict, s: Support, shaft: Shaft,
          rotor: Rotor | None, ranges: dict[str, tuple[float, float, float]]) -> Support:
    """A plain annular seal's support as declared (its coefficients against speed:
    shaftfem.parts.seal)."""
    table = entry("support", i, raw)
    t = validate_table(source, table, _as_lists(raw, BEARING_KEYS), SCHEMA["support"])
    for key, what in (("radial_clearance_um", "the seal's radial clearance, um"),
                      ("pressure_drop_mpa", "the pressure drop across it at the machine's "
                       "rated speed ([rotor] rated_speed_rpm), MPa"),
                      ("fluid_density_kg_m3", "the sealed fluid's density, kg/m^3"),
                      ("viscosity_mpa_s", "the sealed fluid's viscosity, mPa s")):
        if t[key] is None:
            raise SceneError(f"{where(source, table, key)}: missing (kind = \"seal\" needs "
                             f"{what})")
    if rotor is None:
        raise SceneError(f"{where(source, table, 'kind')} = \"seal\": a seal's forces come "
                         "from its speed; add [rotor] with the operating speed")
    _needs_rated(source, table, "pressure_drop_mpa", rotor)
    diameter = _seat_diameter(source, table, t, shaft, s, "seal")
    clearance = t["radial_clearance_um"] * 1e-6
    widest = ranges.get("radial_clearance_um", (0.0, 0.0, t["radial_clearance_um"]))[2]
    if widest * 1e-6 > 0.02 * diameter:
        raise SceneError(f"{where(source, table, 'radial_clearance_um')} = "
                         f"{widest:g}: {widest * 1e-6 / diameter:.3g} of the "
                         "diameter; a plain seal's radial clearance is about 0.001 to 0.005 "
                         "of it (the bulk-flow model holds below 0.02)")
    annular = AnnularSeal(length=s.width, diameter=diameter, clearance=clearance,
                               pressure_drop=t["pressure_drop_mpa"] * MPA, rated=rotor.rated,
                               density=t["fluid_density_kg_m3"],
                               viscosity=t["viscosity_mpa_s"] * 1e-3,
                               inlet_loss=INLET_LOSS if t["inlet_loss"] is None
                               else t["inlet_loss"])
    tolerance = (Tolerance(clearance=_scaled(ranges["radial_clearance_um"], 1e-6))
                 if ranges else None)
    return replace(s, seal=annular, tolerance=tolerance)


def _support(source: str, i: int, t: dict) -> Support:
    table = entry("support", i, t)
    t = validate_table(source, table, _as_lists(t, BEARING_KEYS), SCHEMA["support"])
    springs = ("radial_stiffness_n_per_mm", "axial_stiffness_n_per_mm",
               "tilting_stiffness_nmm_per_rad")
    bearing = None
    if t["kind"] == "springs":
        if t["radial_stiffness_n_per_mm"] is None:
            raise SceneError(f"{where(source, table, 'radial_stiffness_n_per_mm')}: missing "
                             "(kind = \"springs\" needs the bearing's radial stiffness, N/mm)")
    elif t["kind"] in PHYSICS_KEYS:
        if t["radial_stiffness_n_per_mm"] is not None:
            raise SceneError(f"{where(source, table, 'radial_stiffness_n_per_mm')}: not with "
                             f"kind = \"{t['kind']}\": its "
                             + ("elements give" if t["kind"] in ("ball", "roller")
                                else "film gives")
                             + " its stiffness")
    elif t["kind"] == "bearing":
        if t["radial_stiffness_n_per_mm"] is not None:
            raise SceneError(f"{where(source, table, 'radial_stiffness_n_per_mm')}: not with "
                             "kind = \"bearing\"; give kxx_n_per_mm (and kyy_n_per_mm)")
        if t["coupling"] == "rigid":
            raise SceneError(f"{where(source, table, 'coupling')} = \"rigid\": kind = "
                             "\"bearing\" acts on the seat's mean motion; leave coupling out")
        bearing = _bearing(source, table, t)
    else:
        for key in springs:
            if t[key] is not None:
                raise SceneError(f"{where(source, table, key)} = {t[key]:g}: only with kind = "
                                 "\"springs\", \"bearing\", \"journal\", \"ball\" or "
                                 f"\"roller\" (this support is {t['kind']!r})")
    takes = PHYSICS_KEYS.get(t["kind"], ())
    for key in (*JOURNAL_KEYS, *ROLLING_KEYS, *SEAL_KEYS, "load_n", "load_angle_deg"):
        if key not in takes and t[key] is not None and SCHEMA["support"][key].default != t[key]:
            kinds = " or ".join(f'"{k}"' for k, keys in PHYSICS_KEYS.items() if key in keys)
            raise SceneError(f"{where(source, table, key)} = {t[key]!r}: only with kind = "
                             f"{kinds} (this support is {t['kind']!r})")
    if takes and t["coupling"] == "rigid":
        raise SceneError(f"{where(source, table, 'coupling')} = \"rigid\": a {t['kind']}"
                         f"{'' if t['kind'] == 'seal' else ' bearing'} acts on the seat's mean "
                         "motion; leave coupling out")
    rolling = _rolling(source, table, t) if t["kind"] in ("ball", "roller") else None
    if t["kind"] != "bearing":
        for key in (*BEARING_KEYS, "speeds_rpm"):
            if t[key] is not None:
                raise SceneError(f"{where(source, table, key)} = {t[key]!r}: only with kind = "
                                 f"\"bearing\" (this support is {t['kind']!r})")
    if t["kind"] == "clamped" and t["coupling"] == "rigid":
        raise SceneError(f"{where(source, table, 'coupling')} = \"rigid\": a clamped seat "
                         "already holds every point of its band; leave coupling out")
    radial = (t["radial_stiffness_n_per_mm"] or 0.0) * 1e3
    width = t["width_mm"] * MM
    return Support(name=t["name"] or f"support {i + 1}", position=t["position_mm"] * MM,
                   width=width, kind=t["kind"], radial=radial,
                   axial=(t["axial_stiffness_n_per_mm"] or 0.0) * 1e3,
                   tilting=(t["tilting_stiffness_nmm_per_rad"] or 0.0) * 1e-3,
                   coupling=t["coupling"], bearing=bearing, rolling=rolling,
                   slope_limit=_si(t["slope_limit_mrad"], 1e-3))


def _placed(source: str, table: str, t: dict, shaft: Shaft,
            attachments: tuple[Attachment, ...]) -> float:
    """The axial position (mm) a table gives as position_mm, or as a part's centre."""
    if (t["position_mm"] is None) == (t["part"] is None):
        raise SceneError(f"{where(source, table, 'position_mm')}: give either position_mm "
                         "or part (the name of an [[attachment]]), not both nor neither")
    position = t["position_mm"]
    if t["part"] is not None:
        named = [a for a in attachments if a.name == t["part"]]
        if not named:
            raise SceneError(f"{where(source, table, 'part')} = {t['part']!r}: no "
                             "[[attachment]] of that name; the scene's parts: "
                             + (", ".join(repr(a.name) for a in attachments) or "none"))
        position = named[0].position / MM
    if shaft.step is None and position > shaft.length / MM:
        raise SceneError(f"{where(source, table, 'position_mm')} = {position:g}: "
                         f"must lie on the shaft, 0 to {shaft.length / MM:g} mm")
    return position


def _static(source: str, data: dict) -> tuple[float, float, float]:
    """[static]'s gravity as an acceleration vector, m/s^2."""
    t = validate_table(source, "static", data.get("static", {}), SCHEMA["static"])
    d = t["gravity_direction"]
    norm = math.sqrt(sum(x * x for x in d))
    return tuple(t["gravity_m_s2"] * x / norm for x in d)


def _forces(source: str, data: dict, shaft: Shaft, attachments: tuple[Attachment, ...],
            torques: tuple[Torque, ...]) -> tuple[PointForce, ...]:
    """[[force]] in SI (m, N), each at its position or its part's centre; a gear's from
    its geometry and the torque through its part (_gear_force)."""
    out = []
    for i, e in enumerate(_array(source, data, "force")):
        table = entry("force", i, e)
        t = validate_table(source, table, e, SCHEMA["force"])
        position = _placed(source, table, t, shaft, attachments)
        force = PointForce(name=t["name"] or t["part"] or f"force {i + 1}",
                           position=position * MM, fx=t["fx_n"], fy=t["fy_n"], fz=t["fz_n"],
                           width=_hub(t, attachments),
                           travel=_travel(source, table, t, shaft, position))
        if t["gear_pitch_diameter_mm"] is not None:
            force = _gear_force(source, table, e, t, force, torques)
        out.append(force)
    return tuple(out)


def _gear_force(source: str, table: str, given: dict, t: dict, force: PointForce,
                torques: tuple[Torque, ...]) -> PointForce:
    """A gear's tooth force on the shaft, from its pitch diameter d, normal pressure
    angle alpha_n and helix angle beta and the torque T through its part (positive
    entering): tangential T / r at the mesh point (its moment about the axis is T),
    radial F_t tan(alpha_n) / cos(beta) towards the axis, axial F_t tan(beta) (its sign
    the helix angle's, for power entering), and the thrust's moment about the gear's
    centre, r e_r x F_a e_z, standing where the teeth meet."""
    mixed = [k for k in ("fx_n", "fy_n", "fz_n") if k in given]
    if mixed:
        raise SceneError(f"{where(source, table, mixed[0])}: a gear's force comes from "
                         "gear_pitch_diameter_mm and its torque; leave out fx_n, fy_n, fz_n")
    if t["part"] is None:
        raise SceneError(f"{where(source, table, 'gear_pitch_diameter_mm')}: a gear is a "
                         "part: give `part` (its [[attachment]]), and a [[torque]] on it")
    through = [q for q in torques
               if abs(q.position - force.position) < 1e-9 and q.width == force.width]
    if len(through) != 1:
        raise SceneError(f"{where(source, table, 'gear_pitch_diameter_mm')}: gear "
                         f"{t['part']!r} needs one [[torque]] on the same part (the power it "
                         f"passes); found {len(through)}")
    r = 0.5 * t["gear_pitch_diameter_mm"] * MM
    T = through[0].torque
    tangential = T / r
    alpha, beta = math.radians(t["gear_pressure_angle_deg"]), math.radians(
        t["gear_helix_angle_deg"])
    radial = abs(tangential) * math.tan(alpha) / math.cos(beta)
    axial = math.copysign(abs(tangential) * math.tan(abs(beta)), beta * T) if beta else 0.0
    phi = math.radians(t["gear_mesh_angle_deg"])
    c, s = math.cos(phi), math.sin(phi)
    return replace(force, fx=-tangential * s - radial * c, fy=tangential * c - radial * s,
                   fz=axial, mx=r * axial * s, my=-r * axial * c)


def _travel(source: str, table: str, t: dict, shaft: Shaft, position: float) -> float | None:
    """Where a load travels to (m), or None: a bare position on the shaft, not its own."""
    to = t["travel_to_mm"]
    if to is None:
        return None
    if t["part"] is not None:
        raise SceneError(f"{where(source, table, 'travel_to_mm')}: a part's load stays at its "
                         "part; a travelling load (a follower) takes position_mm")
    if shaft.step is None and to > shaft.length / MM:
        raise SceneError(f"{where(source, table, 'travel_to_mm')} = {to:g}: must lie on the "
                         f"shaft, 0 to {shaft.length / MM:g} mm")
    if to == position:
        raise SceneError(f"{where(source, table, 'travel_to_mm')} = {to:g}: the load's own "
                         "position_mm; leave travel_to_mm out for a load that stays")
    return to * MM


def _hub(t: dict, attachments: tuple[Attachment, ...]) -> float:
    """The width of the hub a load comes through (m): its part's, 0 at a bare position."""
    return next((a.width for a in attachments if a.name == t["part"]), 0.0)


def _strength(source: str, data: dict, material: Material, rotor: Rotor | None,
              sizing: dict | None) -> Strength | None:
    """[strength] in SI with the material's strengths (given, or its name's row in
    scene.materials), or None when the scene has none."""
    if "strength" not in data:
        return None
    from shaftfem.scene.materials import shaft_steel

    t = validate_table(source, "strength", data["strength"], SCHEMA["strength"])
    speed = t["speed_rpm"]
    if speed is None and rotor is not None and rotor.speeds:
        speed = rotor.speeds[0] / RPM
    if speed is None and sizing is not None:
        speed = sizing["speed_rpm"]
    row = shaft_steel(material.name)
    given = {k: t[k] for k in ("tensile_strength_mpa", "yield_strength_mpa")}
    for key, value in given.items():
        if value is None and row is None:
            raise SceneError(f"{where(source, 'strength', key)}: missing: [material] name = "
                             f"{material.name!r} is not a steel shaftfem knows (docs/strength.md "
                             "lists them); give the material's R_m and R_p0.2")
    rm = given["tensile_strength_mpa"] or (row.tensile_strength_mpa if row else 0.0)
    rp = given["yield_strength_mpa"] or (row.yield_strength_mpa if row else 0.0)
    if rp >= rm:
        raise SceneError(f"{where(source, 'strength', 'yield_strength_mpa')} = {rp:g}: must be "
                         f"below the tensile strength, {rm:g} MPa")
    blank = t["strength_diameter_mm"] or (row.diameter_mm if row is not None else 16.0)
    by_row = row is not None and None in given.values()
    return Strength(speed=(speed or 0.0) * RPM, tensile_strength=rm * MPA,
                    yield_strength=rp * MPA, strength_diameter=blank * MM,
                    roughness=t["roughness_rz_um"] * 1e-6,
                    fatigue_safety=t["required_fatigue_safety"],
                    yield_safety=t["required_yield_safety"], peak_factor=t["peak_factor"],
                    target_error=t["target_error_percent"] / 100,
                    source=row.source if by_row and row is not None else "given",
                    fkm_group=row.fkm_group if row is not None else "Steel",
                    size_exponents=(row.a_dm, row.a_dp) if row is not None else (0.3, 0.4),
                    travel_positions=t["travel_positions"])


def _torques(source: str, data: dict, shaft: Shaft, attachments: tuple[Attachment, ...],
             strength: Strength | None) -> tuple[Torque, ...]:
    """[[torque]] in SI (m, N m), each at its position or over its part's hub; one left
    without torque_nm and power_kw takes the balance; they must balance."""
    out: list[Torque] = []
    open_: list[tuple[int, str]] = []   # the torques without a value: (index, table)
    for i, e in enumerate(_array(source, data, "torque")):
        table = entry("torque", i, e)
        t = validate_table(source, table, e, SCHEMA["torque"])
        position = _placed(source, table, t, shaft, attachments)
        if t["torque_nm"] is not None and t["power_kw"] is not None:
            raise SceneError(f"{where(source, table, 'power_kw')}: give torque_nm or power_kw, "
                             "not both")
        torque = t["torque_nm"]
        if t["power_kw"] is not None:
            if strength is None or strength.speed <= 0:
                raise SceneError(f"{where(source, table, 'power_kw')}: a power needs the speed "
                                 "it is given at: [strength] speed_rpm (or [rotor] speed_rpm)")
            torque = t["power_kw"] * 1e3 / strength.speed
        if torque is None:
            open_.append((i, table))
        out.append(Torque(name=t["name"] or t["part"] or f"torque {i + 1}",
                          position=position * MM, torque=torque or 0.0,
                          width=_hub(t, attachments),
                          travel=_travel(source, table, t, shaft, position)))
    if len(open_) > 1:
        raise SceneError(f"{source}: {open_[1][1]}: only one torque may leave out torque_nm "
                         f"and power_kw (it takes the balance; {open_[0][1]} does already)")
    total = sum(q.torque for q in out)
    if open_:
        k = open_[0][0]
        out[k] = replace(out[k], torque=-total)
    elif out and abs(total) > 1e-6 * max(abs(q.torque) for q in out):
        entering = sum(q.torque for q in out if q.torque > 0)
        raise SceneError(f"{source}: [[torque]]: {entering:g} N m enter the shaft and "
                         f"{entering - total:g} N m leave it: a torque with nowhere to go; "
                         "the torques must balance (leave out torque_nm and power_kw on one, "
                         "and it takes the rest)")
    return tuple(out)


def _unbalances(source: str, data: dict, shaft: Shaft,
                attachments: tuple[Attachment, ...]) -> tuple[Unbalance, ...]:
    """[[unbalance]] in SI (m, kg m, rad), each at its position or its part's centre;
    they need [rotor]."""
    out = []
    for i, e in enumerate(_array(source, data, "unbalance")):
        table = entry("unbalance", i, e)
        t = validate_table(source, table, e, SCHEMA["unbalance"])
        if "rotor" not in data:
            raise SceneError(f"{source}: {table}: an unbalance needs the shaft turning: add "
                             "[rotor] with its speed_rpm")
        position = _placed(source, table, t, shaft, attachments)
        out.append(Unbalance(name=t["name"] or t["part"] or f"unbalance {i + 1}",
                             position=position * MM, amount=t["amount_g_mm"] * 1e-6,
                             phase=math.radians(t["phase_deg"])))
    return tuple(out)


def _rotor(source: str, data: dict, shaft: Shaft) -> Rotor | None:
    """[rotor] in SI (rad/s), or None when the scene has none."""
    if "rotor" not in data:
        return None
    t = validate_table(source, "rotor", _as_lists(data["rotor"], ("speed_rpm",)), SCHEMA["rotor"])
    band = t["speed_range_rpm"]
    if t["speed_rpm"] is None and band is None:
        raise SceneError(f"{where(source, 'rotor', 'speed_rpm')}: missing: give the operating "
                         "speed(s), r/min, or speed_range_rpm = [lowest, highest]")
    listed = sorted(t["speed_rpm"] or [])
    for a, b in zip(listed, listed[1:]):
        if b - a < 1.0:
            raise SceneError(f"{where(source, 'rotor', 'speed_rpm')} = {t['speed_rpm']!r}: "
                             f"{a:g} and {b:g} r/min are less than 1 r/min apart: list each "
                             "operating speed once")
    speeds = listed or list(band)
    if band is not None:   # a range's ends are where its whirl is tabled
        speeds = sorted({*speeds, *band})
    top = max(speeds)
    end = t["max_speed_rpm"] if t["max_speed_rpm"] is not None else DEFAULT_SPEED_HEADROOM * top
    if end < top:
        raise SceneError(f"{where(source, 'rotor', 'max_speed_rpm')} = {end:g}: must reach the "
                         f"highest operating speed ({top:g} r/min)")
    for z in t["probes_mm"]:
        if shaft.step is None and z > shaft.length / MM:
            raise SceneError(f"{where(source, 'rotor', 'probes_mm')} = {t['probes_mm']!r}: "
                             f"{z:g} mm is off the shaft, 0 to {shaft.length / MM:g} mm")
    return Rotor(speeds=tuple(n * RPM for n in speeds), max_speed=end * RPM,
                 frame=t["frame"], points=t["campbell_points"],
                 basis_modes=t["basis_modes"] or 0,
                 probes=tuple(z * MM for z in t["probes_mm"]),
                 ranges=() if band is None else ((band[0] * RPM, band[1] * RPM),),
                 min_log_dec=t["min_log_dec"], log_dec_modes=t["log_dec_modes"],
                 tolerance_cases=t["tolerance_cases"],
                 amplitude_limit=(None if t["amplitude_limit_um"] is None
                                  else t["amplitude_limit_um"] * 1e-6),
                 level1=t["level1"],
                 level1_qa=(None if t["level1_qa_n_per_mm"] is None
                            else t["level1_qa_n_per_mm"] * 1e3),
                 runup=(None if t["runup_rpm_per_s"] is None
                        else t["runup_rpm_per_s"] * RPM),
                 rated=(t["rated_speed_rpm"] or 0.0) * RPM)


def _keyed_default(a: Attachment, shaft: Shaft) -> Attachment:
    """A part whose joint the scene leaves to the default sits on its seat as a keyed fit
    where its hub overlaps a keyway ("distributing": the conservative side, its hub adds
    no stiffness), else as a shrink fit ("rigid"); the study brackets it with the other."""
    if a.joint_given:
        return a
    lo, hi = a.position - a.width / 2, a.position + a.width / 2
    keyed = any(k.start < hi and k.start + k.length > lo for k in shaft.keyways)
    return replace(a, joint="distributing" if keyed else "rigid")


def _needs_rated(source: str, table: str, key: str, rotor: Rotor) -> None:
    """A seal's drop or a stage's power is the machine's at its rated speed: without it
    the operating speeds would change the machine, not where it runs."""
    if rotor.rated <= 0:
        raise SceneError(f"{where(source, 'rotor', 'rated_speed_rpm')}: missing ({table}'s "
                         f"{key} is given at the machine's rated speed: say which, r/min, "
                         "for example the highest operating speed)")


def _attachment(source: str, i: int, t: dict) -> Attachment:
    table = entry("attachment", i, t)
    joint_given = isinstance(t, dict) and t.get("joint") is not None
    t = validate_table(source, table, t, SCHEMA["attachment"])
    polar, diametral = t["polar_inertia_kg_m2"], t["diametral_inertia_kg_m2"]
    if t["mass_kg"] == 0 and polar + diametral > 0:
        raise SceneError(f"{where(source, table, 'mass_kg')} = 0: a part with "
                         "moments of inertia has a mass")
    if diametral < polar / 2 * (1 - 1e-12):
        raise SceneError(
            f"{where(source, table, 'diametral_inertia_kg_m2')} = {diametral:g}: "
            f"a rigid part's moment about a diameter is at least half its polar moment "
            f"({polar / 2:g} kg m^2; a thin disk has exactly half)")
    stage = ("stage_power_kw", "stage_diameter_mm", "stage_width_mm")
    given = [k for k in stage if t[k] is not None]
    if given and len(given) < 3:
        missing = next(k for k in stage if t[k] is None)
        raise SceneError(f"{where(source, table, missing)}: missing (a stage's cross-coupling "
                         "needs its power, kW, its diameter and its flow width, mm)")
    train = ("coupling_stiffness_nm_per_rad", "coupled_inertia_kg_m2")
    given = [k for k in train if t[k] is not None]
    if len(given) == 1:
        missing = next(k for k in train if t[k] is None)
        raise SceneError(f"{where(source, table, missing)}: missing (a coupling to another "
                         "machine needs its torsional stiffness, N m/rad, and that machine's "
                         "polar inertia, kg m^2)")
    return Attachment(name=t["name"] or f"attachment {i + 1}", position=t["position_mm"] * MM,
                      width=t["width_mm"] * MM, mass=t["mass_kg"],
                      polar_inertia=t["polar_inertia_kg_m2"],
                      diametral_inertia=t["diametral_inertia_kg_m2"], joint=t["joint"],
                      joint_given=joint_given,
                      coupling_stiffness=t["coupling_stiffness_nm_per_rad"] or 0.0,
                      coupled_inertia=t["coupled_inertia_kg_m2"] or 0.0,
                      slope_limit=_si(t["slope_limit_mrad"], 1e-3),
                      deflection_limit=_si(t["deflection_limit_um"], 1e-6))


def _si(value: float | None, unit: float) -> float | None:
    """A key's value in SI, or None when it is left out."""
    return None if value is None else value * unit


def _stage(source: str, i: int, raw: dict, a: Attachment, rotor: Rotor | None) -> Attachment:
    """A part with a stage on it, as declared (its cross-coupling: shaftfem.parts.wachel)."""
    table = entry("attachment", i, raw)
    t = validate_table(source, table, raw, SCHEMA["attachment"])
    if t["stage_power_kw"] is None:
        return a
    if rotor is None:
        raise SceneError(f"{where(source, table, 'stage_power_kw')}: a stage's cross-coupling "
                         "needs the shaft turning: add [rotor] with its speed_rpm")
    _needs_rated(source, table, "stage_power_kw", rotor)
    return replace(a, stage=Stage(power=t["stage_power_kw"] * 1e3,
                                  diameter=t["stage_diameter_mm"] * MM,
                                  width=t["stage_width_mm"] * MM, kind=t["stage_kind"],
                                  density_ratio=t["density_ratio"]))
