"""The turning shaft: whirl frequencies against speed (the Campbell diagram), the
critical speeds where they cross the excitation orders, and how far the modal basis
they are solved on moves them.

One standstill modal run gives the basis (fem.rotor); every speed is then a small
dense eigenproblem on it. Frequencies are always given in the stationary frame, as a
vibration probe on the housing sees them: a rotating-frame mode at f_r is seen at
f_r + n (forward component) and |f_r - n| (backward component), n the spin in Hz;
each is reported at its larger component, the other beside it.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.whirl import (
    FORWARD,
    RPM,
    WHIRLING,
    Campbell,
    CriticalSpeed,
    Onset,
    Truncation,
    Whirl,
    category,
)
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene
from shaftfem.scene.schema import MAX_MODE_COUNT

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult
    from shaftfem.fem.rotor import Roots, RotorModel

# Of the basis, the whirl solved on this share too: its change is the truncation check.
CHECK_SHARE = 2 / 3
# Log decrements within this of zero are zero (an undamped model's round-off).
ROUND_OFF = 1e-9
# The spin, as a share of the lowest frequency, that stands for standstill in whirl_at.
STANDSTILL = 1e-5
# The whirl frequencies may move by at most this (relative) between the basis and two
# thirds of it; else the basis is doubled (up to the largest mode count). Far below the
# discretisation's own bounds (0.1 % and more).
TRUNCATION = 1e-4
# Basis size when [rotor] does not give one: this many times the modes asked for ...
BASIS_FACTOR = 3
# ... and at least this many.
BASIS_MIN = 30


def choose_frame(scene: Scene) -> tuple[str, str]:
    """The frame the scene's rotor is solved in, and why; a shaft that is not a solid of
    revolution in bearings that are not isotropic is refused (its equations have
    coefficients periodic in time in either frame)."""
    rotor = scene.rotor
    if rotor is None:
        raise SceneError(f"{scene.source}: no [rotor] table: give the operating speed "
                         "([rotor] speed_rpm) to see the shaft turn")
    anisotropic = [s.name for s in scene.held if s.bearing is not None
                   and not s.bearing.isotropic]
    shape = ("a solid of revolution" if scene.axisymmetric else
             "not a solid of revolution (" + ", ".join(
                 w for w, on in (("keyways", bool(scene.shaft.keyways)),
                                 ("grooves", scene.grooves is not None),
                                 ("a STEP solid", scene.shaft.step is not None)) if on) + ")")
    if rotor.frame == "stationary" and not scene.axisymmetric:
        raise SceneError(f"{scene.source}: rotor.frame = \"stationary\": the shaft is {shape}; "
                         "the stationary frame takes shafts of revolution only: use \"rotating\" "
                         "or \"auto\"")
    if rotor.frame == "rotating" and anisotropic:
        raise SceneError(f"{scene.source}: rotor.frame = \"rotating\": bearing(s) "
                         f"{', '.join(anisotropic)} differ along x and y; the rotating frame "
                         "takes isotropic bearings only (kxx = kyy, kxy = -kyx, likewise c): "
                         "use \"stationary\" or \"auto\"")
    if not scene.axisymmetric and anisotropic:
        raise SceneError(f"{scene.source}: the shaft is {shape} and bearing(s) "
                         f"{', '.join(anisotropic)} differ along x and y: its equations are "
                         "periodic in time in either frame, which shaftfem does not solve; "
                         "make the bearings isotropic (kxx = kyy, kxy = -kyx, likewise c) or the "
                         "shaft one of revolution")
    if rotor.frame != "auto":
        return rotor.frame, f"as [rotor] frame asks; the shaft is {shape}"
    if scene.axisymmetric:
        return "stationary", (f"auto: the shaft is {shape}, so its modes are solved in the "
                              "stationary frame, gyroscopic moments included")
    return "rotating", (f"auto: the shaft is {shape}, so its modes are solved in the frame "
                        "turning with it (Coriolis and spin softening), its bearings isotropic")


def basis_size(scene: Scene) -> int:
    """How many standstill modes the whirl is solved on."""
    assert scene.rotor is not None
    return scene.rotor.basis_modes or max(BASIS_FACTOR * scene.modes.count, BASIS_MIN)


def whirl_at(model: RotorModel, omega: float, count: int) -> list[Whirl]:
    """The lowest `count` modes at the spin omega (rad/s), in the stationary frame. At
    standstill a shaft of revolution's bending pairs are double and their orbit any:
    there each mode takes the whirl it has at a spin of STANDSTILL times the lowest
    frequency (the limit from above), its frequency and damping those at rest."""
    if omega == 0.0:
        rest = _whirl_rows(model, 0.0, count)
        start = _whirl_rows(model, STANDSTILL * math.sqrt(float(model.omega2[0])), count)
        return [replace(r, whirl=s.whirl, whirl_index=s.whirl_index)
                for r, s in zip(rest, start)]
    return _whirl_rows(model, omega, count)


def _seen(model: RotorModel, omega: float) -> tuple[Roots, list[tuple]]:
    """The roots at the spin omega and each as the stationary frame sees it, lowest
    first: (frequency Hz, whirl, whirl index, kind, rotating-frame Hz, other component's
    Hz or None, decay rate 1/s, its column among the roots)."""
    from shaftfem.fem.rotor import dominant_kinds, roots, whirl_index

    r = roots(model, omega)
    W = whirl_index(model, r.y)
    kinds = dominant_kinds(model, r.y)
    n = omega / (2 * math.pi)
    rows = []
    for j, (lam, w, kind) in enumerate(zip(r.lam, W, kinds)):
        f_r = lam.imag / (2 * math.pi)
        f, index, other = f_r, float(w), None
        if model.frame == "rotating" and kind in WHIRLING and omega > 0:
            forward, backward = f_r + n, f_r - n
            if w >= 0:
                f, other = forward, abs(backward)
            else:   # the backward component: seen backward above n, forward below it
                f, other, index = abs(backward), forward, (w if backward > 0 else -w)
        direction = ("forward" if index > FORWARD else "backward" if index < -FORWARD
                     else "mixed")
        rows.append((f, direction, index, kind, f_r, other, -lam.real, j))
    rows.sort(key=lambda row: row[0])
    return r, rows


def _whirl_rows(model: RotorModel, omega: float, count: int) -> list[Whirl]:
    out = []
    for k, (f, direction, index, kind, f_r, other, decay, _) in enumerate(
            _seen(model, omega)[1][:count]):
        wd = 2 * math.pi * f
        decay = decay if abs(decay) > ROUND_OFF * wd else 0.0
        out.append(Whirl(speed_rpm=omega / RPM, mode=k + 1, frequency_hz=f, whirl=direction,
                         whirl_index=index, log_dec=2 * math.pi * decay / wd if wd > 0 else 0.0,
                         damping_ratio=decay / math.hypot(decay, wd), kind=kind,
                         rotating_frame_hz=f_r, companion_hz=other))
    return out


def synchronous_check(model: RotorModel, critical: list[CriticalSpeed]) -> float | None:
    """The largest relative difference between the 1x crossings found on the diagram and
    the same critical speeds from the synchronous eigenproblem (fem.rotor), matched by
    whirl and number; None where that eigenproblem does not apply (the rotating frame,
    bearings that change with speed or damp)."""
    from shaftfem.fem.rotor import synchronous_speeds

    if model.frame != "stationary" or any(
            len(b.coefficients.speeds) or np.any(np.array(b.coefficients.damping(0.0)))
            for b in model.bearings):
        return None
    ones = [c for c in critical if c.order == 1]
    if not ones:
        return None
    speeds, index = synchronous_speeds(model)
    worst = 0.0
    for whirl, sign in (("forward", 1), ("backward", -1)):
        direct = speeds[sign * index > FORWARD]
        for c in (c for c in ones if c.whirl == whirl):
            if c.mode > direct.size:
                return math.inf
            worst = max(worst, abs(c.speed_rpm * RPM / direct[c.mode - 1] - 1))
    return worst


def mode_shapes(model: RotorModel, omega: float, count: int) -> np.ndarray:
    """The complex modal coordinates (N, count) of whirl_at's rows at the spin omega
    (rad/s), in the same order, each scaled to a largest entry of 1."""
    r, rows = _seen(model, omega)
    y = r.y[:, [row[-1] for row in rows[:count]]]
    return y / y[np.argmax(np.abs(y), axis=0), np.arange(y.shape[1])]


def curve_row(model: RotorModel, omega: float, whirl: str, k: int, count: int
              ) -> Whirl | None:
    """The k-th lowest mode of one whirl (a curve of the diagram) at the spin omega, or
    None where that whirl has fewer modes among the lowest `count`."""
    ws = sorted((w for w in whirl_at(model, omega, count) if category(w) == whirl),
                key=lambda w: w.frequency_hz)
    return ws[k] if k < len(ws) else None


def crossings(model: RotorModel, speeds: np.ndarray, rows: list[list[Whirl]],
              orders: tuple[int, ...], count: int) -> list[CriticalSpeed]:
    """Every crossing of a forward or backward whirl curve with an order line, found
    on the diagram's speeds and refined by root finding on the reduced model."""
    from scipy.optimize import brentq

    def row(omega: float, whirl: str, k: int) -> Whirl | None:
        return curve_row(model, omega, whirl, k, count)

    def curve(omega: float, whirl: str, k: int) -> float:
        w = row(omega, whirl, k)
        return math.nan if w is None else w.frequency_hz

    out = []
    for whirl in ("forward", "backward"):
        per_speed = [sorted(w.frequency_hz for w in r if category(w) == whirl) for r in rows]
        n_curves = min((len(f) for f in per_speed), default=0)
        for k in range(n_curves):
            f = np.array([p[k] for p in per_speed])
            for order in orders:
                g = f - order * speeds / (2 * math.pi)
                for i in np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0):
                    def gap(om: float, k: int = k, order: int = order, whirl: str = whirl
                            ) -> float:
                        return curve(om, whirl, k) - order * om / (2 * math.pi)
                    try:
                        om = brentq(gap, speeds[i], speeds[i + 1], xtol=1e-10 * speeds[i + 1])
                    except ValueError:   # the curve's numbering changed inside the bracket
                        continue
                    at = row(om, whirl, k)
                    out.append(CriticalSpeed(order=order, whirl=whirl, speed_rpm=om / RPM,
                                             frequency_hz=order * om / (2 * math.pi), mode=k + 1,
                                             log_dec=at.log_dec if at is not None else 0.0))
    return sorted(out, key=lambda c: (c.speed_rpm, c.order))


