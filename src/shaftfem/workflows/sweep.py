"""Design sweeps: many variants of one scene, each a full modal run, on Dask.

Each variant runs in a Dask worker process (gmsh keeps global state, so one
thread per process). The client reads and checks the base scene and sends its
content with every variant, so a worker needs no access to the user's files:
on a cluster (`--scheduler`), only the same shaftfem version, which is checked
when the sweep connects. Every finished variant is appended to the results CSV at
once, so an interrupted sweep resumes where it stopped; a variant that fails
(bad geometry, a failed boolean) is recorded with its error and the rest go on.

Resuming is keyed by everything that defines a variant's result: beside the results
file a key file holds the base scene's content, the mesh size, the mode count, the
swept parameters, whether errors are bounded, and shaftfem's version. A folder whose
key differs holds another sweep's rows and is refused; the same sweep with values
added to its axes resumes and runs only the new ones.
"""

from __future__ import annotations

import csv
import math
import os
import time
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

from shaftfem.errors import ClusterError, SceneError
from shaftfem.runtime import RunOptions, worker_env
from shaftfem.scene.load import SceneText, load_scene
from shaftfem.store import atomic_path, content_key
from shaftfem.workflows.sweep_file import Sweep

# In a sweep's folder while it runs: its lock, and its workers' temp folder
LOCK, WORKER_TMP = ".sweep.lock", ".sweep-tmp"


def variant_id(overrides: dict) -> str:
    return content_key({k: round(v, 12) for k, v in overrides.items()}, length=12)


def run_variant(base: SceneText | str, overrides: dict, mesh_size_mm: float | None = None,
                estimate: bool = False, n_modes: int | None = None,
                options: RunOptions = RunOptions()) -> dict:
    """One variant, start to finish; never raises: a failure is a row with its error.

    `base`: the scene's content (as sent to workers), or a scene file or name. Records
    the lowest `n_modes` (default: the scene's count), run with `options`."""
    t0 = time.perf_counter()
    row = {"id": variant_id(overrides), **overrides}
    try:
        from shaftfem.checks.resonance import check_result
        from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes

        scene = with_mesh(load_scene(base, overrides=overrides), mesh_size_mm)
        scene = with_modes(scene, count=n_modes or scene.modes.count)
        options = replace(options, keep_solves=False)  # each variant is solved once
        if scene.rotor is not None:
            r = _turning_fields(row, scene, options)
        else:
            r = run_modes(scene, options)
            v = check_result(r)
            if v is not None:
                row["min_margin"] = v.approaches[0].margin
                row["margin_ok"] = v.ok
        m = r.modes
        for i in range(min(n_modes or scene.modes.count, m.count)):
            row[f"f{i + 1}_hz"] = float(m.frequencies[i])
            row[f"kind{i + 1}"] = m.kinds[i]
        if estimate:
            from shaftfem.workflows.bounded import estimate_errors

            est = estimate_errors(r, options)
            for i in range(m.count):
                row[f"err{i + 1}"] = float(est.relative_error[i])
        row["dofs"] = m.n_dofs
        row["status"] = "ok"
        row["error"] = ""
    except Exception as exc:  # recorded, so that one bad variant does not stop the sweep
        row["status"] = "failed"
        row["error"] = f"{type(exc).__name__}: {exc}".replace("\n", " ")
    row["wall_s"] = round(time.perf_counter() - t0, 3)
    row["worker_pid"] = os.getpid()
    return row


# how long a client waits for a scheduler to answer (Dask retries a refused connection
# until then)
CONNECT_TIMEOUT = "10s"
# a turning shaft's columns: its lowest 1x critical speeds, the separation margin
# check_whirl judges (the closest approach), the least log decrement up to the highest
# operating speed, the largest unbalance peak and its speed, and Level I's Q_0 / Q_A
ROTOR_COLUMNS = ["crit1_rpm", "crit2_rpm", "critical_margin", "least_log_dec",
                 "unbalance_peak_um", "unbalance_peak_rpm", "level1_ratio"]


def columns(parameters: list[str], n_modes: int, rotor: bool = False) -> list[str]:
    """The results table's columns: the swept parameters, then per mode f, kind, error
    (and a turning shaft's ROTOR_COLUMNS)."""
    per_mode = [f"{c}{i + 1}{u}" for c, u in (("f", "_hz"), ("kind", ""), ("err", ""))
                for i in range(n_modes)]
    return (["id"] + parameters + ["dofs"] + per_mode + (ROTOR_COLUMNS if rotor else [])
            + ["min_margin", "margin_ok", "status", "error", "wall_s", "worker_pid"])


