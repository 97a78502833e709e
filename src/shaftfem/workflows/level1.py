"""API 684's Level I stability screening (API 617, 8th edition, 2014, section 2.6.5): a
cross-coupled stiffness Q (kxy = Q, kyx = -Q) applied at the impeller, or at mid-span
between the bearings, at the highest operating speed; the first forward mode's log
decrement against Q; Q_0, where it falls to zero; and at the anticipated Q_A (the
stages' Wachel estimate, or a value given) the log decrement delta_A and the ratio
Q_0 / Q_A. Q_0 is where the first of the lowest four forward lateral modes turns
unstable, and the mode screened is that one, followed over Q by its frequency: on stiff
bearings it is the first forward mode (as in ross), but on soft ones heavily damped
rigid-body modes can lie below the forward bending mode that Q destabilises.

API 617's criteria: the rotor passes the screening when Q_0 / Q_A >= 2 and
delta_A >= 0.1; otherwise a Level II analysis (every destabilising source modelled) is
required. As ross's run_level1 does, the stages' own cross-coupling and the seals are
left out of the rotor the screening loads (Q stands for them).

The rotor is the turning shaft's reduced model (workflows.campbell.turning); Q acts on
the mean motion of the shaft's section at its plane, as a bearing would, so each Q is
one small eigenproblem, and Q_0 is found by root finding on them.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.whirl import Level1
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import BearingCoefficients, Scene

if TYPE_CHECKING:
    from shaftfem.fem.rotor import BearingModal, RotorModel

# API 617's Level I criteria
RATIO_MIN = 2.0
LOG_DEC_MIN = 0.1
POINTS = 20
# where the log decrement changes by more than this share of its range between two
# steps of Q, their middle is solved too: at most REFINE_MAX middles a round, REFINE_ROUNDS
# rounds
STEEP = 0.1
REFINE_MAX = 12
REFINE_ROUNDS = 3
# the lowest forward modes screened; the least damped of them is the one judged
FORWARD = 4


def cross(q: float) -> BearingCoefficients:
    """A cross-coupled stiffness q (N/m): the force a quarter turn ahead of the motion."""
    return BearingCoefficients(speeds=(), kxx=(0.0,), kxy=(q,), kyx=(-q,), kyy=(0.0,),
                               cxx=(0.0,), cxy=(0.0,), cyx=(0.0,), cyy=(0.0,))


def forward_modes(model: RotorModel, omega: float) -> list[tuple[float, float]]:
    """The lowest FORWARD forward lateral modes at the spin omega (rad/s): (frequency Hz,
    log decrement) each, lowest first."""
    from shaftfem.workflows.campbell import whirl_at

    rows = whirl_at(model, omega, model.size)
    ahead = sorted((w for w in rows if w.whirl == "forward"
                    and w.kind not in ("torsion", "axial")), key=lambda w: w.frequency_hz)
    if not ahead:
        raise SceneError("no forward whirling mode in the basis at the highest operating "
                         "speed: Level I screens the first forward modes")
    return [(w.frequency_hz, w.log_dec) for w in ahead[:FORWARD]]


def screening_plane(scene: Scene, at: float | None) -> tuple[float, str]:
    """Where Q is applied (m) and why: `at`, else the stage with the largest Wachel
    estimate, else mid-span between the outermost bearings."""
    if at is not None:
        if not 0.0 <= at <= scene.shaft.length:
            raise SceneError(f"--at-mm {at * 1e3:g}: where Q acts must lie on the shaft, 0 to "
                             f"{scene.shaft.length * 1e3:g} mm")
        return at, "as asked"
    stages = [a for a in scene.attachments if a.cross_coupling is not None]
    if stages:
        top = scene.rotor.top_speed if scene.rotor is not None else 0.0
        a = max(stages, key=lambda a: _stage_q(a, top))
        return a.position, f"at the stage {a.name!r}"
    zs = [s.position for s in scene.supports if s.kind != "seal"]
    if len(zs) < 2:
        raise SceneError(f"{scene.source}: Level I applies Q at mid-span between the bearings, "
                         "or at a stage: give two bearings, a stage (stage_power_kw) or the "
                         "plane")
    return 0.5 * (min(zs) + max(zs)), "at mid-span between the bearings"


def _stage_q(part, omega: float) -> float:
    """A stage's Wachel q (N/m) at the spin omega."""
    assert part.cross_coupling is not None
    return float(part.cross_coupling.stiffness(omega)[0][1])


