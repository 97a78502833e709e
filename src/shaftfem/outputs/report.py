"""The design report: one Markdown file with the tables, the pictures and a verdict."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from shaftfem.outputs import tables
from shaftfem.store import write_text

if TYPE_CHECKING:
    from shaftfem.checks.resonance import ResonanceVerdict
    from shaftfem.checks.sizing import SizingResult
    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.fem.hanging import HangingModes
    from shaftfem.fem.modes import Modes
    from shaftfem.fem.response import Participation
    from shaftfem.fem.result import ModalResult
    from shaftfem.fem.whirl import Campbell, Level1, RunUp, UcsMap


@dataclass(frozen=True)
class RotorStudy:
    """A turning shaft's study for the report: its Campbell run and verdict, the
    critical speed map and Level I (None where not made), and what `shaftfem campbell`
    prints."""

    campbell: Campbell
    verdict: ResonanceVerdict
    ucs: UcsMap | None
    level1: Level1 | None
    text: str
    runup: RunUp | None = None
    cases: list | None = None   # the study's cases side by side (workflows.cases), if several
    unscreened: str | None = None   # why Level I was left out, where it was


STUDY_NOTE = ("The verdict at the top (and the exit status) takes the scene's flat "
              "separation margin unless [resonance] criterion = \"api684\"; this summary "
              "judges every item as API 684 (and API 617's Level I) do.")
# what a Markdown image link can show
IMAGES = (".png", ".jpg", ".jpeg", ".gif", ".svg", ".webp")

def title_rows(scene, wall_seconds: float | None = None) -> tuple[list[str], list[list[str]]]:
    """The report's title block: the scene's machine, job, revision, date and engineer
    (where it gives them), what it describes, its file, and when and by what it was
    made."""
    import datetime

    from shaftfem import __version__

    rows = [[k, v] for k, v in scene.title_block]
    if scene.description:
        rows.append(["description", scene.description])
    rows.append(["scene file", str(scene.source)])
    made = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    rows.append(["made", f"{made} by shaftfem {__version__}"
                 + (f" in {wall_seconds:.1f} s" if wall_seconds is not None else "")])
    return ["title block", ""], rows


def study_cases(study: RotorStudy) -> list[tuple[str, Campbell]]:
    """The study's cases as (name, Campbell run) pairs: the nominal one alone where the
    study has no others."""
    if study.cases:
        return [(r.case.name, r.campbell) for r in study.cases]
    return [("nominal", study.campbell)]


CASES_NOTE = ("Each case is solved and judged as the nominal one; the verdict takes the "
              "worst. The summary above gives each case as itself; the pictures and "
              "tables below are the nominal case's, and each other case's follow them "
              "under its name. Minimum clearance goes with cold oil (the stiffest films), "
              "maximum clearance with hot oil (the softest); a part whose joint the scene "
              "does not give is run on both joints.")
# a case's own pictures, in the order its part of the section shows them
CASE_PICTURES = (("campbell", "Campbell diagram"), ("critical_shapes", "Deflected shapes at "
                                                    "the critical speeds"),
                 ("bode", "Unbalance response"), ("weight_2x", "The weight's 2x whirl"))


def case_suffix(name: str) -> str:
    """What follows a file's stem for a case's own files: '_' and its name in lower-case
    words joined by '-' ("max clearance, hot oil" -> "_max-clearance-hot-oil")."""
    return "_" + "-".join("".join(ch if ch.isalnum() else " " for ch in name.lower()).split())


def case_sections(study: RotorStudy, pictures: Sequence[Path]
                  ) -> list[tuple[str, list[tuple[str, Path]], str]]:
    """Each case but the nominal one: its name, its pictures among `pictures` with their
    headings, and its whirl, critical speed and stability text."""
    from shaftfem.outputs.tables import campbell_text

    by_name = {Path(p).name: Path(p) for p in pictures}
    out = []
    for r in (study.cases or [])[1:]:
        tail = case_suffix(r.case.name)
        shown = [(title, by_name[f"{stem}{tail}.png"]) for stem, title in CASE_PICTURES
                 if f"{stem}{tail}.png" in by_name]
        out.append((r.case.name, shown, campbell_text(r.campbell)))
    return out


def shown_in_study(study: RotorStudy, pictures: Sequence[Path]) -> set[str]:
    """The names of the pictures the rotordynamic section shows."""
    return ({name for name, _ in STUDY_PICTURES}
            | {p.name for _, shown, _ in case_sections(study, pictures) for _, p in shown})
# the study's pictures that are the nominal case's where there are others
NOMINAL_PICTURES = ("campbell.png", "critical_shapes.png", "bode.png", "weight_2x.png",
                    "level1.png", "runup.png")
# the study's pictures, in the order the section shows them, with their headings
STUDY_PICTURES = (("bearings.png", "Bearing and seal coefficients against speed"),
                  ("pads.png", "Tilting pads' coefficients against the whirl's frequency"),
                  ("campbell.png", "Campbell diagram"), ("ucs.png", "Critical speed map"),
                  ("critical_shapes.png", "Deflected shapes at the critical speeds"),
                  ("bode.png", "Unbalance response"),
                  ("weight_2x.png", "The weight's 2x whirl"), ("level1.png", "Level I screening"),
                  ("runup.png", "Run-up"))


def rotordynamics_markdown(study: RotorStudy, pictures: Sequence[Path]) -> list[str]:
    """The report's rotordynamic section: the API 684 summary, then each picture with
    its heading, then the whirl and critical speed tables."""
    names = {Path(p).name for p in pictures}
    lines = ["## Rotordynamics (API 684)", "", "### Summary against API 684", ""]
    head, rows = tables.api684_rows(study)
    lines += tables.markdown(head, rows) + ["", STUDY_NOTE, ""]
    if study.cases:
        lines += ["### The study's cases", "", CASES_NOTE, ""]
        lines += tables.markdown(*tables.cases_rows(study.cases)) + [""]
    nominal = " (nominal case)" if study.cases else ""
    for name, title in STUDY_PICTURES:
        if name in names:
            lines += [f"### {title}{nominal if name in NOMINAL_PICTURES else ''}", "",
                      f"![{title}]({name})", ""]
            if name == "bearings.png":
                lines += tables.markdown(*tables.bearing_rows(study_cases(study))) + [""]
            if name == "pads.png":
                lines += tables.markdown(*tables.pad_rows(study_cases(study)[0][1])) + [""]
            if name == "level1.png" and study.level1 is not None:
                lines += ["```text", tables.level1_text(study.level1), "```", ""]
            if name == "ucs.png" and study.ucs is not None:
                lines += ["```text", tables.ucs_text(study.ucs), "```", ""]
            if name == "runup.png" and study.runup is not None:
                lines += ["```text", tables.runup_text(study.runup), "```", ""]
    lines += [f"### Whirl, critical speeds and stability{nominal}", "", "```text", study.text,
              "```"]
    for case, shown, text in case_sections(study, pictures):
        lines += ["", f"### Case: {case}", ""]
        for title, path in shown:
            lines += [f"#### {title} ({case})", "", f"![{title}, {case}]({path.name})", ""]
        lines += ["```text", text, "```"]
    return lines


def report_markdown(result: ModalResult, verdict: ResonanceVerdict | None,
                    sizing: SizingResult | None = None, pictures: Sequence[Path] = (),
                    files: Sequence[Path] = (), estimate: ErrorEstimate | None = None,
                    free: Modes | HangingModes | None = None,
                    participation: Participation | None = None,
                    rotor: RotorStudy | None = None, wall_seconds: float | None = None,
                    strength=None) -> str:
    """report.md's text; `strength`: the shaft under its duty (workflows.strength);
    picture and file names are relative to the report's folder;
    `rotor`: the rotordynamic study, for a shaft with [rotor]; `free`: the same shaft's
    modes hanging free; `wall_seconds`: the whole run's time until the report (s)."""
    scene = result.scene
    lines = [f"# Modal design report: {scene.name}", ""]
    head, rows = title_rows(scene, wall_seconds)
    lines += tables.markdown(head, rows) + [""]
    lines += [x for line in tables.verdict_lines(verdict) for x in (line, "")]
    if strength is not None:
        lines += [f"**STRENGTH: {'PASS' if strength.ok else 'FAIL'}** - "
                  f"{tables.strength_verdict(strength, short=True)} (section Strength below)", ""]
    lines += ["## Shaft", ""] + [f"- {line}" for line in shaft_facts(result)] + [""]
    if sizing is not None:
        lines += ["## Sizing (paper equations 1-9)", ""] + tables.sizing_markdown(sizing) + [""]
    if scene.supports or scene.attachments:
        lines += ["## Installation", ""] + [f"- {l}" for l in tables.installation_lines(result)]
        lines.append("")
    title = "installed" if scene.held else "free-free"
    lines += [f"## Natural frequencies ({title})", ""] + tables.modes_markdown(result, estimate)
    lines += ["", f"Rigid-body modes: {result.modes.n_rigid}."]
    if estimate is not None:
        lines += tables.estimate_notes(estimate, scene)
    if free is not None:
        lines += ["", "### Installed beside free-free (same mesh)", ""]
        lines += tables.side_by_side_markdown(result, free)
    if participation is not None:
        lines += ["", "### Effective modal mass for base motion at the supports", ""]
        lines += tables.participation_markdown(result, participation)
    if rotor is not None:
        lines += ["", *rotordynamics_markdown(rotor, pictures)]
        shown = shown_in_study(rotor, pictures)
        pictures = [p for p in pictures if Path(p).name not in shown]
    lines += ["", "## Resonance check", ""]
    lines += (tables.verdict_markdown(verdict) if verdict is not None
              else ["No [[excitation]] sources in the scene: nothing to check against."])
    lines.append("")
    if strength is not None:
        lines += ["## Strength under the duty (FKM, local stresses)", ""]
        lines += tables.strength_markdown(strength) + [""]
        if any(Path(p).name == "hot_spots.png" for p in pictures):
            lines += ["![hot spots](hot_spots.png)", ""]
            pictures = [p for p in pictures if Path(p).name != "hot_spots.png"]
    if pictures:
        # an image link for a picture, a plain link for anything else (campbell.csv)
        lines += ["## Pictures", ""] + [
            f"![{Path(p).stem}]({Path(p).name})" if Path(p).suffix.lower() in IMAGES
            else f"- [{Path(p).name}]({Path(p).name})" for p in pictures]
        lines.append("")
    if files:
        lines += ["## Files", ""] + [f"- `{Path(f).name}`" for f in files] + [""]
    lines += ["## Run time", "", tables.run_time_text(result, estimate, wall_seconds), ""]
    return "\n".join(lines)


