"""The shaft hanging free, on the turning shaft's basis: its bearings' stiffness taken out.

The rotor's basis (fem.rotor) holds its standstill modes and its bearings' static
shapes, so a bearing's stiffness enters it exactly to first order: with every bearing
at zero,

    (diag(w^2) - sum_b beta_b^T diag(k_b(0)) beta_b) y = w_free^2 y

is a Rayleigh-Ritz of the free shaft on that basis (an upper bound on each frequency).
The static shapes span its sideways rigid motions (a rigid motion u has K u in the
bearings' seats), which come out at zero. It holds only where the bearings are all
that hold the shaft (each a seat's mean motion, no axial or tilting hold in K), and
the frequencies are kept only where two thirds of the basis gives them within
CHANGE: else None, and the free shaft is solved on its own.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.scene.model import BearingCoefficients, Scene

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult
    from shaftfem.fem.rotor import RotorModel

# how far (relative) the free frequencies may move on two thirds of the basis: the
# comparison prints them to 0.01 Hz
CHANGE = 1e-4
# a rigid motion comes out at zero up to round-off: below this share of the lowest
# elastic frequency
RIGID = 1e-4
FREE = BearingCoefficients(speeds=(), kxx=(0.0,), kxy=(0.0,), kyx=(0.0,), kyy=(0.0,),
                           cxx=(0.0,), cxy=(0.0,), cyx=(0.0,), cyy=(0.0,))


@dataclass(frozen=True)
class HangingModes:
    """The free shaft's lowest elastic modes on the rotor's basis: frequencies (Hz),
    kinds, and how far two thirds of the basis moves them (relative)."""

    frequencies: np.ndarray
    kinds: list[str]
    change: float

    @property
    def count(self) -> int:
        return self.frequencies.size


def held_by_bearings_alone(scene: Scene) -> bool:
    """Whether every support of the scene is a bearing (its stiffness its coefficients')
    on its seat's mean motion (a distributing seat) with no axial or tilting hold: what
    the rotor's basis can take out again."""
    return bool(scene.held) and all(
        (s.bearing is not None or s.awaits_part) and s.coupling == "distributing"
        and s.axial == 0 and s.tilting == 0 for s in scene.held)


def _frequencies(model: RotorModel) -> tuple[np.ndarray, np.ndarray]:
    """The model's undamped standstill frequencies (Hz, all) with no bearing, and their
    modal coordinates."""
    free = replace(model, bearings=tuple(replace(b, coefficients=FREE)
                                         for b in model.bearings))
    K = free.matrices(0.0)[1]
    lam, Y = np.linalg.eigh(0.5 * (K + K.T))
    return np.sqrt(np.maximum(lam, 0.0)) / (2 * math.pi), Y


def hanging_modes(result: ModalResult, model: RotorModel, count: int
                  ) -> HangingModes | None:
    """The lowest `count` elastic modes of the shaft of `result` hanging free, from the
    rotor model on its standstill modes (`model`, with its residual modes and shapes);
    None where the basis cannot give them (see the module)."""
    from shaftfem.fem.modes import classify, energy_split

    if (model.shapes is None or not model.residual or not held_by_bearings_alone(result.scene)
            or {s.name for s in result.scene.held} - {b.name for b in model.bearings}):
        return None
    n_rigid = 6 - (result.installed.n_rigid if result.installed is not None else 6)
    f, Y = _frequencies(model)
    elastic = np.arange(n_rigid, min(n_rigid + count, f.size))
    if elastic.size < count or (n_rigid and f[n_rigid - 1] > RIGID * f[n_rigid]):
        return None
    g, _ = _frequencies(model.truncated(2 * (model.size - model.residual) // 3))
    change = float(np.max(np.abs(g[elastic] / f[elastic] - 1)))
    if change > CHANGE:
        return None
    shapes = model.shapes @ Y[:, elastic]
    system = result.system
    kinds = [classify(e) for e in energy_split(shapes, system.nodes, system.mass_scalar)]
    return HangingModes(frequencies=f[elastic], kinds=kinds, change=change)
