"""Every text table shaftfem prints or writes: terminal tables and Markdown.

Pure formatting: each function takes a result and returns text, every number
with its unit.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from shaftfem.checks.resonance import ResonanceVerdict
    from shaftfem.checks.sizing import SizingResult
    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.fem.hanging import HangingModes
    from shaftfem.fem.modes import Modes
    from shaftfem.fem.response import Participation
    from shaftfem.fem.result import ModalResult, ModelMoves
    from shaftfem.fem.whirl import Campbell, GrowthZone
    from shaftfem.scene.model import Scene


def markdown(head: list[str], rows: list[list[str]]) -> list[str]:
    """A Markdown table, as lines."""
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    return out + ["| " + " | ".join(r) + " |" for r in rows]


def aligned(rows: list[list[str]], left: frozenset[int] | set[int] = frozenset()) -> list[str]:
    """Rows of cells as text columns two spaces apart, right-aligned (columns `left`
    left-aligned), the first row the header."""
    widths = [max(len(r[k]) for r in rows) for k in range(len(rows[0]))]
    return ["  ".join(c.ljust(w) if k in left else c.rjust(w)
                      for k, (c, w) in enumerate(zip(r, widths))).rstrip() for r in rows]


def timings(result: ModalResult, est: ErrorEstimate | None = None) -> dict[str, float]:
    """Each step's wall time, s: the run's own, then the bound's where it was timed, and
    the total of both."""
    out = dict(result.timings.items())
    if est is not None and est.seconds > 0:
        total = out.pop("total")
        out.update(bound=est.seconds, total=total + est.seconds)
    return out


def timings_line(result: ModalResult, est: ErrorEstimate | None = None) -> str:
    return ", ".join(f"{k} {v:.1f} s" for k, v in timings(result, est).items())


def run_time_text(result: ModalResult, est: ErrorEstimate | None = None,
                  wall_seconds: float | None = None) -> str:
    """The run's time in all (until the report), then where the standstill modal run's
    went."""
    parts = timings_line(result, est)
    if wall_seconds is None:
        return parts
    return (f"{wall_seconds:.1f} s in all, until this report; of it the standstill modal "
            f"run: {parts}")


def estimate_notes(est: ErrorEstimate, scene: Scene | None = None) -> list[str]:
    """How the bounds were made, how to read them, where they rest on less, and (given
    the scene) what they cover and what they do not."""
    straightened = ("" if est.straightening is None else
                    ", and each mode's shift from the straightened elements' faces, up to "
                    f"{100 * float(est.straightening.max()):.2g} %")
    return ([f"error bound: the true frequency lies between f (1 - lower) and f (1 + upper). "
             f"The computed frequencies converge from above, so the discretisation error "
             f"({est.method}) counts downwards only; the geometry allowances count both "
             f"ways: the mesh's volume difference from the solid, {100 * est.geometry:.1g} %"
             f"{straightened}."] + list(est.notes)
            + ([bound_coverage(scene)] if scene is not None else []))


def bound_coverage(scene: Scene) -> str:
    """What an interval covers (the discretisation and the mesh's geometry, for the model
    as given) and what of this scene's model it does not."""
    outside = ["the material's values"]
    if scene.held:
        outside.append("the bearings' stiffness and how the seats hold the shaft")
    if scene.attachments:
        outside.append("the parts' joints (rigid or distributing)")
    if scene.attachments or scene.held:
        outside[-1] += " (`shaftfem modes --sensitivity` shows what flipping them moves)"
    outside.append("rotation: the shaft stands still here (with [rotor], `shaftfem campbell` "
                   "gives its whirl)" if scene.rotor is None else
                   "rotation: these are standstill modes (`shaftfem campbell` turns them)")
    return ("the interval covers the discretisation and the mesh's geometry, for the model "
            "as given; not " + "; nor ".join(outside) + ".")


def _percent(x: float) -> str:
    return f"{100 * x:.2g} %"


def bound_text(est: ErrorEstimate, i: int) -> str:
    """'-0.24 % +0.003 %': how far below and above f the true frequency may lie (two
    significant digits), '*' marking a bound not confirmed."""
    e = est.relative_error[i]
    if not math.isfinite(e):
        return "n/a"
    return f"-{_percent(e)} +{_percent(est.upward[i])}{'' if est.reliable[i] else '*'}"


def interval_text(low: float, high: float) -> str:
    """'[428.12, 434.64] Hz': where the true frequency lies (ErrorEstimate.interval)."""
    if not (math.isfinite(low) and math.isfinite(high)):
        return "n/a"
    return f"[{low:.2f}, {high:.2f}] Hz"


def _range(span, unit: float, fmt: str) -> str:
    """' (min to max)' of a tolerance range (min, nominal, max) in a unit; '' without one."""
    return "" if span is None else f" ({span[0] * unit:{fmt}} to {span[2] * unit:{fmt}})"


def _oil(j) -> str:
    """A journal's oil: its viscosity, or its grade at its temperature before the part
    gave the viscosity."""
    if j.oil_supply_temperature is not None:
        return (f"ISO VG {j.oil_iso_vg} fed at {j.oil_supply_temperature:g} C"
                + ("" if j.oil_flow is None else f", {j.oil_flow * 60e3:.3g} l/min")
                + " (the film heats: its temperature at each speed from its heat balance)")
    if j.viscosity is None:
        return f"ISO VG {j.oil_iso_vg} at {j.oil_temperature:g} C"
    return f"{j.viscosity * 1e3:.3g} mPa s"


def bore_words(j) -> str:
    """A journal's bore in a few words ('' for the plain bore)."""
    b = j.bore
    if b is None:
        return ""
    if b.kind == "tilting_pad":
        return (f", {b.pads} tilting pads of {math.degrees(b.arc):g} deg (preload "
                f"{b.preload:g}, pivots at {b.offset:g}, the load "
                f"{'between pads' if b.between else 'on a pad'})")
    lemon = f"elliptical (preload {b.preload:g}), " if b.kind == "elliptical" else ""
    return f", {lemon}two axial grooves of {math.degrees(b.groove):g} deg"


def installation_lines(result: ModalResult) -> list[str]:
    """How the shaft is held and what sits on it, one line each."""
    scene = result.scene
    if not scene.supports and not scene.attachments:
        return ["free-free: the shaft hangs free (no [[support]] in the scene)"]
    out = []
    if scene.hanging_free:
        out.append("free-free: the scene's supports are left off (--free); same mesh")
    for s in scene.held:
        what = {"rigid": "rigid, radially and axially", "rigid-radial": "rigid, radially",
                "clamped": "clamped"}.get(s.kind)
        if what is None and s.journal is not None:
            j, t = s.journal, s.tolerance
            what = (f"journal bearing {j.diameter * 1e3:g} x {j.length * 1e3:g} mm{bore_words(j)}, "
                    f"radial clearance {j.clearance * 1e6:g} um"
                    + _range(t and t.clearance, 1e6, "g") + f", oil {_oil(j)}"
                    + _range(t and t.viscosity, 1e3, ".3g")
                    + ": its film's coefficients against speed in the rotordynamics section")
        elif what is None and s.seal is not None:
            ring, t = s.seal, s.tolerance
            what = (f"annular seal {ring.diameter * 1e3:g} x {ring.length * 1e3:g} mm, radial "
                    f"clearance {ring.clearance * 1e6:g} um" + _range(t and t.clearance, 1e6, "g")
                    + f", {ring.pressure_drop / 1e6:g} MPa across it: no force at standstill, "
                    "its coefficients against speed in the rotordynamics section")
        elif what is None and s.bearing is not None:
            b = s.bearing
            k, c = b.stiffness(0.0), b.damping(0.0)
            what = (f"bearing kxx {k[0][0] / 1e3:.4g}, kyy {k[1][1] / 1e3:.4g}, "
                    f"kxy {k[0][1] / 1e3:.4g}, kyx {k[1][0] / 1e3:.4g} N/mm; "
                    f"cxx {c[0][0] / 1e3:.4g}, cyy {c[1][1] / 1e3:.4g} N s/mm"
                    + (" (at standstill; against speed)" if b.speeds else ""))
        if what is None:
            parts = [f"k_r {s.radial / 1e3:.4g} N/mm"]
            if s.axial:
                parts.append(f"k_a {s.axial / 1e3:.4g} N/mm")
            if s.tilting:
                parts.append(f"k_t {s.tilting * 1e3:.4g} N mm/rad")
            what = "springs " + ", ".join(parts)
        out.append(f"support {s.name}: seat {s.seat[0] * 1e3:g}-{s.seat[1] * 1e3:g} mm, {what}")
    for a in scene.attachments:
        out.append(f"part {a.name}: seat {a.seat[0] * 1e3:g}-{a.seat[1] * 1e3:g} mm, "
                   f"{a.mass:g} kg, I_p {a.polar_inertia:.3g} kg m^2, "
                   f"I_d {a.diametral_inertia:.3g} kg m^2, {a.joint} joint")
    if result.installed is not None:
        free = ", ".join(result.installed.free) or "none"
        out.append(f"rigid motions the supports leave free: {free}")
    return out


def shape_lines(shaft) -> list[str]:
    """What the shaft is, where it is more than a plain bar: its sections, bores, keyways,
    or what the import of its STEP file found."""
    if shaft.step is not None:
        return [shaft.step.summary]
    if shaft.plain:
        return []
    parts = []
    for s in shaft.profile:
        d = (f"{s.diameter_start * 1e3:g}" if not s.conical
             else f"{s.diameter_start * 1e3:g}-{s.diameter_end * 1e3:g}")
        parts.append(f"{s.length * 1e3:g} x {d}" + (f"/{s.bore * 1e3:g}" if s.bore else ""))
    keys = "".join(f", keyway {k.width * 1e3:g} x {k.depth * 1e3:g} x {k.length * 1e3:g} mm at "
                   f"{k.start * 1e3:g}-{k.end * 1e3:g} mm" for k in shaft.keyways)
    return [f"shaft: {len(shaft.profile)} section(s), length x diameter[/bore] "
            f"{', '.join(parts)} mm{keys}"]


