"""The design report: one Markdown file with the tables, the pictures and a verdict."""

from __future__ import annotations

from pathlib import Path

from .export import atomic_path


def _table(head: list[str], rows: list[list[str]]) -> list[str]:
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return out


def verdict_line(verdict) -> str:
    if verdict.ok:
        a = verdict.approaches[0]
        return (f"**VERDICT: PASS** - no natural frequency within {100 * verdict.required:g} % "
                f"of any excitation harmonic (closest: mode {a.mode}, {a.frequency:.1f} Hz, vs "
                f"{a.source} x{a.order} at {a.excitation:.1f} Hz: {100 * a.margin:.0f} % apart)")
    a = verdict.violations[0]
    return (f"**VERDICT: FAIL** - mode {a.mode} ({a.frequency:.1f} Hz, {a.kind}) is only "
            f"{100 * a.margin:.1f} % from {a.source} x{a.order} at {a.excitation:.1f} Hz "
            f"(required {100 * verdict.required:g} %)")


def write_report(path: str | Path, result, verdict, sizing=None, pictures=(),
                 files=(), estimate=None) -> Path:
    """report.md beside the exported files; picture paths are written relative to it."""
    path = Path(path)
    scene, m = result.scene, result.modes
    lines = [f"# Modal design report: {scene.name}", "", verdict_line(verdict), ""]
    g = scene.grooves
    lines += ["## Shaft", "",
              f"- {scene.shaft.length * 1e3:g} mm long, {scene.shaft.diameter * 1e3:g} mm "
              f"diameter, {scene.material.name} (E = {scene.material.youngs_modulus / 1e6:g} MPa, "
              f"nu = {scene.material.poisson_ratio:g}, rho = {scene.material.density:g} kg/m^3)"]
    if g:
        hands = " and ".join("right" if h > 0 else "left" for h in g.hands)
        lines.append(f"- grooves: {hands}-hand, pitch {g.pitch * 1e3:g} mm, width "
                     f"{g.width * 1e3:g} mm (axial), depth {g.depth * 1e3:g} mm, root radius "
                     f"{g.root_radius * 1e3:g} mm, over {g.length * 1e3:g} mm from "
                     f"{g.start * 1e3:g} mm; removed volume {result.shape.groove_volume_cad * 1e9:.1f}"
                     f" mm^3 (analytic {result.shape.groove_volume_analytic * 1e9:.1f} mm^3)")
    lines += [f"- mesh: P{scene.mesh.order}, {m.n_dofs} DOFs, {result.mesh.n_elements} elements",
              ""]
    if sizing is not None:
        lines += ["## Sizing (paper equations 1-9)", ""]
        lines += _table(["eq.", "symbol", "value", "unit", "quantity", "note"],
                        [[q.equation, q.symbol, f"{q.value:.4g}", q.unit, q.name, q.note]
                         for q in sizing.quantities])
        lines += [""] + [f"- LIMIT BROKEN: {v}" for v in sizing.violations] + [""]
    lines += ["## Natural frequencies (free-free)", ""]
    rows = []
    for i, (f, kind, r) in enumerate(zip(m.frequencies, m.kinds, m.residuals)):
        err = ""
        if estimate is not None:
            err = f"{100 * estimate.relative_error[i]:.2g} %"
            err += f" (p = {estimate.observed_order[i]:.2f})"
            err += "" if estimate.reliable[i] else " unreliable"
        rows.append([str(i + 1), f"{f:.2f}", kind, f"{r:.1e}", err])
    lines += _table(["mode", "frequency (Hz)", "kind", "residual", "estimated error"], rows)
    lines += ["", f"Rigid-body modes: {m.n_rigid}."]
    if estimate is not None:
        lines += [f"Estimated error: three meshes (sizes x1, x{estimate.ratio:g}, "
                  f"x{estimate.ratio**2:g}), observed order p per mode."] + estimate.notes()
    lines.append("")
    lines += ["## Resonance check", ""]
    lines += _table(
        ["source", "order", "excitation (Hz)", "closest mode", "frequency (Hz)", "margin",
         "required", ""],
        [[a.source, str(a.order), f"{a.excitation:.2f}", str(a.mode), f"{a.frequency:.2f}",
          f"{100 * a.margin:.1f} %", f"{100 * a.required:g} %", "ok" if a.ok else "TOO CLOSE"]
         for a in verdict.closest_per_harmonic()])
    lines.append("")
    if pictures:
        lines += ["## Pictures", ""]
        lines += [f"![{Path(p).stem}]({Path(p).name})" for p in pictures] + [""]
    if files:
        lines += ["## Files", ""] + [f"- `{Path(f).name}`" for f in files] + [""]
    t = result.seconds
    lines += ["## Run time", "", ", ".join(f"{k} {v:.1f} s" for k, v in t.items()), ""]
    with atomic_path(path) as tmp:
        tmp.write_text("\n".join(lines))
    return path


