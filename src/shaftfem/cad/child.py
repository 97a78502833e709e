"""One function call in a child Python process, so that native code that aborts (gmsh's
high-order optimiser has: an uncaught C++ exception) ends the child, not the caller.

A fresh interpreter (`python -m shaftfem.cad.child`), not multiprocessing: spawning
re-runs the caller's main script, which a user's script without a main guard would
not survive, and forking copies threads that hold locks.
"""

from __future__ import annotations

import importlib
import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path


class ChildCrashed(RuntimeError):
    """The child process ended without a result (killed, or aborted by native code)."""


def call_in_child(function, *args):
    """function(*args) (a module-level function) in a child process; its exceptions are
    raised here; a child that dies raises ChildCrashed with its last error line."""
    with tempfile.TemporaryDirectory(prefix="shaftfem-child-") as folder:
        job, result = Path(folder) / "job.pkl", Path(folder) / "result.pkl"
        job.write_bytes(pickle.dumps((function.__module__, function.__qualname__, args)))
        run = subprocess.run([sys.executable, "-m", "shaftfem.cad.child", str(job), str(result)],
                             stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, env=os.environ.copy())
        if run.returncode != 0 or not result.exists():
            lines = run.stderr.decode(errors="replace").strip().splitlines()
            raise ChildCrashed(f"exit code {run.returncode}"
                               + (f": {lines[-1]}" if lines else ""))
        ok, value = pickle.loads(result.read_bytes())
    if not ok:
        raise value
    return value


def _main(job: str, result: str) -> None:
    module, name, args = pickle.loads(Path(job).read_bytes())
    try:
        out = (True, getattr(importlib.import_module(module), name)(*args))
    except Exception as exc:  # carried to the caller, who raises it
        out = (False, exc)
    Path(result).write_bytes(pickle.dumps(out))


if __name__ == "__main__":
    _main(*sys.argv[1:3])
