"""report.html: the design report as one self-contained page for people without
ParaView: the verdict, the tables, the pictures, and a 3D view of every mode that the
reader can turn, step through and animate.

It opens from a file with no server and no network: the pictures are inlined, and the
3D view is trame-vtk's vtk.js viewer (shaftfem.outputs.web_scene) with the modes'
scene inlined, stepped and animated by report_view.js.
"""

from __future__ import annotations

import base64
import html
import json
from collections.abc import Sequence
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
    from shaftfem.outputs.render import Drawing
    from shaftfem.outputs.report import RotorStudy

STYLE = """
body { font-family: system-ui, sans-serif; margin: 0 auto; max-width: 1100px; padding: 1em 2em;
       height: auto; color: #222; line-height: 1.45; }
h1 { font-size: 1.6em; } h2 { font-size: 1.25em; margin-top: 1.6em; }
pre { white-space: pre-wrap; overflow-wrap: anywhere; }
table { border-collapse: collapse; margin: 0.6em 0; font-variant-numeric: tabular-nums; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: right; }
th { background: #f2f4f7; } td.text, th.text { text-align: left; }
.verdict { font-size: 1.1em; padding: 0.6em 0.9em; border-radius: 4px; }
.pass { background: #e6f4ea; } .fail { background: #fce8e6; } .none { background: #f2f4f7; }
.caveat { background: #fff4e0; padding: 0.6em 0.9em; border-radius: 4px; }
#view3d { position: relative; width: 100%; height: 420px; border: 1px solid #ccc; }
.controls { margin: 0.5em 0; display: flex; gap: 0.5em; align-items: center; }
.controls button, .controls select { font-size: 1em; }
img { max-width: 100%; border: 1px solid #eee; }
.note { color: #555; font-size: 0.92em; }
"""


def _table(rows: tuple[list[str], list[list[str]]], text_columns: Sequence[str] = ()) -> str:
    head, body = rows
    left = {k for k, h in enumerate(head) if h in text_columns}
    out = ["<table><thead><tr>" + "".join(
        ('<th class="text">' if k in left else "<th>") + html.escape(h) + "</th>"
        for k, h in enumerate(head)) + "</tr></thead><tbody>"]
    for r in body:
        cells = [('<td class="text">' if k in left else "<td>") + html.escape(c) + "</td>"
                 for k, c in enumerate(r)]
        out.append("<tr>" + "".join(cells) + "</tr>")
    return "\n".join(out + ["</tbody></table>"])


def _paragraphs(lines: Sequence[str], cls: str = "note") -> str:
    return "\n".join(f'<p class="{cls}">{html.escape(line)}</p>' for line in lines)


def _picture(path: Path) -> str:
    data = base64.b64encode(Path(path).read_bytes()).decode()
    return (f'<figure><img alt="{html.escape(path.stem)}" src="data:image/png;base64,{data}">'
            f"<figcaption class=\"note\">{html.escape(path.name)}</figcaption></figure>")


def _rotordynamics(study: RotorStudy, pictures: Sequence[Path]) -> str:
    """The rotordynamic section: the API 684 summary, each picture under its heading,
    the whirl and critical speeds."""
    from shaftfem.outputs.report import (
        CASES_NOTE,
        NOMINAL_PICTURES,
        STUDY_NOTE,
        STUDY_PICTURES,
        case_sections,
        study_cases,
    )

    by_name = {Path(p).name: Path(p) for p in pictures}
    head, rows = tables.api684_rows(study)
    parts = ['<section id="rotordynamics"><h2>Rotordynamics (API 684)</h2>',
             "<h3>Summary against API 684</h3>", _table((head, rows), ("case", "item",
                                                                        "the rotor", "required",
                                                                        "result")),
             _paragraphs([STUDY_NOTE])]
    if study.cases:
        parts += ["<h3>The study's cases</h3>", _paragraphs([CASES_NOTE]),
                  _table(tables.cases_rows(study.cases), ("",))]
    nominal = " (nominal case)" if study.cases else ""
    for name, title in STUDY_PICTURES:
        if name in by_name:
            parts += [f"<h3>{html.escape(title)}"
                      f"{nominal if name in NOMINAL_PICTURES else ''}</h3>",
                      _picture(by_name[name])]
            if name == "bearings.png":
                parts.append(_table(tables.bearing_rows(study_cases(study)),
                                    ("case", "bearing")))
            if name == "pads.png":
                parts.append(_table(tables.pad_rows(study_cases(study)[0][1]), ("bearing",)))
            if name == "level1.png" and study.level1 is not None:
                parts.append(f"<pre>{html.escape(tables.level1_text(study.level1))}</pre>")
            if name == "ucs.png" and study.ucs is not None:
                parts.append(f"<pre>{html.escape(tables.ucs_text(study.ucs))}</pre>")
            if name == "runup.png" and study.runup is not None:
                parts.append(f"<pre>{html.escape(tables.runup_text(study.runup))}</pre>")
    parts += [f"<h3>Whirl, critical speeds and stability{nominal}</h3>",
              f"<pre>{html.escape(study.text)}</pre>"]
    for case, shown, text in case_sections(study, pictures):
        parts.append(f"<h3>Case: {html.escape(case)}</h3>")
        for title, path in shown:
            parts += [f"<h4>{html.escape(title)} ({html.escape(case)})</h4>", _picture(path)]
        parts.append(f"<pre>{html.escape(text)}</pre>")
    parts.append("</section>")
    return "\n".join(parts)


