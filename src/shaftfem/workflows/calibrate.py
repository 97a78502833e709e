"""Calibration: which values of unknown scene keys reproduce target frequencies?

A calibration file (TOML):

    base = "paper2018"
    mesh_size_mm = 12.0
    grid = 4                                   # points per unknown in the coarse grid
    [unknowns]                                 # scene keys with bounds, file units
    "shaft.length_mm" = {min = 500.0, max = 600.0}
    "grooves.depth_mm" = {min = 2.0, max = 4.0}
    [targets]
    frequencies_hz = [432.16, 433.60, 1158.30, 1166.40, 2149.90, 2195.20]
    uncertainty_percent = 1.0                  # one value, or one per frequency

Method: the sweep engine evaluates a coarse grid (on Dask); from its best point
SciPy's `least_squares` (trust region, bounds) minimises the weighted residuals
r_i = (f_i - t_i) / sigma_i. How well each parameter is determined comes from
the Jacobian at the optimum: cov = (J^T J)^-1 in units of the residuals, so the
standard deviation says how far a parameter may move before the fit worsens by
one sigma. Note that every evaluation re-meshes: a finite-difference step
smaller than a few percent of a parameter's range would see mesh noise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from shaftfem.errors import SceneError, ShaftfemError
from shaftfem.runtime import RunOptions
from shaftfem.scene.load import SceneText, check_entries, load_scene, read_scene_text, scene_beside
from shaftfem.scene.schema import DEFAULT_MODE_COUNT, SCHEMA
from shaftfem.scene.toml_reading import known_keys, number, parameter, read_toml, split_parameter
from shaftfem.workflows.sweep import run_sweep, run_variant
from shaftfem.workflows.sweep_file import Sweep, check_count, check_variants, mesh_size


@dataclass(frozen=True)
class Calibration:
    base: SceneText | str   # the base scene's content (read by the client), or a scene name
    mesh_size_mm: float | None
    unknowns: dict          # name -> (min, max)
    targets: np.ndarray     # Hz
    sigma: np.ndarray       # Hz
    grid: int
    n_modes: int = DEFAULT_MODE_COUNT  # modes per evaluation: the base scene's, or the targets'


@dataclass(frozen=True)
class CalibrationResult:
    parameters: dict        # name -> best value
    std: dict               # name -> standard deviation (same units)
    frequencies: np.ndarray
    residuals_sigma: np.ndarray
    chi2: float
    evaluations: int
    grid_best: dict

    def as_dict(self, cal: Calibration) -> dict:
        """The JSON record of the fit (units in the key names)."""
        return {"parameters": self.parameters, "std": self.std, "grid_best": self.grid_best,
                "targets_hz": cal.targets, "model_hz": self.frequencies,
                "residuals_sigma": self.residuals_sigma, "chi2": self.chi2,
                "evaluations": self.evaluations}


def load_calibration(path: str | Path) -> Calibration:
    """Read and check a calibration file (every entry, before any modal run)."""
    path = Path(path)
    src = path.name
    d = known_keys(src, read_toml(path, "calibration file"),
                   {"base", "mesh_size_mm", "grid", "unknowns", "targets"})
    for key in ("base", "unknowns", "targets"):
        if key not in d:
            raise SceneError(f"{src}: {key}: missing")
    if not isinstance(d["base"], str):
        raise SceneError(f"{src}: base = {d['base']!r}: must be a scene name or file")
    if not isinstance(d["unknowns"], dict) or not d["unknowns"]:
        raise SceneError(f"{src}: unknowns = {d['unknowns']!r}: must be a table of at least "
                         "one scene key with bounds, e.g. \"shaft.length_mm\" = "
                         "{min = 500, max = 600}")
    unknowns = {}
    for name, b in d["unknowns"].items():
        where = f"unknowns.{parameter(src, name)}"
        table, _, key = split_parameter(name) or ("", None, "")
        if SCHEMA[table][key].kind is int:
            raise SceneError(f"{src}: {where}: an integer key cannot be an unknown (the fit "
                             "moves its value continuously); sweep it instead")
        known_keys(src, b, {"min", "max"}, where)
        lo = number(src, f"{where}.min", b.get("min"), -1e300, 1e300)
        hi = number(src, f"{where}.max", b.get("max"), -1e300, 1e300)
        if not lo < hi:
            raise SceneError(f"{src}: {where}: min = {lo:g} must be below max = {hi:g}")
        unknowns[name] = (lo, hi)
    t = known_keys(src, d["targets"], {"frequencies_hz", "uncertainty_percent"}, "targets")
    freqs = t.get("frequencies_hz")
    if not isinstance(freqs, list) or not freqs:
        raise SceneError(f"{src}: targets.frequencies_hz = {freqs!r}: must be a list of "
                         "frequencies in Hz")
    targets = np.array([number(src, f"targets.frequencies_hz[{i}]", f, 0, 1e7)
                        for i, f in enumerate(freqs)])
    u = t.get("uncertainty_percent", 1.0)
    if isinstance(u, list):
        if len(u) != len(targets):
            raise SceneError(f"{src}: targets.uncertainty_percent has {len(u)} values for "
                             f"{len(targets)} frequencies: give one, or one per frequency")
        u = [number(src, f"targets.uncertainty_percent[{i}]", x, 0, 100)
             for i, x in enumerate(u)]
    else:
        u = number(src, "targets.uncertainty_percent", u, 0, 100)
    grid = d.get("grid", 3)
    if isinstance(grid, bool) or not isinstance(grid, int) or not 2 <= grid <= 20:
        raise SceneError(f"{src}: grid = {grid!r}: must be an integer in [2, 20]")
    check_count(src, grid ** len(unknowns), f"grid = {grid} over {len(unknowns)} unknowns")
    base = read_scene_text(scene_beside(d["base"], path))  # its content travels to workers
    check_entries(src, base, list(unknowns))
    size = mesh_size(src, d.get("mesh_size_mm"), base)
    n_modes = max(len(targets), load_scene(base).modes.count)
    cal = Calibration(base=base, mesh_size_mm=size, unknowns=unknowns, targets=targets,
                      sigma=targets * np.asarray(u) / 100, grid=grid, n_modes=n_modes)
    check_variants(src, base, grid_points(cal))
    return cal


def grid_points(cal: Calibration) -> list[dict]:
    """The coarse grid's variants: `grid` values from min to max on every unknown."""
    names = list(cal.unknowns)
    axes = [np.linspace(cal.unknowns[n][0], cal.unknowns[n][1], cal.grid) for n in names]
    return [dict(zip(names, map(float, p)))
            for p in np.array(np.meshgrid(*axes)).reshape(len(names), -1).T]


