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
    def one(v: float) -> np.ndarray:
        return np.array([v], dtype=float)

    many = assess_many(one(amplitude), one(mean), one(peak), one(gradient), one(diameter),
                       strength)
    return PointAssessment(**{k: float(v[0]) for k, v in many.items()})


def assess_many(amplitude: np.ndarray, mean: np.ndarray, peak: np.ndarray,
                gradient: np.ndarray, diameter: np.ndarray,
                strength: Strength) -> dict[str, np.ndarray]:
    """FKM at many points at once (arrays as `assess` takes them, one value a point):
    PointAssessment's fields by name, an array each."""
    F, c = _pylife(strength.fkm_group)
    n_points = len(amplitude)
    blank = strength.strength_diameter * 1e3
    a_dm, a_dp = strength.size_exponents
    d_mm = np.asarray(diameter, dtype=float) * 1e3
    rm = strength.tensile_strength / MPA * np.array([size_factor(d, blank, a_dm) for d in d_mm])
    rp = strength.yield_strength / MPA * np.array([size_factor(d, blank, a_dp) for d in d_mm])

    def each(value) -> np.ndarray:
        return np.full(n_points, value, dtype=object if isinstance(value, str) else float)

    sw = F.reversed_mat_strength_chap4(rm, each(1.0), each(c["fw_s"]))
    n = F.stieler_support(each(1.0), each(c["aG"]), each(c["bG"]),
                          np.asarray(gradient, dtype=float) * 1e-3, rm)
    kr = F.rough_factor(rm, each(strength.roughness * 1e6), each(1.0), each(c["aR_s"]),
                        each(c["RmNmin"]), each("None"))
    kf = F.kf_constant(each(strength.fkm_group))
    kwk = F.design_factor(n, kf, kr, each(1.0), each(1.0), each(1.0))
    m = F.sm_sensitivity_chap4(rm, each(c["a_M"]), each(c["b_M"]), each(1.0))
    sa, sm = np.asarray(amplitude, float) / MPA, np.asarray(mean, float) / MPA
    cycling = sa > 0
    kak = np.ones(n_points)
    if cycling.any():
        sa_, sm_ = sa[cycling], sm[cycling]
        total = sm_ + sa_
        r = np.where(total != 0, (sm_ - sa_) / np.where(total != 0, total, 1.0), 2.0)
        kak[cycling] = F.sm_factor(r, np.asarray(m, float)[cycling], sm_ / sa_)
    sw, n, kr, kf, kwk, m = (np.asarray(v, dtype=float) for v in (sw, n, kr, kf, kwk, m))
    sak = kak * sw / kwk
    sp = np.asarray(peak, float) / MPA * strength.peak_factor
    with np.errstate(divide="ignore"):
        return dict(
            tensile_strength=rm, yield_strength=rp, reversed_strength=sw, support=n,
            roughness=kr, notch_estimate=kf, design=kwk, mean_sensitivity=m,
            mean_stress=kak, amplitude_strength=sak,
            fatigue_utilisation=sa * strength.fatigue_safety / sak,
            fatigue_safety=np.where(cycling, sak / np.where(cycling, sa, 1.0), np.inf),
            yield_utilisation=sp * strength.yield_safety / rp,
            yield_safety=np.where(sp > 0, rp / np.where(sp > 0, sp, 1.0), np.inf))
