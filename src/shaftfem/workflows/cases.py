"""The cases an API 684 study runs: the bearings' tolerance ends and the parts' joints.

A journal's film, and a seal's, change with their clearance and the oil's viscosity,
both known only within a tolerance. Rotor engineers bracket them with two cases beside
the nominal one:

- minimum clearance with cold oil: the stiffest, most damping films;
- maximum clearance with hot oil: the softest, least damping ones.

A part shrunk on the shaft stiffens the stretch under its hub by an amount between
none (`joint = "distributing"`) and all of it (`"rigid"`, the default). Where the scene
does not say, both are run. Each case is its own scene (its journals' and seals'
coefficients, its joints), solved and judged as the nominal one is; the verdict takes
the worst (`combined`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from shaftfem.runtime import RunOptions

if TYPE_CHECKING:
    from shaftfem.checks.resonance import ResonanceVerdict
    from shaftfem.fem.whirl import Campbell, Level1
    from shaftfem.scene.model import Scene, Support

OTHER_JOINT = {"rigid": "distributing", "distributing": "rigid"}


@dataclass(frozen=True)
class Case:
    """One case of the study: which end of the tolerance ranges its clearances
    ("min", "nominal", "max") and its oil ("cold", "nominal", "hot") take, and the joint
    of every part whose scene table gives none (None: the default)."""

    name: str
    clearance: str = "nominal"
    oil: str = "nominal"
    joint: str | None = None


def cases_of(scene: Scene) -> tuple[Case, ...]:
    """The study's cases: the nominal one; minimum clearance with cold oil and maximum
    clearance with hot oil where a journal or seal gives a range (all four corners of
    clearance and oil with [rotor] tolerance_cases = "corners"); the parts' other
    joint where a part leaves its joint to the default. One case: nothing to bracket."""
    spans = [s.tolerance for s in scene.supports if s.tolerance is not None]
    clear = any(t.clearance is not None for t in spans)
    oil = any(t.viscosity is not None or t.temperature is not None for t in spans)
    out = [Case("nominal")]
    if clear or oil:
        words = [w for w, on in (("clearance", clear), ("oil", oil)) if on]
        ends = [("min", "cold"), ("max", "hot")]
        if clear and oil and scene.rotor is not None and scene.rotor.tolerance_cases == "corners":
            ends += [("min", "hot"), ("max", "cold")]   # the other two corners, on request
        for c, o in ends:
            name = ", ".join(f"{c} clearance" if w == "clearance" else f"{o} oil" for w in words)
            out.append(Case(name, clearance=c if clear else "nominal",
                            oil=o if oil else "nominal"))
    loose = sorted({a.joint for a in scene.attachments if not a.joint_given})
    for joint in loose:
        out.append(Case(f"{OTHER_JOINT[joint]} joints", joint=OTHER_JOINT[joint]))
    return tuple(out)


def _end(span: tuple[float, float, float] | None, end: str) -> float | None:
    if span is None:
        return None
    return {"min": span[0], "nominal": span[1], "max": span[2]}[end]


def case_support(s: Support, case: Case, scene: Scene) -> Support:
    """A journal's or seal's support at the case's ends of its tolerance ranges: its
    clearance and its oil (a viscosity, or the temperature of an oil given by its
    grade), its coefficients cleared for its part to give again (workflows.equip)."""
    t = s.tolerance
    if t is None or (case.clearance == "nominal" and case.oil == "nominal"):
        return s
    clearance = _end(t.clearance, case.clearance)
    # cold oil: the most viscous, at the lowest temperature
    hot = {"cold": "min", "hot": "max", "nominal": "nominal"}[case.oil]
    if s.journal is not None:
        j = replace(s.journal, clearance=clearance or s.journal.clearance)
        if t.temperature is not None and j.oil_supply_temperature is not None:
            j = replace(j, oil_supply_temperature=_end(t.temperature, hot), viscosity=None)
        elif t.temperature is not None:
            j = replace(j, oil_temperature=_end(t.temperature, hot), viscosity=None)
        elif t.viscosity is not None:
            j = replace(j, viscosity=_end(t.viscosity, {"min": "max", "max": "min",
                                                        "nominal": "nominal"}[hot]))
        return replace(s, journal=j, bearing=None)
    if s.seal is not None and clearance is not None:
        return replace(s, seal=replace(s.seal, clearance=clearance), bearing=None)
    return s


def case_scene(scene: Scene, case: Case) -> Scene:
    """The scene as the case has it: its journals and seals at the case's tolerance
    ends, and its parts without a joint of their own on the case's."""
    supports = tuple(case_support(s, case, scene) for s in scene.supports)
    attachments = tuple(replace(a, joint=case.joint) if case.joint and not a.joint_given
                        else a for a in scene.attachments)
    return replace(scene, supports=supports, attachments=attachments)


@dataclass(frozen=True)
class CaseResult:
    """One case solved and judged: its Campbell run, its verdict and its Level I
    screening (None where the scene asks for none)."""

    case: Case
    campbell: Campbell
    verdict: ResonanceVerdict
    level1: Level1 | None


def run_case(scene: Scene, case: Case, margin: float | None = None,
             options: RunOptions = RunOptions()) -> CaseResult:
    """One case's Campbell run, verdict and Level I screening."""
    from shaftfem.checks.whirl_check import check_whirl, with_level1
    from shaftfem.workflows.campbell import run_campbell

    s = case_scene(scene, case)
    c = run_campbell(s, options)
    verdict = check_whirl(c, margin)
    level1 = None
    if s.rotor is not None and s.rotor.level1:
        from shaftfem.workflows.level1 import run_level1

        level1 = run_level1(s, options=options)
        verdict = with_level1(verdict, level1)
    return CaseResult(case, c, verdict, level1)


def run_cases(scene: Scene, margin: float | None = None,
              options: RunOptions = RunOptions()) -> list[CaseResult]:
    """Every case of the study (cases_of) solved and judged, the nominal first."""
    out = []
    for case in cases_of(scene):
        if case.name != "nominal":
            options.say(f"the case: {case.name}")
        out.append(run_case(scene, case, margin, options))
    return out


def combined(results: list[CaseResult]) -> ResonanceVerdict:
    """The study's verdict over its cases, the worst of them: every case's pairs (each
    named by its case) and every case's reasons to fail; a pass only if every case
    passes."""
    from shaftfem.checks.resonance import ResonanceVerdict

    first = results[0].verdict
    if len(results) == 1:
        return first

    def named(text: str, r: CaseResult) -> str:
        return f"{r.case.name}: {text}"

    approaches = [replace(a, source=f"{a.source} ({r.case.name})")
                  for r in results for a in r.verdict.approaches]
    approaches.sort(key=lambda a: (a.exempt, a.margin - a.required))
    unstable = [named(u, r) for r in results for u in r.verdict.unstable]
    underdamped = [named(u, r) for r in results for u in r.verdict.underdamped]
    response = [named(u, r) for r in results for u in r.verdict.response]
    warnings = list(first.warnings)   # the nominal case's, then what the others add
    for r in results[1:]:
        warnings += [named(w, r) for w in r.verdict.warnings if w not in first.warnings]
    turning = ((first.turning or "") + f"; {len(results)} cases ("
               + ", ".join(r.case.name for r in results) + "), the verdict takes the worst")
    return ResonanceVerdict(approaches=approaches, required=first.required,
                            free_free=first.free_free,
                            free_free_intended=first.free_free_intended, turning=turning,
                            unstable=unstable, underdamped=underdamped,
                            warnings=warnings, response=response)
