"""Where results live: content keys, the cache folder, atomic files and staged folders.

Every file shaftfem writes appears whole or not at all: it is written under a
temporary name beside its final one and renamed into place (a rename within
one folder is atomic). Cache entries are named by a hash of everything they
depend on, so a changed input can never fetch a stale result, and carry a
checksum of their content, so a damaged entry (truncated, emptied, garbled or
altered) is never used: it is discarded, said in one line, and rebuilt.
"""

from __future__ import annotations

import csv
import functools
import hashlib
import json
import math
import os
import shutil
import tempfile
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from shaftfem.errors import SceneError


class CacheWarning(UserWarning):
    """A cache entry failed its check; it is discarded and rebuilt."""


def checksum(*parts: bytes) -> str:
    h = hashlib.sha256()
    for p in parts:
        h.update(p)
    return h.hexdigest()


def discard(what: str, why: str, *paths: Path) -> None:
    """Remove a damaged cache entry, saying so in one line."""
    warnings.warn(f"cached {what} is damaged ({why}); discarded and rebuilt", CacheWarning,
                  stacklevel=3)
    for p in paths:
        Path(p).unlink(missing_ok=True)


def save_arrays(path: Path, fields: dict[str, Any]) -> None:
    """A cache entry of named arrays (.npz), with a checksum of them, written atomically."""
    with atomic_path(path) as tmp:
        np.savez(tmp, **fields, sha256=np.str_(_arrays_checksum(fields)))


def load_arrays(path: Path, names: tuple[str, ...]) -> tuple[dict | None, str]:
    """The arrays `names` of a save_arrays entry if it is whole and unaltered, else
    (None, why)."""
    import zipfile

    try:
        with np.load(path) as z:
            fields = {k: z[k] for k in names}
            stored = str(z["sha256"])
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as exc:
        return None, f"{type(exc).__name__}: {exc}"
    if stored != _arrays_checksum(fields):
        return None, "its content does not match its checksum"
    return fields, ""


def _arrays_checksum(fields: dict) -> str:
    return checksum(*(np.ascontiguousarray(fields[k]).tobytes() for k in sorted(fields)))


def cache_dir() -> Path:
    """The cache root: $SHAFTFEM_CACHE, else the platform's cache folder for shaftfem
    (~/.cache/shaftfem on Linux, or $XDG_CACHE_HOME/shaftfem)."""
    import platformdirs

    return Path(os.environ.get("SHAFTFEM_CACHE") or platformdirs.user_cache_dir("shaftfem"))


@functools.cache
def scratch_dir() -> Path:
    """A folder of this process's own, removed when it exits: where a run that keeps
    nothing (--no-cache) puts the files it needs while it runs (the solid's BREP)."""
    import atexit

    path = Path(tempfile.mkdtemp(prefix="shaftfem-"))
    atexit.register(shutil.rmtree, path, True)
    return path


def probe_writable(folder: Path, what: str) -> None:
    """Refuse (SceneError) a folder that cannot be made or written, by trying to, and
    leave no folder behind that the try made."""
    made = []
    p = Path(folder)
    while not p.exists() and p != p.parent:
        made.append(p)
        p = p.parent
    try:
        Path(folder).mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=".probe-", dir=folder)
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        raise SceneError(f"{what}: cannot write there ({exc.strerror or exc}: "
                         f"{exc.filename or folder})") from exc
    finally:
        for m in made:  # the deepest first
            try:
                m.rmdir()
            except OSError:
                pass


def check_cache() -> None:
    """The cache root must be a folder shaftfem can write (SceneError naming it)."""
    root = cache_dir()
    where = (f"the cache SHAFTFEM_CACHE={root}" if os.environ.get("SHAFTFEM_CACHE")
             else f"the cache {root}")
    if root.exists() and not root.is_dir():
        raise SceneError(f"{where}: is a file, not a folder; point SHAFTFEM_CACHE at a "
                         "writable folder, or run with --no-cache")
    try:
        probe_writable(root, where)
    except SceneError as exc:
        raise SceneError(f"{exc}; point SHAFTFEM_CACHE at a writable folder, or run with "
                         "--no-cache") from exc


