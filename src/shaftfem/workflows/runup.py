"""A run-up (or coast-down) through the critical speeds: the turning shaft's reduced
model (workflows.campbell.turning) integrated in time at a constant angular
acceleration alpha, driven by the scene's unbalances.

The spin Omega(t) = Omega_0 + alpha t turns the shaft by phi(t) = Omega_0 t + alpha t^2 / 2;
an unbalance m e at the phase theta pushes on its plane with

    F = m e (Omega^2 cos(phi + theta) + alpha sin(phi + theta),
             Omega^2 sin(phi + theta) - alpha cos(phi + theta))

(its centripetal and its tangential reaction). M q'' + D(Omega) q' + K(Omega) q = F is
integrated by Newmark's average acceleration (unconditionally stable, no numerical
damping) at STEPS steps per period of the fastest motion the model carries at that
moment (the spin, or below its lowest whirl frequency that mode: time_steps), D and K
taken at each step's speed. A peak passed quickly is lower and later than the steady
one (Lewis 1932): the resonance has no time to build up.

A shaft that is not of revolution is integrated in the frame turning with it, where its
own matrices are constant: there an unbalance's force stands still, the bearings' parts
that differ along x and y turn at twice the shaft's angle, the acceleration adds the
Euler force, and each probe's motion is turned back to the housing's frame.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.whirl import WHIRLING, RunUp
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene

if TYPE_CHECKING:
    from shaftfem.fem.rotor import RotorModel

# Newmark steps per turn of the shaft (or per period of its lowest whirl, if slower),
# and speeds of the coefficient table the steps interpolate D and K in
STEPS = 150
TABLE = 400
MAX_STEPS = 5_000_000


def time_steps(start: float, stop: float, accel: float, floor: float,
               steps_per_turn: int = STEPS) -> np.ndarray:
    """The times (s, from 0) of a run from `start` to `stop` (rad/s) at `accel`: each step
    a 1 / steps_per_turn of the period of the fastest motion the model then carries,
    the spin or, slower than `floor` (rad/s, its lowest whirl frequency, which the start
    sets ringing), that mode. The peak's error falls as the step's square (0.035 % at
    150 a turn on Friswell's 5.9.1 passing its first critical), and it is the same at
    every speed; a run from rest takes half the steps per turn of one stepped throughout
    at its top speed."""
    duration = (stop - start) / accel
    period = 2 * math.pi / steps_per_turn
    times = [0.0]
    t = 0.0
    while t < duration:
        w = max(abs(start + accel * t), floor)
        dt = period / w
        # the speed at the step's end (a run-up grows into a shorter step)
        dt = min(dt, period / max(abs(start + accel * min(t + dt, duration)), floor))
        t = min(t + dt, duration)
        times.append(t)
        if len(times) > MAX_STEPS + 1:
            raise SceneError(f"a run-up of {duration:.4g} s takes more than {MAX_STEPS:,} "
                             "time steps: accelerate faster or span fewer speeds")
    return np.array(times)


def lowest_whirl(model: RotorModel) -> float:
    """The lowest whirl frequency of the model at standstill (rad/s): the slowest mode a
    run's start sets ringing (none: 0)."""
    w = [math.sqrt(w2) for w2, kind in zip(model.omega2, model.kinds)
         if kind in WHIRLING and w2 > 0]
    return min(w) if w else 0.0


def newmark_run_up(model: RotorModel, start: float, stop: float, accel: float,
                   forces: list[tuple[np.ndarray, complex]], probes: list[np.ndarray],
                   steps_per_turn: int = STEPS) -> tuple[np.ndarray, np.ndarray, list[np.ndarray]]:
    """The time (s), the spin (rad/s) and each probe's (x, y) motion (2, n_t) (m), as the
    housing sees it, of the model run from `start` to `stop` (rad/s) at `accel`
    (rad/s^2, negative for a coast-down), from rest at the start, on time_steps.
    forces: (beta, m e e^{i theta}) per unbalance; probes: each section's beta (2, N)."""
    if accel == 0 or (stop - start) / accel <= 0:
        raise SceneError("a run-up needs an acceleration taking the speed from the start to "
                         "the stop")
    floor = lowest_whirl(model) or max(abs(start), abs(stop))
    times = time_steps(start, stop, accel, floor, steps_per_turn)
    return times, start + accel * times, integrate(model, start, accel, times, forces, probes)


def integrate(model: RotorModel, start: float, accel: float, times: np.ndarray,
              forces: list[tuple[np.ndarray, complex]], probes: list[np.ndarray],
              q0: np.ndarray | None = None) -> list[np.ndarray]:
    """Each probe's (x, y) motion (2, n_t) (m), as the housing sees it, of the model
    spun at Omega(t) = start + accel t (rad/s) over `times` (s, from 0), from rest (or
    from the displacement q0), by Newmark's average acceleration. In the frame turning
    with the shaft, its angle phi = start t + accel t^2 / 2 turns the bearings' parts
    that differ along x and y (D(t) = D + D_c cos 2 phi + D_s sin 2 phi, and K), the
    spin's change adds the Euler force (accel / 2) G q (G = 2 int rho Phi^T S Phi, the
    Coriolis matrix per rad/s), an unbalance's force stands still, and each probe's
    motion is turned back by phi."""
    rotating = model.frame == "rotating"
    ends = (start, start + accel * float(times[-1]))
    speeds = np.linspace(min(ends), max(ends), TABLE)
    N = model.size
    table = [model.matrices(float(w)) for w in speeds]
    D_tab = np.array([d for d, _ in table])
    # the spin's change adds the Euler force (accel / 2) G q in the turning frame
    K_tab = np.array([k for _, k in table]) + (0.5 * accel * model.G if rotating else 0.0)
    periodic = [rotating and model.periodic(float(w)) for w in speeds]
    P_tab = (np.array([model.periodic_parts(float(w)) if p else (np.zeros((N, N)),) * 4
                       for w, p in zip(speeds, periodic)]) if any(periodic) else None)
    M_tab = np.array([model.mass(float(w)) for w in speeds]) if any(
        b.coefficients.has_mass for b in model.bearings) else None

    # each step's place in the table (linear in the speed between its rows), angle, load
    span = speeds[-1] - speeds[0]
    w_t = start + accel * times
    pos = (w_t - speeds[0]) / span * (TABLE - 1) if span > 0 else np.zeros(times.size)
    row = np.clip(np.floor(pos), 0, TABLE - 2).astype(int)
    frac = pos - row
    phi_t = start * times + 0.5 * accel * times * times
    B = np.array([beta for beta, _ in forces]) if forces else np.zeros((0, 2, N))
    U = np.array([u for _, u in forces], dtype=complex)          # m e e^{i theta}
    P = np.array(probes)                                    # (p, 2, N)

    def loads(k0: int, k1: int) -> np.ndarray:
        """The unbalances' modal forces at steps k0..k1-1 (k1 - k0, N)."""
        w = w_t[k0:k1, None]
        c = U[None, :] * (1.0 if rotating else np.exp(1j * phi_t[k0:k1, None]))
        fx = w * w * c.real + accel * c.imag
        fy = w * w * c.imag - accel * c.real
        return fx @ B[:, 0] + fy @ B[:, 1]

    def matrices(k0: int, k1: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """M, D and K at steps k0..k1-1 (k1 - k0, N, N): linear in the speed between
        the table's rows, the parts that differ along x and y turned by 2 phi."""
        i, f = row[k0:k1], frac[k0:k1, None, None]
        D = (1 - f) * D_tab[i] + f * D_tab[i + 1]
        K = (1 - f) * K_tab[i] + f * K_tab[i + 1]
        M = (np.broadcast_to(np.eye(N), D.shape) if M_tab is None
             else (1 - f) * M_tab[i] + f * M_tab[i + 1])
        if P_tab is not None:
            Dc, Ds, Kc, Ks = ((1 - f) * P_tab[i, j] + f * P_tab[i + 1, j] for j in range(4))
            c, sn = np.cos(2 * phi_t[k0:k1, None, None]), np.sin(2 * phi_t[k0:k1, None, None])
            D, K = D + c * Dc + sn * Ds, K + c * Kc + sn * Ks
        return M, D, K

    # each probe's (x, y) in the turning frame, turned back by phi to the housing's
    out = np.empty((P.shape[0], 2, times.size))
    q = np.zeros(N) if q0 is None else np.array(q0, dtype=float)
    v = np.zeros(N)
    M0, D0, K0 = (m[0] for m in matrices(0, 1))
    a = np.linalg.solve(M0, loads(0, 1)[0] - D0 @ v - K0 @ q)
    out[:, :, 0] = P @ q
    beta_n, gamma = 0.25, 0.5
    # a block of steps at a time: their loads, matrices and Newmark's inverse
    # (M + gamma dt D + beta dt^2 K)^-1 made at once, the step itself three products
    BLOCK = 1024
    for k0 in range(1, times.size, BLOCK):
        k1 = min(k0 + BLOCK, times.size)
        F = loads(k0, k1)
        dt = times[k0:k1] - times[k0 - 1:k1 - 1]
        M, D, K = matrices(k0, k1)
        try:
            inv = np.linalg.inv(M + (gamma * dt)[:, None, None] * D
                                + (beta_n * dt * dt)[:, None, None] * K)
        except np.linalg.LinAlgError:
            raise np.linalg.LinAlgError(f"Newmark's steps {k0} to {k1 - 1}: a singular "
                                        "system") from None
        Q = np.empty((k1 - k0, N))
        for j in range(k1 - k0):
            h = float(dt[j])
            pred_q = q + h * v + ((0.5 - beta_n) * h * h) * a
            pred_v = v + ((1 - gamma) * h) * a
            a = inv[j] @ (F[j] - D[j] @ pred_v - K[j] @ pred_q)
            q = pred_q + (beta_n * h * h) * a
            v = pred_v + (gamma * h) * a
            Q[j] = q
        out[:, :, k0:k1] = np.einsum("pcn,kn->pck", P, Q)
    if rotating:
        c, sn = np.cos(phi_t), np.sin(phi_t)
        x, y = out[:, 0].copy(), out[:, 1].copy()
        out[:, 0], out[:, 1] = c * x - sn * y, sn * x + c * y
    return [out[i] for i in range(P.shape[0])]


def envelope(times: np.ndarray, speeds: np.ndarray, xy: np.ndarray, start: float,
             accel: float) -> tuple[np.ndarray, np.ndarray]:
    """Per turn of the shaft: its mean speed (rad/s) and the largest radius of the
    orbit (m) in it."""
    phi = start * times + 0.5 * accel * times**2
    turn = np.floor(np.abs(phi) / (2 * math.pi)).astype(int)
    r = np.hypot(xy[0], xy[1])
    n = int(turn.max()) + 1
    peak = np.zeros(n)
    np.maximum.at(peak, turn, r)
    mean = np.bincount(turn, speeds, n) / np.maximum(np.bincount(turn, None, n), 1)
    keep = np.bincount(turn, None, n) > 0
    return mean[keep][:-1], peak[keep][:-1]       # the last turn is partial


def run_run_up(scene: Scene, start_rpm: float, stop_rpm: float, accel_rpm_per_s: float,
               options: RunOptions = RunOptions(), steps_per_turn: int = STEPS) -> RunUp:
    """The scene's rotor run from start_rpm to stop_rpm at accel_rpm_per_s (negative:
    a coast-down) with its unbalances: each probe's envelope against speed, its peak,
    the orbit there, and the steady response at the same speeds."""
    from shaftfem.fem.floquet import any_unbalance_response as steady
    from shaftfem.fem.rotor import orbit, section_motion
    from shaftfem.workflows.campbell import RPM, turning
    from shaftfem.workflows.unbalance import forced

    if scene.rotor is None or not scene.unbalances:
        raise SceneError(f"{scene.source}: a run-up needs [rotor] and an [[unbalance]] to "
                         "drive it")
    result, model, _ = turning(scene, options)
    model = forced(result, model)
    forces = [(section_motion(result, u.position, model.shapes),
               u.amount * complex(math.cos(u.phase), math.sin(u.phase)))
              for u in scene.unbalances]
    names = [u.name for u in scene.unbalances] + [f"probe at {p * 1e3:g} mm"
                                                  for p in scene.rotor.probes]
    probes = [beta for beta, _ in forces] + [section_motion(result, p, model.shapes)
                                            for p in scene.rotor.probes]
    start, stop, accel = start_rpm * RPM, stop_rpm * RPM, accel_rpm_per_s * RPM
    times, speeds, xy = newmark_run_up(model, start, stop, accel, forces, probes,
                                       steps_per_turn)
    envelopes, peaks, orbits, steady_major = [], [], [], []
    for track in xy:
        w, r = envelope(times, speeds, track, start, accel)
        envelopes.append((w / RPM, r))
        i = int(np.argmax(r))
        peaks.append((float(w[i] / RPM), float(r[i])))
        t_peak = (w[i] - start) / accel
        window = np.abs(times - t_peak) <= 2 * math.pi / max(w[i], 1e-9)
        orbits.append(track[:, window])
    grid = envelopes[0][0]
    for beta in probes:
        steady_major.append(np.array([orbit(model, beta, steady(model, w * RPM, forces))[1]
                                      for w in grid]))
    return RunUp(scene=scene, accel_rpm_per_s=accel_rpm_per_s, names=tuple(names),
                 speeds_rpm=grid, envelopes=tuple(r for _, r in envelopes),
                 steady=tuple(steady_major), peaks=tuple(peaks), orbits=tuple(orbits),
                 steps=len(times) - 1)
