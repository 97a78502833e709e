"""The design workflow: sizing, modes with error estimates, the resonance verdict,
files, pictures and a report, in one call.

    from shaftfem import load_scene, run_design
    d = run_design(load_scene("paper2018"), "out/paper2018")
    d.ok, d.report

A scene without [[excitation]] sources gets everything but the verdict (the
report says there was nothing to check against); a scene without [sizing]
skips the sizing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from shaftfem.errors import SceneError
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene

MANIFEST = "design.manifest.json"   # lists every file of the last complete design run
# what the pictures' process needs, imported before the modes come
PICTURE_MODULES = ("numpy", "scipy.sparse", "skfem", "pyvista", "PIL.Image", "meshio",
                   "shaftfem.fem.result", "shaftfem.outputs.render", "shaftfem.outputs.export")

if TYPE_CHECKING:
    from shaftfem.aside import Aside
    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.cad.solid import ShaftShape
    from shaftfem.checks.resonance import ResonanceVerdict
    from shaftfem.checks.sizing import SizingResult
    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.fem.hanging import HangingModes
    from shaftfem.fem.modes import Modes
    from shaftfem.fem.response import Participation
    from shaftfem.fem.result import ModalResult
    from shaftfem.workflows.adapt import Adapted
    from shaftfem.workflows.strength import StrengthResult


@dataclass(frozen=True)
class DesignResult:
    """A design run: the sizing (None without a [sizing] table), the modal result and
    its bounds, the resonance verdict (None without excitations), the files and pictures
    written, the report's path, and for an installed shaft the effective masses. `ok`
    is False when a mode is too close to an excitation harmonic."""

    sizing: SizingResult | None
    result: ModalResult
    estimate: ErrorEstimate | None
    verdict: ResonanceVerdict | None   # None: the scene has no excitations
    files: list[Path]
    pictures: list[Path]
    report: Path
    adapted: Adapted | None = None   # how the mesh was adapted, when it was
    participation: Participation | None = None   # installed shafts: effective masses
    strength: StrengthResult | None = None   # a scene with [strength]: under its duty

    @property
    def ok(self) -> bool:
        """No mode too close to an excitation harmonic (also when there was none), and the
        strength checks passed where the scene has them."""
        return ((self.verdict is None or self.verdict.ok)
                and (self.strength is None or self.strength.ok))


def run_design(scene: Scene, out: str | Path, margin: float | None = None,
               estimate: bool = True, options: RunOptions = RunOptions(),
               html: bool = True, choose: bool = False) -> DesignResult:
    """Everything a designer signs off: sizing, modes with bounds, resonance verdict,
    files, pictures, report.md and (unless `html` is False) report.html, published
    together into the folder `out`. `margin`: required separation (fraction), default
    the scene's; `choose`: as run_bounded's."""
    import time

    from shaftfem.store import staged_directory

    started = time.perf_counter()
    out = Path(out)
    # every file of the run is published at once, under design.manifest.json; work that
    # the study does not wait on (the modes' pictures, a rotor's mode shapes, the free
    # shaft's modes, the critical speed map) is done beside it, on the other core, the
    # files into the same staged folder
    with staged_directory(out, MANIFEST) as stage:
        run = _Run(scene, stage, options)
        try:
            return run.design(out, margin, estimate, html, choose, started)
        finally:
            run.close()


class _Run:
    """One design run and the work it has put aside (aside.Aside), stopped with it."""

    def __init__(self, scene: Scene, stage: Path, options: RunOptions) -> None:
        self.scene, self.stage, self.options = scene, stage, options
        self.map: Aside | None = None
        self.pictures: Aside | None = None
        self.free: Aside | None = None
        self.charts: Aside | None = None
        self.hanging: HangingModes | None = None

    def free_beside(self, options: RunOptions) -> None:
        """The same shaft hanging free, solved beside the run on the scene's own mesh
        (which does not hang on the modes)."""
        from shaftfem.aside import Aside

        self.options.say("the same shaft hanging free, on the same mesh, for comparison, "
                         "beside the run")
        self.free = Aside(_free_modes, self.scene, options)

    def close(self) -> None:
        for job in (self.map, self.pictures, self.free, self.charts):
            if job is not None:
                job.close()

    def design(self, out: Path, margin, estimate, html, choose, started) -> DesignResult:
        import time

        from shaftfem.aside import Aside
        from shaftfem.checks.resonance import check_result
        from shaftfem.checks.sizing import size_from_scene
        from shaftfem.fem.hanging import hanging_modes, held_by_bearings_alone
        from shaftfem.outputs.export import (
            listed,
            write_mode_tables,
            write_shape_files,
            write_solid_files,
        )
        from shaftfem.outputs.report import write_report
        from shaftfem.workflows.bounded import run_bounded

        scene, stage, options = self.scene, self.stage, self.options
        say = options.say
        quiet = replace(options, progress=None)   # for the work aside
        sizing = None
        if scene.sizing is not None:
            say("sizing (equations 1-9)")
            sizing = size_from_scene(scene)
        # the pictures' process loads its libraries while the modes are solved
        self.pictures = Aside.waiting(*PICTURE_MODULES)
        compare = bool(scene.held) and scene.target_error is None
        # a rotor in bearings alone hangs free on its own basis (fem.hanging), known once
        # the basis is; another shaft's free modes are solved beside the run from the start
        hanging = compare and scene.rotor is not None and held_by_bearings_alone(scene)
        if compare and not hanging:
            self.free_beside(quiet)
        if scene.rotor is not None:
            from shaftfem.workflows.campbell import turning
            from shaftfem.workflows.static import equipped

            # the map needs the journals' loads and the mesh, not the whirl's basis: it is
            # solved beside the basis (which leaves the other core half idle), not beside
            # the study's line after it, which keeps both busy
            loaded = equipped(scene, options)
            say("the rotordynamic study: the critical speed map, beside the run")
            self.map = Aside(_map, loaded, quiet)
            # the whirl's basis (kept in the process for the study): the design's modes,
            # fewer, of the same pencil are then refined from its solve
            say("the shaft turning: its standstill basis")
            standstill, model, _ = turning(loaded, options)
            if hanging:
                self.hanging = hanging_modes(standstill, model, scene.modes.count)
                if self.hanging is not None:
                    say("the same shaft hanging free: on the rotor's basis, its bearings "
                        "taken out")
                else:
                    self.free_beside(quiet)

        # a rotor's study leaves the other core idle long enough for its mode shapes too;
        # a standing shaft's bound does not (the paper's cold design: 11 s after its
        # modal run with the shapes written here, 15 s with them aside)
        turns = scene.rotor is not None

        def solved(result: ModalResult) -> None:
            say("mode shapes, mesh and pictures, beside the run")
            assert self.pictures is not None
            self.pictures.start(_shapes_and_pictures, result, stage, turns)

        bounded = run_bounded(scene, estimate, options, choose, solved)
        result, est = bounded.result, bounded.estimate
        verdict = check_result(result, margin)
        campbell, study = None, None
        if scene.rotor is not None:
            from shaftfem.outputs.report import RotorStudy
            from shaftfem.outputs.tables import campbell_text
            from shaftfem.workflows.cases import combined, run_cases
            from shaftfem.workflows.level1 import level1_too_slow, run_level1

            say("the shaft turning: whirl, Campbell diagram, critical speeds")
            cases = run_cases(scene, margin, options)   # the nominal one first
            campbell, verdict = cases[0].campbell, combined(cases)
            # its charts and whirl files are drawn beside Level I and the run-up
            self.charts = Aside(_campbell_files, campbell, stage)
            level1, unscreened = cases[0].level1, None
            if level1 is None:
                unscreened = level1_too_slow(model, scene.rotor.top_speed)
                if unscreened is None:
                    say("the rotordynamic study: Level I")
                    level1 = _or_none(run_level1, scene, options)
                else:
                    say(f"the rotordynamic study: Level I not screened: {unscreened}")
            runup = None
            if scene.rotor.runup is not None and scene.unbalances:
                from shaftfem.workflows.runup import run_run_up

                say("the rotordynamic study: the run-up")
                top = scene.rotor.max_speed * 30 / math.pi
                runup = run_run_up(scene, 0.0, top, scene.rotor.runup * 30 / math.pi, options)
            assert self.map is not None
            ucs = self.map.result()
            study = RotorStudy(campbell, verdict, ucs, level1, campbell_text(campbell), runup,
                               cases if len(cases) > 1 else None, unscreened)
        free: Modes | HangingModes | None = None
        part, response, basis = None, None, None
        if scene.held:
            from shaftfem.fem.response import modal_basis, participation, response_sweep

            if self.hanging is not None:
                free = self.hanging
            elif self.free is not None:
                free = self.free.result()
            else:   # an adapted mesh: known only now
                say("the same shaft hanging free, on the same mesh, for comparison")
                free = _free_modes(scene, options, result.shape, result.mesh)
            basis = modal_basis(result)
            part = participation(basis)
            if base_motion_drawn(scene):
                response = response_sweep(result, "x", basis=basis)
        assert self.pictures is not None
        shapes, pictures = (self.pictures.result() if turns
                            else (write_shape_files(result, stage), None))
        say("the mode table and the solid (shaft.step)")
        tables, solid = write_mode_tables(result, stage, est), write_solid_files(result, stage)
        more = []
        if response is not None:
            more.append(_response_picture(result, response, basis, stage / "response.png"))
        whirl_files = []
        if campbell is not None:
            assert self.charts is not None
            charts = study_pictures(study, stage)
            drawn, whirl_files = self.charts.result()
            more += drawn + charts
        if pictures is None:
            pictures = self.pictures.result()[1]
        assert pictures is not None
        for p in pictures:
            say(f"picture {p.name}")
        files = listed(shapes, tables, solid) + whirl_files
        strength = None
        if scene.strength is not None:
            from shaftfem.outputs.export import write_strength_files
            from shaftfem.outputs.plots import hot_spots_figure, save_png
            from shaftfem.workflows.strength import run_strength

            say("strength under the duty: hot spots, FKM, seat slopes")
            strength = run_strength(scene, options)
            more.append(save_png(hot_spots_figure(strength), stage / "hot_spots.png"))
            files += write_strength_files(strength, stage)
        pictures = pictures + more
        wall = time.perf_counter() - started
        write_report(stage / "report.md", result, verdict, sizing, pictures, files, est,
                     free=free, participation=part, rotor=study, wall_seconds=wall,
                     strength=strength)
        if html:
            from shaftfem.outputs.report_html import write_report_html

            say("report.html: the report with a 3D view of every mode")
            write_report_html(stage / "report.html", result, verdict, sizing, pictures, est,
                              free=free, participation=part, rotor=study,
                              wall_seconds=wall, strength=strength)
        files, pictures = [out / p.name for p in files], [out / p.name for p in pictures]
        report = out / "report.md"
        say(f"report written: {report}")
        return DesignResult(sizing=sizing, result=result, estimate=est, verdict=verdict,
                            files=files, pictures=pictures, report=report,
                            adapted=bounded.adapted, participation=part, strength=strength)


def _shapes_and_pictures(result: ModalResult, folder: Path,
                         shapes: bool) -> tuple[list[Path], list[Path]]:
    """The pictures of the modes, after (when `shapes`) the mode shapes for ParaView and
    the mesh."""
    from shaftfem.outputs.export import write_shape_files
    from shaftfem.outputs.render import render_into

    return write_shape_files(result, folder) if shapes else [], render_into(result, folder)


def _campbell_files(c, folder: Path) -> tuple[list[Path], list[Path]]:
    """The Campbell diagram's pictures (campbell_pictures) and its whirl files for
    ParaView, in `folder`."""
    from shaftfem.outputs.whirl_files import write_whirl_files

    return campbell_pictures(c, folder), write_whirl_files(c, folder)


def _free_modes(scene: Scene, options: RunOptions, shape: ShaftShape | None = None,
                mesh: ShaftMesh | None = None) -> Modes:
    """The modes of the shaft hanging free, on the installed shaft's mesh (`shape` and
    `mesh`; else the scene's own, from the cache where the run has built them)."""
    from shaftfem.workflows.pipeline import built, solve_mesh

    if shape is None or mesh is None:
        _, shape, mesh = built(scene, options)
    return solve_mesh(scene.free(), shape, mesh, options).modes


