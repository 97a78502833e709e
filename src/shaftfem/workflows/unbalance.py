"""The turning shaft's steady response to its unbalances against speed (a Bode plot
at each probe), its peaks, each peak's amplification factor by the half-power method
and its separation margin from the operating speeds against API 684's.

The probes are the unbalances' planes, the bearings' seats and [rotor] probes_mm (the
mean motion of the section, as a proximity probe reads a shaft): amplitude along x,
and the orbit's major semi-axis.
"""

from __future__ import annotations

import math

import numpy as np

from shaftfem.checks.resonance import AF_CRITICALLY_DAMPED, api684_margin
from shaftfem.errors import SceneError
from shaftfem.fem.whirl import RPM, Bode, Peak, UnbalanceResponse
from shaftfem.scene.model import Scene

# The Bode plot's speeds, from 0 to the Campbell diagram's end.
BODE_POINTS = 400


def api684_required(af: float, below: bool) -> float | None:
    """API 684's separation margin for a peak of amplification factor af, below or
    above the operating speed (fraction); None (no margin required) below AF 2.5."""
    if af < AF_CRITICALLY_DAMPED:
        return None
    return api684_margin(af, above=not below)


def unbalance_response(scene: Scene, result, model, speeds_rpm: np.ndarray | None = None
                       ) -> UnbalanceResponse:
    """The response of the turning shaft (`model` on the standstill `result`) to the
    scene's unbalances at every probe, from 0 to the Campbell diagram's end."""
    from shaftfem.fem.rotor import orbit, section_motion
    from shaftfem.fem.rotor import unbalance_response as solve

    if not scene.unbalances:
        raise SceneError(f"{scene.source}: no [[unbalance]] to respond to")
    rotor = scene.rotor
    assert rotor is not None
    forces = [(section_motion(result, u.position), u.amount * complex(math.cos(u.phase),
                                                                       math.sin(u.phase)))
              for u in scene.unbalances]
    probes = [(u.name, u.position, beta) for u, (beta, _) in zip(scene.unbalances, forces)]
    probes += [(b.name, s.position, b.beta) for b, s in
               zip(model.bearings, [s for s in scene.held if s.bearing is not None])]
    probes += [(f"probe at {z * 1e3:g} mm", z, section_motion(result, z)) for z in rotor.probes]
    grid = (np.linspace(0.0, rotor.max_speed / RPM, BODE_POINTS + 1)[1:]
            if speeds_rpm is None else np.asarray(speeds_rpm, dtype=float))

    def at(rpm: float, beta: np.ndarray) -> tuple[float, float, float]:
        return orbit(model, beta, solve(model, rpm * RPM, forces))

    bode, peaks = [], []
    operating = [om / RPM for om in rotor.speeds]
    for name, z, beta in probes:
        rows = np.array([at(n, beta) for n in grid])
        b = Bode(name, z, grid, rows[:, 0], np.degrees(rows[:, 2]), rows[:, 1])
        found = find_peaks(name, b, lambda n, beta=beta: at(n, beta)[0], operating,
                           lambda n: grows(model, n * RPM))
        # a lightly damped peak is narrower than the grid: draw it through its own speeds
        extra = np.array([p.speed_rpm + k * w for p in found for w in
                          [(p.half_power_rpm[1] - p.half_power_rpm[0]) if p.half_power_rpm
                           else 1e-3 * p.speed_rpm] for k in np.linspace(-4, 4, 33)])
        extra = np.setdiff1d(extra[(extra > grid[0]) & (extra < grid[-1])], grid)
        if extra.size:
            order = np.argsort(np.concatenate([grid, extra]), kind="stable")
            rows = np.vstack([rows, [at(n, beta) for n in extra]])[order]
            speeds = np.concatenate([grid, extra])[order]
            b = Bode(name, z, speeds, rows[:, 0], np.degrees(rows[:, 2]), rows[:, 1])
        bode.append(b)
        peaks += found
    return UnbalanceResponse(tuple(bode), tuple(peaks))


def grows(model, omega: float) -> bool:
    """Whether a mode of the turning shaft grows at the spin omega (rad/s): there it has
    no steady unbalance response."""
    from shaftfem.fem.rotor import roots

    r = roots(model, omega)
    scale = 1e-9 * max(float(np.max(np.abs(r.lam))) if r.lam.size else 1.0, 1.0)
    return r.divergence > 0 or bool(np.any(r.lam.real > scale))


def find_peaks(name: str, b: Bode, amplitude, operating: list[float],
               unstable=lambda n: False) -> list[Peak]:
    """The peaks of one probe's Bode curve, each refined on `amplitude` (r/min -> m), its
    half-power speeds and amplification factor, and its margin from the nearest of the
    `operating` speeds (r/min). Where a mode grows (`unstable(n)`) a peak is no steady
    response: it is marked so, with no amplification factor."""
    from scipy.optimize import minimize_scalar

    grid, a = b.speeds_rpm, b.amplitude
    out = []
    for i in np.flatnonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:])) + 1:
        best = minimize_scalar(lambda n: -amplitude(n), bounds=(grid[i - 1], grid[i + 1]),
                               method="bounded", options={"xatol": 1e-7 * grid[i]})
        n_c, peak = float(best.x), -float(best.fun)
        near = min(operating, key=lambda n: abs(n - n_c))
        if unstable(n_c):
            out.append(Peak(name, n_c, peak, None, None, abs(n_c - near) / near, None,
                            unstable=True))
            continue
        half = peak / math.sqrt(2)
        hp = None
        sides = [_half_power(amplitude, n_c, half, grid[0], -1),
                 _half_power(amplitude, n_c, half, grid[-1], +1)]
        if sides[0] is not None and sides[1] is not None:
            hp = (sides[0], sides[1])
        af = n_c / (hp[1] - hp[0]) if hp and hp[1] > hp[0] else None
        required = api684_required(af, n_c < near) if af is not None else None
        out.append(Peak(name, n_c, peak, hp, af, abs(n_c - near) / near, required))
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