def _turning_fields(row: dict, scene, options: RunOptions):
    """A turning shaft's columns of its row (ROTOR_COLUMNS, and the verdict's margin):
    its Campbell run (whose standstill basis the frequencies are read from), the
    unbalance peak and, where a stage gives Q_A, Level I. Returns the standstill run."""
    from shaftfem.checks.whirl_check import check_whirl
    from shaftfem.workflows.campbell import run_campbell

    c = run_campbell(scene, options)
    crit = sorted(cs.speed_rpm for cs in c.critical_speeds
                  if cs.order == 1 and not cs.critically_damped)
    for k in (0, 1):
        row[f"crit{k + 1}_rpm"] = float(crit[k]) if len(crit) > k else ""
    v = check_whirl(c)
    if v.approaches:
        row["critical_margin"] = row["min_margin"] = float(v.approaches[0].margin)
    row["margin_ok"] = v.ok
    if c.stability is not None:
        row["least_log_dec"] = float(c.stability.log_dec)
    if c.unbalance is not None and c.unbalance.peaks:
        top = max(c.unbalance.peaks, key=lambda p: p.amplitude)
        row["unbalance_peak_um"] = float(top.amplitude) * 1e6
        row["unbalance_peak_rpm"] = float(top.speed_rpm)
    if any(a.stage is not None for a in scene.attachments):
        from shaftfem.workflows.level1 import run_level1

        level1 = run_level1(scene, options=options)
        row["level1_ratio"] = "" if level1.ratio is None else float(level1.ratio)
    return c.result


def worker_version() -> str:
    """The shaftfem version of the process that runs this (a worker)."""
    from shaftfem import __version__

    return __version__


def _connect(address: str):
    """A client of the cluster at `address` whose workers all run this shaftfem version."""
    from distributed import Client

    from shaftfem import __version__

    try:
        client = Client(address, timeout=CONNECT_TIMEOUT)
    except OSError as exc:
        raise ClusterError(f"no Dask scheduler answers at {address}: {exc}") from exc
    try:
        client.wait_for_workers(1, timeout=60)
        versions = client.run(worker_version)
    except TimeoutError as exc:
        client.close()
        raise ClusterError(f"the Dask scheduler at {address} has no workers (waited 60 s)") from exc
    except Exception as exc:  # a worker that cannot even import shaftfem
        client.close()
        raise ClusterError(f"the workers at {address} cannot run shaftfem "
                           f"({type(exc).__name__}: {exc}); install shaftfem {__version__} "
                           "in the workers' environment") from exc
    wrong = {w: v for w, v in versions.items() if v != __version__}
    if wrong:
        client.close()
        raise ClusterError(f"the workers at {address} run another shaftfem than this one "
                           f"({__version__}): " + ", ".join(f"{w}: {v}" for w, v in wrong.items())
                           + f"; install shaftfem {__version__} on them")
    return client


def read_results(path: str | Path) -> list[dict]:
    path = Path(path)
    if not path.exists():
        return []
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def _drop_partial_line(path: Path) -> None:
    """A sweep killed while writing can leave half a row: cut it off before appending."""
    if not path.exists() or path.stat().st_size == 0:
        return
    data = path.read_bytes()
    if not data.endswith(b"\n"):
        keep = data.rfind(b"\n") + 1
        with open(path, "r+b") as fh:
            fh.truncate(keep)


@contextmanager
def _owned(folder: Path):
    """Hold the sweep's lock on `folder` (a second sweep into it is refused) and give its
    workers a temp folder there that is removed at the end. The lock is an flock: the
    system releases it when the process dies, so a killed sweep leaves no stale lock;
    a sweep that ends (or fails, say on a scheduler that never answers) removes the lock
    file too, and the folder if it made it and nothing was written there."""
    import fcntl
    import shutil

    made = not folder.exists()
    folder.mkdir(parents=True, exist_ok=True)
    fh = open(folder / LOCK, "a+")  # noqa: SIM115 (held until the sweep ends)
    try:
        fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError as exc:
        fh.close()
        raise SceneError(f"another sweep is writing into {folder}: wait for it to finish "
                         "or choose another --out") from exc
    tmp = folder / WORKER_TMP
    try:
        tmp.mkdir(exist_ok=True)
        yield tmp
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
        (folder / LOCK).unlink(missing_ok=True)
        fh.close()
        if made:
            try:
                folder.rmdir()  # only if empty
            except OSError:
                pass


