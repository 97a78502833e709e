"""The commands: each builds its scene and options from the command line, calls one
library function, prints the result and returns the exit code."""

from __future__ import annotations

import sys
import time
from pathlib import Path

from shaftfem.errors import EXIT_COMPUTATION, SceneError
from shaftfem.runtime import RunOptions


class Progress:
    """Progress lines with elapsed time on stderr, for the long steps."""

    def __init__(self, quiet: bool = False):
        self.t0 = time.perf_counter()
        self.quiet = quiet

    def __call__(self, msg: str) -> None:
        if not self.quiet:
            print(f"[{time.perf_counter() - self.t0:7.1f} s] {msg}", file=sys.stderr, flush=True)


def _options(args) -> RunOptions:
    """How the command line asks the run to be carried out."""
    return RunOptions(use_cache=not getattr(args, "no_cache", False),
                      factoriser=getattr(args, "solver", "auto"),
                      progress=Progress(args.quiet))


def check_outputs(args) -> None:
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
    if (hasattr(args, "no_cache") and not args.no_cache) or args.func in (cmd_sweep,
                                                                         cmd_calibrate):
        check_cache()


def _scene(args):
    """The scene with the command line's mesh and mode overrides."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.bounded import with_accuracy
    from shaftfem.workflows.pipeline import with_mesh, with_modes

    scene = with_mesh(load_scene(args.scene), args.mesh_size, args.order,
                      getattr(args, "geometry_order", None))
    if getattr(args, "free", False):
        scene = scene.free()
    scene = with_accuracy(scene, args.accuracy, args.max_dofs, fixed=args.mesh_size is not None)
    return with_modes(scene, args.modes, args.max_frequency)


def _bounded(args, estimate: bool = False):
    """(result, bound or None, adaptation or None) as the command line asks."""
    from shaftfem.workflows.bounded import run_bounded

    b = run_bounded(_scene(args), estimate, _options(args), choose=_chooses(args))
    if b.adapted is not None:
        print(b.adapted.summary(), file=sys.stdout if b.adapted.reached else sys.stderr)
    return b.result, b.estimate, b.adapted


def _chooses(args) -> bool:
    """--accuracy with no --mesh-size, --order or --geometry-order: the discretisation
    is shaftfem's to choose (workflows.route)."""
    return args.accuracy is not None and all(
        getattr(args, k, None) is None for k in ("mesh_size", "order", "geometry_order"))


def _accuracy_status(args, adapted) -> int:
    """1 when a strict accuracy was asked for and not reached."""
    return 1 if adapted is not None and not adapted.reached and args.strict_accuracy else 0


def _margin(args) -> float | None:
    return None if args.margin is None else args.margin / 100


def _write_json(path: str, data: dict) -> None:
    from shaftfem.store import write_json

    write_json(path, data)
    print(f"wrote {path}")


def cmd_modes(args) -> int:
    from shaftfem.outputs.export import modes_record
    from shaftfem.outputs.tables import modes_text

    result, est, adapted = _bounded(args, estimate=not args.no_estimate)
    moves = None
    if args.sensitivity:
        from shaftfem.workflows.sensitivity import sensitivity

        moves = sensitivity(result, _options(args))
    print(modes_text(result, est, moves))
    if result.scene.held:
        from shaftfem.fem.response import modal_basis, participation
        from shaftfem.outputs.tables import participation_text

        print("\n" + participation_text(result, participation(modal_basis(result))))
    turning = None
    if args.speed_rpm is not None:
        from shaftfem.outputs.tables import whirl_text
        from shaftfem.workflows.campbell import whirl_table

        c = whirl_table(result.scene, args.speed_rpm, _options(args))
        print(f"\nframe: {c.frame} ({c.why})")
        print(whirl_text(c.operating, f"the shaft turning at {args.speed_rpm:,.0f} r/min "
                         f"({args.speed_rpm / 60:.2f} Hz), stationary frame:"))
        t = c.truncation
        print(f"modal basis: {t.size} standstill modes; on {t.smaller} the whirl frequencies "
              f"move by at most {t.change * 100:.2g} %")
        turning = {"speed_rpm": args.speed_rpm, "frame": c.frame,
                   "whirl": [w.as_dict() for w in c.operating],
                   "basis": {"modes": t.size, "checked_against": t.smaller,
                             "largest_change": t.change}}
    if args.json:
        record = modes_record(result, est, moves)
        if turning is not None:
            record = {**record, "turning": turning}
        _write_json(args.json, record)
    return _accuracy_status(args, adapted)


def _publish_figure(out: str, name: str, record) -> None:
    """NAME.png of a study's record in `out`, published with NAME.manifest.json: all its
    files or none (an interrupt, a failure), as every command with --out."""
    from shaftfem.outputs import plots
    from shaftfem.store import staged_directory

    with staged_directory(out, f"{name}.manifest.json") as stage:
        plots.save_png(getattr(plots, f"{name}_figure")(record), stage / f"{name}.png")
    print(f"wrote {Path(out) / f'{name}.png'}")