def anticipated(scene: Scene, given: float | None) -> tuple[float | None, str]:
    """Q_A (N/m) and where it comes from: given, else the sum of the stages' Wachel
    estimates at the highest operating speed, else none."""
    if given is not None:
        if not (math.isfinite(given) and given > 0):
            raise SceneError(f"--qa-n-per-mm {given / 1e3:g}: the anticipated cross-coupling "
                             "Q_A must be a positive number of N/mm")
        return given, "given"
    stages = [a for a in scene.attachments if a.cross_coupling is not None]
    if not stages:
        return None, "none: no stage gives its power and no Q_A is given"
    top = scene.rotor.top_speed if scene.rotor is not None else 0.0
    return (float(sum(_stage_q(a, top) for a in stages)),
            f"Wachel's estimate of {len(stages)} stage(s) at the highest operating speed")


def slow_spin(model, top: float) -> str | None:
    """What makes Level I slow on this rotor, or None: its equations periodic at its
    highest operating speed `top` (rad/s), where Hill's method took more than HILL_MAX
    harmonics for the Campbell diagram (a spin slow against the bearings' split); Level
    I solves that again at over a hundred applied cross-couplings, each costing as the
    cube of the harmonics."""
    from shaftfem.fem.floquet import HILL_MAX, harmonics_taken

    taken = harmonics_taken(model, top)   # (none where the equations are constant)
    if taken is None or taken <= HILL_MAX:
        return None
    return (f"at {top * 30 / math.pi:,.0f} r/min the shaft (not of revolution, in bearings "
            f"that differ along x and y) took {taken} harmonics of Hill's method, against "
            f"{HILL_MAX} at most for a quick solve")


def level1_too_slow(model, top: float) -> str | None:
    """Why design leaves out the Level I screening the scene did not ask for (slow_spin),
    or None. `shaftfem level1`, or [rotor] level1 = true, screens it all the same."""
    why = slow_spin(model, top)
    return None if why is None else (
        f"{why}; Level I would solve it again at over a hundred cross-couplings: "
        "`shaftfem level1` (or [rotor] level1 = true) screens it")