def calibrate(cal: Calibration, workdir: str | Path, workers: int = 2,
              scheduler: str | None = None,
              options: RunOptions = RunOptions()) -> CalibrationResult:
    """The unknowns' best values and standard deviations (file units) for the targets:
    a grid on the sweep engine (local workers, or the cluster at `scheduler`; resumable
    in `workdir`), then a local bounded least-squares fit."""
    from scipy.optimize import least_squares

    names = list(cal.unknowns)
    lo = np.array([cal.unknowns[n][0] for n in names])
    hi = np.array([cal.unknowns[n][1] for n in names])
    # 1. coarse grid on the sweep engine (resumable like any sweep)
    base = read_scene_text(cal.base)  # read once here; its content goes to the workers
    rows = run_sweep(Sweep(base, cal.mesh_size_mm, grid_points(cal), names, cal.n_modes),
                     Path(workdir) / "grid.csv", workers=workers, scheduler=scheduler,
                     options=options)
    x0 = _best_grid_point(cal, rows, names, options)
    # 2. local least squares in scaled coordinates s = (x - lo) / (hi - lo)
    count = {"n": len(rows)}
    run = replace(options, progress=None)

    def fun(s: np.ndarray) -> np.ndarray:
        x = lo + s * (hi - lo)
        count["n"] += 1
        r = _residuals(cal, run_variant(base, dict(zip(names, map(float, x))),
                                        cal.mesh_size_mm, n_modes=cal.n_modes, options=run),
                       names)
        options.say(f"calibrate: run {count['n']}: "
                    + ", ".join(f"{n} = {v:.4g}" for n, v in zip(names, x))
                    + f": chi^2 = {np.sum(r ** 2):.3g}")
        return r

    # a grid point on a bound is moved just inside: started exactly on a bound, the bounded
    # fit stayed there (a hidden 537 mm length from a 500/600 mm grid: 24 runs at 500 mm)
    s0 = np.clip((x0 - lo) / (hi - lo), 0.05, 0.95)
    fit = least_squares(fun, s0, bounds=(0.0, 1.0), diff_step=0.02, x_scale=1.0,
                        max_nfev=30)
    x = lo + fit.x * (hi - lo)
    return CalibrationResult(parameters=dict(zip(names, map(float, x))),
                             std=dict(zip(names, map(float, _std(fit.jac, hi - lo)))),
                             frequencies=cal.targets + fit.fun * cal.sigma,
                             residuals_sigma=fit.fun, chi2=float(np.sum(fit.fun ** 2)),
                             evaluations=count["n"], grid_best=dict(zip(names, map(float, x0))))