CAMPBELL_MANIFEST = "campbell.manifest.json"   # the files of the last complete campbell run


def cmd_campbell(args) -> int:
    from shaftfem.outputs.tables import campbell_text
    from shaftfem.workflows.campbell import run_campbell, speed_grid

    scene = _scene(args)
    grid = speed_grid(*args.speeds_rpm) if args.speeds_rpm else None
    c = run_campbell(scene, _options(args), grid)
    print(campbell_text(c))
    if args.out:
        from shaftfem.outputs.whirl_files import write_whirl_files
        from shaftfem.store import staged_directory
        from shaftfem.workflows.design import campbell_pictures

        out = Path(args.out)
        # every file of the run is published at once, or none (an interrupt, a failure)
        with staged_directory(out, CAMPBELL_MANIFEST) as stage:
            pictures = campbell_pictures(c, stage)
            files = write_whirl_files(c, stage)
        for path in pictures:
            print(f"wrote {out / path.name}")
        print(f"wrote {len(files)} files of the whirl at the operating speed(s) for ParaView: "
              f"{out / files[-1].name} (real and imaginary parts of each mode)")
    if args.json:
        _write_json(args.json, {"scene": scene.name, **c.as_dict()})
    return 0


UCS_MANIFEST = "ucs.manifest.json"   # the files of the last complete ucs run


def cmd_ucs(args) -> int:
    import json

    import numpy as np

    from shaftfem.outputs.tables import ucs_csv, ucs_text
    from shaftfem.workflows.ucs import run_ucs

    scene = _scene(args)
    ks = None
    if args.stiffness_n_per_mm:
        a, b, n = args.stiffness_n_per_mm
        ks = np.logspace(np.log10(a * 1e3), np.log10(b * 1e3), n)
    kind = "standstill" if args.standstill else "backward" if args.backward else "forward"
    m = run_ucs(scene, ks, _options(args), kind=kind)
    print(ucs_text(m))
    if args.out:
        from shaftfem.outputs.plots import save_png
        from shaftfem.outputs.ucs_plot import ucs_figure
        from shaftfem.store import staged_directory

        out = Path(args.out)
        with staged_directory(out, UCS_MANIFEST) as stage:
            save_png(ucs_figure(m), stage / "ucs.png", dpi=130)
            (stage / "ucs.csv").write_text(ucs_csv(m))
            (stage / "ucs.json").write_text(json.dumps({"scene": scene.name, **m.as_dict()},
                                                       indent=1))
        for name in ("ucs.png", "ucs.csv", "ucs.json"):
            print(f"wrote {out / name}")
    if args.json:
        _write_json(args.json, {"scene": scene.name, **m.as_dict()})
    return 0


def cmd_level1(args) -> int:
    import numpy as np

    from shaftfem.outputs.tables import level1_text
    from shaftfem.workflows.level1 import run_level1

    scene = _scene(args)
    qs = None
    if args.q_n_per_mm:
        a, b, n = args.q_n_per_mm
        qs = np.linspace(a, b, n)
    r = run_level1(scene, qs, args.at_mm, args.qa_n_per_mm, _options(args))
    print(level1_text(r))
    if args.out:
        _publish_figure(args.out, "level1", r)
    if args.json:
        _write_json(args.json, {"scene": scene.name, **r.as_dict()})
    return 1 if r.passed is False else 0


def cmd_runup(args) -> int:
    from shaftfem.outputs.tables import runup_text
    from shaftfem.workflows.runup import run_run_up

    scene = _scene(args)
    if scene.rotor is None:
        raise SceneError(f"{scene.source}: no [rotor] table: a run-up needs the shaft turning")
    accel = args.accel_rpm_per_s
    top = scene.rotor.max_speed * 30 / 3.141592653589793
    start, stop = args.speeds_rpm or ((0.0, top) if accel > 0 else (top, 0.0))
    if accel == 0 or (stop - start) / accel <= 0:
        raise SceneError(f"--accel-rpm-per-s {accel:g}: takes the speed from {start:g} to "
                         f"{stop:g} r/min the other way (give a positive acceleration for a "
                         "run-up, a negative one for a coast-down)")
    r = run_run_up(scene, start, stop, accel, _options(args))
    print(runup_text(r))
    if args.out:
        _publish_figure(args.out, "runup", r)
    if args.json:
        _write_json(args.json, {"scene": scene.name, **r.as_dict()})
    return 0


