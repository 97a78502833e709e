"""Design sweeps: many variants of one scene, each a full modal run, on Dask.

A sweep file (TOML) names a base scene and the values of any numeric scene keys:

    base = "paper2018"              # scene name in geometry/ or a path
    mesh_size_mm = 12               # optional: element size for every variant
    [axes]                          # full grid over these ("table.key" = values)
    "grooves.depth_mm" = [2.0, 3.0, 4.0]
    "shaft.length_mm" = {start = 500, stop = 600, num = 3}
    # or, instead of [axes], an explicit list:
    # points = [{"grooves.depth_mm" = 2.0, "shaft.length_mm" = 520}, ...]

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
added to its axes resumes and runs only the new ones. Every variant's scene is
checked when the file is loaded, and grids beyond MAX_VARIANTS are refused there.
"""

from __future__ import annotations

import csv
import itertools
import math
import os
import time
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path

from shaftfem.errors import ClusterError, SceneError
from shaftfem.runtime import RunOptions, worker_env
from shaftfem.scene.load import SceneText, check_entries, load_scene, read_scene_text, scene_beside
from shaftfem.scene.schema import known_keys, number, parameter, read_toml
from shaftfem.store import atomic_path, content_key

# The largest sweep or calibration grid accepted: at 5-40 s a variant, 10,000 variants
# keep two workers busy for one to five days; a larger grid is a typo more often than
# a plan (three axes of 1000 values, or 20^5 calibration points).
MAX_VARIANTS = 10_000
# In a sweep's folder while it runs: its lock, and its workers' temp folder
LOCK, WORKER_TMP = ".sweep.lock", ".sweep-tmp"


@dataclass(frozen=True)
class Sweep:
    base: SceneText             # the base scene's content, read by the client
    mesh_size_mm: float | None
    variants: list[dict]        # each: {"table.key": value in file units}
    parameters: list[str]
    n_modes: int                # the lowest n_modes of every variant are recorded

    def key(self, estimate: bool) -> dict:
        """What defines every variant's result besides its own values."""
        from shaftfem import __version__

        return {"base": self.base.source, "base_content": content_key({"text": self.base.text}),
                "mesh_size_mm": self.mesh_size_mm, "n_modes": self.n_modes,
                "parameters": list(self.parameters), "estimate": estimate,
                "shaftfem": __version__}


def check_count(source: str, n: int, what: str) -> None:
    """Refuse a sweep or grid of more than MAX_VARIANTS variants, before it is built."""
    if n > MAX_VARIANTS:
        raise SceneError(f"{source}: {what} make {n:,} variants; at most {MAX_VARIANTS:,} "
                         "are run (split the sweep, or use fewer values)")


def check_variants(source: str, base: SceneText, variants: list[dict]) -> None:
    """Every variant's scene is valid (a seat past the shaft end, a negative depth): the
    first bad one is named with its values, before any variant runs."""
    for i, v in enumerate(variants):
        try:
            load_scene(base, overrides=v)
        except SceneError as exc:
            values = ", ".join(f"{k} = {x:g}" for k, x in v.items())
            raise SceneError(f"{source}: variant {i + 1} ({values}): {exc}") from exc


def _axis_values(source: str, name: str, spec) -> list[float]:
    where = f"axes.{name}"
    if isinstance(spec, list):
        if not spec:
            raise SceneError(f"{source}: {where} = []: give at least one value")
        return [number(source, where, v, -1e300, 1e300) for v in spec]
    if isinstance(spec, dict):
        known_keys(source, spec, {"start", "stop", "num"}, where)
        n = spec.get("num")
        if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 1000:
            raise SceneError(f"{source}: {where}.num = {n!r}: must be an integer in [1, 1000]")
        a = number(source, f"{where}.start", spec.get("start"), -1e300, 1e300)
        b = number(source, f"{where}.stop", spec.get("stop"), -1e300, 1e300)
        return [a + (b - a) * i / max(n - 1, 1) for i in range(n)]
    raise SceneError(f"{source}: {where} = {spec!r}: expected a list of numbers or "
                     "{start = ..., stop = ..., num = ...}")


