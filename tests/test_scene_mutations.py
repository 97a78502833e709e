"""Generated bad scenes: every key of the paper's scene given values of the wrong kind,
non-finite, absurd or out of range, each key left out and an unknown key added. Each
must be refused by the command line before any work: exit 2, one line on stderr that
names the file and the key, no traceback, no file written.

`shaftfem size` reads and validates the whole scene and then only does arithmetic, so a
mutation that slipped through shows as exit 0 or 1 within milliseconds, not as a solve.
"""

import json
import math
import tomllib

import pytest

from shaftfem.cli import main
from shaftfem.scene.load import GEOMETRY_DIR
from shaftfem.scene.schema import SCHEMA

PAPER = tomllib.loads((GEOMETRY_DIR / "paper2018.toml").read_text())

FLOATS = [math.nan, math.inf, -math.inf, 1e300, -1e300, "text", True, [1.0], {"a": 1.0}]
INTS = [2.5, math.nan, "text", True, -1, 10**12, [1]]
STRINGS = [5, 1.5, True, ["a"]]
BOOLS = [1, 0, "true", 1.5, [True]]
LISTS = {"hands": ["right", [], ["up"], [1], ["left", "left"], ["right", "left", "right"]],
         "orders": [1, [], [0], [-2], [1.5], ["one"]],
         "axis_from_mm": [1.0, [], [0.0, 1.0], [0, 0, 0, 1], ["a", "b", "c"]],
         "axis_to_mm": [1.0, [], [0.0, 1.0], [0, 0, 0, 1], ["a", "b", "c"]]}


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) \
            else repr(v)
    if isinstance(v, (int, str)):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return "{ " + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + " }"


def _toml(data: dict) -> str:
    lines = [f"{k} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, (dict, list))
             or (isinstance(v, list) and not (v and isinstance(v[0], dict)))]
    for k, v in data.items():
        if isinstance(v, dict):
            lines += [f"[{k}]"] + [f"{kk} = {_toml_value(x)}" for kk, x in v.items()]
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                lines += [f"[[{k}]]"] + [f"{kk} = {_toml_value(x)}" for kk, x in item.items()]
    return "\n".join(lines) + "\n"


def _mutations():
    cases = []
    tables = {"": {k: v for k, v in PAPER.items() if not isinstance(v, (dict, list))}}
    tables.update({k: v for k, v in PAPER.items() if isinstance(v, dict)})
    tables["excitation"] = PAPER["excitation"][0]
    for table, present in tables.items():
        for key, spec in SCHEMA[table].items():
            if spec.kind is float:
                bad = FLOATS
            elif spec.kind is int:
                bad = INTS
            elif spec.kind is str:
                bad = STRINGS
            elif spec.kind is bool:
                bad = BOOLS
            else:
                bad = LISTS[key]
            cases += [(table, key, "value", v) for v in bad]
            if spec.required and key in present:
                cases.append((table, key, "missing", None))
        cases.append((table, "no_such_key_mm", "unknown", 1.0))
    return cases


CASES = _mutations()


def _mutated(table: str, key: str, how: str, value) -> dict:
    data = json.loads(json.dumps(PAPER))
    if table == "excitation":
        target = data["excitation"][0]
    elif table == "":
        target = data
    else:
        target = data.setdefault(table, {})
    if how == "missing":
        del target[key]
    else:
        target[key] = value
    return data


def test_there_are_at_least_200_mutations():
    assert len(CASES) >= 200, len(CASES)


@pytest.mark.parametrize("table,key,how,value", CASES,
                         ids=[f"{t or 'top'}.{k}-{h}-{i}" for i, (t, k, h, _) in enumerate(CASES)])
def test_a_mutated_scene_is_refused_naming_the_key(tmp_path, capsys, monkeypatch, table, key,
                                                   how, value):
    scene = tmp_path / "mutated.toml"
    scene.write_text(_toml(_mutated(table, key, how, value)))
    monkeypatch.chdir(tmp_path)
    assert main(["size", str(scene)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "Traceback" not in err[0] and "mutated.toml" in err[0] and key in err[0], err[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mutated.toml"]
