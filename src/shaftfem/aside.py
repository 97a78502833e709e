"""Work done beside the main line of a run, on the other core: pictures that nothing
downstream reads, and studies that share nothing with the one in hand.

`Aside(job, *args)` runs `job(*args)` in a new Python (`python -m shaftfem.aside`, the
job and its arguments handed over as a pickle on its stdin; `job` a module-level
function); `.result()` waits for it and gives what it returned, or raises what it
raised. `Aside.waiting(*modules)` starts that Python before its job is known, importing
`modules` meanwhile, and `.start(job, *args)` hands the job over when it is: the
pictures of a run's modes start the moment the modes are solved, their libraries
loaded while the run solved them.

A new Python, never a fork of this one: a fork would inherit the solver's thread pools
mid-flight (OpenMP in a forked child can wait forever on a lock its parent's thread
held), and multiprocessing's spawn would run a user's script again. With
SHAFTFEM_ASIDE=0, or inside a daemonic worker (a Dask one), the job runs right there
instead, with the same answer.

Ctrl-C or an error in the run stops the other process (`close`) inside the run's staged
folder, so that nothing half-written is ever published.
"""

from __future__ import annotations

import os
import sys
import threading
from collections.abc import Callable
from typing import Any


class AsideStopped(RuntimeError):
    """The other process ended without an answer (it died, or what it gave back could
    not be read): not an error its job raised."""


def aside_allowed() -> bool:
    """Whether work can go to another process here: the user did not turn it off
    (SHAFTFEM_ASIDE=0) and this process is not a daemon (those may have no children)."""
    import multiprocessing as mp

    return os.environ.get("SHAFTFEM_ASIDE", "1") != "0" and not mp.current_process().daemon


class Aside:
    """`job(*args)` run in another Python process (or right here, see aside_allowed)."""

    def __init__(self, job: Callable[..., Any], *args: Any) -> None:
        self._begin(())
        self.start(job, *args)

    @classmethod
    def waiting(cls, *modules: str) -> Aside:
        """The other process started, importing `modules` until `start` gives its job."""
        aside = cls.__new__(cls)
        aside._begin(modules)
        return aside

    def _begin(self, modules: tuple[str, ...]) -> None:
        self._process = None
        self._value: tuple[bool, Any] | None = None
        self._given = False
        self._writer: threading.Thread | None = None
        if not aside_allowed():
            return
        import subprocess
        import tempfile
        from pathlib import Path

        from shaftfem.runtime import worker_env

        self._folder = tempfile.TemporaryDirectory(prefix="shaftfem-aside-")
        self._answer = Path(self._folder.name) / "answer.pickle"
        self._said = Path(self._folder.name) / "stderr.txt"   # a file: a pipe could fill
        # one thread for each of its libraries: the run's own solver has the other core
        env = {**os.environ, **worker_env(), "MKL_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
        with open(self._said, "wb") as said:
            self._process = subprocess.Popen(
                [sys.executable, "-m", "shaftfem.aside", str(self._answer), *modules],
                stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=said, env=env)

    def start(self, job: Callable[..., Any], *args: Any) -> None:
        """Hand the job over (or, where nothing may go aside, do it now)."""
        import pickle

        assert not self._given, "an Aside runs one job"
        self._given = True
        if self._process is None:
            try:
                self._value = (True, job(*args))
            except Exception as e:   # given back by result(), as the other process's is
                self._value = (False, e)
            return
        data = pickle.dumps((job, args), protocol=pickle.HIGHEST_PROTOCOL)
        pipe = self._process.stdin
        assert pipe is not None

        def hand_over() -> None:   # in a thread: the run goes on while the pipe drains
            import signal

            # gmsh resets SIGPIPE to its default, which ends the whole run where the other
            # process was stopped (or died) mid-hand-over: blocked in this thread, a
            # write to a closed pipe raises BrokenPipeError instead
            if hasattr(signal, "pthread_sigmask"):
                signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGPIPE})
            try:
                pipe.write(data)
                pipe.close()
            except (BrokenPipeError, ValueError):   # it ended first: result() says how
                pass

        self._writer = threading.Thread(target=hand_over, daemon=True)
        self._writer.start()

    def result(self, timeout: float | None = None) -> Any:
        """What the job returned; what it raised is raised here. Not done within
        `timeout` seconds, the other process is stopped and TimeoutError raised (a job
        run right here has no limit)."""
        assert self._given, "result() of an Aside given no job"
        if self._value is None:
            self._value = self._collect(timeout)
        ok, value = self._value
        if not ok:
            raise value
        return value

    def _collect(self, timeout: float | None) -> tuple[bool, Any]:
        import pickle
        import subprocess

        process = self._process
        assert process is not None
        try:
            process.wait(timeout)
        except subprocess.TimeoutExpired:
            self.close()
            raise TimeoutError(f"the work beside the run took more than {timeout:.0f} s: "
                               "stopped") from None
        try:
            if process.returncode == 0:
                ok, value = pickle.loads(self._answer.read_bytes())
                return bool(ok), value
            tail = self._said.read_text(errors="replace").strip().splitlines()[-1:]
        except Exception as e:   # an exception that cannot be rebuilt: said in words
            return False, AsideStopped(f"the work beside the run failed: {e}")
        finally:
            self.close()
        return False, AsideStopped(f"the work beside the run stopped (exit status "
                                   f"{process.returncode}){': ' + tail[0] if tail else ''}")

    def close(self) -> None:
        """Stop the other process if it still runs (an error or Ctrl-C in the run)."""
        if self._process is not None:
            if self._process.poll() is None:
                self._process.terminate()
            self._process.wait()
            if self._writer is not None:
                self._writer.join()
            if self._process.stdin is not None and not self._process.stdin.closed:
                try:
                    self._process.stdin.close()
                except (BrokenPipeError, ValueError):
                    pass
            self._process = None
            self._folder.cleanup()


def _main(answer: str, *modules: str) -> int:
    """The other process: `modules` imported, then the job read from stdin (none: the
    run ended first), its answer (or exception) written to `answer`."""
    import importlib
    import pickle
    from pathlib import Path

    import shaftfem.runtime

    shaftfem.runtime.configure_threads()
    for name in modules:
        try:
            importlib.import_module(name)
        except ImportError:   # the job, if it needs it, says so itself
            pass
    try:
        job, args = pickle.load(sys.stdin.buffer)
    except EOFError:
        return 0
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
    sys.exit(_main(*sys.argv[1:]))
