"""Scenes in code: the scene file's tables as typed Python objects, in its units (mm,
MPa, kg, r/min), composed into a `Scene` by `make_scene` and varied by `vary`.

Each object is the table of the same name, key for key; a key left at None is a key left
out of the file (its default applies). A scene made here goes through the very checks a
file goes through (shaftfem.scene.load), so a bad value is refused with the same message,
and the scene is the same, to the bit, as the one its file gives:

    import shaftfem as sf
    shaft = sf.Shaft(sections=[sf.Section(length_mm=40, diameter_mm=25, fillet_mm=1),
                               sf.Section(length_mm=220, diameter_mm=35)],
                     keyways=[sf.Keyway(position_mm=150, length_mm=50)])
    scene = sf.make_scene(name="stepped", shaft=shaft,
                          material=sf.Material(youngs_modulus_mpa=210e3, poisson_ratio=0.3,
                                               density_kg_m3=7850),
                          mesh=sf.Mesh(element_size_mm=8))
    scene.to_toml("stepped.toml")        # the same scene as a file, for CI
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

from shaftfem.errors import SceneError
from shaftfem.scene.load import load_scene
from shaftfem.scene.model import Scene
from shaftfem.scene.schema import SCHEMA

Number = float | int
Numbers = Number | list[Number] | tuple[Number, ...]


def _plain(value: Any) -> Any:
    """A value as TOML holds it: tuples as lists, mappings as dicts, NumPy scalars as
    Python numbers."""
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        return value.item()   # numpy.float64(8.0) -> 8.0
    return value


@dataclass(frozen=True, kw_only=True)
class _Table:
    """One table of the scene file; `table()` gives its keys as the file has them."""

    TABLE: ClassVar[str]

    def table(self) -> dict[str, Any]:
        return {f.name: _plain(getattr(self, f.name)) for f in dataclasses.fields(self)
                if getattr(self, f.name) is not None}


@dataclass(frozen=True, kw_only=True)
class Section(_Table):
    """[[section]]: one section of a stepped profile, from the left end, mm."""

    TABLE: ClassVar[str] = "section"
    length_mm: Number | None = None
    diameter_mm: Number | None = None
    diameter_start_mm: Number | None = None
    diameter_end_mm: Number | None = None
    bore_mm: Number | None = None
    fillet_mm: Number | None = None
    chamfer_mm: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Keyway(_Table):
    """[[keyway]]: a keyway milled into the shaft, mm and deg."""

    TABLE: ClassVar[str] = "keyway"
    position_mm: Number | None = None
    length_mm: Number | None = None
    width_mm: Number | None = None
    depth_mm: Number | None = None
    angle_deg: Number | None = None
    form: str | None = None
    corner_radius_mm: Number | None = None
    cutter_diameter_mm: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Shaft:
    """The shaft: [shaft] (a plain bar's length and diameter, the end chamfer, or a STEP
    file and its axis) with its [[section]] and [[keyway]] tables."""

    sections: tuple[Section, ...] | list[Section] = ()
    keyways: tuple[Keyway, ...] | list[Keyway] = ()
    length_mm: Number | None = None
    diameter_mm: Number | None = None
    end_chamfer_mm: Number | None = None
    step_file: str | None = None
    axis_from_mm: Numbers | None = None
    axis_to_mm: Numbers | None = None

    def tables(self) -> dict[str, Any]:
        shaft = {k: _plain(getattr(self, k)) for k in SCHEMA["shaft"]
                 if getattr(self, k) is not None}
        out: dict[str, Any] = {"shaft": shaft} if shaft else {}
        if self.sections:
            out["section"] = [_entry(s, Section) for s in self.sections]
        if self.keyways:
            out["keyway"] = [_entry(k, Keyway) for k in self.keyways]
        return out


@dataclass(frozen=True, kw_only=True)
class Material(_Table):
    """[material]: the shaft's material, MPa and kg/m^3."""

    TABLE: ClassVar[str] = "material"
    name: str | None = None
    youngs_modulus_mpa: Number | None = None
    poisson_ratio: Number | None = None
    density_kg_m3: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Grooves(_Table):
    """[grooves]: the helical grooves, mm."""

    TABLE: ClassVar[str] = "grooves"
    hands: list[str] | tuple[str, ...] | None = None
    pitch_mm: Number | None = None
    width_mm: Number | None = None
    depth_mm: Number | None = None
    root_radius_mm: Number | None = None
    grooved_length_mm: Number | None = None
    start_mm: Number | None = None
    runout_mm: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Mesh(_Table):
    """[mesh]: the element sizes (mm), orders, accuracy target (%) and DOF budget."""

    TABLE: ClassVar[str] = "mesh"
    element_size_mm: Number | None = None
    groove_element_size_mm: Number | None = None
    edge_element_size_mm: Number | None = None
    order: int | None = None
    geometry_order: int | None = None
    target_error_percent: Number | None = None
    max_dofs: int | None = None


