"""The same numbers from two versions of shaftfem: campbell, ucs, level1, frf and design
run on every example with a [rotor], each writing its JSON, and two such runs compared
number by number.

    python benchmarks/same_numbers.py run OUT [--src SRC] [--only NAME] [--commands a,b]
    python benchmarks/same_numbers.py compare BEFORE AFTER [--rtol 1e-9]

`run` uses the shaftfem of folder SRC (a checkout's src/, default this one's) with a
fresh cache, so that a version compared is computed, not read back. `compare` reads the
JSON files of two runs, walks them side by side and lists every number that differs by
more than rtol of its size, then exits 1 if any does. Used to show that a rebuild of the
code changed no number.

What is not a number of the physics is skipped: timings and paths, and the round-off
diagnostics (a mode's residual and backward error, the mass-orthonormality error), which
measure round-off itself. A number's size is that of the quantity it belongs to: in a
list of records (the modes), a quantity given along an axis is sized by its largest over
the list along any axis (a bending mode's effective mass along the axis, 1e-25 kg, is
round-off of a quantity whose modes reach kilograms; a frequency is its own size), and a
percentage of a frequency (an error bound) is
compared as the part of that frequency it is.
"""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

# each command with the arguments it needs beyond the scene (frf: a force 100 mm from
# the left end, which lies on every example's shaft; level1: an anticipated Q where the
# scene names none)
COMMANDS = {
    "campbell": [],
    "ucs": [],
    "level1": ["--qa-n-per-mm", "1000"],
    "frf": ["--at-mm", "100", "--frequencies-hz", "10:500:25"],
    "design": ["--no-html"],
}
# keys whose values are the run's circumstances, not its physics; and round-off's own
# measures
SKIP = {"seconds", "timings", "time", "times", "wall", "elapsed", "version", "path", "paths",
        "out", "files", "cache", "created", "source", "folder", "date", "peak_mb",
        "timings_s", "residual", "residuals", "backward_error", "mass_orthonormality_error"}


def examples() -> list[Path]:
    return sorted(p for p in (ROOT / "examples").glob("*.toml")
                  if "\n[rotor]" in p.read_text(encoding="utf-8"))


def run(out: Path, src: Path, only: str | None, commands: list[str]) -> int:
    out.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, "PYTHONPATH": str(src)}
    failed = 0
    with tempfile.TemporaryDirectory() as cache:
        env["SHAFTFEM_CACHE"] = cache
        for scene in examples():
            if only and only != scene.stem:
                continue
            for command in commands:
                extra = COMMANDS[command]
                target = out / f"{scene.stem}.{command}.json"
                folder = Path(cache) / "out" / scene.stem / command
                # design writes its JSON files into its folder (modes.json, ...)
                asked = [] if command == "design" else ["--json", str(target)]
                t = time.perf_counter()
                proc = subprocess.run(
                    [sys.executable, "-m", "shaftfem", command, str(scene), *asked,
                     "--out", str(folder), *extra],
                    env=env, capture_output=True, text=True, stdin=subprocess.DEVNULL)
                if command == "design":
                    for f in sorted(folder.glob("*.json")):
                        if "manifest" not in f.name:
                            (out / f"{scene.stem}.design.{f.name}").write_bytes(f.read_bytes())
                wall = time.perf_counter() - t
                print(f"{scene.stem:40s} {command:9s} exit {proc.returncode}  {wall:6.1f} s",
                      flush=True)
                (out / f"{scene.stem}.{command}.exit").write_text(
                    f"{proc.returncode}\n{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}")
                failed += proc.returncode not in (0, 1)
    return 1 if failed else 0


def _number(x: object) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def family(key: str) -> str:
    """A field's quantity whatever its axis: effective_mass_x_kg and effective_mass_rz_kg_m2
    are both effective_mass_*."""
    return re.sub(r"_(x|y|z|rx|ry|rz)(_.*)?$", "_*", key)


