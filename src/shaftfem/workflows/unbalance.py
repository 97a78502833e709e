"""The turning shaft's steady response to its unbalances against speed (a Bode plot
at each probe), its peaks, each peak's amplification factor by the half-power method
and its separation margin from the operating speeds against API 684's.

The probes are the unbalances' planes, the bearings' seats and [rotor] probes_mm (the
mean motion of the section, as a proximity probe reads a shaft): amplitude along x,
and the orbit's major semi-axis.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from shaftfem.checks.resonance import AF_CRITICALLY_DAMPED, api684_margin
from shaftfem.checks.whirl_check import forward_only
from shaftfem.errors import SceneError
from shaftfem.fem.whirl import RPM, Bode, Peak, UnbalanceResponse, WeightWhirl
from shaftfem.scene.model import Scene

# The Bode plot's speeds, from 0 to the Campbell diagram's end.
BODE_POINTS = 400


def api684_required(af: float, below: bool) -> float | None:
    """API 684's separation margin for a peak of amplification factor af, below or
    above the operating speed (fraction); None (no margin required) below AF 2.5."""
    if af < AF_CRITICALLY_DAMPED:
        return None
    return api684_margin(af, above=not below)


def unbalance_response(scene: Scene, result, model, speeds_rpm: np.ndarray | None = None,
                       criticals: list[float] | None = None) -> UnbalanceResponse:
    """The response of the turning shaft (`model` on the standstill `result`) to the
    scene's unbalances at every probe, from 0 to the Campbell diagram's end. Where the
    supports leave the shaft free to move sideways (damping only, or no support) the
    basis also holds those rigid motions. In a model with no damping a peak is
    unbounded: the peaks are the 1x critical speeds (`criticals`, r/min; by default
    found directly) whose mode the unbalances drive, each given by its speed."""
    from shaftfem.fem.floquet import any_unbalance_response as solve
    from shaftfem.fem.rotor import orbit

    if not scene.unbalances:
        raise SceneError(f"{scene.source}: no [[unbalance]] to respond to")
    rotor = scene.rotor
    assert rotor is not None
    model = forced(result, model)
    probes = probes_of(scene, result, model)
    # the unbalances' planes are the first probes
    forces = [(beta, u.amount * complex(math.cos(u.phase), math.sin(u.phase)))
              for u, (_, _, beta) in zip(scene.unbalances, probes)]
    grid = (np.linspace(0.0, rotor.max_speed / RPM, BODE_POINTS + 1)[1:]
            if speeds_rpm is None else np.asarray(speeds_rpm, dtype=float))
    damped = any(np.any(np.array(b.coefficients.cxx + b.coefficients.cyy + b.coefficients.cxy
                                 + b.coefficients.cyx)) for b in model.bearings)
    # round-off of unbalances that cancel: far below the rigid rotor's eccentricity
    mass = float(result.system.mass_scalar.sum()) + sum(a.mass for a in scene.attachments)
    floor = ROUND_OFF * sum(abs(u.amount) for u in scene.unbalances) / mass

    singular: list[float] = []
    if not damped:
        singular = (criticals if criticals is not None
                    else _one_x(model, rotor.max_speed, forward_only(scene, model.frame)))

    responses: dict[float, np.ndarray] = {}   # one solve a speed, read at every probe

    def at(rpm: float, beta: np.ndarray) -> tuple[float, ...]:
        if rpm not in responses:
            responses[rpm] = solve(model, rpm * RPM, forces)
        return orbit(model, beta, responses[rpm])

    bode, peaks = [], []
    operating = [om / RPM for om in rotor.speeds]
    spans = [(lo / RPM, hi / RPM) for lo, hi in rotor.spans]
    for name, pz, beta in probes:
        rows = np.array([at(n, beta) for n in grid])
        b = _bode(name, pz, grid, rows)
        if damped:
            found = [p for p in find_peaks(name, b, lambda n, beta=beta: at(n, beta)[1],
                                           operating, lambda n: grows(model, n * RPM), spans)
                     if p.amplitude > floor]
        else:
            found = poles(name, lambda n, beta=beta: at(n, beta)[1], singular, spans)
        # a lightly damped peak is narrower than the grid: draw it through its own speeds
        extra = np.array([p.speed_rpm + k * w for p in found for w in
                          [(p.half_power_rpm[1] - p.half_power_rpm[0]) if p.half_power_rpm
                           else 1e-3 * p.speed_rpm] for k in np.linspace(-4, 4, 33)])
        extra = np.setdiff1d(extra[(extra > grid[0]) & (extra < grid[-1])], grid)
        if extra.size:
            order = np.argsort(np.concatenate([grid, extra]), kind="stable")
            rows = np.vstack([rows, [at(n, beta) for n in extra]])[order]
            b = _bode(name, pz, np.concatenate([grid, extra])[order], rows)
        if any(r.ndim == 2 for r in responses.values()):
            from shaftfem.fem.floquet import unbalance_orders

            def third(n: float, beta: np.ndarray = beta) -> float:
                q = responses[n]   # (every speed drawn was solved for the 1x)
                if q.ndim == 1:
                    return 0.0
                c = unbalance_orders(beta, q)
                return abs(c.get(3, 0j)) + abs(c.get(-3, 0j))
            b = replace(b, major_3x=np.array([third(float(n)) for n in b.speeds_rpm]))
        bode.append(b)
        peaks += found
    return UnbalanceResponse(tuple(bode), tuple(peaks), damped=damped)


def probes_of(scene: Scene, result, model) -> list[tuple[str, float, np.ndarray]]:
    """Where a forced response is read: the unbalances' planes, the bearings' seats and
    [rotor] probes_mm, each (name, z (m), its section's motion beta (2, N) on `model`'s
    basis); a plane off the shaft is refused, naming its key."""
    from shaftfem.fem.rotor import section_motion

    rotor = scene.rotor
    assert rotor is not None
    z = result.system.nodes[:, 2]
    for u in scene.unbalances:
        _on_shaft(scene, f"[[unbalance]] {u.name!r}: position_mm", u.position, z)
    for p in rotor.probes:
        _on_shaft(scene, "[rotor] probes_mm", p, z)
    shapes = model.shapes
    probes = [(u.name, u.position, section_motion(result, u.position, shapes))
              for u in scene.unbalances]
    probes += [(b.name, s.position, b.beta) for b, s in
               zip(model.bearings, [s for s in scene.held if s.bearing is not None])]
    probes += [(f"probe at {p * 1e3:g} mm", p, section_motion(result, p, shapes))
               for p in rotor.probes]
    return probes


def weight_whirl(scene: Scene, result, model) -> tuple[WeightWhirl, ...]:
    """The 2x whirl the shaft's weight drives where it is not a solid of revolution
    (`model` in the rotating frame: the weight turns backwards at the spin seen from the
    shaft, and the stiff and soft diameters make a 2x whirl of it), at the bearings'
    seats, the unbalances' planes and [rotor] probes_mm: the peak of the 2x orbit's
    major semi-axis from 0 to the Campbell diagram's end (BODE_POINTS speeds, then
    refined), and its size at the highest operating speed. None in the stationary frame
    (a shaft of revolution's weight only sags it) or without a weight across the axis."""
    from scipy.optimize import minimize_scalar

    from shaftfem.fem.floquet import gravity_response, stationary_orders

    rotor = scene.rotor
    gx, gy = scene.gravity[0], scene.gravity[1]
    if rotor is None or model.frame != "rotating" or math.hypot(gx, gy) == 0.0:
        return ()
    model = forced(result, model)
    assert model.weight is not None
    load = complex(gx, gy) * (model.weight[0] - 1j * model.weight[1])
    responses: dict[float, np.ndarray] = {}

    def orders(rpm: float, beta: np.ndarray) -> dict[int, complex]:
        if rpm not in responses:
            responses[rpm] = gravity_response(model, rpm * RPM, load)
        return stationary_orders(beta, responses[rpm])

    def twice(rpm: float, beta: np.ndarray) -> float:
        c = orders(rpm, beta)
        return abs(c[1]) + abs(c[-1])

    grid = np.linspace(0.0, rotor.max_speed / RPM, BODE_POINTS + 1)[1:]
    top = max(rotor.speeds) / RPM if rotor.speeds else grid[-1]
    out = []
    for name, _, beta in probes_of(scene, result, model):
        values = np.array([twice(n, beta) for n in grid])
        i = int(np.argmax(values))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        best = minimize_scalar(lambda n, beta=beta: -twice(n, beta), bounds=(lo, hi),
                               method="bounded", options={"xatol": 1e-6 * hi})
        # the curve drawn through the grid and its peak
        order = np.argsort(np.append(grid, best.x), kind="stable")
        speeds, curve = np.append(grid, best.x)[order], np.append(values, -best.fun)[order]
        out.append(WeightWhirl(name, float(best.x), float(-best.fun), twice(top, beta),
                               abs(orders(top, beta)[0]), tuple(speeds.tolist()),
                               tuple(curve.tolist())))
    return tuple(out)


def _one_x(model, top: float, forward: bool) -> list[float]:
    """The 1x critical speeds up to the spin top (rad/s), r/min, found directly (with
    `forward`, those of forward whirl only)."""
    from shaftfem.fem.tracking import direct_applies, direct_crossings
    from shaftfem.fem.whirl import FORWARD

    if direct_applies(model) is not None:
        return []
    return sorted(d.omega / RPM for d in direct_crossings(model, (1,), top)
                  if not (forward and d.component != "forward" and d.index < -FORWARD))


# Near a pole the response grows as 1 / |n - n_c|: from 1e-2 to 1e-9 of the speed a
# driven mode's grows 1e7 times; one the unbalances barely reach (a backward mode of a
# shaft of revolution, reached through its mesh's asymmetry) far less.
POLE = (1e-2, 1e-9, 1e4)


def poles(name: str, amplitude, criticals: list[float],
          spans: list[tuple[float, float]]) -> list[Peak]:
    """An undamped model's peaks at one probe: the critical speeds (r/min) whose mode
    the unbalances drive, each unbounded, with its separation margin."""
    from shaftfem.checks.whirl_check import span_margin

    far, near, gain = POLE
    out = []
    for n_c in sorted(set(criticals)):
        if amplitude(n_c * (1 - near)) < gain * amplitude(n_c * (1 - far)):
            continue
        margin, _ = min((span_margin(n_c, lo, hi) for lo, hi in spans), key=lambda m: m[0])
        out.append(Peak(name, n_c, math.inf, None, None, margin, None, unbounded=True))
    return out


# Below this share of the rigid rotor's eccentricity (sum |U| / mass) a response is
# round-off: the unbalances cancel.
ROUND_OFF = 1e-9


def forced(result, model):
    """The model a forced response is solved on: where the supports leave the shaft free
    to move sideways (damping only, or no support), with those rigid motions in its
    basis, its bearings (their coefficients as `model` has them) on the new shapes."""
    from shaftfem.fem.rotor import lateral_rigid, rotor_model

    if not lateral_rigid(result).shape[1]:
        return model
    rigid = rotor_model(result, model.frame, rigid=True)
    return replace(rigid, bearings=_bearings_of(model, rigid))


def _bearings_of(model, rigid):
    """The bearings of `model` (their coefficients, which a caller may have changed) on
    the shapes of `rigid`, the same rotor with its free rigid motions."""
    return tuple(replace(b, beta=r.beta) for b, r in zip(model.bearings, rigid.bearings))


def _on_shaft(scene: Scene, key: str, z: float, nodes_z: np.ndarray) -> None:
    lo, hi = float(nodes_z.min()), float(nodes_z.max())
    if not lo - 1e-9 <= z <= hi + 1e-9:
        raise SceneError(f"{scene.source}: {key} = {z * 1e3:g}: off the shaft, which spans "
                         f"{lo * 1e3:g} to {hi * 1e3:g} mm along its axis")


def _bode(name: str, z: float, speeds: np.ndarray, rows: np.ndarray) -> Bode:
    """A probe's Bode record from orbit rows (|x|, major, phase x, |y|, phase y)."""
    return Bode(name, z, speeds, rows[:, 0], _unwrapped(rows[:, 2]), rows[:, 1],
                amplitude_y=rows[:, 3], phase_y_deg=_unwrapped(rows[:, 4]))


def _unwrapped(phase: np.ndarray) -> np.ndarray:
    """A phase (rad) as one continuous lag in degrees: unwrapped, then shifted by whole
    turns so that it starts in (-180, 180]."""
    deg = np.degrees(np.unwrap(phase))
    return deg - 360.0 * math.ceil((deg[0] - 180.0) / 360.0) if deg.size else deg


def grows(model, omega: float) -> bool:
    """Whether a mode of the turning shaft grows at the spin omega (rad/s): there it has
    no steady unbalance response."""
    from shaftfem.fem.floquet import any_roots as roots

    r = roots(model, omega)
    scale = 1e-9 * max(float(np.max(np.abs(r.lam))) if r.lam.size else 1.0, 1.0)
    return r.divergence > 0 or bool(np.any(r.lam.real > scale))


def find_peaks(name: str, b: Bode, amplitude, operating: list[float],
               unstable=lambda n: False, spans: list[tuple[float, float]] | None = None
               ) -> list[Peak]:
    """The peaks of one probe's Bode curve, each refined on `amplitude` (r/min -> m), its
    half-power speeds and amplification factor, and its margin from the nearest of the
    `operating` speeds (r/min). Where a mode grows (`unstable(n)`) a peak is no steady
    response: it is marked so, with no amplification factor."""
    from scipy.optimize import minimize_scalar

    from shaftfem.checks.whirl_check import span_margin

    grid, a = b.speeds_rpm, b.major
    spans = spans or [(n, n) for n in operating]
    out = []
    for i in np.flatnonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:])) + 1:
        # on the logarithm: an undamped peak is a pole, which the raw amplitude's
        # range of many decades hides from the search
        best = minimize_scalar(lambda n: -math.log(max(amplitude(n), 1e-300)),
                               bounds=(grid[i - 1], grid[i + 1]), method="bounded",
                               options={"xatol": 1e-9 * grid[i]})
        n_c = float(best.x)
        peak = amplitude(n_c)
        margin, above = min((span_margin(n_c, lo, hi) for lo, hi in spans),
                            key=lambda m: m[0])
        if unstable(n_c):
            out.append(Peak(name, n_c, peak, None, None, margin, None, unstable=True))
            continue
        half = peak / math.sqrt(2)
        hp = None
        sides = [_half_power(amplitude, n_c, half, grid[0], -1),
                 _half_power(amplitude, n_c, half, grid[-1], +1)]
        if sides[0] is not None and sides[1] is not None:
            hp = (sides[0], sides[1])
        af = n_c / (hp[1] - hp[0]) if hp and hp[1] > hp[0] else None
        required = api684_required(af, not above) if af is not None else None
        out.append(Peak(name, n_c, peak, hp, af, margin, required))
    return out


def _half_power(amplitude, n_c: float, half: float, end: float, side: int) -> float | None:
    """The speed (r/min) on one side of a peak at n_c where the amplitude falls to
    `half`: stepping out from the peak by doubling steps (a lightly damped peak is
    narrower than any grid), then by root finding; None when it does not fall there
    before `end`."""
    from scipy.optimize import brentq

    step, near = 1e-7 * n_c, n_c
    while True:
        far = n_c + side * step
        if (far - end) * side > 0:
            far = end
        if amplitude(far) < half:
            lo, hi = sorted((near, far))
            return float(brentq(lambda n: amplitude(n) - half, lo, hi))
        if far == end:
            return None
        near, step = far, 2 * step
