"""The module map in the docs (docs/contributing.md, Layout) is the package: every module
it lists exists where it says, every module of src/shaftfem is listed, and each imports
only modules listed above it."""

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "shaftfem"


def _readme_modules() -> list[str]:
    """The modules of the docs' Layout, in its order, as paths below src/shaftfem."""
    text = (ROOT / "docs" / "contributing.md").read_text()
    block = text[text.index("## Layout"):]
    block = block[block.index("```") + 3:]
    block = block[:block.index("```")]
    found: list[str] = []
    package = None
    for line in block.splitlines():
        if line.startswith("src/shaftfem/"):
            package = ""
            continue
        if package is None or not line.strip():
            continue
        if not line.startswith(" "):
            package = None  # the tree below src/ has ended
            continue
        sub = re.match(r"^  (\w+)/\s*$", line)
        if sub:
            package = sub.group(1)
            continue
        mod = re.match(r"^( {2,4})(\w+\.py)\b", line)
        if mod:
            found.append(f"{package}/{mod.group(2)}" if len(mod.group(1)) == 4 else mod.group(2))
    return found


def _module(path: str) -> str:
    """'fem/eigen.py' -> 'shaftfem.fem.eigen'; 'cli/__init__.py' -> 'shaftfem.cli'."""
    parts = ["shaftfem", *path.removesuffix(".py").split("/")]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def test_the_docs_layout_lists_every_module_where_it_is():
    actual = {str(p.relative_to(SRC)) for p in SRC.rglob("*.py")
              if p.name != "__init__.py" or p.parent.name == "cli" or p.parent == SRC}
    actual.discard("__main__.py")
    listed = _readme_modules()
    assert len(listed) == len(set(listed))
    assert set(listed) == actual, (f"in the docs' layout, not in the tree: "
                                   f"{sorted(set(listed) - actual)}; in the tree, not in the "
                                   f"layout: {sorted(actual - set(listed))}")


def test_every_module_imports_only_what_the_layout_lists_above_it():
    """One-way data flow, type-only imports included (the public API in __init__ excepted:
    it names everything, lazily)."""
    listed = [m for m in _readme_modules() if m != "__init__.py"]
    rank = {_module(m): i for i, m in enumerate(listed)}
    upward = []
    for path in listed:
        me = _module(path)
        for node in ast.walk(ast.parse((SRC / path).read_text())):
            if not isinstance(node, ast.ImportFrom) or node.module is None:
                continue
            # `from shaftfem.cli import commands` imports the module shaftfem.cli.commands
            modules = [m for m in (f"{node.module}.{a.name}" for a in node.names) if m in rank]
            for other in (m for m in modules or [node.module] if m in rank and m != me):
                if rank[other] > rank[me]:
                    upward.append(f"{me} imports {other}")
    assert not upward, upward


def test_the_cad_and_fem_stages_leave_the_cache_to_the_workflows():
    """The stages are pure functions of their inputs: the cache (shaftfem.store) is a layer
    around them (workflows.stages), never imported inside cad/ or fem/."""
    inside = []
    for path in sorted((SRC / "cad").glob("*.py")) + sorted((SRC / "fem").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                     [node.module or ""] + [f"{node.module}.{a.name}" for a in node.names]
                     if isinstance(node, ast.ImportFrom) else [])
            if any(n == "shaftfem.store" for n in names):
                inside.append(str(path.relative_to(SRC)))
    assert not inside, inside


def test_every_subpackage_is_packaged():
    """pyproject.toml lists its packages by name: a subpackage left off installs
    without it, and an installed shaftfem fails on its first import of it."""
    import tomllib
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    listed = set(tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
                 ["packages"])
    found = {".".join(p.parent.relative_to(root / "src").parts)
             for p in (root / "src" / "shaftfem").rglob("__init__.py")}
    assert found <= listed, sorted(found - listed)


def _imports(path: Path) -> list[tuple[str, str]]:
    """(module, name) for every `from module import name` in a file."""
    return [(node.module, a.name) for node in ast.walk(ast.parse(path.read_text()))
            if isinstance(node, ast.ImportFrom) and node.module for a in node.names]


def test_the_scene_declares_parts_and_the_workflows_only_load_it():
    """The walk is one way: scene/ validates and holds declarations and never asks a
    part for its physics (no import of parts/), and the workflows take from the loader
    only what loads a scene (the parts' coefficients come from workflows.equip)."""
    physics = [f"{p.relative_to(SRC)} imports {m}" for p in sorted((SRC / "scene").glob("*.py"))
               for m, _ in _imports(p) if m == "shaftfem.parts" or m.startswith("shaftfem.parts.")]
    assert not physics, physics
    loading = {"load_scene", "SceneText", "read_scene_text", "check_entries", "scene_beside",
               "resolve_scene_path", "GEOMETRY_DIR", "DEFAULT_SCENE", "scene_from_dict"}
    beyond = [f"{p.relative_to(SRC)} imports {name} from scene.load"
              for p in sorted((SRC / "workflows").glob("*.py"))
              for m, name in _imports(p) if m == "shaftfem.scene.load" and name not in loading]
    assert not beyond, beyond
