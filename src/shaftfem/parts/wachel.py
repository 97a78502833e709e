"""An impeller's or a stage's aerodynamic cross-coupling, Wachel's estimate (API 617,
API 684): the stage's torque over its diameter and flow width,

    q = B T / (D H) (rho_d / rho_s),     T = P / Omega,

with B = 3 for a centrifugal impeller (D its diameter, H the narrower of its
discharge and the diffuser's widths) and 1.5 for an axial stage (D its pitch diameter,
H its blade height), and rho_d / rho_s the gas's density at discharge over suction.
API 617 writes it q_A = B C P / (D H N) (rho_d / rho_s) with C = 63 (hp, in, r/min,
klbf/in), the same with the torque written out: 63,025 hp in lbf / (r/min).

It acts on the part as a cross-coupled stiffness, kxy = q, kyx = -q: a force turned a
quarter turn ahead of the displacement, which drives forward whirl. q is given at
the rated speed; at other speeds the torque follows the fan law, T ~ Omega^2, so
q ~ Omega^2.
"""

from __future__ import annotations

import math

from shaftfem.scene.model import BearingCoefficients, Rotor, Stage

B = {"centrifugal": 3.0, "axial": 1.5}


def cross_coupling(power: float, speed: float, diameter: float, width: float,
                   kind: str = "centrifugal", density_ratio: float = 1.0) -> float:
    """Wachel's q (N/m) of a stage of `power` (W) at `speed` (rad/s), its diameter and
    width (m)."""
    return B[kind] * (power / speed) / (diameter * width) * density_ratio


def at_speed(q_rated: float, rated: float, omega: float) -> float:
    """q (N/m) at the spin omega (rad/s), by the fan law from q_rated at `rated`."""
    return q_rated * (omega / rated) ** 2


def api617(hp: float, rpm: float, d_in: float, h_in: float, kind: str = "centrifugal",
           density_ratio: float = 1.0) -> float:
    """API 617's own form, q_A = B C P / (D H N) (rho_d / rho_s) with C = 63: klbf/in
    from hp, in and r/min (a check on cross_coupling)."""
    return B[kind] * 63.0 * hp / (d_in * h_in * rpm) * density_ratio


KLBF_PER_IN = 4.4482216152605e3 / 0.0254   # N/m
HP = 745.69987158227                       # W
IN = 0.0254                                # m
RPM = math.pi / 30                         # rad/s

# A stage's cross-coupling is tabled at this many speeds from 0 to the Campbell
# diagram's end (q ~ speed^2; linear between them: 1e-5 of q at most).
STAGE_POINTS = 161


def coefficients(stage: Stage, rotor: Rotor) -> BearingCoefficients:
    """The stage's cross-coupling against speed: Wachel's q at the machine's rated
    speed, by the fan law elsewhere (the operating speeds in the table: q there
    exactly)."""
    rated = rotor.rated
    q = cross_coupling(stage.power, rated, stage.diameter, stage.width, stage.kind,
                       stage.density_ratio)
    speeds = sorted({*(rotor.max_speed * k / (STAGE_POINTS - 1) for k in range(STAGE_POINTS)),
                     *rotor.speeds})
    kxy = tuple(at_speed(q, rated, w) for w in speeds)
    zero = (0.0,)
    return BearingCoefficients(speeds=tuple(speeds), kxx=zero, kxy=kxy,
                               kyx=tuple(-k for k in kxy), kyy=zero, cxx=zero, cxy=zero,
                               cyx=zero, cyy=zero)