def _map(scene: Scene, options: RunOptions):
    """The critical speed map of the study, None where the scene allows none."""
    from shaftfem.workflows.ucs import run_ucs

    return _or_none(run_ucs, scene, options)


def _or_none(run, scene: Scene, options: RunOptions):
    """`run(scene, options=options)`, None where the scene does not allow it (no
    bearings to vary, no forward mode)."""
    try:
        return run(scene, options=options)
    except SceneError:
        return None


def base_motion_drawn(scene: Scene) -> bool:
    """Whether design draws the response to base motion (response.png): for a shaft in
    supports that does not turn. A turning shaft's response is its unbalance response
    (bode.png), damped by its own bearings; the base-motion sweep rests on [damping]'s
    modal ratio instead, which would contradict the rotor's log decrements."""
    return bool(scene.held) and scene.rotor is None


def write_campbell_csv(c, path: Path) -> Path:
    """campbell.csv: each curve at each of its speeds (speed r/min, curve, frequency Hz,
    whirl, whirl index, log dec, kind)."""
    import csv
    import io

    from shaftfem.store import write_text

    buf = io.StringIO()
    names = ["speed_rpm", "curve", "frequency_hz", "whirl", "whirl_index", "log_dec", "kind"]
    w = csv.DictWriter(buf, fieldnames=names, lineterminator="\n")
    w.writeheader()
    for row in c.csv_rows():
        w.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in row.items()})
    return write_text(path, buf.getvalue())