def _residuals(cal: Calibration, row: dict, names: list[str]) -> np.ndarray:
    """(f - target) / sigma of one run's row; a failed run never becomes a model frequency."""
    if row["status"] != "ok":
        at = ", ".join(f"{n} = {row[n]:g}" for n in names)
        raise ShaftfemError(f"calibration run at {at} failed: {row['error']}")
    f = np.array([float(row[f"f{i + 1}_hz"]) for i in range(len(cal.targets))])
    return (f - cal.targets) / cal.sigma


def _best_grid_point(cal: Calibration, rows: list[dict], names: list[str],
                     options: RunOptions) -> np.ndarray:
    """The grid point of least chi^2."""
    ok = [r for r in rows if r["status"] == "ok"]
    if not ok:
        raise ShaftfemError(f"every one of the {len(rows)} grid runs failed; the first: "
                            f"{rows[0]['error']}")
    chi2 = [float(np.sum(_residuals(cal, r, names) ** 2)) for r in ok]
    best = ok[int(np.argmin(chi2))]
    x0 = np.array([float(best[n]) for n in names])
    options.say(f"calibrate: best grid point {dict(zip(names, map(float, x0)))}, "
                f"chi^2 = {min(chi2):.3g}")
    return x0


def _std(jac: np.ndarray, span: np.ndarray) -> np.ndarray:
    """Standard deviations of the unknowns from the Jacobian of the sigma-weighted
    residuals in scaled coordinates (inf where it is singular)."""
    J = jac * 1.0
    try:
        return np.sqrt(np.clip(np.diag(np.linalg.inv(J.T @ J)), 0, None)) * span
    except np.linalg.LinAlgError:
        return np.full(span.size, math.inf)


def calibration_text(res: CalibrationResult, cal: Calibration) -> str:
    lines = ["parameter                best value     std. dev.   bounds"]
    for k, v in res.parameters.items():
        lo, hi = cal.unknowns[k]
        lines.append(f"{k:<24} {v:>10.3f}  {res.std[k]:>12.3g}   [{lo:g}, {hi:g}]")
    lines += ["", "mode   target (Hz)    model (Hz)    diff     in sigma"]
    for i, (t, f, r) in enumerate(zip(cal.targets, res.frequencies, res.residuals_sigma)):
        lines.append(f"{i + 1:>4}  {t:>11.2f}  {f:>12.2f}  {100 * (f / t - 1):>+6.2f} %  "
                     f"{r:>+8.2f}")
    lines += ["", f"chi^2 = {res.chi2:.3g} for {len(cal.targets)} targets and "
              f"{len(res.parameters)} unknowns; {res.evaluations} modal runs"]
    return "\n".join(lines)