def _strength(result, pictures: Sequence[Path]) -> str:
    """The strength section: its verdict, the hot spots (their K_t beside the tables'),
    the picture that numbers them, the seats."""
    by_name = {Path(p).name: Path(p) for p in pictures}
    notched = tables.notch_factor_lines(result)
    parts = ['<section id="strength"><h2>Strength under the duty (FKM, local stresses)</h2>',
             f'<p class="verdict {"pass" if result.ok else "fail"}">'
             f"{html.escape(tables.strength_verdict(result))}</p>",
             _paragraphs([tables.strength_intro(result)]),
             _paragraphs(list(result.notes), "caveat"),
             _table(tables.strength_spot_rows(result), ("hot spot",))]
    if notched:
        parts += [_paragraphs(notched[:1]), "<ul>" + "".join(
            f"<li>{html.escape(r.strip())}</li>" for r in notched[1:]) + "</ul>"]
    if "hot_spots.png" in by_name:
        parts.append(_picture(by_name["hot_spots.png"]))
    parts += ["<h3>Slopes and deflections</h3>",
              _table(tables.strength_seat_rows(result), ("seat or part", "limit's source", "")),
              _paragraphs(["The stresses and FKM's utilisation on the whole surface: "
                           "strength.vtp (ParaView)."]), "</section>"]
    return "\n".join(parts)


def _verdict(verdict: ResonanceVerdict | None) -> str:
    lines = tables.verdict_lines(verdict)
    cls = "none" if verdict is None else "pass" if verdict.ok else "fail"
    out = f'<p class="verdict {cls}" id="verdict">{html.escape(lines[0].replace("**", ""))}</p>'
    return out + "".join(f'<p class="caveat">{html.escape(x)}</p>' for x in lines[1:])


def _view(result: ModalResult, drawing: Drawing | None = None) -> str:
    """The 3D view's controls and its container, the scene inlined as base64."""
    from shaftfem.outputs.web_scene import mode_scene

    m = result.modes
    names = [f"mode {k + 1}: {f:.2f} Hz, {kind}" for k, (f, kind)
             in enumerate(zip(m.frequencies, m.kinds))]
    zipped, framing = mode_scene(result, drawing)
    scene = base64.b64encode(zipped).decode()
    return f"""
<div class="controls">
  <button id="mode-previous" type="button">&larr; previous</button>
  <select id="mode-select" aria-label="mode"></select>
  <button id="mode-next" type="button">next &rarr;</button>
  <button id="mode-play" type="button">animate</button>
  <span id="mode-label"></span>
</div>
<div id="view3d" data-scene="{scene}"></div>
<p class="note">Drag to turn, scroll to zoom. Colour: displacement over the mode's largest
displacement (dark blue 0, yellow 1); grey: the shaft at rest; orange: bearings; blue: parts.
The motion is drawn large (a mode shape has no amplitude of its own).</p>
<script type="application/json" id="shaftfem-modes">{json.dumps(dict(modes=names, **framing))}</script>"""