def study_pictures(study, folder: Path) -> list[Path]:
    """bearings.png (the coefficients against speed of each case), ucs.png, level1.png
    and runup.png of the rotordynamic study, where it has them; each case's but the
    nominal one's Campbell diagram, critical speeds' shapes, unbalance response (and
    weight's 2x whirl), its name after each file's stem."""
    from shaftfem.outputs.plots import level1_figure, save_png
    from shaftfem.outputs.report import case_suffix
    from shaftfem.outputs.ucs_plot import ucs_figure

    out = []
    for r in (study.cases or [])[1:] if study is not None else []:
        out += campbell_pictures(r.campbell, folder, case_suffix(r.case.name), orbits=False,
                                 case=r.case.name)
    if study is not None:
        from shaftfem.outputs.plots import bearings_figure
        from shaftfem.outputs.report import study_cases

        fig = bearings_figure(study_cases(study))
        if fig is not None:
            out.append(save_png(fig, folder / "bearings.png", dpi=110))
        from shaftfem.outputs.plots import pads_figure

        fig = pads_figure(study_cases(study)[0][1])
        if fig is not None:
            out.append(save_png(fig, folder / "pads.png", dpi=110))
    if study is not None and study.ucs is not None:
        out.append(save_png(ucs_figure(study.ucs), folder / "ucs.png", dpi=130))
    if study is not None and study.level1 is not None:
        out.append(save_png(level1_figure(study.level1), folder / "level1.png", dpi=130))
    if study is not None and study.runup is not None:
        from shaftfem.outputs.plots import runup_figure

        out.append(save_png(runup_figure(study.runup), folder / "runup.png", dpi=130))
    return out


