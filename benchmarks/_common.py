"""Helpers for the benchmark scripts: a run in a fresh process, so its peak memory is its own."""

# As the CLI does: one OpenBLAS thread, set before NumPy loads, in this process and
# (through the environment) in the fresh processes it spawns (shaftfem.runtime).
import shaftfem.runtime

shaftfem.runtime.configure_threads()

import multiprocessing as mp  # noqa: E402
import platform  # noqa: E402
from concurrent.futures import ProcessPoolExecutor


def in_fresh_process(fn, *args, **kwargs):
    with ProcessPoolExecutor(max_workers=1, mp_context=mp.get_context("spawn")) as pool:
        return pool.submit(fn, *args, **kwargs).result()


def machine() -> str:
    import os

    mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    return f"{os.cpu_count()} cores, {mem:.0f} GB, {platform.processor() or platform.machine()}"


def peak_mb() -> float:
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def run_measured(command: list[str], env: dict[str, str] | None = None) -> dict:
    """A command run to its end: its stdout and stderr (text), exit code, wall time (s)
    and peak memory (MB) of that process and the children it waited for (wait4's own
    usage: RUSAGE_CHILDREN would give the largest of every child so far)."""
    import os
    import subprocess
    import tempfile
    import time

    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        t = time.perf_counter()
        proc = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                                env=env)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t
        proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
        out.seek(0)
        err.seek(0)
        return {"stdout": out.read(), "stderr": err.read(), "returncode": proc.returncode,
                "wall": wall, "peak": usage.ru_maxrss / 1024}


def options(args: list[str], defaults: dict[str, str]) -> tuple[dict[str, str], list[str]]:
    """The values of the `--flag value` pairs in `args` for the flags of `defaults` (else
    their defaults), and the other arguments in order."""
    values, rest, it = dict(defaults), [], iter(args)
    for a in it:
        if a in defaults:
            values[a] = next(it)
        else:
            rest.append(a)
    return values, rest


# The paper's shaft (free-free, Hz): NGSolve order 4, 541k DOFs, on netgen's own curved
# mesh of the exported STEP of the solid as built since 2026-12-04 (root fillets meeting
# the floor at 4.4 degrees; 0.04-0.08 % from its order 3: docs/verification.md). Tables
# measured before that date are of the solid before, against its own reference.
PAPER_REFERENCE_HZ = (432.345, 443.605, 1194.718, 1223.043, 2334.896, 2382.666, 2733.028,
                      3816.800, 3885.261, 4450.090)