def run_sweep(sweep: Sweep, results: str | Path, workers: int = 2,
              scheduler: str | None = None, estimate: bool = False,
              options: RunOptions = RunOptions()) -> list[dict]:
    """Run every variant not yet in `results` (a CSV file) on Dask; append each row as
    it finishes, and return all rows: the variant's values (file units), f1_hz, kind1,
    ... per mode, the smallest margin, DOFs, status ('ok' or 'failed') and error.
    `results` must be new, or hold rows of this same sweep (its key file says so).
    The workers solve with `options`' cache use and factoriser, one thread each on a
    local cluster."""
    results = Path(results)
    with _owned(results.parent) as tmp:
        _claim(results, sweep.key(estimate))
        try:
            return _run_sweep(sweep, results, workers, scheduler, estimate, options, tmp)
        finally:
            if not results.exists():  # no row was written: the key claims nothing
                key_path(results).unlink(missing_ok=True)


def key_path(results: Path) -> Path:
    """The key file beside a results table: what defines its rows."""
    return results.with_name(results.stem + ".key.json")


def _claim(results: Path, key: dict) -> None:
    """Make `results` this sweep's: refuse rows made under another key (another base
    scene, mesh size, mode count, parameter set, estimate or version), else write the key."""
    import json

    path = key_path(results)
    has_rows = results.exists() and results.stat().st_size > 0
    try:
        held = json.loads(path.read_text()) if path.exists() else None
    except (OSError, ValueError):
        held = {}
    if has_rows and held != key:
        differ = ([k for k in key if held.get(k) != key[k]] if isinstance(held, dict) and held
                  else ["no key file: rows of unknown origin"])
        raise SceneError(f"{results} holds the rows of another sweep ({', '.join(differ)} "
                         f"differ); give another --out, or delete {results.parent} to start "
                         "afresh")
    if held != key:
        with atomic_path(path) as tmp:
            tmp.write_text(json.dumps(key, indent=1) + "\n")


def _run_sweep(sweep: Sweep, results: Path, workers: int, scheduler: str | None,
               estimate: bool, options: RunOptions, tmp: Path) -> list[dict]:
    from distributed import Client, LocalCluster, as_completed

    say = options.say
    _drop_partial_line(results)
    done = {r["id"] for r in read_results(results)}
    todo = [v for v in sweep.variants if variant_id(v) not in done]
    say(f"sweep: {len(sweep.variants)} variants, {len(done)} already in {results.name}, "
        f"{len(todo)} to run")
    if not todo:
        return read_results(results)
    new_file = not results.exists() or results.stat().st_size == 0
    results.parent.mkdir(parents=True, exist_ok=True)
    if scheduler:
        client, cluster, threads = _connect(scheduler), None, None
    else:
        # the workers already share the cores: one assembly thread each
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None,
                               env={**worker_env(), "TMPDIR": str(tmp)})
        client, threads = Client(cluster), 1
    t0, n_ok, n_failed = time.perf_counter(), 0, 0
    try:
        worker = replace(options, threads=threads, progress=None)
        futures = [client.submit(run_variant, sweep.base, v, sweep.mesh_size_mm, estimate,
                                 sweep.n_modes, worker, pure=False) for v in todo]
        with open(results, "a", newline="") as fh:
            turning = load_scene(sweep.base).rotor is not None
            w = csv.DictWriter(fh, fieldnames=columns(sweep.parameters, sweep.n_modes, turning),
                               extrasaction="ignore")
            if new_file:
                w.writeheader()
            for fut in as_completed(futures):
                row = fut.result()
                w.writerow(row)
                fh.flush()
                os.fsync(fh.fileno())
                n_ok += row["status"] == "ok"
                n_failed += row["status"] != "ok"
                k = n_ok + n_failed
                left = (time.perf_counter() - t0) / k * (len(todo) - k)
                say(f"sweep: {k}/{len(todo)} done ({n_failed} failed), about "
                    f"{math.ceil(left)} s left")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return read_results(results)