def onsets(model: RotorModel, speeds: np.ndarray, rows: list[list[Whirl]], count: int
           ) -> list[Onset]:
    """Every speed where a whirl curve's log decrement changes from positive to negative
    (the mode starts to grow), on the diagram's speeds, refined by root finding."""
    from scipy.optimize import brentq

    def curve(omega: float, whirl: str, k: int) -> Whirl | None:
        return curve_row(model, omega, whirl, k, count)

    out = []
    for whirl in ("forward", "backward", "mixed"):
        per_speed = [sorted((w for w in r if category(w) == whirl), key=lambda w: w.frequency_hz)
                     for r in rows]
        for k in range(min((len(p) for p in per_speed), default=0)):
            d = np.array([p[k].log_dec for p in per_speed])
            # an undamped model's decrements are zero to round-off: only a sign that
            # changes beyond that is a change of stability
            for i in np.flatnonzero((d[:-1] > ROUND_OFF) & (d[1:] < -ROUND_OFF)):
                def logdec(om: float, k: int = k, whirl: str = whirl) -> float:
                    w = curve(om, whirl, k)
                    return math.nan if w is None else w.log_dec
                try:
                    om = brentq(logdec, speeds[i], speeds[i + 1], xtol=1e-10 * speeds[i + 1])
                except ValueError:
                    continue
                w = curve(om, whirl, k)
                assert w is not None
                out.append(Onset(om / RPM, whirl, k + 1, w.frequency_hz))
    return sorted(out, key=lambda o: o.speed_rpm)