@dataclass(frozen=True, kw_only=True)
class Excitation(_Table):
    """[[excitation]]: a source turning at `speed_rpm`, exciting its `orders`."""

    TABLE: ClassVar[str] = "excitation"
    name: str | None = None
    speed_rpm: Number | None = None
    orders: list[int] | tuple[int, ...] | None = None


@dataclass(frozen=True, kw_only=True)
class Support(_Table):
    """[[support]]: a bearing seat, mm; stiffness N/mm (N mm/rad tilting), damping
    N s/mm, each a number or a list against `speeds_rpm`."""

    TABLE: ClassVar[str] = "support"
    name: str | None = None
    position_mm: Number | None = None
    width_mm: Number | None = None
    kind: str | None = None
    kxx_n_per_mm: Numbers | None = None
    kyy_n_per_mm: Numbers | None = None
    kxy_n_per_mm: Numbers | None = None
    kyx_n_per_mm: Numbers | None = None
    cxx_n_s_per_mm: Numbers | None = None
    cyy_n_s_per_mm: Numbers | None = None
    cxy_n_s_per_mm: Numbers | None = None
    cyx_n_s_per_mm: Numbers | None = None
    speeds_rpm: Numbers | None = None
    radial_stiffness_n_per_mm: Number | None = None
    axial_stiffness_n_per_mm: Number | None = None
    tilting_stiffness_nmm_per_rad: Number | None = None
    radial_clearance_um: Number | None = None
    diameter_mm: Number | None = None
    viscosity_mpa_s: Number | None = None
    oil_iso_vg: int | None = None
    oil_temperature_c: Number | None = None
    oil_supply_temperature_c: Number | None = None
    pad_temperature_limit_c: Number | None = None
    oil_flow_l_min: Number | None = None
    load_n: Number | None = None
    load_angle_deg: Number | None = None
    cavitation: str | None = None
    bore: str | None = None
    pads: int | None = None
    pad_arc_deg: Number | None = None
    preload: Number | None = None
    pivot_offset: Number | None = None
    load_between_pads: bool | None = None
    pad_inertia_kg_mm2: Number | None = None
    pivot_stiffness_n_per_mm: Number | None = None
    pad_mass_kg: Number | None = None
    pad_thickness_mm: Number | None = None
    groove_arc_deg: Number | None = None
    min_film_um: Number | None = None
    elements: int | None = None
    element_diameter_mm: Number | None = None
    pitch_diameter_mm: Number | None = None
    roller_length_mm: Number | None = None
    contact_angle_deg: Number | None = None
    preload_n: Number | None = None
    pressure_drop_mpa: Number | None = None
    fluid_density_kg_m3: Number | None = None
    inlet_loss: Number | None = None
    coupling: str | None = None
    slope_limit_mrad: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Attachment(_Table):
    """[[attachment]]: a part fixed on the shaft (wheel, pulley, rotor), mm, kg, kg m^2."""

    TABLE: ClassVar[str] = "attachment"
    name: str | None = None
    position_mm: Number | None = None
    width_mm: Number | None = None
    mass_kg: Number | None = None
    polar_inertia_kg_m2: Number | None = None
    diametral_inertia_kg_m2: Number | None = None
    stage_power_kw: Number | None = None
    stage_diameter_mm: Number | None = None
    stage_width_mm: Number | None = None
    stage_kind: str | None = None
    density_ratio: Number | None = None
    coupling_stiffness_nm_per_rad: Number | None = None
    coupled_inertia_kg_m2: Number | None = None
    joint: str | None = None
    slope_limit_mrad: Number | None = None
    deflection_limit_um: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Rotor(_Table):
    """[rotor]: the shaft turning, r/min."""

    TABLE: ClassVar[str] = "rotor"
    speed_rpm: Numbers | None = None
    max_speed_rpm: Number | None = None
    rated_speed_rpm: Number | None = None
    frame: str | None = None
    campbell_points: int | None = None
    probes_mm: Numbers | None = None
    basis_modes: int | None = None
    speed_range_rpm: Numbers | None = None
    amplitude_limit_um: Number | None = None
    min_log_dec: Number | None = None
    tolerance_cases: str | None = None
    log_dec_modes: str | None = None
    level1: bool | None = None
    level1_qa_n_per_mm: Number | None = None
    runup_rpm_per_s: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Unbalance(_Table):
    """[[unbalance]]: an unbalance at a plane (mm) or on a part, g mm at phase_deg."""

    TABLE: ClassVar[str] = "unbalance"
    name: str | None = None
    position_mm: Number | None = None
    part: str | None = None
    amount_g_mm: Number | None = None
    phase_deg: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Static(_Table):
    """[static]: gravity, m/s^2, and the direction it pulls in."""

    TABLE: ClassVar[str] = "static"
    gravity_m_s2: Number | None = None
    gravity_direction: Numbers | None = None


