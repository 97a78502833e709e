"""`shaftfem` on the command line: parse, call one library function, print, exit code.

Exit codes: 0 success, 1 a check failed (resonance), 2 bad input, 3 a failure inside
the computation (mesher, solver, cache, disk, cluster). Every error is one line on
stderr naming what was wrong; no traceback (SHAFTFEM_DEBUG=1 shows one).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

from shaftfem.errors import EXIT_BAD_INPUT, EXIT_COMPUTATION, SceneError, ShaftfemError
from shaftfem.scene.schema import DEFAULT_MAX_DOFS, MAX_DOFS_LIMIT, MAX_MODE_COUNT

# factor.FACTORIZERS plus "auto"; spelled out here because the CLI must not import
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


def _number(kind, high: float, exclusive: bool = False):
    """An argparse type: a finite number in (0, high] ((0, high) if exclusive)."""
    def parse(text: str):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not {kind.__name__}") from None
        if not (0 < v < high if exclusive else 0 < v <= high):  # also refuses nan and inf
            raise argparse.ArgumentTypeError(
                f"{text!r} must be in (0, {high:g}{')' if exclusive else ']'}")
        return v
    return parse


_size_mm = _number(float, 20_000)
_percent = _number(float, 100, exclusive=True)
_hz = _number(float, 1e7)
_count = _number(int, MAX_MODE_COUNT)
_workers = _number(int, 1024)
_accuracy = _number(float, 50)
_max_dofs = _number(int, MAX_DOFS_LIMIT)


def _sizes(text: str) -> list[float]:
    try:
        v = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected sizes in mm, e.g. 12,9,6.75") from None
    if not v or not all(0 < x <= 20_000 for x in v):
        raise argparse.ArgumentTypeError(f"{text!r}: sizes must be in (0, 20000] mm")
    return v


def _check_outputs(args) -> None:
    """Refuse output paths, and a cache, that cannot work before any heavy work, not
    after it: by writing there (os.access says yes to root on a read-only folder)."""
    from shaftfem.store import check_cache, probe_writable

    for name, folder in (("json", False), ("out", True)):
        path = getattr(args, name, None)
        if path is None:
            continue
        if not str(path).strip():
            raise SceneError(f"--{name} '': give a {'folder' if folder else 'file name'}")
        p = Path(path)
        if folder and p.exists() and not p.is_dir():
            raise SceneError(f"--out {path}: is a file, not a folder")
        if not folder and p.is_dir():
            raise SceneError(f"--json {path}: is a folder; give a file name")
        probe_writable(p if folder else p.parent, f"--{name} {path}")
    if (hasattr(args, "no_cache") and not args.no_cache) or args.func in (_cmd_sweep,
                                                                         _cmd_calibrate):
        check_cache()


def _scene(args):
    """The scene with the command line's mesh and mode overrides."""
    from shaftfem.scene.model import load_scene
    from shaftfem.workflows.adapt import with_accuracy
    from shaftfem.workflows.pipeline import with_mesh, with_modes

    scene = with_mesh(load_scene(args.scene), args.mesh_size, args.order)
    if getattr(args, "free", False):
        scene = scene.free()
    scene = with_accuracy(scene, args.accuracy, args.max_dofs, fixed=args.mesh_size is not None)
    return with_modes(scene, args.modes, args.max_frequency)


def _bounded(args, estimate: bool = False):
    """(result, bound or None, adaptation or None) as the command line asks."""
    from shaftfem.workflows.adapt import run_bounded

    result, est, adapted = run_bounded(_scene(args), estimate=estimate,
                                       use_cache=not args.no_cache,
                                       progress=_Progress(args.quiet), factorizer=args.solver)
    if adapted is not None:
        print(adapted.summary(), file=sys.stdout if adapted.reached else sys.stderr)
    return result, est, adapted


def _accuracy_status(args, adapted) -> int:
    """1 when a strict accuracy was asked for and not reached."""
    return 1 if adapted is not None and not adapted.reached and args.strict_accuracy else 0


def _margin(args) -> float | None:
    return None if args.margin is None else args.margin / 100


def _write_json(path: str, data: dict) -> None:
    from shaftfem.store import write_json

    write_json(path, data)
    print(f"wrote {path}")


def _cmd_modes(args) -> int:
    from shaftfem.outputs.export import modes_record
    from shaftfem.outputs.tables import modes_text

    result, est, adapted = _bounded(args, estimate=not args.no_estimate)
    print(modes_text(result, est))
    if result.scene.held:
        from shaftfem.fem.response import modal_basis, participation
        from shaftfem.outputs.tables import participation_text

        print("\n" + participation_text(result, participation(modal_basis(result))))
    if args.json:
        _write_json(args.json, modes_record(result, est))
    return _accuracy_status(args, adapted)


