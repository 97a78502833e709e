"""Ctrl-C that always stops: the command runs in a child process, and this one stops it.

gmsh's booleans and VTK's renders run in C++ for seconds at a time, and Python only
sees a Ctrl-C between bytecodes; VTK even swallows it. So the `shaftfem` command forks:
the child runs the command, ignoring Ctrl-C, and the parent only waits. Both stay in
the terminal's process group, so Ctrl-Z suspends both and a kill of the group ends
both. On Ctrl-C (SIGINT) or SIGTERM the parent kills the child and every process it
started (Dask workers) at once, removes what the child had staged but not published (the staging
folders of its output folder, a sweep's lock and temp folder, an output folder the
run made), prints one line and exits 130 (143 for SIGTERM). Published files are
manifest-vouched (shaftfem.store), and cache entries are written atomically and
checksummed, so the next run is correct. Elsewhere than on POSIX, or with
SHAFTFEM_NO_SUPERVISOR set, the command runs in this process.
"""

from __future__ import annotations

import os
import shutil
import signal
import sys
from collections.abc import Callable
from pathlib import Path

EXIT_INTERRUPTED = 130  # 128 + SIGINT, as shells report it


class _Stop(Exception):
    def __init__(self, signum: int):
        self.signum = signum


def supervised(run: Callable[[], int], outputs: list[Path]) -> int:
    """run() in a child process; its exit code, or 128 + the signal that stopped it.
    `outputs`: the folders the command may write into (cleaned after a stop)."""
    if os.name != "posix" or os.environ.get("SHAFTFEM_NO_SUPERVISOR"):
        return run()
    made = _missing(outputs)
    import time

    started = time.time()

    def stop(signum, _frame):
        raise _Stop(signum)

    # set before the fork, so that no Ctrl-C falls between the two
    old = {s: signal.signal(s, stop) for s in (signal.SIGINT, signal.SIGTERM)}
    pid = 0
    try:
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:  # the child: the parent alone takes Ctrl-C, and stops the child
            signal.signal(signal.SIGINT, signal.SIG_IGN)
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
            _follow(os.getppid())
            code = 1
            try:
                code = run()
            finally:
                sys.stdout.flush()
                sys.stderr.flush()
                import atexit

                atexit._run_exitfuncs()
                os._exit(code)
        _, status = os.waitpid(pid, 0)
        code = os.waitstatus_to_exitcode(status)
        return 128 - code if code < 0 else code   # killed by signal N: 128 + N, as shells say
    except _Stop as s:
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, signal.SIG_IGN)  # a second Ctrl-C must not cut the clean-up
        if pid:
            _kill_tree(pid)
        _clean(outputs, made, pid)
        what = "interrupted" if s.signum == signal.SIGINT else "terminated"
        done = _published(outputs, started)
        print(f"shaftfem: {what}; " + ("nothing was published" if not done else
              f"what it had published stands ({', '.join(done)}: each set complete, "
              "vouched by its manifest); nothing half-written was left"),
              file=sys.stderr, flush=True)
        return 128 + s.signum
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)


def _follow(parent: int) -> None:
    """If the parent dies (SIGKILL, which it cannot catch), end this process and what
    it started too, as a kill of the whole command would."""
    import threading
    import time

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.1)
        _kill_tree(os.getpid())

    threading.Thread(target=watch, daemon=True, name="shaftfem-follow-parent").start()


def _kill_tree(pid: int) -> None:
    """Process `pid` and every process it started (Dask workers), at once (psutil: the
    descendants, whatever their process group)."""
    import psutil

    try:
        root = psutil.Process(pid)
        procs = root.children(recursive=True) + [root]
    except psutil.NoSuchProcess:
        procs = []
    for p in procs:
        try:
            p.kill()
        except psutil.NoSuchProcess:
            pass
    if pid != os.getpid():
        try:
            os.waitpid(pid, 0)
        except ChildProcessError:
            pass


def _published(outputs: list[Path], since: float) -> list[str]:
    """For each output folder the run published files in (written since `since`, the
    run's start; staging folders are gone by now): "N files in folder"."""
    out = []
    for folder in outputs:
        folder = Path(folder)
        if not folder.is_dir():
            continue
        n = sum(1 for f in folder.rglob("*") if f.is_file() and f.stat().st_mtime >= since)
        if n:
            out.append(f"{n} file{'s' if n > 1 else ''} in {folder}")
    return out


def _missing(outputs: list[Path]) -> list[Path]:
    """The output folders, and their ancestors, that do not exist yet (deepest first)."""
    out = []
    for folder in outputs:
        p = Path(folder)
        while not p.exists() and p != p.parent:
            out.append(p)
            p = p.parent
    return out


def _clean(outputs: list[Path], made: list[Path], pid: int) -> None:
    """Remove what a killed run had staged but not published, and the folders it made
    that hold nothing else."""
    from shaftfem.store import STAGING
    from shaftfem.workflows.sweep import LOCK, WORKER_TMP

    for folder in outputs:
        folder = Path(folder)
        if not folder.is_dir():
            continue
        for stage in folder.glob(f"{STAGING}{pid}-*"):
            shutil.rmtree(stage, ignore_errors=True)
        shutil.rmtree(folder / WORKER_TMP, ignore_errors=True)
        (folder / LOCK).unlink(missing_ok=True)
    for p in made:  # deepest first
        try:
            p.rmdir()
        except OSError:
            pass
