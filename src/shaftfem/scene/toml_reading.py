"""Reading scene-like TOML files against the schema: each value checked and coerced,
every error naming the file, the key, the value and what is allowed."""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path
from typing import Any

from shaftfem.errors import SceneError
from shaftfem.scene.schema import SCHEMA, TABLES, Key


def where(source: str, table: str, key: str) -> str:
    """'file: table.key', or 'file: support 2 ("drive end"): key' for an entry of an
    array of tables (see `entry`)."""
    if " " in table:
        return f"{source}: {table}: {key}"
    return f"{source}: {table + '.' if table else ''}{key}"


def entry(table: str, i: int, raw: object = None) -> str:
    """Entry i (from 0) of an array of tables as people count it, from 1, and by its
    name when it has one: 'support 1 ("drive end")'."""
    name = raw.get("name") if isinstance(raw, dict) else getattr(raw, "name", None)
    label = f"{table} {i + 1}"
    return label + (f' ("{name}")' if isinstance(name, str) and name and name != label else "")


def _coerce(source: str, table: str, key: str, spec: Key, value: Any) -> Any:
    at = where(source, table, key)
    if spec.kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SceneError(f"{at} = {value!r}: expected a number ({spec.doc})")
        value = float(value)
        if not math.isfinite(value):
            raise SceneError(f"{at} = {value!r}: expected a finite number ({spec.doc})")
    elif spec.kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise SceneError(f"{at} = {value!r}: expected an integer ({spec.doc})")
    elif spec.kind is bool:
        if not isinstance(value, bool):
            raise SceneError(f"{at} = {value!r}: expected true or false ({spec.doc})")
    elif spec.kind is str:
        if not isinstance(value, str):
            raise SceneError(f"{at} = {value!r}: expected a string ({spec.doc})")
    elif isinstance(spec.kind, tuple) and spec.kind[0] == "list":
        if spec.kind[1] is float and isinstance(value, list) and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                for v in value):
            value = [float(v) for v in value]  # [0, 0, 1] means numbers too
        if not isinstance(value, list) or not all(isinstance(v, spec.kind[1]) for v in value):
            raise SceneError(f"{at} = {value!r}: expected a list ({spec.doc})")
    if spec.check is not None and not spec.check(value):
        raise SceneError(f"{at} = {value!r}: must be {spec.allowed} ({spec.doc})")
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
                f"{where(source, table, key)}: unknown key; allowed: {', '.join(schema)}"
            )
        out[key] = _coerce(source, table, key, schema[key], value)
    for key, spec in schema.items():
        if key not in out:
            if spec.required:
                raise SceneError(f"{where(source, table, key)}: missing ({spec.doc})")
            out[key] = spec.default
    return out


def read_toml(path: str | Path, what: str = "file") -> dict:
    """A TOML file as a dict; a missing or malformed file is a SceneError naming it.
    A UTF-8 byte-order mark (Windows editors write one) is accepted."""
    path = Path(path)
    try:
        return tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except FileNotFoundError as exc:
        raise SceneError(f"{what} {str(path)!r}: no such file") from exc
    except (IsADirectoryError, PermissionError) as exc:
        raise SceneError(f"{what} {str(path)!r}: cannot be read ({exc.strerror})") from exc
    except UnicodeDecodeError as exc:
        raise SceneError(f"{path.name}: not a text file (TOML is UTF-8 text)") from exc
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{path.name}: not valid TOML: {exc}") from exc


# --------------------------------------------------------------------------
# Checks for the other files the tool reads (sweeps, calibrations): each error names
# the file, the key, the value and what is allowed.


def known_keys(source: str, data: object, allowed: set[str], where_: str = "") -> dict:
    """`data` must be a table whose keys are all in `allowed`."""
    if not isinstance(data, dict):
        raise SceneError(f"{source}: {where_ or 'the file'} = {data!r}: must be a table")
    for key in data:
        if key not in allowed:
            raise SceneError(f"{source}: {where_ + '.' if where_ else ''}{key}: unknown key; "
                             f"allowed: {', '.join(sorted(allowed))}")
    return data


def number(source: str, key: str, value: object, low: float, high: float) -> float:
    """A finite number with low < value <= high."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and low < value <= high):
        raise SceneError(f"{source}: {key} = {value!r}: must be a number in ({low:g}, {high:g}]")
    return float(value)


# Tables a scene may repeat ([[support]]): a parameter names one entry by its index.
ARRAY_TABLES = tuple(name for name, table in TABLES.items() if table.repeated)


def split_parameter(name: str) -> tuple[str, int | None, str] | None:
    """'table.key' -> (table, None, key); 'table[i].key' -> (table, i, key); else None."""
    m = re.fullmatch(r"([a-z_]+)(?:\[(\d+)\])?\.([a-z0-9_]+)", name)
    if m is None:
        return None
    table, index, key = m.groups()
    if (index is None) == (table in ARRAY_TABLES):
        return None
    return table, None if index is None else int(index), key


def parameter(source: str, name: object) -> str:
    """A numeric scene key written 'table.key' (e.g. 'grooves.depth_mm'), or
    'table[i].key' for entry i of a repeated table (e.g. 'support[1].position_mm')."""
    parts = split_parameter(name) if isinstance(name, str) else None
    spec = SCHEMA.get(parts[0], {}).get(parts[2]) if parts else None
    if spec is None or spec.kind not in (float, int):
        raise SceneError(f"{source}: {name!r}: not a numeric scene key; a parameter is "
                         "'table.key', e.g. 'grooves.depth_mm' or 'shaft.length_mm', or "
                         "'table[i].key' for a repeated table, e.g. 'support[1].position_mm'")
    return str(name)
