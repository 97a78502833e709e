"""The scene file reference (docs/scene-file.md) as Markdown, made from the schema.

Every key's unit comes from its name's suffix, its bounds and their reasons from the
schema's words, so the page cannot say what the reader does not get. A table or key
without a description is an error here, and so fails the docs test.
"""

from __future__ import annotations

from shaftfem.scene.schema import SCHEMA, TABLES, Key

# A key's unit, by the suffix of its name (the longest that matches wins).
UNITS = {
    "_mm": "mm", "_mpa": "MPa", "_kg_m3": "kg/m^3", "_rpm": "r/min", "_kw": "kW",
    "_deg": "deg", "_n_per_mm": "N/mm", "_n_s_per_mm": "N s/mm", "_nmm_per_rad": "N mm/rad",
    "_kg": "kg", "_g_mm": "g mm",
    "_kg_m2": "kg m^2", "_percent": "%", "_hz": "Hz", "_um": "um", "_mpa_s": "mPa s",
    "_n": "N", "_temperature_c": "C", "_m_s2": "m/s^2",
}

HEAD = """\
# Scene file reference

A scene file is a TOML file that describes one shaft: its geometry, material, mesh,
supports and parts, and what excites it. `geometry/paper2018.toml` is the paper's shaft;
copy a shipped scene and change it. Every key names its unit (`_mm`, `_mpa`, `_rpm`,
...); inside, shaftfem works in SI. Unknown keys, wrong types and values out of range
are errors that name the file, the key, the value and what is allowed (exit status 2).

A bearing given by its physics rather than its coefficients has its own page (the
model, equations, inputs and checks): [journal bearings](journal-bearing.md)
(`kind = "journal"`), [rolling bearings](rolling-bearing.md) (`kind = "ball"`,
`"roller"`), [annular seals](seal.md) (`kind = "seal"`), and a stage's
[aerodynamic cross-coupling](cross-coupling.md) on an
`[[attachment]]` (`stage_power_kw`), as is a [coupling to another machine](coupling.md)
(`coupling_stiffness_nm_per_rad`).

This page is generated from the schema in `shaftfem.scene.schema` by
`python scripts/write_docs.py`; a test fails when the two disagree.
"""


def unit(key: str) -> str:
    """The unit a key's name ends with ('-' for a number without one)."""
    ends = [s for s in UNITS if key.endswith(s)]
    return UNITS[max(ends, key=len)] if ends else "-"


def _type(k: Key) -> str:
    names = {float: "number", int: "integer", str: "text", bool: "true or false"}
    if isinstance(k.kind, tuple):
        return f"list of {names[k.kind[1]]}"
    return names[k.kind]


def _default(k: Key) -> str:
    if k.required:
        return "required"
    if k.default is None:
        return "optional"
    if isinstance(k.default, str):
        return f'"{k.default}"'
    if isinstance(k.default, bool):
        return "true" if k.default else "false"   # as TOML writes it
    return f"{k.default:g}" if isinstance(k.default, float) else str(k.default)


def _cell(text: str) -> str:
    """Text that stays in one Markdown table cell."""
    return " ".join(text.replace("|", "\\|").split())


def _heading(name: str) -> str:
    table = TABLES[name]
    if name == "":
        return "## Top level"
    return f"## `[[{name}]]`" if table.repeated else f"## `[{name}]`"


def scene_reference() -> str:
    """The scene file reference page, one section per table in the schema's order."""
    missing = sorted(set(SCHEMA) ^ set(TABLES))
    if missing:
        raise ValueError(f"tables without a description, or described but not in SCHEMA: {missing}")
    out = [HEAD]
    for name, keys in SCHEMA.items():
        table = TABLES[name]
        if not table.doc.strip():
            raise ValueError(f"table [{name}] has no description")
        need = ("Required." if table.required
                else "Optional; may appear several times." if table.repeated else "Optional.")
        if not table.required and any(k.required for k in keys.values()):
            need += " Where it is given, its required keys must be."
        out += [_heading(name), "", f"{table.doc} {need}", "",
                "| key | unit | type | default | allowed | meaning |",
                "|---|---|---|---|---|---|"]
        for key, k in keys.items():
            if not k.doc.strip():
                raise ValueError(f"key {name + '.' if name else ''}{key} has no description")
            out.append(f"| `{key}` | {unit(key)} | {_type(k)} | {_cell(_default(k))} | "
                       f"{_cell(k.allowed) or 'any'} | {_cell(k.doc)} |")
        out.append("")
    return "\n".join(out)