def field_sizes(a: list, b: list) -> dict[str, float]:
    """The size of each quantity given along an axis (family), over two lists of records:
    its largest magnitude there along any axis (such a field is zero by symmetry on some
    records, and round-off there). Any other field, a frequency, is its own size."""
    sizes: dict[str, float] = {}
    for rec in (*a, *b):
        if isinstance(rec, dict):
            for k, v in rec.items():
                if family(k) != k and _number(v) and math.isfinite(v):
                    sizes[family(k)] = max(sizes.get(family(k), 0.0), abs(v))
    return sizes


def differences(a: object, b: object, where: str, rtol: float, size: float = 0.0
                ) -> list[str]:
    """Every place where two JSON values differ: a number by more than rtol of the
    larger or of `size` (its quantity's, see the module's docstring), anything else at
    all."""
    if isinstance(a, dict) and isinstance(b, dict):
        return _record(a, b, where, rtol, {})
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{where}: {len(a)} items before, {len(b)} after"]
        sizes = field_sizes(a, b)
        out = []
        for i, (x, y) in enumerate(zip(a, b)):
            if isinstance(x, dict) and isinstance(y, dict):
                out += _record(x, y, f"{where}[{i}]", rtol, sizes)
            else:
                out += differences(x, y, f"{where}[{i}]", rtol, size)
        return out
    if _number(a) and _number(b):
        assert isinstance(a, (int, float)) and isinstance(b, (int, float))
        if math.isnan(a) and math.isnan(b):
            return []
        if a == b or abs(a - b) <= rtol * max(abs(a), abs(b), size):
            return []
        return [f"{where}: {a!r} before, {b!r} after"]
    return [] if a == b else [f"{where}: {a!r} before, {b!r} after"]


def _record(a: dict, b: dict, where: str, rtol: float, sizes: dict[str, float]) -> list[str]:
    """A record of a list compared field by field, each at its quantity's size over the
    list (field_sizes; a percentage at 100)."""
    out = []
    for k in sorted(set(a) | set(b)):
        if k in SKIP:
            continue
        if k not in a or k not in b:
            out.append(f"{where}.{k}: only in {'after' if k in b else 'before'}")
            continue
        out += differences(a[k], b[k], f"{where}.{k}", rtol,
                           100.0 if k.endswith("_percent") else sizes.get(family(k), 0.0))
    return out


def compare(before: Path, after: Path, rtol: float) -> int:
    names = sorted({p.name for p in before.glob("*.json")} | {p.name for p in after.glob("*.json")})
    bad = 0
    for name in names:
        a, b = before / name, after / name
        if not (a.exists() and b.exists()):
            print(f"{name}: only in {'after' if b.exists() else 'before'}")
            bad += 1
            continue
        found = differences(json.loads(a.read_text()), json.loads(b.read_text()), "", rtol)
        print(f"{name}: {'same' if not found else f'{len(found)} numbers differ'}")
        for line in found[:20]:
            print("   ", line)
        bad += bool(found)
    for code in sorted(before.glob("*.exit")):
        other = after / code.name
        if other.exists() and code.read_text().split()[0] != other.read_text().split()[0]:
            print(f"{code.stem}: exit {code.read_text().split()[0]} before, "
                  f"{other.read_text().split()[0]} after")
            bad += 1
    print(f"{len(names)} JSON files, {bad} differ (rtol {rtol:g})")
    return 1 if bad else 0


def main(argv: list[str]) -> int:
    if len(argv) >= 2 and argv[0] == "run":
        src = Path(argv[argv.index("--src") + 1]) if "--src" in argv else ROOT / "src"
        only = argv[argv.index("--only") + 1] if "--only" in argv else None
        commands = (argv[argv.index("--commands") + 1].split(",") if "--commands" in argv
                    else list(COMMANDS))
        return run(Path(argv[1]), src.resolve(), only, commands)
    if len(argv) >= 3 and argv[0] == "compare":
        rtol = float(argv[argv.index("--rtol") + 1]) if "--rtol" in argv else 1e-9
        return compare(Path(argv[1]), Path(argv[2]), rtol)
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