def report_html(result: ModalResult, verdict: ResonanceVerdict | None,
                sizing: SizingResult | None = None, pictures: Sequence[Path] = (),
                estimate: ErrorEstimate | None = None, free: Modes | HangingModes | None = None,
                participation: Participation | None = None, rotor: RotorStudy | None = None,
                drawing: Drawing | None = None, wall_seconds: float | None = None,
                strength=None) -> str:
    """report.html's text: the vtk.js viewer page with the report around its view
    (`rotor`: the rotordynamic study, for a shaft with [rotor]; `drawing`: the modes'
    drawing the pictures were made from, where there is one; `strength`: the shaft under
    its duty, for a scene with [strength])."""
    from shaftfem.outputs.report import shaft_facts, shown_in_study, title_rows
    from shaftfem.outputs.web_scene import viewer_html

    scene = result.scene
    parts = [f"<h1>Modal design report: {html.escape(scene.name)}</h1>",
             _table(title_rows(scene, wall_seconds), ("title block", "")), _verdict(verdict),
             "" if strength is None else
             f'<p class="verdict {"pass" if strength.ok else "fail"}">STRENGTH: '
             f'{"PASS" if strength.ok else "FAIL"} - '
             f"{html.escape(tables.strength_verdict(strength, short=True))} "
             '(<a href="#strength">Strength</a> below)</p>',
             "<h2>Mode shapes</h2>", _view(result, drawing),
             "<h2>Shaft</h2><ul>" + "".join(f"<li>{html.escape(x)}</li>"
                                            for x in shaft_facts(result)) + "</ul>"]
    if sizing is not None:
        parts += ["<h2>Sizing (paper equations 1-9)</h2>",
                  _table(tables.sizing_rows(sizing), ("symbol", "unit", "quantity")),
                  _paragraphs([f"LIMIT BROKEN: {v}" for v in sizing.violations], "caveat")]
    if scene.supports or scene.attachments:
        parts += ["<h2>Installation</h2><ul>" + "".join(
            f"<li>{html.escape(x)}</li>" for x in tables.installation_lines(result)) + "</ul>"]
    title = "installed" if scene.held else "free-free"
    parts += [f"<h2>Natural frequencies ({title})</h2>",
              _table(tables.modes_rows(result, estimate), ("kind",)),
              _paragraphs([f"Rigid-body modes: {result.modes.n_rigid}."]
                          + (tables.estimate_notes(estimate, scene) if estimate is not None
                             else []))]
    if free is not None:
        parts += ["<h3>Installed beside free-free (same mesh)</h3>",
                  _table(tables.side_by_side_rows(result, free), ("kind",))]
    if participation is not None:
        parts += ["<h3>Effective modal mass for base motion at the supports</h3>",
                  _table(tables.participation_rows(result, participation))]
    if rotor is not None:
        parts.append(_rotordynamics(rotor, pictures))
        shown = shown_in_study(rotor, pictures)
        pictures = [p for p in pictures if Path(p).name not in shown]
    parts.append("<h2>Resonance check</h2>")
    parts.append(_table(tables.verdict_rows(verdict), ("source", "kind", "")) if verdict
                 is not None else _paragraphs(["No [[excitation]] sources in the scene: "
                                               "nothing to check against."]))
    if strength is not None:
        parts.append(_strength(strength, pictures))
        pictures = [p for p in pictures if Path(p).name != "hot_spots.png"]
    pngs = [p for p in pictures if Path(p).suffix == ".png"]
    if pngs:
        parts += ["<h2>Pictures</h2>"] + [_picture(Path(p)) for p in pngs]
    parts += ["<h2>Run time</h2>",
              _paragraphs([tables.run_time_text(result, estimate, wall_seconds)])]
    body = "\n".join(parts)
    script = (Path(__file__).with_name("report_view.js")).read_text(encoding="utf-8")
    # the viewer puts vtk.js's favicons from the web into the page's head: a page that
    # must open with no network asks for none
    page = viewer_html().replace(
        "https://kitware.github.io/vtk-js/icon/favicon-${t}x${t}.png", "data:,")
    page = page.replace("<title>VTK.js | Example - OfflineLocalView</title>",
                        f"<title>shaftfem: {html.escape(scene.name)}</title>", 1)
    page = page.replace("</head>", f"<style>{STYLE}</style>\n</head>", 1)   # after the viewer's
    page = page.replace("<body>", f"<body>\n{body}\n", 1)
    head, tail = page.rsplit("</body>", 1)
    return f"{head}<script>\n{script}\n</script>\n</body>{tail}"


def write_report_html(path: str | Path, result: ModalResult,
                      verdict: ResonanceVerdict | None, sizing: SizingResult | None = None,
                      pictures: Sequence[Path] = (), estimate: ErrorEstimate | None = None,
                      free: Modes | HangingModes | None = None,
                      participation: Participation | None = None,
                      rotor: RotorStudy | None = None, drawing: Drawing | None = None,
                      wall_seconds: float | None = None,
                      strength=None) -> Path:
    return write_text(path, report_html(result, verdict, sizing, pictures, estimate, free,
                                        participation, rotor, drawing, wall_seconds, strength))
