"""The README's module map is the package: every module it lists exists where it says,
and every module of src/shaftfem is listed."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _readme_modules() -> set[str]:
    text = (ROOT / "README.md").read_text()
    block = text[text.index("## Layout"):]
    block = block[block.index("```") + 3:]
    block = block[:block.index("```")]
    found, package = set(), None
    for line in block.splitlines():
        if line.startswith("src/shaftfem/"):
            package = ""
            continue
        if package is None:
            continue
        if not line.startswith("  ") or line.startswith("   " * 7):
            if not line.startswith(" "):
                package = None  # the tree below src/ has ended
            continue
        sub = re.match(r"^  (\w+)/\s*$", line)
        if sub:
            package = sub.group(1)
            continue
        mod = re.match(r"^ {2,4}(\w+\.py)\b", line)
        if mod:
            indent = len(line) - len(line.lstrip())
            found.add(f"{package}/{mod.group(1)}" if indent == 4 else mod.group(1))
    return found


def test_the_readme_layout_lists_every_module_where_it_is():
    src = ROOT / "src" / "shaftfem"
    actual = {str(p.relative_to(src)) for p in src.rglob("*.py")
              if p.name != "__init__.py" or p.parent.name == "cli" or p.parent == src}
    actual.discard("__main__.py")
    listed = _readme_modules()
    assert listed == actual, (f"in the README, not in the tree: {sorted(listed - actual)}; "
                              f"in the tree, not in the README: {sorted(actual - listed)}")