@dataclass(frozen=True, kw_only=True)
class Force(_Table):
    """[[force]]: a static radial force on a cross-section (mm) or a part, N."""

    TABLE: ClassVar[str] = "force"
    name: str | None = None
    position_mm: Number | None = None
    part: str | None = None
    fx_n: Number | None = None
    fy_n: Number | None = None
    fz_n: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Resonance(_Table):
    """[resonance]: the separation margin (%) and how it is judged."""

    TABLE: ClassVar[str] = "resonance"
    required_margin_percent: Number | None = None
    criterion: str | None = None
    free_free: bool | None = None


@dataclass(frozen=True, kw_only=True)
class ModesWanted(_Table):
    """[modes]: how many modes, or every mode below max_frequency_hz."""

    TABLE: ClassVar[str] = "modes"
    count: int | None = None
    max_frequency_hz: Number | None = None


@dataclass(frozen=True, kw_only=True)
class Response(_Table):
    """[response]: modal damping (%) and the point whose response is shown (mm)."""

    TABLE: ClassVar[str] = "response"
    damping_ratio_percent: Number | None = None
    point_mm: Number | None = None


# the single tables make_scene and vary take, by keyword, and the repeated ones
SINGLE: dict[str, type[_Table]] = {"material": Material, "mesh": Mesh, "grooves": Grooves,
                                   "rotor": Rotor, "resonance": Resonance, "modes": ModesWanted,
                                   "response": Response, "static": Static}
REPEATED: dict[str, type[_Table]] = {"supports": Support, "attachments": Attachment,
                                     "excitations": Excitation, "unbalances": Unbalance,
                                     "forces": Force}
class _Unset:
    """vary's default for a table it is not given: the scene's is kept."""

    def __repr__(self) -> str:   # as the signature reads in help() and the docs
        return "unchanged"


_UNSET: Any = _Unset()