def residual_line(residuals) -> str:
    """The eigenpairs' residuals as a fixed threshold they all meet (the values themselves
    depend on where the solver started, and are in the JSON)."""
    top = max(residuals, default=0.0)
    limit = next((t for t in (1e-8, 1e-6, 1e-4) if top < t), None)
    what = "residuals ||K x - w^2 M x|| / ||K x||"
    return f"{what}: all below {limit:g}" if limit else f"{what}: up to {top:.1e}"


def _feature_size(scene) -> str:
    """' (grooves 4 mm)': the finer size, named after what the scene has that takes it."""
    shaft = scene.shaft
    has = [name for name, there in (
        ("grooves", scene.grooves is not None),
        ("fillets", any(s.fillet for s in shaft.profile)),
        ("chamfers", shaft.end_chamfer or any(s.chamfer for s in shaft.profile)),
        ("keyways", shaft.keyways)) if there]
    return f" ({', '.join(has)} {scene.mesh.groove_size * 1e3:g} mm)" if has else ""


def modes_text(result: ModalResult, est: ErrorEstimate | None = None,
               moves: ModelMoves | None = None) -> str:
    """The modes table as a designer reads it (`moves`: the model's choices flipped, its
    largest move per mode beside the bound)."""
    m, scene = result.modes, result.scene
    exc = scene.excitations[0] if scene.excitations else None
    # rounded up to a power of ten: the rigid modes' numerical noise, not a result
    top = max(m.rigid_frequencies, default=0.0)
    rigid = (f"rigid-body modes: {m.n_rigid} (all below "
             f"{10.0 ** math.ceil(math.log10(max(top, 1e-12))):g} Hz)"
             if m.n_rigid else "rigid-body modes: none")
    lines = [
        f"scene {scene.name}: P{scene.mesh.order}, {m.n_dofs} DOFs, "
        f"{result.mesh.n_elements} elements, element size {scene.mesh.size * 1e3:g} mm"
        f"{_feature_size(scene)}, solver {m.factoriser}",
        *shape_lines(scene.shaft),
        *installation_lines(result),
        f"{rigid}; Sturm check: {m.inertia_count} eigenvalues below "
        f"{m.inertia_shift_hz:.1f} Hz, as many as found",
        residual_line(m.residuals),
        "",
    ]
    shown = moves is not None and bool(moves.choices)
    rows = [["mode", "frequency", "kind"]
            + (["error bound", "true frequency in"] if est is not None else [])
            + (["model's choices move it"] if shown else [])
            + ([f"f / {exc.name} {hz(exc.frequency)}"] if exc else [])]
    bounds = _bound_cells(m.frequencies, est)
    largest = moves.largest() if moves is not None and shown else []
    for i, (f, kind) in enumerate(zip(m.frequencies, m.kinds)):
        rows.append([str(i + 1), f"{f:.2f} Hz", kind] + bounds[i]
                    + ([f"{100 * largest[i][0]:+.2f} % ({largest[i][1].split(' (')[0]})"]
                       if shown else [])
                    + ([f"{f / exc.frequency:.2f}"] if exc else []))
    lines += aligned(rows, left={2} | ({5 if est is not None else 3} if shown else set()))
    if moves is not None:
        lines += [""] + sensitivity_lines(moves)
    if est is not None:
        lines += [""] + estimate_notes(est, scene)
    lines += [f"WARNING: {w}" for w in result.warnings]
    lines += ["", "time: " + timings_line(result, est)]
    return "\n".join(lines)


def sensitivity_lines(moves: ModelMoves) -> list[str]:
    """What each flipped choice does to the frequencies, one line each."""
    import numpy as np

    if not moves.choices:
        return ["the model's choices: none to flip (no parts, no held seats)"]
    lines = ["the model's choices, each flipped and solved again on the same mesh "
             "(what the bound does not cover):"]
    for choice, row in zip(moves.choices, moves.moves):
        lo, hi = np.nanmin(row), np.nanmax(row)
        lines.append(f"  {choice}: frequencies move {100 * lo:+.2f} to {100 * hi:+.2f} %")
    return lines


PARTICIPATION_UNITS = {"x": "kg", "y": "kg", "z": "kg", "rz": "kg m^2"}


def participation_rows(result: ModalResult, p: Participation) -> tuple[list[str], list[list[str]]]:
    """Effective mass and cumulative fraction per mode and base-motion direction."""
    from shaftfem.fem.response import DIRECTIONS

    head = ["mode", "frequency"] + [f"m_eff {d} ({PARTICIPATION_UNITS[d]})" for d in DIRECTIONS] + [
        f"sum {d}" for d in DIRECTIONS]
    def mass(values) -> list[str]:   # round-off below 1e-9 of the total is 0
        return [f"{v:.4g}" if abs(v) >= 1e-9 * t else "0" for v, t in zip(values, p.total)]

    rows = []
    if any(v > 0 for v in p.rigid):
        rows.append(["rigid", "0 Hz"] + mass(p.rigid)
                    + [f"{100 * v:.1f} %" for v in p.rigid / p.total])
    for i, f in enumerate(result.modes.frequencies):
        rows.append([str(i + 1), f"{f:.2f} Hz"] + mass(p.effective[i])
                    + [f"{100 * v:.1f} %" for v in p.cumulative[i]])
    rows.append(["total", ""] + [f"{v:.4g}" for v in p.total] + ["100 %"] * len(DIRECTIONS))
    return head, rows


def participation_text(result: ModalResult, p: Participation) -> str:
    """ANSYS-style: effective modal mass per direction of base motion at the supports."""
    head, rows = participation_rows(result, p)
    return "\n".join(["effective modal mass for base motion at the supports (x, y lateral, "
                      "z axial, rz turn about the axis)"] + aligned([head] + rows))


def participation_markdown(result: ModalResult, p: Participation) -> list[str]:
    return markdown(*participation_rows(result, p))


def _amplified(v: ResonanceVerdict) -> bool:
    return any(a.amplification is not None for a in v.approaches)


def hz(f: float) -> str:
    """A frequency as people write it: two decimals at most, no trailing zeros."""
    return f"{f:.2f}".rstrip("0").rstrip(".") + " Hz"


def verdict_rows(v: ResonanceVerdict) -> tuple[list[str], list[list[str]]]:
    """The closest mode to each excitation harmonic, closest first."""
    amp = _amplified(v)
    head = (["source", "order", "excitation", "closest mode", "frequency", "kind", "margin",
             "required"] + (["amplification"] if amp else []) + [""])
    rows = [[a.source, str(a.order), f"{a.excitation:.2f} Hz", str(a.mode),
             f"{a.frequency:.2f} Hz", a.kind, f"{100 * a.margin:.1f} %",
             f"{100 * a.required:.3g} %"] + ([f"{a.amplification:.3f}x"] if amp else [])
            + ["ok" if a.ok else "TOO CLOSE"] for a in v.closest_per_harmonic()]
    return head, rows


def verdict_text(v: ResonanceVerdict) -> str:
    """The resonance table, columns sized to their contents, and the verdict."""
    head, rows = verdict_rows(v)
    lines = aligned([head] + rows, left={0, 5, len(head) - 1})
    if _amplified(v):
        lines += ["", "amplification: transmissibility |u / u_base| at the response point "
                  "for lateral base motion at the supports, at the harmonic's frequency"]
    lines += [""] + [line.replace("**", "") for line in verdict_lines(v)]
    return "\n".join(lines)


FREE_FREE_CAVEAT = (
    "free-free: no [[support]] holds this shaft, so these are its modes hanging free. In "
    "its bearings its first bending mode can lie far lower (about half for a shaft on two "
    "bearings; see the installed-shaft guide). Add [[support]] tables to check the shaft as "
    "installed, or set [resonance] free_free = true (or pass --free) when free-free is what "
    "the check is for.")


FREE_FREE_MEANT = (
    "free-free, as the scene says ([resonance] free_free = true, or --free): these are the "
    "shaft's modes hanging free. In its bearings they lie lower (the first bending mode about "
    "half as high for a shaft on two bearings).")


def zone_causes(c: Campbell, z: GrowthZone) -> str:
    """What a zone of growth holds, in words: the curves whose log decrement falls below
    zero in it, a divergence, a periodic rotor's parametric resonance."""
    words = []
    curves = [h for h in z.holds if h.startswith("curve ")]
    if curves:
        words.append(f"{', '.join(curves)}: log decrement below zero")
    if "divergence" in z.holds:
        words.append("a mode locks to the shaft and grows (divergence; the shaft is stiffer "
                     "across one diameter than across the other)")
    if "parametric" in z.holds:
        words.append("a form of the periodic rotor grows while it oscillates (a parametric "
                     "or combination resonance, two forms meeting 2 k n)")
    return "; ".join(words)


def _spans_text(spans) -> str:
    """Where the shaft runs, r/min: '3,000 r/min' or '30 and 2,800-3,200 r/min'."""
    parts = [f"{lo:,.0f}" if lo == hi else f"{lo:,.0f}-{hi:,.0f}" for lo, hi in spans]
    return (" and ".join(parts) if len(parts) < 3 else
            ", ".join(parts[:-1]) + " and " + parts[-1]) + " r/min"