def shaft_facts(result: ModalResult) -> list[str]:
    """What the shaft is and how it was meshed, a line each."""
    scene, m = result.scene, result.modes
    mat, g = scene.material, scene.grooves
    lines = [f"{scene.shaft.length * 1e3:g} mm long, {scene.shaft.diameter * 1e3:g} mm "
             f"largest diameter, {mat.name} (E = {mat.youngs_modulus / 1e6:g} MPa, "
             f"nu = {mat.poisson_ratio:g}, rho = {mat.density:g} kg/m^3)"]
    lines += tables.shape_lines(scene.shaft)
    if g:
        hands = " and ".join("right" if h > 0 else "left" for h in g.hands)
        lines.append(f"grooves: {hands}-hand, pitch {g.pitch * 1e3:g} mm, width "
                     f"{g.width * 1e3:g} mm (axial), depth {g.depth * 1e3:g} mm, root radius "
                     f"{g.root_radius * 1e3:g} mm, over {g.length * 1e3:g} mm from "
                     f"{g.start * 1e3:g} mm"
                     f"{f', running out over {g.runout * 1e3:g} mm beyond' if g.runout else ''}"
                     "; removed volume"
                     f"{' (grooves and keyways)' if scene.shaft.keyways else ''} "
                     f"{result.shape.groove_volume_cad * 1e9:.1f} mm^3 (analytic "
                     f"{result.shape.groove_volume_analytic * 1e9:.1f} mm^3)")
    lines.append(f"mesh: P{scene.mesh.order}, {m.n_dofs} DOFs, {result.mesh.n_elements} "
                 "elements")
    return lines


def write_report(path: str | Path, result: ModalResult, verdict: ResonanceVerdict | None,
                 sizing: SizingResult | None = None, pictures: Sequence[Path] = (),
                 files: Sequence[Path] = (), estimate: ErrorEstimate | None = None,
                 free: Modes | HangingModes | None = None,
                 participation: Participation | None = None,
                 rotor: RotorStudy | None = None, wall_seconds: float | None = None,
                 strength=None) -> Path:
    return write_text(path, report_markdown(result, verdict, sizing, pictures, files, estimate,
                                            free, participation, rotor, wall_seconds, strength))
