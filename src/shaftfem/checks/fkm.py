"""The FKM guideline's local approach (FKM 2012, chapter 4: local elastic stresses from
FE) at one point of the shaft: fatigue (infinite life) and the static check against
yield.

    sigma_W,zd = f_W,sigma R_m,d                      material's reversed strength
    K_WK = (1 / n_sigma) (1 + (1 / K_f~) (1 / K_R - 1))   design factor
    sigma_WK = sigma_W,zd / K_WK                       the component's at this point
    sigma_AK = K_AK sigma_WK                           with the mean stress (R constant)
    a_BK = sigma_a j_D / sigma_AK                      degree of utilisation, <= 1

n_sigma is Stieler's support factor from the relative stress gradient G (1/mm), K_R the
roughness factor, K_f~ FKM's estimate of the notch factor (2 for steel), K_AK the mean
stress factor of overload case F2 with the sensitivity M_sigma. Amplitudes and means are
von Mises equivalents (ductile steel); the factors are pyLife's implementation of the
guideline's formulas (`pylife.strength.fkm_linear`). R_m and R_p0.2 are carried from the
test blank to the shaft's diameter by the size factor (scene.materials). The yield check
is elastic (plastic support n_pl = 1, on the safe side): a_SK = sigma_peak j_p / R_p,d.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np

from shaftfem.scene.materials import size_factor
from shaftfem.scene.model import Strength

MPA = 1e6


@dataclass(frozen=True)
class PointAssessment:
    """FKM at one point: the strengths carried to its diameter (MPa), the factors, the
    component strength (MPa) and the utilisations (fatigue a_BK, yield a_SK) and safeties."""

    tensile_strength: float
    yield_strength: float
    reversed_strength: float
    support: float
    roughness: float
    notch_estimate: float
    design: float
    mean_sensitivity: float
    mean_stress: float
    amplitude_strength: float
    fatigue_utilisation: float
    fatigue_safety: float
    yield_utilisation: float
    yield_safety: float


@cache
def _pylife(group: str):
    """pyLife's FKM functions and the group's constants (normal stress): loaded once."""
    import pylife._fkm_linear_functions as F
    from pylife.strength.fkm_linear.fkm_functions import FkmLinearFunctions

    consts, _ = FkmLinearFunctions().get_material_constants(group, "normal")
    return F, {k: float(consts[k]) for k in ("fw_s", "aG", "bG", "aR_s", "RmNmin", "a_M",
                                             "b_M")}


def assess(amplitude: float, mean: float, peak: float, gradient: float, diameter: float,
           strength: Strength) -> PointAssessment:
    """FKM at a point with the equivalent stress amplitude, signed mean and peak (Pa),
    the relative stress gradient G (1/m) and the shaft's diameter there (m)."""
    F, c = _pylife(strength.fkm_group)
    d_mm = diameter * 1e3
    blank = strength.strength_diameter * 1e3
    a_dm, a_dp = strength.size_exponents
    rm = strength.tensile_strength / MPA * size_factor(d_mm, blank, a_dm)
    rp = strength.yield_strength / MPA * size_factor(d_mm, blank, a_dp)

    def one(f, *args):
        return float(f(*(np.array([a], dtype=object if isinstance(a, str) else float)
                         for a in args))[0])

    sw = one(F.reversed_mat_strength_chap4, rm, 1.0, c["fw_s"])
    n = one(F.stieler_support, 1.0, c["aG"], c["bG"], gradient * 1e-3, rm)
    kr = one(F.rough_factor, rm, strength.roughness * 1e6, 1.0, c["aR_s"], c["RmNmin"], "None")
    kf = one(F.kf_constant, strength.fkm_group)
    kwk = one(F.design_factor, n, kf, kr, 1.0, 1.0, 1.0)
    m = one(F.sm_sensitivity_chap4, rm, c["a_M"], c["b_M"], 1.0)
    sa, sm = amplitude / MPA, mean / MPA
    if sa > 0:
        r = (sm - sa) / (sm + sa) if sm + sa != 0 else -np.inf
        kak = one(F.sm_factor, r if np.isfinite(r) else 2.0, m, sm / sa)
    else:
        kak = 1.0
    sak = kak * sw / kwk
    a_bk = sa * strength.fatigue_safety / sak
    a_sk = peak / MPA * strength.peak_factor * strength.yield_safety / rp
    return PointAssessment(
        tensile_strength=rm, yield_strength=rp, reversed_strength=sw, support=n,
        roughness=kr, notch_estimate=kf, design=kwk, mean_sensitivity=m, mean_stress=kak,
        amplitude_strength=sak, fatigue_utilisation=a_bk,
        fatigue_safety=sak / sa if sa > 0 else np.inf, yield_utilisation=a_sk,
        yield_safety=rp / (peak / MPA * strength.peak_factor) if peak > 0 else np.inf)