def divergent_bands(model: RotorModel, speeds: np.ndarray) -> list[tuple[float, float]]:
    """The speed bands (r/min) where a root grows without oscillating, their edges found
    by bisection between the diagram's speeds (to 1e-9 of the speed)."""
    from shaftfem.fem.rotor import roots

    def grows(omega: float) -> bool:
        return roots(model, omega).divergence > 0

    flags = [grows(om) for om in speeds]

    def edge(lo: float, hi: float, inside_high: bool) -> float:
        while hi - lo > 1e-9 * hi:
            mid = 0.5 * (lo + hi)
            if grows(mid) == inside_high:
                hi = mid
            else:
                lo = mid
        return 0.5 * (lo + hi)

    bands, start = [], None
    for i, flag in enumerate(flags):
        if flag and start is None:
            start = speeds[0] if i == 0 else edge(speeds[i - 1], speeds[i], True)
        if not flag and start is not None:
            bands.append((start / RPM, edge(speeds[i - 1], speeds[i], False) / RPM))
            start = None
    if start is not None:
        bands.append((start / RPM, speeds[-1] / RPM))
    return bands


def truncation(model: RotorModel, speeds: tuple[float, ...], count: int) -> Truncation:
    """The whirl frequencies of the `count` reported modes on the whole basis against
    its first CHECK_SHARE, at `speeds` (rad/s): the largest relative change."""
    smaller = max(count + 1, math.ceil(CHECK_SHARE * model.size))
    smaller = min(smaller, model.size)
    change = 0.0
    for omega in speeds:
        full = whirl_at(model, omega, count)
        part = whirl_at(model.truncated(smaller), omega, count)
        for a, b in zip(full, part):
            change = max(change, abs(b.frequency_hz - a.frequency_hz) / a.frequency_hz)
    return Truncation(size=model.size, smaller=smaller,
                      speeds_rpm=tuple(o / RPM for o in speeds), change=change)