def verdict_lines(v: ResonanceVerdict | None) -> list[str]:
    """The verdict line, and for a free-free shaft the caveat under it (Markdown bold)."""
    lines = [verdict_line(v)]
    if v is not None:
        lines += [f"UNSTABLE: {u}" for u in v.unstable]
        lines += [f"STABILITY CRITERION NOT MET: {u}" for u in v.underdamped]
        lines += [f"UNBALANCE RESPONSE NOT MET: {u}" for u in v.response]
        lines += [f"warning: {w}" for w in v.warnings]
    if v is not None and v.turning:
        lines.append(f"judged on {v.turning}")
    if v is not None and v.free_free:
        lines.append(FREE_FREE_MEANT if v.free_free_intended else FREE_FREE_CAVEAT)
    return lines


def verdict_line(v: ResonanceVerdict | None) -> str:
    """One line: PASS or FAIL with the closest approach, and on what (Markdown bold)."""
    if v is None:
        return ("**VERDICT: NOT CHECKED** - the scene has no [[excitation]] sources; add them "
                "to check the modes against the excitation harmonics")
    free = " (free-free)" if v.free_free else ""
    if v.unstable:
        return (f"**VERDICT: FAIL{free}** - not stable where the shaft runs: {v.unstable[0]}"
                + (f" (and {len(v.unstable) - 1} more)" if len(v.unstable) > 1 else ""))
    if v.underdamped:
        return (f"**VERDICT: FAIL{free}** - stable where the shaft runs, but a stability "
                f"criterion is not met: {v.underdamped[0]}"
                + (f" (and {len(v.underdamped) - 1} more)" if len(v.underdamped) > 1 else ""))
    if v.response and all(a.ok for a in v.approaches):
        return (f"**VERDICT: FAIL{free}** - stable, the critical speeds clear their margins, "
                f"but the unbalance response does not: {v.response[0]}"
                + (f" (and {len(v.response) - 1} more)" if len(v.response) > 1 else ""))
    if v.ok and not v.approaches:
        return (f"**VERDICT: PASS{free}** - stable, and no critical speed or whirl frequency "
                "meets an excitation harmonic in the range checked")
    if v.ok:
        a = (v.judged or v.approaches)[0]
        if v.turning:
            return (f"**VERDICT: PASS{free}** - every critical speed and whirl frequency "
                    f"clears its required margin (closest: {a.kind}, "
                    f"{100 * a.margin:.1f} % from {a.source} x{a.order}, "
                    f"{100 * a.required:.3g} % required)")
        return (f"**VERDICT: PASS{free}** - no natural frequency within "
                f"{100 * v.required:.3g} % of any excitation harmonic"
                f"{' on the shaft hanging free' if free else ''} (closest: mode {a.mode}, "
                f"{a.frequency:.1f} Hz, vs {a.source} x{a.order} at {a.excitation:.1f} Hz: "
                f"{100 * a.margin:.0f} % apart)")
    bad = sorted(v.violations, key=lambda a: a.margin - a.required)
    a = bad[0]
    flat = all(abs(b.required - v.required) <= 1e-12 for b in bad)
    return (f"**VERDICT: FAIL{free}** - {len(bad)} mode/harmonic pair(s) closer than "
            + (f"{100 * v.required:.3g} %" if flat else "their required margin")
            + f"; the tightest: mode {a.mode} ({a.frequency:.1f} Hz, {a.kind}) "
            f"is only {100 * a.margin:.1f} % from {a.source} x{a.order} at "
            f"{a.excitation:.1f} Hz ({100 * a.required:.3g} % required)")


def verdict_markdown(v: ResonanceVerdict) -> list[str]:
    return markdown(*verdict_rows(v))


def sizing_text(r: SizingResult) -> str:
    lines = [f"{'eq.':<8} {'symbol':<5} {'value':>12}  {'unit':<5} quantity"]
    lines += [f"{q.equation:<8} {q.symbol:<5} {q.value:>12.4f}  {q.unit:<5} {q.name}"
              for q in r.quantities]
    lines.append("")
    if r.ok:
        lines.append("limits: all hold (pressure angle within the self-locking limit)")
    else:
        lines += [f"LIMIT BROKEN: {v}" for v in r.violations]
    return "\n".join(lines)


Rows = tuple[list[str], list[list[str]]]   # (header, rows of cells): a table's content


def sizing_rows(r: SizingResult) -> Rows:
    return (["eq.", "symbol", "value", "unit", "quantity"],
            [[q.equation, q.symbol, f"{q.value:.4g}", q.unit, q.name] for q in r.quantities])


def sizing_markdown(r: SizingResult) -> list[str]:
    return markdown(*sizing_rows(r)) + [""] + [f"- LIMIT BROKEN: {v}" for v in r.violations]


def _bound_cells(frequencies, est: ErrorEstimate | None) -> list[list[str]]:
    """Per mode, the bound's cells: '-1.5 % +0.037 %' and the interval (none without)."""
    if est is None:
        return [[] for _ in frequencies]
    low, high = est.interval(frequencies)
    return [[bound_text(est, i), interval_text(lo, hi)]
            for i, (lo, hi) in enumerate(zip(low, high))]


def modes_rows(result: ModalResult, est: ErrorEstimate | None = None) -> Rows:
    """Each mode's frequency and kind, and with a bound where the true frequency lies."""
    m = result.modes
    bounds = _bound_cells(m.frequencies, est)
    rows = [[str(i + 1), f"{f:.2f}", kind] + bounds[i]
            for i, (f, kind) in enumerate(zip(m.frequencies, m.kinds))]
    return (["mode", "frequency (Hz)", "kind"]
            + ([] if est is None else ["error bound", "true frequency in"]), rows)


def modes_markdown(result: ModalResult, est: ErrorEstimate | None = None) -> list[str]:
    return markdown(*modes_rows(result, est))


def side_by_side_rows(installed: ModalResult, free: Modes | HangingModes) -> Rows:
    """The installed modes beside the free-free ones (the same shaft's modes hanging
    free), mode by mode."""
    a, b = installed.modes, free
    rows = []
    for i in range(max(a.count, b.count)):
        left = [f"{a.frequencies[i]:.2f}", a.kinds[i]] if i < a.count else ["", ""]
        right = [f"{b.frequencies[i]:.2f}", b.kinds[i]] if i < b.count else ["", ""]
        rows.append([str(i + 1)] + left + right)
    return ["mode", "installed (Hz)", "kind", "free-free (Hz)", "kind"], rows


def side_by_side_markdown(installed: ModalResult, free: Modes | HangingModes) -> list[str]:
    return markdown(*side_by_side_rows(installed, free))


def paper_text(result: ModalResult, sizing: SizingResult | None) -> str:
    """The paper's Table 2 (and stated sizing) beside ours."""
    from shaftfem.cases import paper2018

    lines = []
    if result.scene.installed:
        lines += [f"note: the paper's Table 2 is the bare shaft hanging free; this run is "
                  f"{'held by its supports' if result.scene.held else 'free with its parts on'}"
                  " (shaftfem paper geometry/paper2018.toml compares like with like)", ""]
    lines += [f"{'mode':>4} {'paper':>10} {'shaftfem':>10} {'diff':>8}  {'kind':<8} "
              f"{'f/f1 paper':>10} {'f/f1 ours':>10}"]
    for r in paper2018.compare_modes(result.modes.frequencies, result.modes.kinds):
        lines.append(f"{r.mode:>4} {r.paper_hz:>7.2f} Hz {r.ours_hz:>7.2f} Hz "
                     f"{r.difference_percent:>+7.1f} %  {r.kind:<8} "
                     f"{r.paper_ratio:>10.3f} {r.ours_ratio:>10.3f}")
    s, m = result.scene.shaft, result.scene.material
    torsion = (m.shear_modulus / m.density) ** 0.5 / (2 * s.length)
    nearest = paper2018.nearest_to(torsion)
    lines += ["", f"first torsion of a uniform {s.diameter * 1e3:g} mm shaft {s.length * 1e3:g} mm "
              f"long: c_t / 2L = {torsion:.0f} Hz; the paper's nearest mode is {nearest:.1f} Hz "
              f"({100 * (nearest / torsion - 1):+.0f} %)"]
    if sizing is not None:
        lines += ["", "sizing (equations 1-9) against the paper's stated results:"]
        for c in paper2018.compare_sizing(sizing):
            said = "matches" if c.matches else f"{c.difference_percent:+.1f} %"
            lines.append(f"  {c.symbol:<3} equations {c.ours_mm:>8.2f} mm, paper "
                         f"{c.paper_mm:>7.2f} mm ({said})")
    return "\n".join(lines)


def whirl_text(rows, title: str) -> str:
    """A whirl table (workflows.campbell.Whirl rows) under `title`."""
    lines = [title, "mode   frequency  whirl     index  log dec  kind"]
    for w in rows:
        # a rotating-frame mode's other component, where it carries 5 % or more
        other = (f"  (also seen at {w.companion_hz:.2f} Hz)"
                 if w.companion_hz is not None and w.companion_share >= 0.05 else "")
        lines.append(f"{w.mode:4d} {w.frequency_hz:9.2f} Hz  {w.whirl:8s} {w.whirl_index:+.2f} "
                     f"{w.log_dec:8.3f}  {w.kind}{other}")
    return "\n".join(lines)


def _width(names: list[str], head: str, least: int = 18) -> int:
    """A name column's width: its longest name or its head, at least `least` (a name is
    never cut: "non-drive-end bearing" read as "non-drive-end bear" is another part)."""
    return max([least, len(head), *map(len, names)])


