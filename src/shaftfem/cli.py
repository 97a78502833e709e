"""`shaftfem` on the command line: it reads arguments, calls the steps, prints.

Exit codes: 0 success, 1 a check failed (resonance), 2 bad input or a failed step.
Every error is one line on stderr naming what was wrong; no traceback.
"""

from __future__ import annotations

import argparse
import sys
import time

import math

from .errors import ShaftfemError


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


def _run(args):
    """Load the scene (with CLI mesh overrides) and run the modal chain."""
    from .pipeline import run_modes, with_mesh
    from .scene import load_scene

    scene = with_mesh(load_scene(args.scene), args.mesh_size, args.order)
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
    from .export import export_modes

    result = _run(args)
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
    result = _run(args)
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
                      estimate: bool = False):
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
        c.add_argument("--solver", choices=("auto", "pardiso", "cholmod", "superlu"),
                       default="auto", help="sparse factorisation behind shift-invert "
                       "(default: the fastest installed; superlu is pure SciPy)")
        if estimate:
            c.add_argument("--no-estimate", action="store_true",
                           help="skip the error estimate (two extra solves on coarser meshes)")
        c.add_argument("--no-cache", action="store_true", help="rebuild the CAD solid")
        c.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
        c.set_defaults(func=func)
        return c

    modal_command("modes", "first ten free-free natural frequencies", _cmd_modes, estimate=True)
    c = modal_command("check", "resonance check against the scene's excitations (exit 1 if "
                      "a margin is violated)", _cmd_check)
    c.add_argument("--margin", type=_positive_float, metavar="PERCENT",
                   help="required separation margin, %% (default: scene, else 15)")
    modal_command("export", "mode shapes (VTU/PVD), tables (CSV/JSON), mesh (MSH), solid "
                  "(STEP/BREP)", _cmd_export, json=False, out="required")
    modal_command("render", "PNG pictures of the shaft and its first eight modes", _cmd_render,
                  json=False, out="required")
    d = modal_command("design", "sizing, modes, resonance check, files, pictures and a report",
                      _cmd_design, json=False, out="optional", estimate=True)
    d.add_argument("--margin", type=_positive_float, metavar="PERCENT",
                   help="required separation margin, %% (default: scene, else 15)")

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