def cmd_frf(args) -> int:
    import numpy as np

    from shaftfem.outputs.tables import frf_text
    from shaftfem.workflows.frf import run_frequency_response

    scene = _scene(args)
    if scene.rotor is None:
        raise SceneError(f"{scene.source}: no [rotor] table: the frequency response of the "
                         "running machine needs its speed")
    a, b, n = args.frequencies_hz
    freqs = np.linspace(a, b, n)
    speeds = np.array(args.speeds_rpm if args.speeds_rpm else
                      [0.0, *(w * 30 / np.pi for w in scene.rotor.speeds)])
    if any(n < 0 or not np.isfinite(n) for n in speeds):
        raise SceneError(f"--speeds-rpm {' '.join(f'{n:g}' for n in speeds)}: speeds are "
                         "0 r/min or more")
    at = args.at_mm * 1e-3
    probe = at if args.probe_mm is None else args.probe_mm * 1e-3
    r = run_frequency_response(scene, at, probe, freqs, speeds, _options(args))
    print(frf_text(r))
    if args.out:
        _publish_figure(args.out, "frf", r)
    if args.json:
        _write_json(args.json, {"scene": scene.name, **r.as_dict()})
    return 0


def cmd_static(args) -> int:
    from shaftfem.outputs.tables import static_text
    from shaftfem.workflows.static import run_static

    result = run_static(_scene(args), _options(args))
    print(static_text(result))
    if args.out:
        _publish_figure(args.out, "static", result)
    if args.json:
        _write_json(args.json, {"scene": result.scene.name, **result.as_dict()})
    return 0


def cmd_strength(args) -> int:
    from shaftfem.errors import EXIT_CHECK_FAILED
    from shaftfem.outputs.tables import strength_text
    from shaftfem.workflows.strength import run_strength

    result = run_strength(_scene(args), _options(args))
    print(strength_text(result))
    if args.out:
        from shaftfem.outputs.export import write_strength_files
        from shaftfem.outputs.plots import hot_spots_figure, save_png
        from shaftfem.store import staged_directory

        with staged_directory(args.out, "strength.manifest.json") as stage:
            names = [p.name for p in write_strength_files(result, stage)]
            names.append(save_png(hot_spots_figure(result), stage / "hot_spots.png").name)
        print(f"wrote {', '.join(names)} in {args.out}")
    if args.json:
        _write_json(args.json, {"scene": result.scene.name, **result.as_dict()})
    return 0 if result.ok else EXIT_CHECK_FAILED


def cmd_check(args) -> int:
    from shaftfem.checks.resonance import check_result
    from shaftfem.outputs.tables import verdict_text

    scene = _scene(args)
    if scene.rotor is not None:
        from shaftfem.outputs.tables import campbell_text, cases_text
        from shaftfem.workflows.cases import combined, run_cases

        results = run_cases(scene, _margin(args), _options(args))
        nominal, turning = results[0], combined(results)
        print(campbell_text(nominal.campbell) + "\n")
        if len(results) > 1:
            print(cases_text(results) + "\n")
        print(verdict_text(turning))
        strength = _strength_of(scene, args)
        if args.json:
            _write_json(args.json, {"scene": scene.name, **turning.as_dict(),
                                    "campbell": nominal.campbell.as_dict(),
                                    "cases": [{"case": r.case.name, "ok": r.verdict.ok,
                                               **({} if r is nominal else
                                                  {"campbell": r.campbell.as_dict()})}
                                              for r in results], **strength[1]})
        return _with_strength(turning.exit_status, strength[0])
    result, _, adapted = _bounded(args)
    verdict = check_result(result, _margin(args))
    if verdict is None:
        raise SceneError(f"{result.scene.source}: no [[excitation]] sources to check against")
    print(verdict_text(verdict))
    strength = _strength_of(scene, args)
    if args.json:
        _write_json(args.json, {"scene": result.scene.name, **verdict.as_dict(), **strength[1]})
    return _with_strength(verdict.exit_status or _accuracy_status(args, adapted), strength[0])


def _strength_of(scene, args) -> tuple[bool | None, dict]:
    """A scene with [strength]: its strength printed after the resonance verdict, whether
    it passed and its JSON; else (None, {})."""
    if scene.strength is None:
        return None, {}
    from shaftfem.outputs.tables import strength_text
    from shaftfem.workflows.strength import run_strength

    result = run_strength(scene, _options(args))
    print("\n" + strength_text(result))
    return result.ok, {"strength": result.as_dict()}


def _with_strength(status: int, passed: bool | None) -> int:
    """The check's exit status with the strength's: a failed strength check fails it (1)
    whatever the resonance check said (a free-free pass, 4, included)."""
    from shaftfem.errors import EXIT_CHECK_FAILED

    if passed is False and status in (0, 4):
        return EXIT_CHECK_FAILED
    return status