def film_text(films) -> str:
    """Each journal bearing's film at the operating speeds (fem.whirl.FilmRow)."""
    w = _width([f.bearing for f in films], "journal bearing")
    head = (f"{'journal bearing':{w}s} {'speed':>12s} {'ecc.':>6s} {'attitude':>9s} "
            f"{'min film':>10s} {'Sommerfeld':>10s}  K xx, xy, yx, yy (N/mm); C (N s/mm)")
    fed = any(f.journal_w is not None for f in films)
    lines = ["journal bearings at the operating speeds (Reynolds film"
             + ("; tilting pads fed at a supply: their heated film on grown parts"
                if fed else "") + "):", head]
    for f in films:
        k, c = ", ".join(_coefficients(f.K)), ", ".join(_coefficients(f.C))
        flag = ("  the film does not lift the journal here" if not f.lifted else
                f"  below its {f.limit_um:g} um limit" if f.thin else "")
        lines.append(f"{f.bearing:{w}s} {f.speed_rpm:8,.0f} r/min {f.eccentricity:6.3f} "
                     f"{f.attitude_deg:7.1f} deg {f.min_film_um:7.1f} um {f.sommerfeld:10.4g}  "
                     f"K {k}; C {c}{flag}")
    warm = [f for f in films if f.film_c is not None]
    if warm:
        lines += ["", "the films' heating (fed at the supply's temperature; heat balance, "
                  "hot-oil carry-over 0.8; tilting pads' film temperature (their films' "
                  "mean), friction, draw and peaks from their heated films, on the journal "
                  "and pads grown by their heat):"]
    for f in warm:
        # tilting pads' friction and draw come from their heated films (with the
        # journal's share); a plain or fixed bore's from the heat balance
        pads = f.journal_w is not None
        short = (" - less than the pads draw: STARVED (their temperatures assume they get "
                 "it)" if pads else " - less than the film's side flow: STARVED")
        drain = ("" if f.drain_c is None else
                 f"; supply {f.flow * 60e3:.3g} l/min drains at {f.drain_c:.1f} C"
                 + (short if f.starved else ""))
        share = f" (the journal takes {f.journal_w:,.0f} W of it along the shaft)" if pads else ""
        lines.append(f"{f.bearing:{w}s} {f.speed_rpm:8,.0f} r/min: fed at {f.supply_c:g} C, "
                     f"the film runs at {f.film_c:.1f} C, friction {f.power_w:,.0f} W{share}, "
                     f"{'the pads draw' if pads else 'side flow'} "
                     f"{f.side_flow * 60e3:.3g} l/min{drain}"
                     + ("" if f.pad_peak_c is None else
                        f"; peak pad temperature {f.pad_peak_c:.1f} C (limit "
                        f"{f.pad_limit_c:g} C{': ABOVE' if f.hot else ''}); each pad's "
                        "peak from the load's line in the journal's turn: "
                        + ", ".join(f"{t:.1f}" for t in f.pad_peaks_c) + " C")
                     + ("" if f.hot_clearance_um is None else
                        f"; hot clearance {f.hot_clearance_um:.1f} um (the least pad's, at "
                        "its pivot)"))
    return "\n".join(lines)


def campbell_text(c) -> str:
    """What `shaftfem campbell` prints: the frame, the whirl at each operating speed,
    the critical speeds and the basis check (a workflows.campbell.Campbell)."""
    from shaftfem.checks.whirl_check import api684_peaks, span_margin
    from shaftfem.fem.whirl import RPM

    r = c.result
    t = c.truncation
    lines = [f"scene {r.scene.name}: P{r.scene.mesh.order}, {r.modes.n_dofs} DOFs, "
             f"{r.mesh.n_elements} elements", f"frame: {c.frame} ({c.why})"]
    for n in c.operating_rpm:
        rows = [w for w in c.operating if abs(w.speed_rpm - n) <= 1e-9 * n]
        lines += ["", whirl_text(rows, f"at {n:,.0f} r/min ({n / 60:.2f} Hz), stationary frame:")]
    if c.films:
        lines += ["", film_text(c.films)]
    lines += ["", f"critical speeds, 0 to {max(c.speeds_rpm):,.0f} r/min "
              f"(orders {', '.join(f'{o}x' for o in c.orders)}; every curve):"]
    if not c.critical_speeds:
        lines.append("  none: no whirl curve crosses an order line in this range")
    rotor = c.rotor_scene.rotor
    spans = [(lo / RPM, hi / RPM) for lo, hi in rotor.spans] if rotor else []
    for cs in c.critical_speeds:
        lo, hi = min(spans, key=lambda s: span_margin(cs.speed_rpm, *s)[0])
        margin, above = span_margin(cs.speed_rpm, lo, hi)
        where = (f"inside {lo:,.0f}-{hi:,.0f} r/min" if margin == 0 and lo < hi else
                 f"{'+' if above else '-'}{100 * margin:.1f} % from "
                 + (f"{hi if above else lo:,.0f} r/min"))
        curve = (f"curve {cs.mode}" if cs.found == "curve" else "found directly only")
        part = (f", its {cs.component} component ({100 * cs.share:.0f} % of the motion)"
                if cs.component and cs.share < 0.95 else "")
        dec = f", log dec {cs.log_dec:.3g}" if cs.log_dec else ""
        if cs.critically_damped:
            where = (f"critically damped (AF {cs.amplification:.2g}, below 2.5): not a "
                     "critical speed, no margin required")
        lines.append(f"  {cs.order}x {cs.whirl:8s} {cs.speed_rpm:10,.0f} r/min "
                     f"({cs.frequency_hz:.2f} Hz, {curve}{part}{dec}): {where}")
    x = c.crossing_check
    if x is not None and x.applies:
        lines.append(f"  found twice: on the curves ({x.on_curves}) and directly as an "
                     f"eigenproblem in the speed squared ({x.direct}); they agree to "
                     f"{x.largest_difference:.1e}"
                     + (f"; {x.direct_only} found directly only" if x.direct_only else "")
                     + (f"; {x.curves_only} on the curves only" if x.curves_only else ""))
    elif x is not None:
        lines.append(f"  found on the curves followed by shape (the direct route does not "
                     f"apply: {x.why})")
    lines += ["", f"modal basis: {t.size} standstill modes; on {t.smaller} of them the "
              f"reported whirl frequencies move by at most {t.change * 100:.2g} % "
              f"(at {', '.join(f'{s:,.0f}' for s in t.speeds_rpm)} r/min)"]
    st = c.stability
    if st is not None:
        lines.append(f"stability where the shaft runs ({_spans_text(spans)}"
                     + (f", journals lifted from {c.lift_rpm:,.0f} r/min" if c.lift_rpm else "")
                     + "): least log "
                     f"decrement {st.log_dec:.3g} (curve {st.curve}, {st.whirl} whirl, "
                     f"{st.frequency_hz:.2f} Hz, at {st.speed_rpm:,.0f} r/min)"
                     + ("" if not st.judged else f", required above {st.required:g} of "
                        f"{st.applies_text}"))
        if st.reduced_log_dec is not None:
            lines.append(f"  on the tilting pads' own tilts; with their coefficients reduced "
                         f"at the spin (as tools that reduce the pads give them) it would "
                         f"read {st.reduced_log_dec:.3g}")
    lines += [f"UNSTABLE {z.span_text}: {zone_causes(c, z)}; {z.growth_text}"
              for z in c.zones]
    if c.zones and not c.zones[-1].open:
        lines.append(f"stable above {c.zones[-1].to_rpm:,.0f} r/min to the diagram's end")
    if c.unbalance is not None:
        verdict = ("the verdict follows these margins" if api684_peaks(c.rotor_scene)
                   else "for information: the verdict takes [resonance]'s flat margin")
        lines += ["", "unbalance response peaks (the orbit's major semi-axis, 0-peak; "
                  "half-power amplification factor, API 684 separation margin; "
                  f"{verdict}):"]
        if not c.unbalance.peaks:
            lines.append("  none in the speed range")
        if not c.unbalance.damped:
            lines.append("  no damping in the model: at each critical speed the response is "
                         "unbounded (no finite peak, no amplification factor); give the "
                         "bearings' damping (cxx_n_s_per_mm) for the amplitudes")
        for p in c.unbalance.peaks:
            if p.unbounded:
                lines.append(f"  {p.probe}: {p.speed_rpm:,.0f} r/min: unbounded (undamped), "
                             f"margin {p.margin * 100:.1f} %")
                continue
            if p.unstable:
                lines.append(f"  {p.probe}: {p.speed_rpm:,.0f} r/min: a mode grows at this "
                             "speed, so the shaft has no steady unbalance response here (no "
                             "amplification factor): the rotor is unstable")
                continue
            af = (f"AF {p.amplification:.1f}" if p.amplification is not None
                  else "AF not measurable (a half-power point lies outside the range)")
            need = ("margin not judged" if p.amplification is None else
                    "no margin required (AF < 2.5)" if p.required_margin is None else
                    f"required {p.required_margin * 100:.1f} %: "
                    f"{'ok' if p.ok else 'NOT MET'}")
            limit = rotor.amplitude_limit if rotor is not None else None
            over = (f"; above the {limit * 1e6:g} um limit" if limit is not None
                    and p.amplitude > limit else "")
            lines.append(f"  {p.probe}: {p.speed_rpm:,.0f} r/min, {p.amplitude * 1e6:.3g} um, "
                         f"{af}, margin {p.margin * 100:.1f} %, {need}{over}")
        thirds = [b for b in c.unbalance.bode if b.major_3x is not None]
        if thirds:
            import numpy as np

            top = max(c.operating_rpm) if c.operating_rpm else None
            lines += ["", "the unbalance's 3x whirl (the shaft stiffer across one diameter in "
                      "bearings that differ along x and y; the 3x orbit's major semi-axis, "
                      "0-peak, beside the 1x):"]
            for b in thirds:
                assert b.major_3x is not None
                i = int(np.argmax(b.major_3x))
                at = ""
                if top is not None:
                    j = int(np.argmin(np.abs(b.speeds_rpm - top)))
                    at = (f"; {b.major_3x[j] * 1e6:.3g} um at {b.speeds_rpm[j]:,.0f} r/min "
                          f"beside {b.major[j] * 1e6:.3g} um at 1x")
                lines.append(f"  {b.name}: largest {b.major_3x[i] * 1e6:.3g} um at "
                             f"{b.speeds_rpm[i]:,.0f} r/min ({3 * b.speeds_rpm[i] / 60:.2f} Hz)"
                             + at)
    if c.weight_2x:
        top = max(c.operating_rpm) if c.operating_rpm else None
        lines += ["", "the weight's 2x whirl (the shaft is stiffer across one diameter than "
                  "across the other; the 2x orbit's major semi-axis, 0-peak):"]
        for w in c.weight_2x:
            at = (f"; {w.at_operating * 1e6:.3g} um at {top:,.0f} r/min about a "
                  f"{w.sag * 1e6:.3g} um sag" if top is not None else "")
            lines.append(f"  {w.probe}: peak at {w.speed_rpm:,.0f} r/min "
                         f"({2 * w.speed_rpm / 60:.2f} Hz whirl), {w.amplitude * 1e6:.3g} um{at}")
    lines += [f"note: {n}" for n in (*c.notes, *curve_notes(c))]
    return "\n".join(lines)


