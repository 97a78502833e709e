"""The frequency response of the running machine (a hammer test while it turns): the
receptance of a point's mean motion to a force on a section, against the force's
frequency, at each of a few speeds,

    H(omega; Omega) = beta_p (K(Omega) - omega^2 M + i omega D(Omega))^-1 beta_f^T,

on the turning shaft's reduced model, 2 x 2 (x, y response to x, y force), m/N. At
standstill and low frequency it is the shaft's static compliance. A shaft that is not
of revolution is solved in the frame turning with it, where the force turns backwards
and, in bearings that differ along x and y, the response spreads over the frequencies
w + 2 k Omega (fem.floquet.stationary_receptance reads it at w).
"""

from __future__ import annotations

import math

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.whirl import Receptance
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene


def run_frequency_response(scene: Scene, force_at: float, probe_at: float,
                           frequencies_hz: np.ndarray, speeds_rpm: np.ndarray,
                           options: RunOptions = RunOptions()) -> Receptance:
    """H at each speed (r/min) and frequency (Hz): (speeds, frequencies, 2, 2), m/N, for a
    force on the section at force_at (m) and the response of the section at probe_at."""

    from shaftfem.fem.rotor import section_motion
    from shaftfem.workflows.campbell import RPM, turning
    from shaftfem.workflows.unbalance import forced

    if scene.rotor is None:
        raise SceneError(f"{scene.source}: no [rotor] table: the frequency response of the "
                         "running machine needs its speed")
    for what, z in (("--at-mm", force_at), ("--probe-mm", probe_at)):
        if not 0.0 <= z <= scene.shaft.length:
            raise SceneError(f"{what} {z * 1e3:g}: must lie on the shaft, 0 to "
                             f"{scene.shaft.length * 1e3:g} mm")
    from shaftfem.fem.floquet import stationary_receptance

    result, model, _ = turning(scene, options)
    model = forced(result, model)
    bf = section_motion(result, force_at, model.shapes)
    bp = section_motion(result, probe_at, model.shapes)
    H = np.zeros((len(speeds_rpm), len(frequencies_hz), 2, 2), dtype=complex)
    for i, n in enumerate(speeds_rpm):
        if model.frame == "rotating" and n > 0:
            for j, f in enumerate(frequencies_hz):
                H[i, j] = stationary_receptance(model, n * RPM, 2 * math.pi * f, bf, bp)
            continue
        for j, f in enumerate(frequencies_hz):
            H[i, j] = bp @ np.linalg.solve(model.dynamic(n * RPM, 2 * math.pi * f), bf.T)
    return Receptance(scene=scene, force_at=force_at, probe_at=probe_at,
                             frequencies_hz=np.asarray(frequencies_hz, dtype=float),
                             speeds_rpm=np.asarray(speeds_rpm, dtype=float), H=H)