def _titled(fig, case: str):
    """The figure with `case` named in its title (its suptitle, else its first axes')."""
    if not case:
        return fig
    title = fig._suptitle
    if title is not None:
        title.set_text(f"{title.get_text()}, case: {case}")
    elif fig.axes:
        fig.axes[0].set_title(f"{fig.axes[0].get_title()}, case: {case}")
    return fig


def campbell_pictures(c, folder: Path, suffix: str = "", orbits: bool = True,
                      case: str = "") -> list[Path]:
    """campbell.png, campbell.csv, critical_shapes.png (the deflected shape at each 1x
    critical speed), bode.png when the scene has unbalances, weight_2x.png when the
    shaft's weight drives a 2x whirl (a shaft not of revolution), and orbits.png (the
    whirl at the first operating speed), in `folder`; `suffix` after each file's stem
    (a case's: outputs.report.case_suffix) and `case` named in each picture's title."""
    from shaftfem.outputs.campbell_plot import (
        bode_figure,
        campbell_figure,
        critical_shapes_figure,
        weight_figure,
    )
    from shaftfem.outputs.plots import save_png
    from shaftfem.outputs.whirl_files import orbits_figure

    def at(stem: str, ext: str = ".png") -> Path:
        return folder / f"{stem}{suffix}{ext}"

    out = [save_png(_titled(campbell_figure(c), case), at("campbell"), dpi=130),
           write_campbell_csv(c, at("campbell", ".csv")),
           save_png(_titled(critical_shapes_figure(c), case), at("critical_shapes"), dpi=130)]
    if c.unbalance is not None:
        out.append(save_png(_titled(bode_figure(c), case), at("bode"), dpi=130))
    if c.weight_2x:
        out.append(save_png(_titled(weight_figure(c), case), at("weight_2x"), dpi=130))
    if orbits:
        out.append(save_png(_titled(orbits_figure(c), case), at("orbits"), dpi=130))
    return out


def _response_picture(result: ModalResult, response, basis, path: Path) -> Path:
    """response.png: the transmissibility, with its value at every excitation harmonic."""
    import numpy as np

    from shaftfem.fem.response import base_response
    from shaftfem.outputs.plots import response_figure, save_png

    harmonics = [(f"{e.name} x{k}", k * e.frequency) for e in result.scene.excitations
                 for k in e.orders]
    hz = np.array([h for _, h in harmonics])
    at = (base_response(result, hz, response.direction, basis=basis).transmissibility
          if hz.size else np.zeros(0))
    marks = [(text, h, float(v)) for (text, h), v in zip(harmonics, at)]
    return save_png(response_figure(response, marks, f"{result.scene.name}: lateral base "
                                    "motion at the supports"), path)