def content_key(payload: dict, files: tuple[Path, ...] = (), length: int = 20) -> str:
    """A hex hash of `payload` (JSON, floats rounded to 12 digits) and the bytes of `files`."""
    h = hashlib.sha256()
    for f in files:
        h.update(Path(f).read_bytes())
    text = json.dumps(payload, sort_keys=True, default=lambda v: round(v, 12))
    h.update(text.encode())
    return h.hexdigest()[:length]


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path next to `path`; move it into place only on success."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o644)  # mkstemp makes 0600; results are for sharing
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def write_text(path: str | Path, text: str) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def plain(obj):
    """JSON form of NumPy values and paths (json.dumps' `default`)."""
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, (np.floating, np.integer, np.bool_)):
        return obj.item()
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def _finite(value):
    """The value with every infinite or undefined float made null: JSON has neither."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    return value


def json_text(data: dict) -> str:
    """Valid JSON (no Infinity or NaN: null where a number is infinite or undefined)."""
    return json.dumps(_finite(data), indent=2, default=plain, allow_nan=False) + "\n"


def write_json(path: str | Path, data: dict) -> Path:
    return write_text(path, json_text(data))


def write_csv(path: str | Path, rows: list[dict]) -> Path:
    """Rows of equal keys as CSV, header from the first row (atomic)."""
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return Path(path)


STAGING = ".staging-"


@contextmanager
def staged_directory(out: str | Path, manifest: str) -> Iterator[Path]:
    """Write a set of files into a hidden staging folder, then publish them in `out`
    with the manifest `out/manifest` (their names and SHA-256) written last.

    The files of a run are trusted when its manifest lists them (manifest_complete).
    Publishing first removes the old manifest, so a run killed while it moves files
    leaves no manifest that could vouch for a mixed set, and then the files the old
    manifest listed that this run did not write (mode_11 of an earlier 12-mode run);
    on a failure or an interrupt `out` gets none of the files, a folder made for the
    run is removed again, and the staging folders of killed runs go with the next run.
    """
    out = Path(out)
    made = not out.exists()
    out.mkdir(parents=True, exist_ok=True)
    _remove_stale_stages(out)
    stage = Path(tempfile.mkdtemp(prefix=f"{STAGING}{os.getpid()}-", dir=out))
    published = False
    try:
        yield stage
        files = sorted(stage.iterdir())
        sums = {f.name: checksum(f.read_bytes()) for f in files}
        write_json(stage / manifest, {"files": sums})
        old = _listed(out / manifest)
        (out / manifest).unlink(missing_ok=True)
        for name in old - set(sums) - {manifest}:
            (out / name).unlink(missing_ok=True)
        for f in files + [stage / manifest]:  # the manifest last
            os.chmod(f, 0o644)
            os.replace(f, out / f.name)
        published = True
    finally:
        shutil.rmtree(stage, ignore_errors=True)
        if made and not published:
            try:
                out.rmdir()  # only if empty
            except OSError:
                pass


def _listed(path: Path) -> set[str]:
    """The file names a manifest lists (none if it is missing or unreadable); plain
    names only, so a damaged manifest cannot point outside its folder."""
    try:
        names = json.loads(path.read_text())["files"]
    except (OSError, ValueError, KeyError, TypeError):
        return set()
    return {n for n in names if isinstance(n, str) and n == Path(n).name and n not in ("", ".", "..")}


def manifest_complete(out: str | Path, manifest: str) -> bool:
    """Whether `out/manifest` exists and every file it lists is there, unaltered."""
    try:
        listed = json.loads((Path(out) / manifest).read_text())["files"]
        return all(checksum((Path(out) / name).read_bytes()) == s for name, s in listed.items())
    except (OSError, ValueError, KeyError, TypeError):
        return False


def _remove_stale_stages(out: Path) -> None:
    """Staging folders whose process is gone (killed runs)."""
    for stage in out.glob(f"{STAGING}*"):
        pid = stage.name[len(STAGING):].split("-")[0]
        if pid.isdigit() and _alive(int(pid)):
            continue
        shutil.rmtree(stage, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
