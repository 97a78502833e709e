"""`shaftfem` on the command line: it reads arguments, calls the steps, prints.

Exit codes: 0 success, 1 a check failed (resonance), 2 bad input or a failed step.
Every error is one line on stderr naming what was wrong; no traceback.
"""

from __future__ import annotations

import os

# One OpenBLAS thread, set before NumPy and SciPy load (a later runtime limit does
# not have the same effect). MKL PARDISO's threads do the heavy work; NumPy's
# OpenBLAS pool, started beside them, fought MKL's for the cores and doubled the
# eigensolve of the paper's shaft on 2 cores (5.4 s -> 2.8 s without it;
# benchmarks/end_to_end.py). A user's own setting wins.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

from .errors import ShaftfemError  # noqa: E402


# modal.FACTORIZERS plus "auto"; spelled out here because the CLI must not import
# SciPy before a command needs it (`shaftfem size` loads no solver).
SOLVERS = ("auto", "pardiso", "cholmod", "superlu")


class _Progress:
    """Progress lines with elapsed time on stderr, for the long steps."""

    def __init__(self, quiet: bool = False):
        self.t0 = time.perf_counter()
        self.quiet = quiet

    def __call__(self, msg: str) -> None:
        if not self.quiet:
            print(f"[{time.perf_counter() - self.t0:7.1f} s] {msg}", file=sys.stderr, flush=True)