def run_level1(scene: Scene, q_n_per_mm: np.ndarray | None = None,
               at_mm: float | None = None, qa_n_per_mm: float | None = None,
               options: RunOptions = RunOptions()) -> Level1:
    """The Level I screening of the scene's rotor at its highest operating speed: the log
    decrement at each applied cross-coupling of `q_n_per_mm` (N/mm; default 20 from 0 to
    1.5 Q_0, or to 2 Q_A if more), Q applied at `at_mm` (mm from the shaft's left end;
    default: screening_plane), Q_0 and, with an anticipated Q_A (`qa_n_per_mm`, N/mm;
    default the scene's [rotor] level1_qa_n_per_mm or its stages' Wachel estimate), the
    criteria. The units are the scene file's; the result holds SI (N/m, m)."""
    q_values = None if q_n_per_mm is None else np.asarray(q_n_per_mm, dtype=float) * 1e3
    at = None if at_mm is None else at_mm * 1e-3
    q_anticipated = None if qa_n_per_mm is None else qa_n_per_mm * 1e3
    import scipy.optimize

    from shaftfem.fem.rotor import BearingModal, section_motion
    from shaftfem.workflows.campbell import RPM, turning
    from shaftfem.workflows.static import equipped

    if scene.rotor is None:
        raise SceneError(f"{scene.source}: no [rotor] table: Level I screens the shaft at its "
                         "highest operating speed; add [rotor] speed_rpm")
    # a plane off the shaft, or a Q_A that is none, is refused before any solve
    if at is not None:
        screening_plane(scene, at)
    if q_anticipated is not None:
        anticipated(scene, q_anticipated)
    scene = equipped(scene, options)
    assert scene.rotor is not None
    z, where = screening_plane(scene, at)
    if q_anticipated is None and scene.rotor.level1_qa is not None:
        q_anticipated = scene.rotor.level1_qa
    qa, qa_from = anticipated(scene, q_anticipated)
    result, model, _ = turning(scene, options)
    slow = slow_spin(model, scene.rotor.top_speed)
    if slow is not None:   # said before the wait, not after it
        options.say(f"Level I will take long: {slow}; it is solved again at over a hundred "
                    "cross-couplings")
    # the seals and the stages' own cross-coupling out of the loaded rotor (Q stands for
    # them); their seats stay in the mesh and the basis, as the Campbell run has them
    seals = {s.name for s in scene.supports if s.kind == "seal"}
    stages = {f"{a.name} (stage)" for a in scene.attachments if a.cross_coupling is not None}
    # (their coefficients zero rather than the part dropped: what the standstill basis
    # holds of them is taken off too)
    model = replace(model, bearings=tuple(
        replace(b, coefficients=cross(0.0)) if b.name in seals | stages else b
        for b in model.bearings))
    omega = scene.rotor.top_speed
    beta = section_motion(result, z, model.shapes)
    plane: BearingModal = BearingModal("applied Q", beta, cross(0.0), (0.0, 0.0))

    def modes(q: float) -> list[tuple[float, float]]:
        loaded = replace(model, bearings=(*model.bearings, replace(plane, coefficients=cross(q))))
        return forward_modes(loaded, omega)

    def least(q: float) -> float:
        return min(d for _, d in modes(q))

    q0 = None
    if least(0.0) > 0:
        hi = 1e3
        while least(hi) > 0 and hi < 1e13:
            hi *= 4
        if hi < 1e13:
            q0 = float(scipy.optimize.brentq(least, hi / 4 if hi > 1e3 else 0.0, hi,
                                             xtol=1e-9 * hi, rtol=1e-10))
    refine = q_values is None
    if q_values is None:
        # the whole curve to past Q_0, and as many steps again up to twice Q_A: Q_A is
        # resolved however far Q_0 lies beyond it
        top = max(1.5 * (q0 or 0.0), 2.0 * (qa or 0.0)) or 1e6
        near = np.linspace(0.0, 2.0 * qa, POINTS // 2 + 1) if qa else np.zeros(0)
        q_values = np.union1d(np.linspace(0.0, top, POINTS),
                              np.union1d(near, [q0] if q0 is not None else []))
    # the mode Q turns unstable (the least damped at Q_0; without Q_0 the least damped
    # without Q), followed over Q by its frequency, from Q_0 outwards in small steps
    start = q0 if q0 is not None else 0.0
    f_start = min(modes(start), key=lambda m: m[1])[0]
    wanted = sorted({*map(float, q_values), *([qa] if qa is not None else []), 0.0})

    def follow(targets: list[float], q: float = start, f: float = f_start
               ) -> dict[float, tuple[float, float]]:
        out = {}
        for t in targets:
            for step in np.linspace(q, t, 6)[1:] if t != q else [t]:
                f, d = min(modes(float(step)), key=lambda m: abs(m[0] - f))
            out[t], q = (f, d), t
        return out

    seen = {start: (f_start, min(modes(start), key=lambda m: m[1])[1])}
    seen.update(follow([t for t in reversed(wanted) if t < start]))
    seen.update(follow([t for t in wanted if t > start]))
    for _ in range(REFINE_ROUNDS - 1 if refine else 0):
        # where the log decrement turns sharply between two steps, their middle too (a
        # turn of the curve, or the mode followed changing, is then seen, not jumped),
        # each followed from its neighbour on Q_0's side
        span = max(d for _, d in seen.values()) - min(d for _, d in seen.values())
        steep = [(lo, hi) for lo, hi in zip(wanted, wanted[1:])
                 if abs(seen[hi][1] - seen[lo][1]) > max(STEEP * span, 1e-3)][:REFINE_MAX]
        if not steep:
            break
        for lo, hi in steep:
            side = lo if lo >= start else hi
            seen.update(follow([0.5 * (lo + hi)], side, seen[side][0]))
        wanted = sorted({*wanted, *(0.5 * (lo + hi) for lo, hi in steep)})
    q_values = np.array(wanted if refine else q_values, dtype=float)
    decs = np.array([seen[float(q)][1] for q in q_values])
    d0, f0 = seen[0.0][1], seen[0.0][0]
    da = seen[qa][1] if qa is not None else None
    ratio = q0 / qa if (q0 is not None and qa) else None
    passed = None
    if qa is not None:
        passed = bool(da is not None and da >= LOG_DEC_MIN and ratio is not None
                      and ratio >= RATIO_MIN)
    return Level1(scene=scene, speed_rpm=omega / RPM, plane=z, plane_why=where,
                  q=np.asarray(q_values, dtype=float), log_dec=decs, log_dec_0=d0, q0=q0,
                  qa=qa, qa_from=qa_from, log_dec_a=da, ratio=ratio, passed=passed,
                  frequency_hz=f0)