# --------------------------------------------------------------------------
# The paper's Table 2 beside ours

# ANSYS, 1 mm elements, free-free, rigid-body modes not listed (Fu et al. 2018, Table 2)
PAPER_TABLE2_HZ = (432.16, 433.60, 1158.30, 1166.40, 2149.90, 2195.20, 3500.60, 3594.30,
                   3687.50, 5257.80)


def paper_comparison(result) -> list[dict]:
    """Mode by mode: the paper's frequency, ours, the difference and the ratios to mode 1."""
    f = result.modes.frequencies
    rows = []
    for i, (p, ours, kind) in enumerate(zip(PAPER_TABLE2_HZ, f, result.modes.kinds)):
        rows.append({"mode": i + 1, "paper_hz": p, "shaftfem_hz": float(ours), "kind": kind,
                     "difference_percent": 100 * (ours / p - 1),
                     "paper_ratio_to_mode1": p / PAPER_TABLE2_HZ[0],
                     "shaftfem_ratio_to_mode1": float(ours / f[0])})
    return rows


def format_paper_comparison(result) -> str:
    s, m = result.scene.shaft, result.scene.material
    ct = (m.shear_modulus / m.density) ** 0.5
    torsion = ct / (2 * s.length)
    lines = [f"{'mode':>4} {'paper':>10} {'shaftfem':>10} {'diff':>8}  {'kind':<8} "
             f"{'f/f1 paper':>10} {'f/f1 ours':>10}"]
    for r in paper_comparison(result):
        lines.append(f"{r['mode']:>4} {r['paper_hz']:>7.2f} Hz {r['shaftfem_hz']:>7.2f} Hz "
                     f"{r['difference_percent']:>+7.1f} %  {r['kind']:<8} "
                     f"{r['paper_ratio_to_mode1']:>10.3f} {r['shaftfem_ratio_to_mode1']:>10.3f}")
    nearest = min(PAPER_TABLE2_HZ, key=lambda p: abs(p - torsion))
    lines += [
        "",
        f"first torsion of a uniform {s.diameter * 1e3:g} mm shaft {s.length * 1e3:g} mm long: "
        f"c_t / 2L = {torsion:.0f} Hz; the paper's nearest mode is {nearest:.1f} Hz "
        f"({100 * (nearest / torsion - 1):+.0f} %)",
    ]
    return "\n".join(lines)


STUDY_COLUMNS = ["element", "size_mm", "dofs", "mesh_s", "assembly_s", "factorisation_s",
                 "eigensolve_s", "total_s", "peak_memory_mb", "max_rel_error"]


def study_markdown(rows: list[dict], estimate, order: int) -> str:
    """The study table in Markdown, with how its reference was made."""
    lines = _table(STUDY_COLUMNS, [
        [f"{r[c]:.2e}" if c == "max_rel_error" else str(r[c]) for c in STUDY_COLUMNS]
        for r in rows])
    lines += ["", f"Reference: Richardson extrapolation of the three finest P{order} runs; "
              "observed order per mode: "
              + ", ".join(f"{p:.2f}" for p in estimate.observed_order)]
    lines += estimate.notes()
    return "\n".join(lines) + "\n"