def turning(scene: Scene, options: RunOptions = RunOptions()
            ) -> tuple[ModalResult, RotorModel, str]:
    """The scene's standstill modes (the basis), the turning shaft on them, and why its
    frame. A basis that [rotor] basis_modes does not fix is doubled while the reported
    whirl still moves by more than TRUNCATION on it."""
    from shaftfem.fem.rotor import rotor_model
    from shaftfem.workflows.pipeline import run_modes, with_modes

    frame, why = choose_frame(scene)
    if scene.mesh.order > 2:
        raise SceneError(f"{scene.source}: element order {scene.mesh.order}: the turning shaft "
                         "takes orders 1 and 2")
    size = basis_size(scene)
    rotor = scene.rotor
    assert rotor is not None
    speeds = tuple(sorted({*rotor.speeds, rotor.max_speed}))
    while True:
        result = run_modes(with_modes(scene, count=size), options)
        options.say(f"whirl on {result.modes.count} standstill modes, {frame} frame")
        model = rotor_model(result, frame)
        # the basis is enlarged while the whirl still moves on it (from two thirds of it)
        if (rotor.basis_modes or size >= MAX_MODE_COUNT
                or truncation(model, speeds, scene.modes.count).change <= TRUNCATION):
            return result, model, why
        size = min(2 * size, MAX_MODE_COUNT)
        options.say(f"the whirl still moves on the basis: {size} standstill modes")