def _positive_float(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not v > 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be > 0")
    return v


def _estimate(args, result):
    """The discretisation-error estimate (two coarser solves), unless --no-estimate."""
    if getattr(args, "no_estimate", False):
        return None
    from .study import estimate_errors

    return estimate_errors(result, progress=_Progress(args.quiet), factorizer=args.solver)


def _cmd_modes(args) -> int:
    from .export import modes_record, write_json

    result = _run(args)
    est = _estimate(args, result)
    print(format_modes(result, est))
    if args.json:
        rec = modes_record(result)
        if est is not None:
            for row, e, p, ok in zip(rec["elastic_modes"], est.relative_error,
                                     est.observed_order, est.reliable):
                row.update(estimated_error=float(e), observed_order=float(p),
                           estimate_reliable=bool(ok))
        write_json(args.json, rec)
        print(f"wrote {args.json}")
    return 0


def format_modes(result, est=None) -> str:
    """The modes table as a designer reads it (every number with its unit)."""
    m, scene = result.modes, result.scene
    exc = scene.excitations[0] if scene.excitations else None
    lines = [
        f"scene {scene.name}: P{scene.mesh.order}, {m.n_dofs} DOFs, "
        f"{result.mesh.n_elements} elements, element size {scene.mesh.size * 1e3:g} mm "
        f"(grooves {scene.mesh.groove_size * 1e3:g} mm), solver {m.factorizer}",
        f"rigid-body modes: {m.n_rigid} (all below {max(m.rigid_frequencies):.1e} Hz)",
        "",
    ]
    head = f"{'mode':>4}  {'frequency':>12}  {'kind':<8}  {'residual':>9}"
    if est is not None:
        head += f"  {'est. error':>10}  {'order':>5}"
    if exc:
        head += f"  {'f / ' + exc.name + ' ' + format(exc.frequency, 'g') + ' Hz':>20}"
    lines.append(head)
    for i, (f, kind, r) in enumerate(zip(m.frequencies, m.kinds, m.residuals)):
        row = f"{i + 1:>4}  {f:>9.2f} Hz  {kind:<8}  {r:>9.1e}"
        if est is not None:
            e, p = est.relative_error[i], est.observed_order[i]
            mark = " " if est.reliable[i] else "?"
            row += f"  {100 * e:>7.2f} %{mark}  {p:>5.2f}" if math.isfinite(e) else f"  {'n/a':>10}  {'':>5}"
        if exc:
            row += f"  {f / exc.frequency:>20.2f}"
        lines.append(row)
    if est is not None:
        lines.append("")
        lines.append(f"est. error: estimated discretisation error of each frequency (three "
                     f"meshes, sizes x1, x{est.ratio:g}, x{est.ratio**2:g}; observed order p)")
        lines += est.notes()
    for w in result.warnings:
        lines.append(f"WARNING: {w}")
    t = result.seconds
    lines.append("")
    lines.append("time: " + ", ".join(f"{k} {v:.1f} s" for k, v in t.items()))
    return "\n".join(lines)


def _run(args, scene=None):
    """Load the scene (unless given), apply the CLI mesh overrides, run the modal chain."""
    from .pipeline import run_modes, with_mesh
    from .scene import load_scene

    scene = with_mesh(scene or load_scene(args.scene), args.mesh_size, args.order)
    return run_modes(scene, use_cache=not args.no_cache, progress=_Progress(args.quiet),
                     factorizer=args.solver)


def _verdict(args, result):
    from .resonance import check_resonance

    margin = result.scene.required_margin
    if getattr(args, "margin", None) is not None:
        margin = args.margin / 100
    return check_resonance(result.modes.frequencies, result.modes.kinds,
                           result.scene.excitations, margin)


def _cmd_check(args) -> int:
    from .errors import SceneError
    from .export import write_json
    from .resonance import format_verdict

    result = _run(args)
    if not result.scene.excitations:
        raise SceneError(f"{result.scene.source}: no [[excitation]] sources to check against")
    verdict = _verdict(args, result)
    print(format_verdict(verdict))
    if args.json:
        write_json(args.json, {"scene": result.scene.name, **verdict.as_dict()})
        print(f"wrote {args.json}")
    return 0 if verdict.ok else 1


def _cmd_export(args) -> int:
    from pathlib import Path

    from .export import export_modes, write_calculix

    result = _run(args)
    if args.format == "calculix":
        deck = write_calculix(result, Path(args.out) / "shaft.inp")
        print(f"wrote {deck} (run: cd {deck.parent} && ccx -i shaft; frequencies in "
              "shaft.dat, full precision in shaft.eig)")
        return 0
    files = export_modes(result, args.out)
    print(f"wrote {len(files)} files to {args.out}: " + ", ".join(f.name for f in files))
    return 0


def _cmd_render(args) -> int:
    from pathlib import Path

    from .render import render_geometry, render_modes

    result = _run(args)
    out = Path(args.out)
    a = render_geometry(result, out / "geometry.png")
    b = render_modes(result, out / "modes.png")
    print(f"wrote {a} and {b}")
    return 0


def _cmd_design(args) -> int:
    from pathlib import Path

    from .export import export_modes
    from .render import render_geometry, render_modes
    from .report import verdict_line, write_report
    from .resonance import format_verdict
    from .scene import load_scene
    from .sizing import format_sizing, size_from_scene

    progress = _Progress(args.quiet)
    scene = load_scene(args.scene)
    out = Path(args.out or Path("out") / scene.name)
    sizing = None
    if scene.sizing is not None:
        progress("sizing (equations 1-9)")
        sizing = size_from_scene(scene)
        print(format_sizing(sizing) + "\n")
    result = _run(args, scene)
    est = _estimate(args, result)
    print(format_modes(result, est) + "\n")
    verdict = _verdict(args, result)
    print(format_verdict(verdict) + "\n")
    progress("exporting mode shapes, mesh and solid")
    errors = None if est is None else est.relative_error
    files = export_modes(result, out, errors)
    progress("rendering pictures")
    pics = [render_geometry(result, out / "geometry.png"), render_modes(result, out / "modes.png")]
    report = write_report(out / "report.md", result, verdict, sizing, pics, files, est)
    progress(f"report written: {report}")
    print(f"report: {report}")
    print(verdict_line(verdict).replace("**", ""))
    return 0 if verdict.ok else 1


def _cmd_study(args) -> int:
    from pathlib import Path

    from .export import atomic_path, write_csv
    from .report import study_markdown
    from .scene import load_scene
    from .study import plot_study, run_study, study_reference, study_table

    scene = load_scene(args.scene)
    ladders = {k: v for k, v in {2: args.p2, 1: args.p1}.items() if v}
    runs = run_study(scene, ladders, args.solver, progress=_Progress(args.quiet))
    ref, est = study_reference(runs, singular=scene.grooves is not None)
    top = [r for r in runs if r.order == max(ladders)][-1]
    rows = study_table(runs, ref, top.kinds)
    out = Path(args.out)
    write_csv(out / "study.csv", rows)
    md = study_markdown(rows, est, max(ladders))
    with atomic_path(out / "study.md") as tmp:
        tmp.write_text(md)
    plot_study(rows, out / "study.png")
    print(md)
    print(f"wrote {out / 'study.csv'}, {out / 'study.md'}, {out / 'study.png'}")
    return 0


def _sizes(text: str) -> list[float]:
    try:
        v = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected sizes in mm, e.g. 12,9,6.75") from None
    if any(x <= 0 for x in v):
        raise argparse.ArgumentTypeError(f"{text!r}: sizes must be > 0")
    return v


def _cmd_paper(args) -> int:
    from .report import format_paper_comparison

    result = _run(args)
    print(format_paper_comparison(result))
    return 0


def _cmd_sweep(args) -> int:
    from pathlib import Path

    from .sweep import load_sweep, plot_sweep, run_sweep

    sweep = load_sweep(args.sweep)
    out = Path(args.out)
    rows = run_sweep(sweep, out / "results.csv", workers=args.workers,
                     scheduler=args.scheduler, estimate=args.estimate,
                     progress=_Progress(args.quiet))
    ok = sum(r["status"] == "ok" for r in rows)
    print(f"{len(rows)} variants in {out / 'results.csv'}: {ok} ok, {len(rows) - ok} failed")
    pics = plot_sweep(rows, sweep.parameters, out)
    if pics:
        print("plots: " + ", ".join(str(p) for p in pics))
    for r in rows:
        if r["status"] != "ok":
            print(f"  failed {r['id']}: " + ", ".join(f"{p} = {r[p]}" for p in sweep.parameters)
                  + f": {r['error']}")
    return 0


def _cmd_calibrate(args) -> int:
    from pathlib import Path

    from .calibrate import calibrate, load_calibration
    from .export import write_json

    cal = load_calibration(args.calibration)
    out = Path(args.out)
    res = calibrate(cal, out, workers=args.workers, progress=_Progress(args.quiet))
    print(res.format(cal))
    write_json(out / "calibration.json", {
        "parameters": res.parameters, "std": res.std, "grid_best": res.grid_best,
        "targets_hz": cal.targets, "model_hz": res.frequencies,
        "residuals_sigma": res.residuals_sigma, "chi2": res.chi2,
        "evaluations": res.evaluations})
    print(f"wrote {out / 'calibration.json'}")
    return 0


def _cmd_size(args) -> int:
    from .sizing import format_sizing, size_from_scene
    from .export import write_json
    from .scene import load_scene

    scene = load_scene(args.scene)
    result = size_from_scene(scene)
    print(format_sizing(result))
    if args.json:
        write_json(args.json, result.as_dict())
        print(f"wrote {args.json}")
    return 0 if result.ok else 1


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="shaftfem",
        description="Finite-element modal analysis of machine shafts (free-free).",
    )
    sub = p.add_subparsers(dest="command", required=True)

    def modal_command(name: str, help: str, func, json: bool = True, out: str | None = None,
                      estimate: bool = False, margin: bool = False):
        c = sub.add_parser(name, help=help)
        c.add_argument("scene", nargs="?", default=None,
                       help="scene file or name in geometry/ (default: paper2018)")
        c.add_argument("--mesh-size", type=_positive_float, metavar="MM",
                       help="element size away from the grooves, mm (groove sizes scale with it)")
        c.add_argument("--order", type=int, choices=(1, 2), help="element order (default: scene)")
        if json:
            c.add_argument("--json", metavar="FILE", help="also write the results as JSON")
        if out is not None:
            c.add_argument("--out", metavar="DIR", required=out == "required",
                           help="output folder" + ("" if out == "required"
                                                   else " (default: out/SCENE)"))
        c.add_argument("--solver", choices=SOLVERS,
                       default="auto", help="sparse factorisation behind shift-invert "
                       "(default: the fastest installed; superlu is pure SciPy)")
        if margin:
            c.add_argument("--margin", type=_positive_float, metavar="PERCENT",
                           help="required separation margin, %% (default: scene, else 15)")
        if estimate:
            c.add_argument("--no-estimate", action="store_true",
                           help="skip the error estimate (two extra solves on coarser meshes)")
        c.add_argument("--no-cache", action="store_true", help="rebuild the CAD solid and the mesh")
        c.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
        c.set_defaults(func=func)
        return c

    modal_command("modes", "first ten free-free natural frequencies", _cmd_modes, estimate=True)
    modal_command("check", "resonance check against the scene's excitations (exit 1 if "
                  "a margin is violated)", _cmd_check, margin=True)
    e = modal_command("export", "mode shapes (VTU/PVD), tables (CSV/JSON), mesh (MSH), solid "
                      "(STEP/BREP); or a CalculiX deck", _cmd_export, json=False, out="required")
    e.add_argument("--format", choices=("vtk", "calculix"), default="vtk",
                   help="vtk: mode shapes and tables (default); calculix: shaft.inp, a C3D10 "
                   "*FREQUENCY deck of the same mesh and material")
    modal_command("render", "PNG pictures of the shaft and its first eight modes", _cmd_render,
                  json=False, out="required")
    modal_command("design", "sizing, modes, resonance check, files, pictures and a report",
                  _cmd_design, json=False, out="optional", estimate=True, margin=True)

    modal_command("paper", "the paper's Table 2 beside our frequencies", _cmd_paper,
                  json=False)
    sw = sub.add_parser("sweep", help="run many variants of a scene on Dask (resumable)")
    sw.add_argument("sweep", help="sweep file (TOML): base scene and parameter axes or points")
    sw.add_argument("--out", default="out/sweep", help="folder for results.csv (default out/sweep)")
    sw.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    sw.add_argument("--scheduler", metavar="ADDRESS",
                    help="an existing Dask scheduler, e.g. tcp://host:8786, instead of a local one")
    sw.add_argument("--estimate", action="store_true",
                    help="also estimate each frequency's error (three solves per variant)")
    sw.add_argument("-q", "--quiet", action="store_true")
    sw.set_defaults(func=_cmd_sweep)

    ca = sub.add_parser("calibrate", help="find unknown scene values that reproduce target "
                        "frequencies (grid on Dask, then least squares)")
    ca.add_argument("calibration", help="calibration file (TOML): base, unknowns, targets")
    ca.add_argument("--out", default="out/calibrate", help="output folder (default out/calibrate)")
    ca.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    ca.add_argument("-q", "--quiet", action="store_true")
    ca.set_defaults(func=_cmd_calibrate)

    st = sub.add_parser("study", help="work-precision study: a ladder of P1 and P2 meshes")
    st.add_argument("scene", nargs="?", default=None,
                    help="scene file or name in geometry/ (default: paper2018)")
    st.add_argument("--p2", type=_sizes, default=[12.0, 9.0, 6.75, 5.0625],
                    help="P2 element sizes, mm (geometric; the three finest make the reference)")
    st.add_argument("--p1", type=_sizes, default=[8.0, 6.0, 4.5], help="P1 element sizes, mm")
    st.add_argument("--out", default="out/study", help="output folder (default: out/study)")
    st.add_argument("--solver", choices=SOLVERS, default="auto")
    st.add_argument("-q", "--quiet", action="store_true")
    st.set_defaults(func=_cmd_study)

    s = sub.add_parser("size", help="size the screw shaft from its duty (paper eqs. 1-9)")
    s.add_argument("scene", nargs="?", default=None,
                   help="scene file or name in geometry/ (default: paper2018)")
    s.add_argument("--json", metavar="FILE", help="also write the results as JSON")
    s.set_defaults(func=_cmd_size)
    return p


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except ShaftfemError as exc:
        print(f"shaftfem: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("shaftfem: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