def cmd_export(args) -> int:
    from shaftfem.outputs.calculix import write_calculix
    from shaftfem.outputs.export import export_modes

    result, est, adapted = _bounded(args)  # an adapted mesh's bounds go into the tables
    if args.format == "calculix":
        deck = write_calculix(result, Path(args.out) / "shaft.inp")
        print(f"wrote {deck} (run: cd {deck.parent} && ccx -i shaft; frequencies in "
              "shaft.dat, full precision in shaft.eig)")
        return _accuracy_status(args, adapted)
    files = export_modes(result, args.out, est)
    print(f"wrote {len(files)} files to {args.out}: " + ", ".join(f.name for f in files))
    return _accuracy_status(args, adapted)


def cmd_render(args) -> int:
    from shaftfem.outputs.render import render_all

    result, _, adapted = _bounded(args)
    files = render_all(result, args.out, _options(args).say)
    if result.scene.rotor is not None:
        from shaftfem.workflows.campbell import run_campbell
        from shaftfem.workflows.design import campbell_pictures

        files += campbell_pictures(run_campbell(result.scene, _options(args)), Path(args.out))
    print(f"wrote {len(files)} pictures to {args.out}: " + ", ".join(f.name for f in files))
    return _accuracy_status(args, adapted)


def cmd_design(args) -> int:
    from shaftfem.outputs.tables import modes_text, sizing_text, verdict_line, verdict_text
    from shaftfem.workflows.design import run_design

    scene = _scene(args)
    d = run_design(scene, design_out(args, scene.name), margin=_margin(args),
                   estimate=not args.no_estimate, options=_options(args), html=not args.no_html,
                   choose=_chooses(args))
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
    if d.strength is not None:
        from shaftfem.outputs.tables import strength_text

        print("\n" + strength_text(d.strength))
    print(f"\nreport: {d.report}" + ("" if args.no_html else
                                       f" and {d.report.with_suffix('.html')}"))
    status = d.verdict.exit_status if d.verdict is not None else 0
    return _with_strength(status or _accuracy_status(args, d.adapted),
                          None if d.strength is None else d.strength.ok)


def cmd_study(args) -> int:
    from shaftfem.outputs.plots import save_png, study_figure
    from shaftfem.scene.load import load_scene
    from shaftfem.store import write_csv, write_text
    from shaftfem.workflows.study import run_study, study_markdown, summarize_study

    scene = load_scene(args.scene)
    ladders = {k: v for k, v in {2: args.p2, 1: args.p1}.items() if v}
    runs = run_study(scene, ladders, _options(args))
    study = summarize_study(runs, singular=scene.grooves is not None)
    out = Path(args.out)
    md = study_markdown(study)
    files = [write_csv(out / "study.csv", study.rows), write_text(out / "study.md", md),
             save_png(study_figure(study.rows), out / "study.png", dpi=120)]
    print(md)
    print("wrote " + ", ".join(map(str, files)))
    return 0


def cmd_paper(args) -> int:
    from shaftfem.checks.sizing import size_from_scene
    from shaftfem.outputs.tables import paper_text

    result, _, adapted = _bounded(args)
    sizing = size_from_scene(result.scene) if result.scene.sizing else None
    print(paper_text(result, sizing))
    return _accuracy_status(args, adapted)


def design_out(args, scene_name: str) -> Path:
    """design's output folder: --out, else out/ and the scene's name."""
    return Path(args.out or Path("out") / scene_name)


def dask_out(args) -> Path:
    """A sweep's or calibration's output folder: --out, else out/ and its file's name."""
    file = args.sweep if args.func is cmd_sweep else args.calibration
    return Path(args.out or Path("out") / Path(file).stem)


def cmd_sweep(args) -> int:
    from shaftfem.outputs.plots import sweep_plots
    from shaftfem.workflows.sweep import run_sweep
    from shaftfem.workflows.sweep_file import load_sweep

    sweep = load_sweep(args.sweep)
    out = dask_out(args)
    rows = run_sweep(sweep, out / "results.csv", workers=args.workers,
                     scheduler=args.scheduler, estimate=args.estimate, options=_options(args))
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


def cmd_calibrate(args) -> int:
    from shaftfem.workflows.calibrate import calibrate, calibration_text, load_calibration

    cal = load_calibration(args.calibration)
    out = dask_out(args)
    res = calibrate(cal, out, workers=args.workers, scheduler=args.scheduler,
                    options=_options(args))
    print(calibration_text(res, cal))
    _write_json(str(out / "calibration.json"), res.as_dict(cal))
    return 0


def cmd_size(args) -> int:
    from shaftfem.checks.sizing import size_from_scene
    from shaftfem.outputs.tables import sizing_text
    from shaftfem.scene.load import load_scene

    result = size_from_scene(load_scene(args.scene))
    print(sizing_text(result))
    if args.json:
        _write_json(args.json, result.as_dict())
    return 0 if result.ok else 1