def load_sweep(path: str | Path) -> Sweep:
    """Read a sweep file and expand it into variants (every entry checked for form; the
    values themselves are checked per variant, where a bad one is recorded as failed)."""
    path = Path(path)
    src = path.name
    data = known_keys(src, read_toml(path, "sweep file"), {"base", "mesh_size_mm", "axes", "points"})
    if not isinstance(data.get("base"), str):
        raise SceneError(f"{src}: base = {data.get('base')!r}: missing or not a scene name "
                         "or file (the scene the variants start from)")
    if ("axes" in data) == ("points" in data):
        raise SceneError(f"{src}: give either [axes] (a grid) or points (a list)")
    if "axes" in data:
        axes = data["axes"]
        if not isinstance(axes, dict) or not axes:
            raise SceneError(f"{src}: axes = {axes!r}: must be a table of at least one "
                             "parameter, e.g. \"shaft.length_mm\" = [500, 550]")
        names = [parameter(src, n) for n in axes]
        values = [_axis_values(src, n, axes[n]) for n in names]
        check_count(src, math.prod(len(v) for v in values), "the axes")
        variants = [dict(zip(names, combo)) for combo in itertools.product(*values)]
    else:
        points = data["points"]
        if not isinstance(points, list) or not points or not all(isinstance(p, dict) and p
                                                                 for p in points):
            raise SceneError(f"{src}: points = {points!r}: must be a list of at least one "
                             "table of parameters")
        check_count(src, len(points), "the points")
        variants = [{parameter(src, k): number(src, f"points[{i}].{k}", v, -1e300, 1e300)
                     for k, v in p.items()} for i, p in enumerate(points)]
        names = sorted({k for v in variants for k in v})
    base = read_scene_text(scene_beside(data["base"], path))
    check_entries(src, base, names)
    check_variants(src, base, variants)
    size = mesh_size(src, data.get("mesh_size_mm"), base)
    return Sweep(base=base, mesh_size_mm=size, variants=variants, parameters=names,
                 n_modes=load_scene(base).modes.count)


def mesh_size(src: str, size: object, base: SceneText) -> float | None:
    """A sweep or calibration file's mesh_size_mm, checked against its base scene (at most
    the shaft length, within the DOF budget) before any variant runs."""
    if size is None:
        return None
    size = number(src, "mesh_size_mm", size, 0, 20_000)
    from shaftfem.cad.mesh import check_budget
    from shaftfem.workflows.pipeline import with_mesh

    try:
        scene = with_mesh(load_scene(base), size)
        check_budget(scene.shaft, scene.grooves, scene.mesh, scene.max_dofs)
    except SceneError as exc:
        raise SceneError(f"{src}: mesh_size_mm = {size:g} for the base scene: {exc}") from exc
    return size


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
        r = run_modes(scene, options)
        m = r.modes
        for i in range(m.count):
            row[f"f{i + 1}_hz"] = float(m.frequencies[i])
            row[f"kind{i + 1}"] = m.kinds[i]
        if estimate:
            from shaftfem.workflows.bounded import estimate_errors

            est = estimate_errors(r, options)
            for i in range(m.count):
                row[f"err{i + 1}"] = float(est.relative_error[i])
        v = check_result(r)
        if v is not None:
            row["min_margin"] = v.approaches[0].margin
            row["margin_ok"] = v.ok
        row["dofs"] = m.n_dofs
        row["status"] = "ok"
        row["error"] = ""
    except Exception as exc:  # recorded, so that one bad variant does not stop the sweep
        row["status"] = "failed"
        row["error"] = f"{type(exc).__name__}: {exc}".replace("\n", " ")
    row["wall_s"] = round(time.perf_counter() - t0, 3)
    row["worker_pid"] = os.getpid()
    return row


def columns(parameters: list[str], n_modes: int) -> list[str]:
    """The results table's columns: the swept parameters, then per mode f, kind, error."""
    per_mode = [f"{c}{i + 1}{u}" for c, u in (("f", "_hz"), ("kind", ""), ("err", ""))
                for i in range(n_modes)]
    return (["id"] + parameters + ["dofs"] + per_mode
            + ["min_margin", "margin_ok", "status", "error", "wall_s", "worker_pid"])


def worker_version() -> str:
    """The shaftfem version of the process that runs this (a worker)."""
    from shaftfem import __version__

    return __version__


def _connect(address: str):
    """A client of the cluster at `address` whose workers all run this shaftfem version."""
    from distributed import Client

    from shaftfem import __version__

    try:
        client = Client(address, timeout="10s")
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
    """Run every variant not yet in `results` on Dask; append each row as it finishes.
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
            w = csv.DictWriter(fh, fieldnames=columns(sweep.parameters, sweep.n_modes),
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
