"""The work-precision study: a ladder of meshes, their cost, and a reference from the finest.

A single run's error bound is shaftfem.fem.estimate's. The study's reference is a
Richardson extrapolation of its three finest meshes: frequencies from meshes
of sizes h, r h, r^2 h (same scene, all sizes scaled alike) converge as
f(h) ~ f* + C h^p. Three of them give, per mode,

    observed order   p = ln((f3 - f2) / (f2 - f1)) / ln r
    error of f1      e = |f1 - f2| / (r^p - 1)          (Richardson)

The estimate is trusted only where the three frequencies move monotonically and
p is plausible (between P_MIN and the element's smooth-problem order plus one).
A grooved shaft is not a smooth problem: with sharp groove corners p falls to
about 1.3-1.6, and assuming the smooth P2 eigenvalue rate h^4 there has been
seen to under-estimate the error eightfold. So p is never assumed: it is
measured, and where it cannot be measured the estimate falls back to p = 1
(slower than any rate seen on these shafts) and says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaftfem.fem.estimate import matched
from shaftfem.fem.result import Timings
from shaftfem.outputs.tables import markdown
from shaftfem.runtime import RunOptions

# Eigenvalue errors of smooth problems fall as h^(2k) for P_k elements.
SMOOTH_ORDER = {1: 2.0, 2: 4.0}
P_MIN = 0.8            # below this the meshes are not in the asymptotic range
FALLBACK_ORDER = 1.0   # used when the order cannot be measured
SAFETY = 1.25          # Roache's factor for a three-mesh estimate with measured order
SAFETY_FALLBACK = 3.0  # and for an estimate whose order had to be assumed


@dataclass
class Extrapolation:
    """Per mode: estimated relative error of the finest frequency, observed order, trust."""

    relative_error: np.ndarray   # (n,) |f1 - f*| / f1, with the safety factor
    observed_order: np.ndarray   # (n,) nan where not measurable
    reliable: np.ndarray         # (n,) bool
    extrapolated: np.ndarray     # (n,) Richardson-extrapolated frequency, Hz
    ratio: float


# Eigenvalue errors near a re-entrant edge fall as h^(2 lambda): for the 270 degree
# edges where a groove's flat end meets its floor, lambda = 0.5445 (Williams'
# first eigenvalue for a 3 pi / 2 notch), so p = 1.09 asymptotically, whatever the
# element order.
SINGULAR_ORDER = 2 * 0.5445


def theoretical_order(element_order: int, singular: bool) -> float:
    """The asymptotic convergence order of eigenvalues the estimate may not exceed."""
    smooth = SMOOTH_ORDER[element_order]
    return min(smooth, SINGULAR_ORDER) if singular else smooth


def richardson(f1: np.ndarray, f2: np.ndarray, f3: np.ndarray, ratio: float,
               element_order: int = 2, singular: bool = False) -> Extrapolation:
    """Three-mesh error estimate of f1 (finest), f2, f3 (coarser by `ratio` each step).

    The order used is the observed one, but never more than the theoretical
    asymptotic order (pre-asymptotic meshes often show a faster apparent rate).
    """
    f1, f2, f3 = (np.asarray(a, dtype=float) for a in (f1, f2, f3))
    d21, d32 = f2 - f1, f3 - f2
    p_max = SMOOTH_ORDER[element_order] + 1.0
    p_cap = theoretical_order(element_order, singular)
    n = len(f1)
    p = np.full(n, np.nan)
    ok = np.zeros(n, dtype=bool)
    err = np.empty(n)
    fx = np.empty(n)
    for i in range(n):
        if not (np.isfinite(d21[i]) and np.isfinite(d32[i])):
            # a mode missing on a coarser mesh (nan): nothing can be estimated
            err[i] = fx[i] = np.nan
            continue
        if d21[i] != 0 and d32[i] != 0 and np.sign(d21[i]) == np.sign(d32[i]):
            p[i] = math.log(d32[i] / d21[i]) / math.log(ratio)
        if np.isfinite(p[i]) and P_MIN <= p[i] <= p_max:
            ok[i] = True
            # beyond the theoretical rate, trust only that rate (the larger estimate)
            p_use = min(p[i], p_cap)
            e = abs(d21[i]) / (ratio**p_use - 1)
            err[i] = SAFETY * e / f1[i]
            fx[i] = f1[i] - d21[i] / (ratio**p_use - 1)
        else:
            e = max(abs(d21[i]), abs(d32[i]) / ratio**FALLBACK_ORDER) / (
                ratio**FALLBACK_ORDER - 1)
            err[i] = SAFETY_FALLBACK * e / f1[i]
            fx[i] = np.nan
    return Extrapolation(relative_error=err, observed_order=p, reliable=ok, extrapolated=fx,
                         ratio=ratio)


# --------------------------------------------------------------------------
# The work-precision study: a ladder of meshes, P1 and P2


@dataclass(frozen=True)
class StudyRun:
    order: int
    size_mm: float
    dofs: int
    timings: Timings
    peak_memory_mb: float
    frequencies: np.ndarray
    kinds: list[str]


@dataclass(frozen=True)
class StudyResult:
    """The study's runs as table rows, its reference frequencies and how they were made."""

    rows: list[dict]
    reference: np.ndarray
    estimate: Extrapolation
    order: int        # element order of the reference runs