def curve_notes(c) -> list[str]:
    """Why each curve that starts after the diagram's first speed, or ends before its
    last, does (fem.tracking: Curve.began, Curve.ended)."""
    out = []
    for cv in c.curves:
        at, to = cv.speeds_rpm[0], cv.speeds_rpm[-1]
        if cv.began == "pair":
            out.append(f"curve {cv.number} starts at {at:,.0f} r/min: below it its two roots "
                       "are real (overdamped: they decay without whirling); there they meet "
                       "and whirl as a pair")
        elif cv.began == "shape":
            out.append(f"curve {cv.number} starts at {at:,.0f} r/min: a root whose shape "
                       "turned between two speeds faster than the halved steps follow; this "
                       "curve carries it on")
        if cv.ended == "split":
            out.append(f"curve {cv.number} ends at {to:,.0f} r/min: above it the pair parts "
                       "into two real roots (overdamped: no whirl)")
        elif cv.ended == "shape":
            out.append(f"curve {cv.number} ends at {to:,.0f} r/min: its shape turned faster "
                       "than the halved steps follow; another curve carries it on")
    return out


def static_text(result) -> str:
    """What `shaftfem static` prints: the loads, each support's reaction and the
    deflection line's largest value and its value at the supports, parts and forces (a
    workflows.static.StaticResult)."""
    import numpy as np

    s, scene = result.solution, result.scene
    g = float(np.linalg.norm(scene.gravity))
    w = _width([r.name for r in s.reactions], "support", 24)
    lines = [f"scene {scene.name}: static loads, "
             + (f"gravity {g:g} m/s^2 along ({', '.join(f'{v / g:.3g}' for v in scene.gravity)})"
                if g else "no gravity")
             + (f", {len(scene.forces)} force(s)" if scene.forces else ""),
             f"loads: {s.load[0]:,.1f}, {s.load[1]:,.1f}, {s.load[2]:,.1f} N (x, y, z)", "",
             f"{'support':{w}s} {'at':>10s} {'Fx':>12s} {'Fy':>12s} {'Fz':>12s}  (on the shaft)"]
    for r in s.reactions:
        fx, fy, fz = (v if abs(v) >= 0.05 else 0.0 for v in r.force)   # no "-0.0"
        lines.append(f"{r.name:{w}s} {r.position * 1e3:7.1f} mm {fx:10,.1f} N "
                     f"{fy:10,.1f} N {fz:10,.1f} N")
    r = np.hypot(s.x, s.y)
    k = int(np.argmax(r))
    lines += ["", f"largest deflection {r[k] * 1e6:.2f} um at z = {s.z[k] * 1e3:.1f} mm "
              f"(x {s.x[k] * 1e6:.2f} um, y {s.y[k] * 1e6:.2f} um)"]
    places = ([(f"support {x.name}", x.position) for x in scene.held]
              + [(f"part {a.name}", a.position) for a in scene.attachments]
              + [(f"force {f.name}", f.position) for f in scene.forces])
    for name, z in sorted(places, key=lambda p: p[1]):
        x, y = s.deflection_at(z)
        lines.append(f"  {name[:30]:30s} z = {z * 1e3:7.1f} mm: x {x * 1e6:8.2f} um, "
                     f"y {y * 1e6:8.2f} um")
    for f in scene.forces:
        if f.travel is not None:
            lines.append(f"force {f.name} travels from {f.position * 1e3:g} to "
                         f"{f.travel * 1e3:g} mm: taken here at its start; `shaftfem "
                         "strength` moves it along its way and checks the seats at each place")
    return "\n".join(lines)