def _cmd_check(args) -> int:
    from shaftfem.checks.resonance import check_result
    from shaftfem.outputs.tables import verdict_text

    result, _, adapted = _bounded(args)
    verdict = check_result(result, _margin(args))
    if verdict is None:
        raise SceneError(f"{result.scene.source}: no [[excitation]] sources to check against")
    print(verdict_text(verdict))
    if args.json:
        _write_json(args.json, {"scene": result.scene.name, **verdict.as_dict()})
    return 1 if not verdict.ok else _accuracy_status(args, adapted)


def _cmd_export(args) -> int:
    from shaftfem.outputs.export import export_modes, write_calculix

    result, est, adapted = _bounded(args)  # an adapted mesh's bounds go into the tables
    if args.format == "calculix":
        deck = write_calculix(result, Path(args.out) / "shaft.inp")
        print(f"wrote {deck} (run: cd {deck.parent} && ccx -i shaft; frequencies in "
              "shaft.dat, full precision in shaft.eig)")
        return _accuracy_status(args, adapted)
    files = export_modes(result, args.out, est)
    print(f"wrote {len(files)} files to {args.out}: " + ", ".join(f.name for f in files))
    return _accuracy_status(args, adapted)


def _cmd_render(args) -> int:
    from shaftfem.outputs.render import render_all

    result, _, adapted = _bounded(args)
    files = render_all(result, args.out)
    print(f"wrote {len(files)} pictures to {args.out}: " + ", ".join(f.name for f in files))
    return _accuracy_status(args, adapted)


def _cmd_design(args) -> int:
    from shaftfem.outputs.tables import modes_text, sizing_text, verdict_line, verdict_text
    from shaftfem.workflows.design import run_design

    scene = _scene(args)
    d = run_design(scene, _design_out(args, scene.name), margin=_margin(args),
                   estimate=not args.no_estimate, use_cache=not args.no_cache,
                   factorizer=args.solver, progress=_Progress(args.quiet))
    if d.sizing is not None:
        print(sizing_text(d.sizing) + "\n")
    if d.adapted is not None:
        print(d.adapted.summary() + "\n")
    print(modes_text(d.result, d.estimate) + "\n")
    if d.participation is not None:
        from shaftfem.outputs.tables import participation_text

        print(participation_text(d.result, d.participation) + "\n")
    print(verdict_text(d.verdict) if d.verdict is not None
          else verdict_line(None).replace("**", ""))
    print(f"\nreport: {d.report}")
    return 1 if not d.ok else _accuracy_status(args, d.adapted)


def _cmd_study(args) -> int:
    from shaftfem.outputs.plots import save_png, study_figure
    from shaftfem.outputs.tables import study_markdown
    from shaftfem.scene.model import load_scene
    from shaftfem.store import write_csv, write_text
    from shaftfem.workflows.study import run_study, summarize_study

    scene = load_scene(args.scene)
    ladders = {k: v for k, v in {2: args.p2, 1: args.p1}.items() if v}
    runs = run_study(scene, ladders, args.solver, progress=_Progress(args.quiet))
    study = summarize_study(runs, singular=scene.grooves is not None)
    out = Path(args.out)
    md = study_markdown(study)
    files = [write_csv(out / "study.csv", study.rows), write_text(out / "study.md", md),
             save_png(study_figure(study.rows), out / "study.png", dpi=120)]
    print(md)
    print("wrote " + ", ".join(map(str, files)))
    return 0


def _cmd_paper(args) -> int:
    from shaftfem.checks.sizing import size_from_scene
    from shaftfem.outputs.tables import paper_text

    result, _, adapted = _bounded(args)
    sizing = size_from_scene(result.scene) if result.scene.sizing else None
    print(paper_text(result, sizing))
    return _accuracy_status(args, adapted)


def _design_out(args, scene_name: str) -> Path:
    """design's output folder: --out, else out/ and the scene's name."""
    return Path(args.out or Path("out") / scene_name)


def _dask_out(args) -> Path:
    """A sweep's or calibration's output folder: --out, else out/ and its file's name."""
    file = args.sweep if args.func is _cmd_sweep else args.calibration
    return Path(args.out or Path("out") / Path(file).stem)


def _cmd_sweep(args) -> int:
    from shaftfem.outputs.plots import sweep_plots
    from shaftfem.workflows.sweep import load_sweep, run_sweep

    sweep = load_sweep(args.sweep)
    out = _dask_out(args)
    rows = run_sweep(sweep, out / "results.csv", workers=args.workers,
                     scheduler=args.scheduler, estimate=args.estimate,
                     progress=_Progress(args.quiet))
    ok = sum(r["status"] == "ok" for r in rows)
    print(f"{len(rows)} variants in {out / 'results.csv'}: {ok} ok, {len(rows) - ok} failed")
    pics = sweep_plots(rows, sweep.parameters, sweep.n_modes, out)
    if pics:
        print("plots: " + ", ".join(str(p) for p in pics))
    for r in rows:
        if r["status"] != "ok":
            print(f"  failed {r['id']}: " + ", ".join(f"{p} = {r[p]}" for p in sweep.parameters)
                  + f": {r['error']}")
    return 0 if ok else EXIT_COMPUTATION  # nothing usable came out