def run_campbell(scene: Scene, options: RunOptions = RunOptions(),
                 speeds_rpm: np.ndarray | None = None) -> Campbell:
    """The scene's shaft turning: its standstill modes, then the whirl at every speed of
    the Campbell diagram (`speeds_rpm`, default 0 to [rotor] max_speed_rpm at
    [rotor] campbell_points) and at the operating speeds, the critical speeds, the
    stability and the basis check, and the unbalance response."""
    result, model, why = turning(scene, options)
    return campbell_of(scene, result, model, why, speeds_rpm)


def campbell_of(scene: Scene, result: ModalResult, model: RotorModel, why: str,
                speeds_rpm: np.ndarray | None = None) -> Campbell:
    """run_campbell's diagram of the turning shaft `model` on the standstill `result`."""
    rotor = scene.rotor
    assert rotor is not None
    frame = model.frame
    count = scene.modes.count
    grid = (np.linspace(0.0, rotor.max_speed, rotor.points) if speeds_rpm is None
            else np.asarray(speeds_rpm, dtype=float) * RPM)
    rows = [whirl_at(model, om, count) for om in grid]
    orders = rotor_orders(scene)
    critical = crossings(model, grid, rows, orders, count)
    operating = [w for om in rotor.speeds for w in whirl_at(model, om, count)]
    shapes = tuple(mode_shapes(model, om, count) for om in rotor.speeds)
    check = truncation(model, tuple(sorted({*rotor.speeds, float(grid.max())})), count)
    notes = []
    if not scene.held:
        notes.append("the shaft hangs free (no [[support]]): its whirl is a free rotor's")
    if not any(s.bearing is not None for s in scene.held):
        notes.append("no bearing has damping (kind = \"bearing\" with cxx ...): the log "
                     "decrements are zero and no amplification factor can be given")
    synchronous = synchronous_check(model, critical)
    unstable = onsets(model, grid, rows, count)
    bands = divergent_bands(model, grid)
    response = None
    if scene.unbalances:
        from shaftfem.workflows.unbalance import unbalance_response

        response = unbalance_response(scene, result, model)
    return Campbell(frame=frame, why=why, speeds_rpm=tuple(grid / RPM),
                    whirl=tuple(w for r in rows for w in r), operating=tuple(operating),
                    operating_rpm=tuple(om / RPM for om in rotor.speeds),
                    critical_speeds=tuple(critical), orders=orders, truncation=check,
                    result=result, notes=tuple(notes), unbalance=response,
                    onsets=tuple(unstable), divergent=tuple(bands),
                    operating_shapes=shapes, synchronous_check=synchronous)


def whirl_table(scene: Scene, speed_rpm: float, options: RunOptions = RunOptions()
                ) -> Campbell:
    """The shaft turning at one speed (r/min): the scene's [rotor] with that speed as its
    operating one (a scene without [rotor] takes its defaults)."""
    from shaftfem.scene.model import Rotor

    omega = speed_rpm * RPM
    rotor = scene.rotor or Rotor(speeds=(omega,), max_speed=omega)
    scene = replace(scene, rotor=replace(rotor, speeds=(omega,), max_speed=omega))
    return run_campbell(scene, options, np.array([0.0, speed_rpm]))


def speed_grid(start_rpm: float, stop_rpm: float, count: int) -> np.ndarray:
    """`count` speeds from start to stop, r/min."""
    return np.linspace(start_rpm, stop_rpm, count)


def rotor_orders(scene: Scene) -> tuple[int, ...]:
    """The excitation orders of the shaft's own speed: 1x always, and the orders of
    every [[excitation]] that runs at an operating speed of the shaft."""
    rotor = scene.rotor
    assert rotor is not None
    orders = {1}
    for e in scene.excitations:
        if any(abs(e.frequency * 2 * math.pi - om) <= 1e-9 * om for om in rotor.speeds):
            orders.update(e.orders)
    return tuple(sorted(orders))
