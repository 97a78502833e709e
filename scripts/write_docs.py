"""Write the docs pages made from the code: the scene file reference (from the schema)
and the command reference (from the parser).

    python scripts/write_docs.py          # write docs/scene-file.md and docs/commands.md
    python scripts/write_docs.py --check  # exit 1 if a page is not what the code gives
"""

import sys
from collections.abc import Callable
from pathlib import Path

from shaftfem.cli.reference import command_reference
from shaftfem.scene.reference import scene_reference

DOCS = Path(__file__).resolve().parents[1] / "docs"
PAGES: dict[str, Callable[[], str]] = {"scene-file.md": scene_reference,
                                       "commands.md": command_reference}


def main(argv: list[str]) -> int:
    stale = []
    for name, make in PAGES.items():
        page, text = DOCS / name, make()
        if "--check" in argv:
            if not page.exists() or page.read_text() != text:
                stale.append(name)
            continue
        page.write_text(text)
        print(f"wrote {page}")
    if stale:
        print(f"docs/{', docs/'.join(stale)}: not what the code gives; run "
              "python scripts/write_docs.py", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