def _cmd_calibrate(args) -> int:
    from shaftfem.outputs.tables import calibration_text
    from shaftfem.workflows.calibrate import calibrate, load_calibration

    cal = load_calibration(args.calibration)
    out = _dask_out(args)
    res = calibrate(cal, out, workers=args.workers, progress=_Progress(args.quiet),
                    scheduler=args.scheduler)
    print(calibration_text(res, cal))
    _write_json(str(out / "calibration.json"), res.as_dict(cal))
    return 0


def _cmd_size(args) -> int:
    from shaftfem.checks.sizing import size_from_scene
    from shaftfem.outputs.tables import sizing_text
    from shaftfem.scene.model import load_scene

    result = size_from_scene(load_scene(args.scene))
    print(sizing_text(result))
    if args.json:
        _write_json(args.json, result.as_dict())
    return 0 if result.ok else 1


SCENE_HELP = "scene file or name of a shipped scene (default: paper2018)"


class _Parser(argparse.ArgumentParser):
    """argparse, with its errors on one line like every other error (exit 2)."""

    def error(self, message: str):
        print(f"{self.prog}: error: {message} (see {self.prog} --help)", file=sys.stderr)
        raise SystemExit(EXIT_BAD_INPUT)


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(
        prog="shaftfem",
        description="Finite-element modal analysis of machine shafts: free-free, or installed "
        "in the bearings of the scene's [[support]] tables.",
    )
    sub = p.add_subparsers(dest="command", required=True)

    def modal_command(name: str, help: str, func, json: bool = True, out: str | None = None,
                      estimate: bool = False, margin: bool = False):
        c = sub.add_parser(name, help=help)
        c.add_argument("scene", nargs="?", default=None, help=SCENE_HELP)
        c.add_argument("--mesh-size", type=_size_mm, metavar="MM",
                       help="element size away from the grooves, mm (groove sizes scale with it)")
        c.add_argument("--order", type=int, choices=(1, 2), help="element order (default: scene)")
        c.add_argument("--modes", type=_count, metavar="N",
                       help="number of elastic modes (default: the scene's [modes] count, else 10)")
        c.add_argument("--max-frequency", type=_hz, metavar="HZ",
                       help="every elastic mode below this frequency, Hz, instead of a count")
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
            c.add_argument("--margin", type=_percent, metavar="PERCENT",
                           help="required separation margin, %% (default: scene, else 15)")
        if estimate:
            c.add_argument("--no-estimate", action="store_true",
                           help="skip the error bound (one more solve on a coarser mesh)")
        c.add_argument("--accuracy", type=_accuracy, metavar="PERCENT",
                       help="adapt the mesh until every frequency's error bound is below "
                       "PERCENT (default: the scene's [mesh] target_error_percent, else the "
                       "fixed mesh)")
        c.add_argument("--max-dofs", type=_max_dofs, metavar="N",
                       help="DOF budget of the adaptive mesh (default: the scene's, else "
                       f"{DEFAULT_MAX_DOFS})")
        c.add_argument("--strict-accuracy", action="store_true",
                       help="exit 1 when the accuracy asked for is not reached in the budget")
        c.add_argument("--free", action="store_true",
                       help="free-free: leave the scene's [[support]] bearings off (the shaft "
                       "hanging free, as in a hammer test; attached parts stay on)")
        c.add_argument("--no-cache", action="store_true",
                       help="neither read nor write the cache: build the CAD solid and every "
                       "mesh afresh and keep none of them")
        c.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
        c.set_defaults(func=func)
        return c

    modal_command("modes", "natural frequencies with their error bounds (in the scene's "
                  "supports if it has any, else free-free)",
                  _cmd_modes, estimate=True)
    modal_command("check", "resonance check against the scene's excitations (exit 1 if "
                  "a margin is violated)", _cmd_check, margin=True)
    e = modal_command("export", "mode shapes (VTU/PVD), tables (CSV/JSON), mesh (MSH), solid "
                      "(STEP/BREP); or a CalculiX deck", _cmd_export, json=False, out="required")
    e.add_argument("--format", choices=("vtk", "calculix"), default="vtk",
                   help="vtk: mode shapes and tables (default); calculix: shaft.inp, a C3D10 "
                   "*FREQUENCY deck of the same mesh and material")
    modal_command("render", "pictures: the shaft, every mode (PNG) and each mode moving (GIF)",
                  _cmd_render,
                  json=False, out="required")
    modal_command("design", "sizing, modes, resonance check, files, pictures and a report",
                  _cmd_design, json=False, out="optional", estimate=True, margin=True)
    modal_command("paper", "the paper's Table 2 and stated sizing beside ours", _cmd_paper,
                  json=False)

    def dask_command(name: str, help: str, file_help: str, func):
        c = sub.add_parser(name, help=help)
        c.add_argument(name if name == "sweep" else "calibration", help=file_help)
        c.add_argument("--out", help=f"output folder (default out/ and the {name} file's name)")
        c.add_argument("--workers", type=_workers, default=2,
                       help="local worker processes (default 2)")
        c.add_argument("--scheduler", metavar="ADDRESS",
                       help="an existing Dask scheduler, e.g. tcp://host:8786, instead of local "
                       "workers")
        c.add_argument("-q", "--quiet", action="store_true")
        c.set_defaults(func=func)
        return c

    sw = dask_command("sweep", "run many variants of a scene on Dask (resumable)",
                      "sweep file (TOML): base scene and parameter axes or points", _cmd_sweep)
    sw.add_argument("--estimate", action="store_true",
                    help="also bound each frequency's error (one more solve per variant, "
                    "on a coarser mesh)")
    dask_command("calibrate", "find unknown scene values that reproduce target frequencies "
                 "(grid on Dask, then least squares)",
                 "calibration file (TOML): base, unknowns, targets", _cmd_calibrate)

    st = sub.add_parser("study", help="work-precision study: a ladder of P1 and P2 meshes")
    st.add_argument("scene", nargs="?", default=None, help=SCENE_HELP)
    st.add_argument("--p2", type=_sizes, default=[12.0, 9.0, 6.75, 5.0625],
                    help="P2 element sizes, mm (geometric; the three finest make the reference)")
    st.add_argument("--p1", type=_sizes, default=[8.0, 6.0, 4.5], help="P1 element sizes, mm")
    st.add_argument("--out", default="out/study", help="output folder (default: out/study)")
    st.add_argument("--solver", choices=SOLVERS, default="auto")
    st.add_argument("-q", "--quiet", action="store_true")
    st.set_defaults(func=_cmd_study)

    s = sub.add_parser("size", help="size the screw shaft from its duty (paper eqs. 1-9)")
    s.add_argument("scene", nargs="?", default=None, help=SCENE_HELP)
    s.add_argument("--json", metavar="FILE", help="also write the results as JSON")
    s.set_defaults(func=_cmd_size)
    return p