def ucs_text(m) -> str:
    """The critical speed map: each branch's critical speed at a few stiffnesses, and
    where the scene's bearings cross the branches."""
    ks = m.stiffness
    picks = sorted({0, len(ks) // 4, len(ks) // 2, 3 * len(ks) // 4, len(ks) - 1})
    lines = [f"scene {m.scene.name}: undamped critical speed map, {m.title}; every bearing "
             f"alike (isotropic, undamped; seals left out), {len(ks)} stiffnesses from "
             f"{ks[0] / 1e3:.3g} to {ks[-1] / 1e3:.3g} N/mm",
             "", "stiffness (N/mm) " + "".join(f"  branch {i + 1} (r/min)"
                                                for i in range(m.frequencies.shape[0]))]
    for j in picks:
        lines.append(f"{ks[j] / 1e3:16.4g} " + "".join(
            f"{v:19,.0f}" if math.isfinite(v) else f"{'-':>19}" for v in m.speeds_rpm[:, j]))
    if m.bearings:
        lines += ["", "the scene's bearings on the map (their stiffness at each speed meets "
                  "a branch at its critical speed):"]
        for b in m.bearings:
            if not b.crossings:
                lines.append(f"  {b.name}: meets no branch within the map")
            for i, d, k, n in b.crossings:
                lines.append(f"  {b.name}: k{d}{d} {k / 1e3:,.4g} N/mm meets branch {i + 1} "
                             f"at {n:,.0f} r/min")
    lines += ["", f"basis: {m.basis} standstill and residual modes with the bearings at "
              f"{m.reference / 1e3:.4g} N/mm; on two thirds of it the map moves by at most "
              f"{m.change * 100:.2g} %"]
    return "\n".join(lines)


def ucs_csv(m) -> str:
    """stiffness (N/mm), then each branch's critical speed (r/min), one row a stiffness."""
    head = "stiffness_n_per_mm," + ",".join(f"branch_{i + 1}_rpm"
                                            for i in range(m.frequencies.shape[0]))
    rows = [f"{k / 1e3:.6g}," + ",".join(f"{v:.6g}" if math.isfinite(v) else ""
                                         for v in m.speeds_rpm[:, j])
            for j, k in enumerate(m.stiffness)]
    return "\n".join([head, *rows]) + "\n"


def level1_text(r) -> str:
    """API 684's Level I screening: log decrement against Q, Q_0, Q_A and the criteria."""
    lines = [f"scene {r.scene.name}: API 684 Level I stability screening at {r.speed_rpm:,.0f} "
             f"r/min (the highest operating speed), Q applied at {r.plane * 1e3:g} mm "
             f"({r.plane_why}); the stages' cross-coupling and the seals left out",
             f"first forward mode {r.frequency_hz:.2f} Hz, log decrement {r.log_dec_0:.4g} "
             "without Q", "", "      Q (N/mm)   log dec"]
    lines += [f"{q / 1e3:14,.1f}  {d:8.4f}" for q, d in zip(r.q, r.log_dec)]
    lines.append("")
    if r.q0 is None:
        lines.append("Q_0: " + ("none: the mode is unstable without Q" if r.log_dec_0 <= 0
                                else "the mode stays stable up to 1e10 N/mm"))
    else:
        lines.append(f"Q_0 = {r.q0 / 1e3:,.1f} N/mm: the log decrement falls to zero there")
    if r.qa is None:
        lines.append(f"Q_A: {r.qa_from}; give --qa-n-per-mm (or the stages' power) for the "
                     "criteria")
        return "\n".join(lines)
    ratio = "-" if r.ratio is None else f"{r.ratio:.2f}"
    da = "-" if r.log_dec_a is None else f"{r.log_dec_a:.4f}"
    lines.append(f"Q_A = {r.qa / 1e3:,.1f} N/mm ({r.qa_from}): log decrement {da} there, "
                 f"Q_0 / Q_A = {ratio}")
    verdict = ("PASS: Level I screening met" if r.passed else
               "FAIL: a Level II analysis is required")
    lines.append(f"{verdict} (API 617 8th ed. 2.6.5: Q_0 / Q_A >= 2 and log dec at Q_A "
                 ">= 0.1)")
    return "\n".join(lines)


# the passage of a critical speed: the run-up's envelope within this band of speeds
# about the steady response's peak (r/min, as fractions of its speed)
PASSAGE = (0.8, 1.25)


def runup_text(r) -> str:
    """A run-up's peaks beside the steady ones: the passage of each probe's steady peak
    (its envelope's largest value within PASSAGE of it) against the steady peak, and,
    where the run's largest response lies elsewhere, that too, and why it is no passage."""
    import numpy as np

    kind = "run-up" if r.accel_rpm_per_s > 0 else "coast-down"
    lines = [f"scene {r.scene.name}: {kind} at {abs(r.accel_rpm_per_s):,.4g} r/min per s from "
             f"{r.speeds_rpm[0]:,.0f} to {r.speeds_rpm[-1]:,.0f} r/min ({r.steps:,} time steps, "
             "Newmark), driven by the unbalances", "",
             "probe                        passage peak (um, 0-peak)   at (r/min)   steady peak "
             "(um)   at (r/min)"]
    notes = []
    lower = True
    for name, (n, amp), steady, envelope in zip(r.names, r.peaks, r.steady, r.envelopes):
        i = int(steady.argmax())
        at = r.speeds_rpm[i]
        near = (r.speeds_rpm >= PASSAGE[0] * at) & (r.speeds_rpm <= PASSAGE[1] * at)
        j = int(np.flatnonzero(near)[np.argmax(envelope[near])])
        passed, there = float(envelope[j]), float(r.speeds_rpm[j])
        lines.append(f"{name:28s} {passed * 1e6:25.3f} {there:12,.0f} {steady[i] * 1e6:18.3f} "
                     f"{at:12,.0f}")
        change = passed / steady[i] - 1
        lower = lower and change < 0
        later = (there - at) * (1 if r.accel_rpm_per_s > 0 else -1)
        notes.append(f"{name}: the passage's peak {abs(change) * 100:.2g} % "
                     f"{'below' if change < 0 else 'above'} the steady one, "
                     f"{abs(later):,.0f} r/min {'later' if later >= 0 else 'earlier'} in the "
                     "direction of travel")
        if amp > passed * (1 + 1e-9) and not (PASSAGE[0] * at <= n <= PASSAGE[1] * at):
            beside = float(np.interp(n, r.speeds_rpm, steady))
            notes.append(f"{name}: the run's largest response, {amp * 1e6:,.3g} um at "
                         f"{n:,.0f} r/min, is no passage of a critical speed: there the motion "
                         f"outgrows the steady response ({beside * 1e6:,.3g} um), free motion "
                         "the run does not damp out (a mode that grows above an onset of "
                         "instability)")
    lines += ["", *notes]
    if lower:
        lines.append("(passed at a finite rate, a lightly damped resonance has no time to "
                     "build up: its peak comes lower and later)")
    return "\n".join(lines)


def frf_text(r) -> str:
    """Each speed's largest receptance |H_xx| and |H_yy| and the frequency of it."""
    import numpy as np

    lines = [f"scene {r.scene.name}: receptance at {r.probe_at * 1e3:g} mm to a force at "
             f"{r.force_at * 1e3:g} mm, {r.frequencies_hz[0]:g} to {r.frequencies_hz[-1]:g} Hz",
             "", "   speed (r/min)   peak |H_xx| (um/N)   at (Hz)   peak |H_yy| (um/N)   at (Hz)"]
    for n, row in zip(r.speeds_rpm, r.H):
        hx, hy = np.abs(row[:, 0, 0]), np.abs(row[:, 1, 1])
        i, j = int(hx.argmax()), int(hy.argmax())
        lines.append(f"{n:16,.0f} {hx[i] * 1e6:20.4g} {r.frequencies_hz[i]:9.2f} "
                     f"{hy[j] * 1e6:20.4g} {r.frequencies_hz[j]:9.2f}")
    return "\n".join(lines)


def api684_rows(study) -> tuple[list[str], list[list[str]]]:
    """The rotordynamic study against API 684 (and API 617's Level I criteria): each
    item, what the rotor does, what is required, and the result; with several cases,
    each case's items as that case has them (the nominal one marked), and the cases the
    verdict fails in."""
    head = ["item", "the rotor", "required", "result"]
    if not study.cases:
        return head, _api684_case_rows(study.campbell, study.verdict, study.level1,
                                       study.unscreened)
    rows = []
    for r in study.cases:
        name = r.case.name + (" (the scene as given)" if r.case.name == "nominal" else "")
        # the study's own Level I screening is the nominal case's
        lv = r.level1 if r.level1 is not None or r.case.name != "nominal" else study.level1
        # the case named once, on its first row: the rows under it are its own
        rows += [[name if k == 0 else "", *row] for k, row in enumerate(
            _api684_case_rows(r.campbell, r.verdict, lv, study.unscreened))]
    failing = [r.case.name for r in study.cases if not r.verdict.ok]
    rows.append(["all cases", "the verdict (the worst case decides)",
                 "fails in: " + ", ".join(failing) if failing else "every case passes", "-",
                 "FAIL" if failing else "pass"])
    return ["case", *head], rows


def _api684_case_rows(c, verdict, lv, unscreened) -> list[list[str]]:
    """One case's rows of api684_rows: its Campbell run `c`, its verdict, its Level I
    screening `lv` (None: not run) and why Level I was left out (unscreened)."""
    from shaftfem.checks.whirl_check import api684_peaks, judged_peak, running_orbits

    rows = []
    crit = [a for a in verdict.approaches if "critical" in a.kind and not a.exempt]
    if crit:
        a = min(crit, key=lambda a: a.margin - a.required)
        rows.append(["separation margin of the critical speeds from the operating speeds",
                     f"{a.margin * 100:.1f} % ({a.kind})", f"{a.required * 100:.1f} %",
                     "pass" if a.margin >= a.required else "FAIL"])
    else:
        rows.append(["separation margin of the critical speeds from the operating speeds",
                     "no critical speed in the range", "-", "pass"])
    st = c.stability
    if st is not None:
        judged = st.judged
        rows.append(["least log decrement where the shaft runs",
                     f"{st.log_dec:.3g} ({st.whirl} whirl, {st.frequency_hz:.1f} Hz)",
                     f"above {st.required:g}" if judged else "not judged (no damping)",
                     ("pass" if st.log_dec > st.required else "FAIL") if judged else "-"])
    top = c.rotor_scene.rotor.top_speed * 30 / math.pi if c.rotor_scene.rotor else 0.0
    spans = [(lo * 30 / math.pi, hi * 30 / math.pi)
             for lo, hi in (c.rotor_scene.rotor.spans if c.rotor_scene.rotor else ())]
    lift = c.lift_rpm
    inside = [z for z in c.zones if z.to_rpm >= lift and any(
        z.from_rpm <= hi * (1 + 1e-9) and z.to_rpm >= lo * (1 - 1e-9) for lo, hi in spans)]
    rows.append(["zones of growth (instability)",
                 "; ".join(z.span_text.replace("from ", "", 1) for z in c.zones)
                 or "none in the diagram",
                 f"outside {_spans_text(spans)}" if spans else f"above {top:,.0f} r/min",
                 "FAIL" if inside else "pass"])
    if c.unbalance is not None:
        for p in c.unbalance.peaks:
            need = p.required_margin
            # judged as the verdict judges it (checks.whirl_check.judged_peak)
            rows.append([f"unbalance peak at {p.probe}",
                         ("unbounded (no damping)" if p.unbounded
                          else f"{p.amplitude * 1e6:,.3g} um")
                         + f" at {p.speed_rpm:,.0f} r/min, margin {p.margin * 100:.1f} %",
                         ("-" if need is None else f"{need * 100:.1f} % (AF "
                          f"{p.amplification:.1f})" if p.amplification else "-")
                         + ("" if api684_peaks(c.rotor_scene) or need is None
                            else ", for information (a flat margin is judged)"),
                         ("pass" if p.ok else "FAIL") if judged_peak(c.rotor_scene, p)
                         else "-"])
        limit = c.rotor_scene.rotor.amplitude_limit if c.rotor_scene.rotor else None
        # each probe's largest orbit on the Bode plot's speeds (what the verdict judges
        # against the limit, checks.whirl_check.response_findings) and where the shaft runs
        # (the worst probe of each: the verdict lists every probe that fails)
        anywhere = running_orbits(c, anywhere=True)
        if limit is not None and anywhere:
            amp, name, n = max((a, m, x) for m, a, x in anywhere)
            rows.append(["largest unbalance response (any probe, any speed)",
                         f"{amp * 1e6:,.3g} um at {name}, {n:,.0f} r/min",
                         f"{limit * 1e6:,.3g} um", "pass" if amp <= limit else "FAIL"])
        running = running_orbits(c)
        if running:
            amp, name, n = max((a, m, x) for m, a, x in running)
            rows.append(["unbalance response where the shaft runs (any probe)",
                         f"{amp * 1e6:,.3g} um at {name}, {n:,.0f} r/min",
                         "-" if limit is None else f"{limit * 1e6:,.3g} um",
                         "-" if limit is None else ("pass" if amp <= limit else "FAIL")])
    if lv is None and unscreened:
        rows.append(["Level I screening (API 617 8th ed.)", "not screened in this run",
                     "Q_0 / Q_A >= 2, log dec at Q_A >= 0.1", unscreened])
    if lv is not None:
        if lv.qa is None:
            rows.append(["Level I screening (API 617 8th ed.)",
                         "Q_0 " + ("-" if lv.q0 is None else f"{lv.q0 / 1e3:,.1f} N/mm"),
                         "Q_0 / Q_A >= 2, log dec at Q_A >= 0.1", "no Q_A given"])
        else:
            rows.append(["Level I screening (API 617 8th ed.)",
                         f"Q_0 / Q_A {lv.ratio:.2f}, log dec at Q_A {lv.log_dec_a:.3f}"
                         if lv.ratio is not None and lv.log_dec_a is not None else "-",
                         "Q_0 / Q_A >= 2, log dec at Q_A >= 0.1",
                         "pass" if lv.passed else "Level II required"])
    return rows


def cases_rows(results) -> tuple[list[str], list[list[str]]]:
    """The study's cases side by side (workflows.cases): each case's journals and seals
    (clearance, oil viscosity), its judged critical speeds (matched across the cases by
    order and rank) with their whirl, AF, margin and required margin, its least log decrement
    where the shaft runs, its Level I screening and its verdict."""
    head = ["", *(r.case.name for r in results)]
    rows: list[list[str]] = []

    def row(label: str, cell) -> None:
        rows.append([label, *(cell(r) for r in results)])

    for s in results[0].campbell.rotor_scene.supports:
        if s.journal is None and s.seal is None:
            continue

        def seat(r, name=s.name):
            return next(x for x in r.campbell.rotor_scene.supports if x.name == name)

        row(f"{s.name}: radial clearance, um",
            lambda r, seat=seat: f"{(seat(r).journal or seat(r).seal).clearance * 1e6:.1f}")
        if s.journal is not None and s.journal.oil_supply_temperature is not None:
            row(f"{s.name}: oil supply, C",
                lambda r, seat=seat: f"{seat(r).journal.oil_supply_temperature:g}")
        elif s.journal is not None:
            row(f"{s.name}: oil viscosity, mPa s",
                lambda r, seat=seat: f"{seat(r).journal.viscosity * 1e3:.2f}")
    loose = [a.name for a in results[0].campbell.rotor_scene.attachments if not a.joint_given]
    if loose:
        row(f"joint of {', '.join(loose)}", lambda r: next(
            a.joint for a in r.campbell.rotor_scene.attachments if not a.joint_given))

    def judged(r) -> dict[tuple[int, int], object]:
        # matched by order and rank: a mode's whirl on journals may turn with the film
        ranked = sorted((cs for cs in r.campbell.critical_speeds if not cs.critically_damped),
                        key=lambda cs: (cs.order, cs.speed_rpm))
        out: dict[tuple[int, int], object] = {}
        for cs in ranked:
            out[(cs.order, 1 + sum(1 for k in out if k[0] == cs.order))] = cs
        return out

    crits = [judged(r) for r in results]

    def critical(r, key):
        return crits[results.index(r)].get(key)

    def pair(r, cs):
        return min((a for a in r.verdict.approaches if a.order == cs.order and a.kind.endswith(
            f"critical at {cs.speed_rpm:,.0f} r/min")),
            key=lambda a: a.margin - a.required, default=None)

    for key in sorted({k for c in crits for k in c}):
        name = f"{key[0]}x critical speed {key[1]}"

        def speed(r, key=key):
            cs = critical(r, key)
            return "none" if cs is None else f"{cs.speed_rpm:,.0f} ({cs.whirl})"

        def af(r, key=key):
            cs = critical(r, key)
            return ("-" if cs is None or not math.isfinite(cs.amplification)
                    else f"{cs.amplification:.1f}")

        def margin(r, key=key):
            cs = critical(r, key)
            a = None if cs is None else pair(r, cs)
            return "-" if a is None else f"{a.margin * 100:.1f} ({a.required * 100:.1f})"

        row(f"{name}, r/min", speed)
        row(f"{name}: AF", af)
        row(f"{name}: margin (required), %", margin)

    def least(r):
        st = r.campbell.stability
        return "-" if st is None else f"{st.log_dec:.3g} ({st.frequency_hz:.1f} Hz)"
    row("least log decrement where the shaft runs", least)
    if any(r.level1 is not None for r in results):
        row("Level I: Q_0, N/mm", lambda r: "-" if r.level1 is None or r.level1.q0 is None
            else f"{r.level1.q0 / 1e3:,.1f}")
        row("Level I: Q_0 / Q_A (2 required)", lambda r: "-" if r.level1 is None
            or r.level1.ratio is None else f"{r.level1.ratio:.2f}")
        row("Level I: log decrement at Q_A (0.1 required)", lambda r: "-" if r.level1 is None
            or r.level1.log_dec_a is None else f"{r.level1.log_dec_a:.3f}")
    row("verdict", lambda r: "PASS" if r.verdict.ok else "FAIL")
    return head, rows


def cases_text(results) -> str:
    """The cases side by side, as `check` prints them."""
    head, rows = cases_rows(results)
    return "\n".join(["the study's cases (the verdict takes the worst):",
                      *aligned([head, *rows], left=set(range(len(head))))])


def bearing_speeds(c) -> list[float]:
    """The speeds (r/min) the bearings' coefficients are tabulated at: the operating
    speeds and range ends, and a quarter, half, three quarters and all of the diagram's
    top, those below the journals' lift-off left out (the film's values are placeholders
    there)."""
    rotor = c.rotor_scene.rotor
    top = max(c.speeds_rpm)
    ends = {x * 30 / math.pi for span in rotor.spans for x in span}
    wanted = sorted(ends | {f * top for f in (0.25, 0.5, 0.75, 1.0)})
    return [n for n in wanted if n >= c.lift_rpm and n > 0]


def bearing_rows(cases) -> tuple[list[str], list[list[str]]]:
    """Each speed-dependent bearing's and seal's eight coefficients against speed, for
    each case: `cases` a list of (case name, Campbell run)."""
    head = ["case", "bearing", "speed, r/min", "kxx, N/mm", "kxy", "kyx", "kyy",
            "cxx, N s/mm", "cxy", "cyx", "cyy"]
    rows = []
    for name, c in cases:
        for s in c.rotor_scene.held:
            b = s.bearing
            if b is None or not b.speeds:
                continue
            for n in bearing_speeds(c):
                w = n * math.pi / 30
                (kxx, kxy), (kyx, kyy) = b.stiffness(w)
                (cxx, cxy), (cyx, cyy) = b.damping(w)
                rows.append([name, s.name, f"{n:,.0f}",
                             *_coefficients((kxx, kxy, kyx, kyy)),
                             *_coefficients((cxx, cxy, cyx, cyy))])
    return head, rows


def _coefficients(values) -> list[str]:
    """Four coefficients (SI, N/m or N s/m) per mm, as a bearing's table prints them:
    thousands whole and separated, the rest to four figures, and a term below 1e-4 of
    the largest (a pad's cross term) as the zero it is."""
    v = [x / 1e3 for x in values]
    big = max(abs(x) for x in v)
    return ["0" if abs(x) < 1e-4 * big else f"{x:,.0f}" if abs(x) >= 1e3 else f"{x:.4g}"
            for x in v]


# the whirl ratios (whirl over spin) a tilting pads' bearing's coefficients are tabled at
WHIRL_RATIOS = (0.25, 0.5, 0.75, 1.0, 1.5, 2.0)


def pad_rows(c) -> tuple[list[str], list[list[str]]]:
    """Each tilting pads' bearing's coefficients at the first operating speed against the
    whirl's frequency (its tilts condensed at each: BearingCoefficients.at_whirl): a
    Campbell run `c`."""
    head = ["bearing", "speed, r/min", "whirl / spin", "kxx, N/mm", "kxy", "kyx", "kyy",
            "cxx, N s/mm", "cxy", "cyx", "cyy"]
    rows = []
    w = c.rotor_scene.rotor.speeds[0]
    for s in c.rotor_scene.held:
        if s.bearing is None or s.bearing.pads is None:
            continue
        for r in WHIRL_RATIOS:
            K, C = s.bearing.at_whirl(w, r * w)
            rows.append([s.name, f"{w * 30 / math.pi:,.0f}", f"{r:g}",
                         *_coefficients(K.ravel()), *_coefficients(C.ravel())])
    return head, rows


def _degrees(angle: float) -> str:
    """An angle about the axis (rad) in whole degrees, 0 to 359 (359.7 deg is 0)."""
    return f"{round(math.degrees(angle)) % 360:d}"


def strength_text(result) -> str:
    """What `shaftfem strength` prints: the material, each hot spot's stresses with
    their bound and FKM's utilisations, the seats' slopes and deflections against their
    limits, and the verdict (a workflows.strength.StrengthResult)."""
    import math

    scene, st = result.scene, result.scene.strength
    turning = st.speed > 0
    places = [f"{s.feature} z {s.z * 1e3:.1f} mm {_degrees(s.angle)} deg" for s in result.spots]
    w = _width(places, "where", 34)
    lines = [f"scene {scene.name}: strength under the duty"
             + (f" at {st.speed * 60 / (2 * math.pi):,.0f} r/min" if turning else
                " (standing: no fatigue cycle from the radial loads)"),
             f"material R_m {st.tensile_strength / 1e6:,.0f} MPa, R_p0.2 "
             f"{st.yield_strength / 1e6:,.0f} MPa at {st.strength_diameter * 1e3:g} mm "
             f"({st.source}); R_z {st.roughness * 1e6:g} um; required safeties: fatigue "
             f"{st.fatigue_safety:g}, yield {st.yield_safety:g} at {st.peak_factor:g} x the duty",
             f"meshes solved: {', '.join(f'{d:,}' for d in result.dofs)} DOFs; bound wanted "
             f"on each hot spot's stress: {result.target:.1%}", *local_lines(result),
             *result.notes,
             *([travel_line(result)] if result.travel else []), "",
             "hot spots (worst first; stresses von Mises, MPa; a: amplitude over a turn, "
             "m: mean, signed):",
             f"{'#':>2s} {'where':{w}s} {'a':>7s} {'m':>7s} {'peak':>7s} {'bound':>10s} "
             f"{'G 1/mm':>7s} {'n':>5s} {'K_WK':>5s} {'K_AK':>5s} {'S_fat':>6s} {'a_BK':>5s} "
             f"{'S_yld':>6s} {'a_SK':>5s}"]
    for k, (s, where) in enumerate(zip(result.spots, places), 1):
        bound = ("sharp" if not s.converging else "unresolved" if not s.resolved else
                 "?" if s.bound is None else f"+-{s.bound:.1%}")
        f = s.fkm
        lines.append(f"{k:2d} {where:{w}s} {s.amplitude / 1e6:7.1f} {_mpa(s.mean):7.1f} "
                     f"{s.peak / 1e6:7.1f} {bound:>10s} {s.gradient * 1e-3:7.3f} "
                     f"{f.support:5.3f} {f.design:5.3f} {f.mean_stress:5.3f} "
                     f"{_safety(f.fatigue_safety):>6s} {f.fatigue_utilisation:5.2f} "
                     f"{_safety(f.yield_safety):>6s} {f.yield_utilisation:5.2f}")
    if not result.spots:
        lines.append("   none: every surface point lies where a load or reaction enters")
    notched = notch_factor_lines(result)
    if notched:
        lines += ["", *notched]
    ws = _width([c.name for c in result.seats], "seat or part", 24)
    lines += ["", "S_fat, S_yld: safety against fatigue (FKM, infinite life) and yield; a_BK, "
              "a_SK: degree of utilisation with the required safety (<= 1 passes)", "",
              f"{'seat or part':{ws}s} {'at':>9s} {'slope':>10s} {'limit':>10s} "
              f"{'deflection':>12s} {'limit':>10s}  source"]
    for c in result.seats:
        lim = "-" if c.slope_limit is None else f"{c.slope_limit * 1e3:.2f} mrad"
        dlim = "-" if c.deflection_limit is None else f"{c.deflection_limit * 1e6:.1f} um"
        lines.append(f"{c.name:{ws}s} {c.position * 1e3:6.1f} mm {c.slope * 1e3:5.3f} mrad "
                     f"{lim:>10s} {c.deflection * 1e6:9.2f} um {dlim:>10s}  {c.source}"
                     + ("" if c.ok else "  EXCEEDED"))
    lines += ["", "verdict: " + strength_verdict(result)]
    return "\n".join(lines)


def strength_verdict(result, short: bool = False) -> str:
    """The strength check's verdict in a line: each check, the sharp edges, the bounds
    (`short`: what and where only, for a report's opening banner)."""
    checks = [("fatigue", result.fatigue_ok), ("yield", result.yield_ok),
              ("deflection", result.deflection_ok)]
    line = ", ".join(f"{w} {'ok' if ok else 'FAILS'}" for w, ok in checks)
    sharp = [k for k, s in enumerate(result.spots, 1) if not s.converging]
    loose = [k for k, s in enumerate(result.spots, 1) if s.converging and not (
        s.resolved and s.bound is not None and s.bound <= result.target)]
    if sharp:
        line += f"; NOT JUDGED at hot spot(s) {', '.join(map(str, sharp))}: " + (
            "sharp edges (their stress rises as the mesh refines)" if short else
            "their stress rises as the mesh refines, faster than a smooth notch's: a sharp "
            "edge of the geometry, whose elastic stress has no limit (round it), or a notch "
            "far finer than the mesh (give it finer [mesh] sizes)")
    elif loose:
        line += (f"; hot spot(s) {', '.join(map(str, loose))} not bounded to "
                 f"{result.target:.1%}" + ("" if short else
                 " (a bound above it, unknown ('?'), or a notch finer than the mesh there "
                 "('unresolved'): the refinement stopped at its rounds or the DOF budget; give "
                 "finer [mesh] sizes or raise [mesh] max_dofs)"))
        known = [] if short else [
            (max(sp.fkm.fatigue_utilisation, sp.fkm.yield_utilisation) * (1 + sp.bound), k)
            for k, sp in enumerate(result.spots, 1)
            if sp.converging and sp.resolved and sp.bound is not None]
        unknown = [] if short else [
            (max(sp.fkm.fatigue_utilisation, sp.fkm.yield_utilisation), k)
            for k, sp in enumerate(result.spots, 1)
            if sp.converging and not (sp.resolved and sp.bound is not None)]
        if unknown and (not known or max(unknown)[0] > max(known)[0]):
            # a spot without a bound above every bounded one: say so first, lest the
            # bounded ones' largest read as the shaft's
            read, k = max(unknown)
            line += (f"; the largest degree of utilisation read is {read:.2f} (hot spot {k}, "
                     "its bound unknown, and a notch the mesh does not follow reads low)")
        if known:
            worst, k = max(known)
            line += (f"; with each known bound taken against it, the largest degree of "
                     f"utilisation is {worst:.2f} (hot spot {k})")
    return line


def notch_factor_lines(result) -> list[str]:
    """The hot spots on shoulder fillets with their K_t beside the table's, a line each."""
    from shaftfem.checks.notch_tables import SOURCE

    rows = [f"{k:2d} {s.feature}, {f[0].large * 1e3:g}/{f[0].small * 1e3:g} mm, r "
            f"{f[0].radius * 1e3:g} mm: " + ", ".join(
                f"{n.load} {n.computed:.2f} ("
                + ("outside the chart" if n.table is None else f"chart {n.table:.2f}") + ")"
                for n in f) + ("" if s.resolved else
                               " - the mesh does not follow the fillet there: these are low")
            for k, s in enumerate(result.spots, 1) if (f := s.factors)]
    if not rows:
        return []
    return [f"stress concentration at shoulder fillets: K_t from the solid (largest principal "
            f"stress, in torsion largest shear, over the nominal stress of the smaller "
            f"diameter from what the section carries) beside {SOURCE}, which holds "
            "for each load alone, far from seats and loads:", *rows]


def _safety(value: float) -> str:
    return ">99" if value > 99 else f"{value:.2f}"


def travel_line(result) -> str:
    """Where the travelling loads were screened and the worst place, judged: a line (''
    when no load travels)."""
    if not result.travel:
        return ""
    worst = result.travel[result.worst_place]
    return (f"The travelling loads were screened at {len(result.travel)} places from "
            f"{result.travel[0].position * 1e3:.1f} to {result.travel[-1].position * 1e3:.1f} "
            "mm on the coarser mesh (worst degree of utilisation at each: "
            + ", ".join(f"{t.position * 1e3:.1f} mm {t.utilisation:.2f}" for t in result.travel)
            + f"). The hot spots are those of the worst place, {worst.position * 1e3:.1f} mm; "
            "each seat is at the place that tilts it most.")


def local_lines(result) -> list[str]:
    """A line on the hot spots bounded in local models (none where there are none)."""
    local = [(k, s.local_dofs) for k, s in enumerate(result.spots, 1) if s.local_dofs]
    if not local:
        return []
    dofs = sorted(d for _, d in local)
    span = f"{dofs[0]:,}" if dofs[0] == dofs[-1] else f"{dofs[0]:,} to {dofs[-1]:,}"
    return [f"bounded in local models: hot spot(s) {', '.join(str(k) for k, _ in local)}, "
            f"each in a slice of the solid round it ({span} DOFs), its cut faces moved and "
            "loaded as the whole shaft's finest mesh says"]


def strength_intro(result) -> str:
    """The strength section's line on the material, the safeties and the meshes."""
    st = result.scene.strength
    return (f"Material R_m {st.tensile_strength / 1e6:,.0f} MPa, R_p0.2 "
            f"{st.yield_strength / 1e6:,.0f} MPa ({st.source}), R_z {st.roughness * 1e6:g} um; "
            f"required safeties {st.fatigue_safety:g} (fatigue, FKM j_D) and "
            f"{st.yield_safety:g} (yield, at {st.peak_factor:g} x the duty). Meshes solved: "
            + ", ".join(f"{d:,}" for d in result.dofs) + " DOFs."
            + "".join(f" {line[0].upper()}{line[1:]}." for line in local_lines(result))
            + (" " + travel_line(result) if result.travel else ""))


def strength_spot_rows(result) -> tuple[list[str], list[list[str]]]:
    """The hot spots' table: where, the stresses with their bound, FKM's safeties."""

    rows = [[str(k), s.feature, f"{s.z * 1e3:.1f}", _degrees(s.angle),
             f"{s.amplitude / 1e6:.1f}", f"{_mpa(s.mean):.1f}", f"{s.peak / 1e6:.1f}",
             "sharp edge" if not s.converging else "unresolved" if not s.resolved
             else "?" if s.bound is None else f"{s.bound:.1%}",
             f"{s.gradient * 1e-3:.3f}", _safety(s.fkm.fatigue_safety),
             f"{s.fkm.fatigue_utilisation:.2f}", _safety(s.fkm.yield_safety),
             f"{s.fkm.yield_utilisation:.2f}"] for k, s in enumerate(result.spots, 1)]
    return (["#", "hot spot", "z (mm)", "angle (deg)", "amplitude (MPa)", "mean (MPa)",
             "peak (MPa)", "bound", "G (1/mm)", "fatigue safety", "a_BK", "yield safety",
             "a_SK"], rows)


def strength_seat_rows(result) -> tuple[list[str], list[list[str]]]:
    """The seats' and parts' slopes and deflections against their limits."""
    rows = [[c.name, f"{c.position * 1e3:.1f}", f"{c.slope * 1e3:.3f}",
             "-" if c.slope_limit is None else f"{c.slope_limit * 1e3:.2f}",
             f"{c.deflection * 1e6:.2f}",
             "-" if c.deflection_limit is None else f"{c.deflection_limit * 1e6:.1f}",
             c.source, "ok" if c.ok else "EXCEEDED"] for c in result.seats]
    return (["seat or part", "at (mm)", "slope (mrad)", "limit (mrad)", "deflection (um)",
             "limit (um)", "limit's source", ""], rows)


def strength_markdown(result) -> list[str]:
    """The design report's strength section (a workflows.strength.StrengthResult): the
    verdict, the hot spots and the seats as Markdown tables."""
    lines = ["**" + strength_verdict(result) + "**", "", strength_intro(result), "",
             *(x for n in result.notes for x in (n, ""))]
    lines += markdown(*strength_spot_rows(result)) + [""]
    notched = notch_factor_lines(result)
    if notched:
        lines += [notched[0], "", *(f"- {r.strip()}" for r in notched[1:]), ""]
    lines += markdown(*strength_seat_rows(result))
    return lines


def _mpa(stress: float) -> float:
    """A signed stress in MPa as printed to 0.1 MPa, without a minus on a zero ("-0.0")."""
    return round(stress / 1e6, 1) + 0.0