def _entry(value: Any, kind: type[_Table]) -> dict[str, Any]:
    """One table's keys from its object (or a dict of the file's keys, taken as it is)."""
    if isinstance(value, kind):
        return value.table()
    if isinstance(value, Mapping):
        return _plain(value)
    raise SceneError(f"[{kind.TABLE}]: expected shaftfem.{kind.__name__}(...) or a dict of "
                     f"its keys, not {type(value).__name__}")


def _set(tables: dict, given: dict[str, Any]) -> dict:
    """`tables` with each given keyword's table(s) replaced (None: left out)."""
    for word, value in given.items():
        if value is _UNSET:
            continue
        if word == "shaft":
            for t in ("shaft", "section", "keyway"):
                tables.pop(t, None)
            if not isinstance(value, Shaft):
                raise SceneError(f"shaft: expected shaftfem.Shaft(...), not {type(value).__name__}")
            tables.update(value.tables())
        elif word in SINGLE:
            table = SINGLE[word].TABLE
            tables.pop(table, None)
            if value is not None:
                tables[table] = _entry(value, SINGLE[word])
        elif word in REPEATED:
            table = REPEATED[word].TABLE
            tables.pop(table, None)
            if isinstance(value, (str, bytes, Mapping, _Table)) or not isinstance(value, Iterable):
                raise SceneError(f"{word}: expected a list of shaftfem.{REPEATED[word].__name__}"
                                 f"(...), not {type(value).__name__}")
            entries = [_entry(v, REPEATED[word]) for v in value]
            if entries:
                tables[table] = entries
        elif word == "sizing":
            tables.pop("sizing", None)
            if value is not None:
                tables["sizing"] = _plain(value)
        elif word in ("name", "description"):
            tables.pop(word, None)
            if value is not None:
                tables[word] = value
        else:
            raise TypeError(f"unexpected keyword {word!r}")
    return tables


def make_scene(*, shaft: Shaft, material: Material | Mapping, mesh: Mesh | Mapping,
               name: str | None = None, description: str | None = None,
               grooves: Grooves | Mapping | None = None,
               supports: Iterable[Support | Mapping] = (),
               attachments: Iterable[Attachment | Mapping] = (),
               excitations: Iterable[Excitation | Mapping] = (),
               rotor: Rotor | Mapping | None = None,
               unbalances: Iterable[Unbalance | Mapping] = (),
               resonance: Resonance | Mapping | None = None,
               modes: ModesWanted | Mapping | None = None,
               response: Response | Mapping | None = None,
               static: Static | Mapping | None = None,
               forces: Iterable[Force | Mapping] = (),
               sizing: Mapping | None = None) -> Scene:
    """A scene from its tables, checked as a scene file is (SceneError naming the key)."""
    given = dict(locals())
    return load_scene(_set({}, given))


def vary(scene: Scene, *, shaft: Shaft = _UNSET, material: Material | Mapping = _UNSET,
         mesh: Mesh | Mapping = _UNSET, name: str | None = _UNSET,
         description: str | None = _UNSET, grooves: Grooves | Mapping | None = _UNSET,
         supports: Iterable[Support | Mapping] = _UNSET,
         attachments: Iterable[Attachment | Mapping] = _UNSET,
         excitations: Iterable[Excitation | Mapping] = _UNSET,
         rotor: Rotor | Mapping | None = _UNSET,
         unbalances: Iterable[Unbalance | Mapping] = _UNSET,
         resonance: Resonance | Mapping | None = _UNSET, modes: ModesWanted | Mapping | None = _UNSET,
         response: Response | Mapping | None = _UNSET, static: Static | Mapping | None = _UNSET,
         forces: Iterable[Force | Mapping] = _UNSET, sizing: Mapping | None = _UNSET
         ) -> Scene:
    """A variant of `scene`: each table given replaces the scene's (None leaves a single
    table out), the rest kept; checked as a scene file is. To add a support, pass the old
    ones with it: `supports=[*scene.tables["support"], Support(...)]`."""
    given = {k: v for k, v in locals().items() if k != "scene"}
    return load_scene(_set(copy.deepcopy(scene.file_tables()), given))