def _one_run(scene, size_mm: float, order: int, factoriser: str) -> dict:
    """Run in a fresh process, so that its peak memory is its own."""
    import resource

    from shaftfem.workflows.pipeline import run_modes, with_mesh

    r = run_modes(with_mesh(scene, size_mm, order), RunOptions(factoriser=factoriser))
    return {"dofs": r.modes.n_dofs, "timings": r.timings,
            "peak_memory_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
            "frequencies": r.modes.frequencies, "kinds": r.modes.kinds}


def run_study(scene, ladders: dict[int, list[float]],
              options: RunOptions = RunOptions()) -> list[StudyRun]:
    """Solve `scene` at every (order, size) of the ladders, each in its own process."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    runs = []
    ctx = mp.get_context("spawn")
    for order, sizes in ladders.items():
        for h in sorted(sizes, reverse=True):
            options.say(f"study: P{order} at {h:g} mm")
            with ProcessPoolExecutor(max_workers=1, mp_context=ctx) as pool:
                d = pool.submit(_one_run, scene, h, order, options.factoriser).result()
            runs.append(StudyRun(order=order, size_mm=h, **d))
    return runs


def summarize_study(runs: list[StudyRun], singular: bool) -> StudyResult:
    """Reference from the finest runs of the highest order, and every run's error against it."""
    ref, est = study_reference(runs, singular)
    top = max(r.order for r in runs)
    finest = min((r for r in runs if r.order == top), key=lambda r: r.size_mm)
    return StudyResult(rows=study_table(runs, ref, finest.kinds), reference=ref, estimate=est,
                       order=top)


def study_reference(runs: list[StudyRun], singular: bool) -> tuple[np.ndarray, Extrapolation]:
    """Richardson extrapolation of the three finest runs of the highest order."""
    top = max(r.order for r in runs)
    best = sorted([r for r in runs if r.order == top], key=lambda r: r.size_mm)[:3]
    if len(best) < 3:
        raise ValueError("the study needs at least three meshes of the highest order")
    ratio = (best[2].size_mm / best[0].size_mm) ** 0.5
    f1 = best[0].frequencies
    f = [f1] + [matched(best[0].kinds, r.kinds, r.frequencies) for r in best[1:]]
    est = richardson(f[0], f[1], f[2], ratio, top, singular)
    ref = np.where(np.isfinite(est.extrapolated), est.extrapolated, f1)
    return ref, est


def study_table(runs: list[StudyRun], reference: np.ndarray, ref_kinds: list) -> list[dict]:
    rows = []
    for r in runs:
        f = matched(ref_kinds, r.kinds, r.frequencies)
        err = np.abs(f / reference - 1)  # nan where a mode has no counterpart
        rows.append({
            "element": f"P{r.order}", "size_mm": r.size_mm, "dofs": r.dofs,
            **{f"{k}_s": round(v, 3) for k, v in r.timings.items()},
            "peak_memory_mb": round(r.peak_memory_mb),
            "max_rel_error": float(np.nanmax(err)),
            **{f"f{i + 1}_hz": float(x) for i, x in enumerate(f)},
        })
    return rows


# --------------------------------------------------------------------------
# The study as a table


STUDY_COLUMNS = ["element", "size_mm", "dofs", "mesh_s", "assembly_s", "solve_s",
                 "total_s", "peak_memory_mb", "max_rel_error"]


def study_markdown(study: StudyResult) -> str:
    """The study table in Markdown, with how its reference was made."""
    lines = markdown(STUDY_COLUMNS, [
        [f"{r[c]:.2e}" if c == "max_rel_error" else str(r[c]) for c in STUDY_COLUMNS]
        for r in study.rows])
    est = study.estimate
    lines += ["", f"Reference: Richardson extrapolation of the three finest P{study.order} runs; "
              "observed order per mode: " + ", ".join(f"{p:.2f}" for p in est.observed_order)]
    lines += extrapolation_notes(est)
    return "\n".join(lines) + "\n"


def extrapolation_notes(est: Extrapolation) -> list[str]:
    """Where a study's Richardson extrapolation had to assume an order."""
    bad = [i + 1 for i, ok in enumerate(est.reliable) if not ok]
    if not bad:
        return []
    return [f"extrapolation unreliable for mode(s) {', '.join(map(str, bad))}: the meshes "
            "are not yet in the asymptotic range (non-monotone or implausible observed "
            f"order); shown with an assumed order p = {FALLBACK_ORDER:g} and safety factor "
            f"{SAFETY_FALLBACK:g}."]
