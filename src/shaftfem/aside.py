"""Work done beside the main line of a run, on the other core: pictures that nothing
downstream reads, and a study that shares nothing with the one in hand.

`Aside(job, *args)` runs `job(*args)` in a new Python (`python -m shaftfem.aside IN
OUT`, the job and its arguments handed over as a pickle; `job` a module-level
function); `.result()` waits for it and gives what it returned, or raises what it
raised. A new Python, never a fork of this one: a fork would inherit the solver's
thread pools mid-flight (OpenMP in a forked child can wait forever on a lock its
parent's thread held), and multiprocessing's spawn would run a user's script again.
With SHAFTFEM_ASIDE=0, or inside a daemonic worker (a Dask one), the job runs right
there instead, with the same answer.

Ctrl-C or an error in the run stops the other process (`close`) inside the run's staged
folder, so that nothing half-written is ever published.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from typing import Any


def aside_allowed() -> bool:
    """Whether work can go to another process here: the user did not turn it off
    (SHAFTFEM_ASIDE=0) and this process is not a daemon (those may have no children)."""
    import multiprocessing as mp

    return os.environ.get("SHAFTFEM_ASIDE", "1") != "0" and not mp.current_process().daemon


class Aside:
    """`job(*args)` run in another Python process (or right here, see aside_allowed)."""

    def __init__(self, job: Callable[..., Any], *args: Any) -> None:
        self._process = None
        self._value: tuple[bool, Any] | None = None
        if not aside_allowed():
            try:
                self._value = (True, job(*args))
            except Exception as e:   # given back by result(), as the other process's is
                self._value = (False, e)
            return
        import pickle
        import subprocess
        import tempfile
        from pathlib import Path

        from shaftfem.runtime import worker_env

        self._folder = tempfile.TemporaryDirectory(prefix="shaftfem-aside-")
        asked = Path(self._folder.name) / "asked.pickle"
        self._answer = Path(self._folder.name) / "answer.pickle"
        self._said = Path(self._folder.name) / "stderr.txt"   # a file: a pipe could fill
        asked.write_bytes(pickle.dumps((job, args), protocol=pickle.HIGHEST_PROTOCOL))
        # one thread for each of its libraries: the run's own solver has the other core
        env = {**os.environ, **worker_env(), "MKL_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
        with open(self._said, "wb") as said:
            self._process = subprocess.Popen(
                [sys.executable, "-m", "shaftfem.aside", str(asked), str(self._answer)],
                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=said, env=env)

    def result(self) -> Any:
        """What the job returned; what it raised is raised here."""
        if self._value is None:
            self._value = self._collect()
        ok, value = self._value
        if not ok:
            raise value
        return value

    def _collect(self) -> tuple[bool, Any]:
        import pickle

        process = self._process
        assert process is not None
        process.wait()
        try:
            if process.returncode == 0:
                ok, value = pickle.loads(self._answer.read_bytes())
                return bool(ok), value
            tail = self._said.read_text(errors="replace").strip().splitlines()[-1:]
        except Exception as e:   # an exception that cannot be rebuilt: said in words
            return False, RuntimeError(f"the work beside the run failed: {e}")
        finally:
            self.close()
        return False, RuntimeError(f"the work beside the run stopped (exit status "
                                   f"{process.returncode}){': ' + tail[0] if tail else ''}")

    def close(self) -> None:
        """Stop the other process if it still runs (an error or Ctrl-C in the run)."""
        if self._process is not None:
            if self._process.poll() is None:
                self._process.terminate()
            self._process.wait()
            self._process = None
            self._folder.cleanup()


def _main(asked: str, answer: str) -> int:
    """The other process: the job in `asked`, its answer (or exception) in `answer`."""
    import pickle
    from pathlib import Path

    import shaftfem.runtime

    shaftfem.runtime.configure_threads()
    job, args = pickle.loads(Path(asked).read_bytes())
    try:
        out: tuple[bool, Any] = (True, job(*args))
    except Exception as e:
        out = (False, e)
    try:
        data = pickle.dumps(out, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:
        data = pickle.dumps((False, RuntimeError(f"{type(out[1]).__name__}: {out[1]}")))
    tmp = Path(answer + ".part")
    tmp.write_bytes(data)
    tmp.replace(answer)
    return 0


if __name__ == "__main__":
    sys.exit(_main(*sys.argv[1:3]))