def main(argv: list[str] | None = None) -> int:
    from shaftfem.runtime import configure_threads

    configure_threads()  # before NumPy loads (shaftfem.runtime says why)
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:  # --help (0) or a bad command line (2, already said)
        return int(exc.code or 0)
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            _check_outputs(args)
            return args.func(args)
    except ShaftfemError as exc:
        print(f"shaftfem: error: {_one_line(exc)}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        print("shaftfem: interrupted", file=sys.stderr)
        return 130
    except OSError as exc:  # the disk: a folder that is a file, no space, no permission
        print(f"shaftfem: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_COMPUTATION
    except Exception as exc:  # not translated where it happened: still one line, exit 3
        if os.environ.get("SHAFTFEM_DEBUG"):
            raise
        print(f"shaftfem: error: the computation failed unexpectedly: {type(exc).__name__}: "
              f"{_one_line(exc)} (set SHAFTFEM_DEBUG=1 for the traceback)", file=sys.stderr)
        return EXIT_COMPUTATION


def entry() -> None:
    """The `shaftfem` command: main() in a child process that Ctrl-C always stops
    (shaftfem.supervise)."""
    from shaftfem.supervise import supervised

    argv = sys.argv[1:]
    folders = _output_folders(argv)
    if folders is None:  # --help, or a bad command line: nothing to supervise
        sys.exit(main(argv))
    sys.exit(supervised(lambda: main(argv), folders))


def _output_folders(argv: list[str]) -> list[Path] | None:
    """The folders a command line may write into, for the clean-up after a stop; None
    where it does not parse (or asks for help), said by main() itself."""
    import contextlib
    import io

    try:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            args = build_parser().parse_args(argv)
    except SystemExit:
        return None
    if args.func is _cmd_design and not args.out:
        try:
            from shaftfem.scene.model import load_scene

            return [_design_out(args, load_scene(args.scene).name)]
        except Exception:  # the child says what is wrong with the scene
            return []
    if args.func in (_cmd_sweep, _cmd_calibrate):
        return [_dask_out(args)]
    out = getattr(args, "out", None)
    return [Path(out)] if out else []


def _show_warning(message, category, *_args, **_kwargs) -> None:
    print(f"shaftfem: warning: {_one_line(message)}", file=sys.stderr)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


if __name__ == "__main__":
    sys.exit(main())
