"""Compare the installed packages with a lock file: every package the lock pins for this
interpreter and platform must be installed at exactly the pinned version.

    python scripts/check_lock.py requirements/dev.txt

Prints each difference and exits 1 if there is one; 0 and one line otherwise.
"""

from __future__ import annotations

import re
import sys
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from packaging.markers import Marker
from packaging.utils import canonicalize_name

PIN = re.compile(r"^([A-Za-z0-9._-]+)(?:\[[^\]]*\])?==([^\s;\\]+)\s*(?:;\s*([^\\]+?))?\s*\\?$")


def pinned(lock: Path) -> dict[str, str]:
    """{package: version} the lock pins for this interpreter and platform."""
    out = {}
    for line in lock.read_text().splitlines():
        m = PIN.match(line.strip())
        if m and (m.group(3) is None or Marker(m.group(3)).evaluate()):
            out[canonicalize_name(m.group(1))] = m.group(2)
    return out


def differences(lock: Path) -> list[str]:
    """One line per locked package that is missing or at another version."""
    out = []
    for name, want in sorted(pinned(lock).items()):
        try:
            have = version(name)
        except PackageNotFoundError:
            out.append(f"{name}: locked {want}, not installed")
            continue
        if have != want:
            out.append(f"{name}: locked {want}, installed {have}")
    return out


def main(argv: list[str]) -> int:
    lock = Path(argv[1] if len(argv) > 1 else "requirements/dev.txt")
    diff = differences(lock)
    for line in diff:
        print(f"check_lock: {line}", file=sys.stderr)
    if not diff:
        print(f"check_lock: {len(pinned(lock))} packages installed exactly as {lock} pins them")
    return 1 if diff else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
