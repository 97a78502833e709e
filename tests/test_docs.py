"""The docs: the pages made from the code are current, the site builds with warnings as
errors (a broken link, a missing page or image fails), and the README stays short."""

import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from shaftfem.cli.reference import command_reference
from shaftfem.scene import reference, schema
from shaftfem.scene.reference import scene_reference

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def test_the_scene_file_reference_is_what_the_schema_gives():
    assert (DOCS / "scene-file.md").read_text() == scene_reference(), (
        "docs/scene-file.md is not what the schema gives: run python scripts/write_docs.py")


def test_the_command_reference_is_what_the_parser_gives():
    assert (DOCS / "commands.md").read_text() == command_reference(), (
        "docs/commands.md is not what the parser gives: run python scripts/write_docs.py")


def test_every_scene_key_is_on_the_reference_page_with_its_unit():
    page = (DOCS / "scene-file.md").read_text()
    for table, keys in schema.SCHEMA.items():
        for key in keys:
            row = next((line for line in page.splitlines() if line.startswith(f"| `{key}` |")),
                       None)
            assert row is not None, (table, key)
            assert f"| {reference.unit(key)} |" in row, (table, key, row)


def test_a_key_added_to_the_schema_without_its_page_fails(monkeypatch):
    grooves = dict(schema.SCHEMA["grooves"])
    grooves["lead_error_mm"] = schema.Key(float, "helix lead error, mm", required=False)
    monkeypatch.setitem(schema.SCHEMA, "grooves", grooves)
    assert (DOCS / "scene-file.md").read_text() != scene_reference()
    assert "| `lead_error_mm` | mm |" in scene_reference()


def test_a_key_or_table_without_a_description_is_refused(monkeypatch):
    shaft = dict(schema.SCHEMA["shaft"])
    shaft["taper_deg"] = schema.Key(float, " ", required=False)
    monkeypatch.setitem(schema.SCHEMA, "shaft", shaft)
    with pytest.raises(ValueError, match="shaft.taper_deg has no description"):
        scene_reference()
    monkeypatch.setitem(schema.SCHEMA, "shaft", dict(schema.SCHEMA["material"]))
    monkeypatch.setitem(schema.TABLES, "shaft", replace(schema.TABLES["shaft"], doc=""))
    with pytest.raises(ValueError, match=r"table \[shaft\] has no description"):
        scene_reference()


def test_the_site_builds_with_warnings_as_errors(tmp_path):
    out = tmp_path / "html"
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b",
                          "html", str(DOCS), str(out)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-3000:]
    pages = {p.stem for p in DOCS.glob("*.md")}
    assert pages <= {p.stem for p in out.glob("*.html")}
    scene = (out / "scene-file.html").read_text()
    assert "youngs_modulus_mpa" in scene and "tilting_stiffness_nmm_per_rad" in scene
    api = (out / "api.html").read_text()
    assert "run_bounded" in api and "ErrorEstimate" in api  # autodoc found the docstrings


def test_the_readme_is_short_and_its_links_resolve():
    text = (ROOT / "README.md").read_text()
    assert len(text.splitlines()) <= 150
    targets = re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", text)
    local = [t for t in targets if "://" not in t]
    assert local, "the README links into the docs"
    missing = [t for t in local if not (ROOT / t).exists()]
    assert not missing, missing


def _public_docstrings():
    """(where, text) of every public module, class and function docstring in shaftfem."""
    import ast

    for path in sorted((ROOT / "src" / "shaftfem").rglob("*.py")):
        tree = ast.parse(path.read_text())
        where = path.relative_to(ROOT)
        if ast.get_docstring(tree):
            yield f"{where}", ast.get_docstring(tree)
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and not node.name.startswith("_"):
                text = ast.get_docstring(node)
                if text:
                    yield f"{where}:{node.name}", text


def test_docstrings_name_the_orders_and_flags_the_command_line_takes():
    """A docstring that gives a range of element orders gives one the command line takes
    (and all of it when it starts at the lowest), and a --flag it names is one of the
    command line's (the ParaView script's own --png and --mode aside)."""
    from shaftfem.cli.parser import build_parser
    from shaftfem.scene.schema import ELEMENT_ORDERS

    parser = build_parser()
    flags = {o for a in parser._actions for o in a.option_strings}
    for sub in parser._subcommands().values():
        flags |= {o for a in sub._actions for o in a.option_strings}
    low, high = min(ELEMENT_ORDERS), max(ELEMENT_ORDERS)
    wrong = []
    for where, text in _public_docstrings():
        text = " ".join(text.split())
        for a, b in re.findall(r"orders?\D{0,12}?(\d) to (\d)", text):
            a, b = int(a), int(b)
            if not low <= a <= b <= high or (a == low and b != high):
                wrong.append(f"{where}: orders {a} to {b} (the command line takes {low} to {high})")
        for flag in re.findall(r"(?<![\w-])--[a-z][a-z0-9-]*", text):
            if flag not in flags and not where.startswith("src/shaftfem/outputs/paraview_script"):
                wrong.append(f"{where}: {flag} is no flag of the command line")
    assert not wrong, "\n".join(wrong)


def test_every_benchmark_script_makes_a_table_named_after_it():
    """benchmarks/tables.py lists each docs table with its script: every script there
    exists and is its key's name, every script in benchmarks/ is one of them (but the
    entry point, its helpers and the bit-for-bit checks), and the docs cite no script
    that is gone."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("tables", ROOT / "benchmarks" / "tables.py")
    assert spec is not None and spec.loader is not None
    tables = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tables)
    scripts = {command[0] for _, command in tables.TABLES.values()}
    for key, (_, command) in tables.TABLES.items():
        assert command[0] == key.replace("-", "_").replace(".", "_") + ".py", key
    present = {p.name for p in (ROOT / "benchmarks").glob("*.py")}
    helpers = {"_common.py", "tables.py", "ngsolve_reference.py", "frequency_bits.py",
               "ross_reference.py", "verification_reference.py", "journal_tables.py",
               "same_numbers.py", "notch_reference.py", "axisymmetric_reference.py",
               "tilting_pad_reference.py", "section_torsion_reference.py",
               "groove_root_kink.py", "crossings_refined.py", "keyseat_chart.py"}
    assert present - helpers == scripts
    cited = set()
    for page in [ROOT / "README.md", *(ROOT / "docs").glob("*.md")]:
        cited |= set(re.findall(r"benchmarks/(\w+\.py)", page.read_text()))
    assert cited <= present, cited - present
