"""Resonance check: how far each natural frequency sits from each excitation harmonic.

For mode frequency f and the k-th harmonic of a source at f_exc, the separation
margin is |f - k f_exc| / (k f_exc). The check holds when every margin is at
least the required margin (default 15 %).

The default follows common machinery practice: a flat separation margin of about
15 % between a natural frequency and any running-speed harmonic. API 684 and
API 617 tie the required margin to each mode's amplification factor (more margin
for lightly damped modes, none for critically damped ones): `[resonance]
criterion = "api684"` takes the margin from the amplification factor of the
scene's modal damping, AF = 1 / (2 zeta) (2 %: AF 25, margin 16.3 %).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.fem.whirl import CRITICALLY_DAMPED_AF
from shaftfem.scene.model import Excitation
from shaftfem.scene.schema import DEFAULT_MARGIN_PERCENT

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult

DEFAULT_MARGIN = DEFAULT_MARGIN_PERCENT / 100


@dataclass(frozen=True)
class Approach:
    """One mode against one source harmonic."""

    mode: int            # 1-based elastic mode number
    frequency: float     # Hz
    kind: str
    source: str
    order: int
    excitation: float    # k f_exc, Hz
    margin: float        # |f - k f_exc| / (k f_exc)
    required: float
    # installed shaft: transmissibility at the response point for lateral base motion at
    # k f_exc (shaftfem.fem.response); None for a free shaft
    amplification: float | None = None
    # listed, never judged nor the closest: a critically damped crossing (AF < 2.5)
    exempt: bool = False

    @property
    def ok(self) -> bool:
        return self.margin >= self.required


@dataclass
class ResonanceVerdict:
    """Every pair of an elastic mode and an excitation harmonic with its separation
    margin abs(f - k f_exc) / (k f_exc) (a fraction), closest first; `ok` when every
    margin is at least its required one."""

    approaches: list[Approach]   # every pair, closest first
    required: float
    # nothing holds the shaft: its free-free modes, which lie above those in its bearings
    free_free: bool = False
    # ... and the scene (or --free) says free-free is what the check is meant on
    free_free_intended: bool = False
    # the shaft turning ([rotor]): what the verdict rests on (None: standstill modes)
    turning: str | None = None
    # the turning shaft's stability: each reason it fails (a mode that grows or is damped
    # less than required at a speed it runs through, a divergence in its running range)
    unstable: list[str] = field(default_factory=list)
    # ... and each stability criterion it meets short while stable (a log decrement above
    # zero but at or below the required one, a failed Level I screening)
    underdamped: list[str] = field(default_factory=list)
    # what is printed beside the verdict and does not fail it (onsets beyond the range)
    warnings: list[str] = field(default_factory=list)
    # what the unbalance response fails (under API 684 a peak nearer the running range
    # than its amplification factor's margin; an orbit above [rotor] amplitude_limit_um
    # at any speed of the Bode plot): the rows the report marks FAIL fail the verdict too
    response: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return (all(a.ok for a in self.approaches) and not self.unstable
                and not self.underdamped and not self.response)

    @property
    def exit_status(self) -> int:
        """0 pass, 1 fail, 4 a pass on a free-free shaft not declared free-free."""
        from shaftfem.errors import EXIT_CHECK_FAILED, EXIT_FREE_FREE

        if not self.ok:
            return EXIT_CHECK_FAILED
        return EXIT_FREE_FREE if self.free_free and not self.free_free_intended else 0

    @property
    def violations(self) -> list[Approach]:
        return [a for a in self.approaches if not a.ok]

    @property
    def judged(self) -> list[Approach]:
        """The pairs the verdict rests on, tightest first (margin less required)."""
        return sorted((a for a in self.approaches if not a.exempt),
                      key=lambda a: a.margin - a.required)

    def closest_per_harmonic(self) -> list[Approach]:
        """For each source harmonic, its tightest judged pair (least margin beyond the
        required one; an exempt pair only where nothing else meets that harmonic), and
        every pair that fails: the rows a reader checks the verdict against."""
        best: dict[tuple[str, int], Approach] = {}

        def tighter(a: Approach, b: Approach) -> bool:
            return (a.exempt, a.margin - a.required) < (b.exempt, b.margin - b.required)

        for a in self.approaches:
            key = (a.source, a.order)
            if key not in best or tighter(a, best[key]):
                best[key] = a
        rows = list(best.values()) + [a for a in self.violations if a not in best.values()]
        return sorted(rows, key=lambda a: (a.ok, a.exempt, a.margin - a.required))

    def as_dict(self) -> dict:
        return {
            "ok": self.ok,
            "free_free": self.free_free,
            "exit_status": self.exit_status,
            "required_margin": self.required,
            "turning": self.turning,
            "unstable": list(self.unstable),
            "stability_criteria_not_met": list(self.underdamped),
            "unbalance_response_not_met": list(self.response),
            "warnings": list(self.warnings),
            "approaches": [
                {"mode": a.mode, "frequency_hz": a.frequency, "kind": a.kind, "source": a.source,
                 "order": a.order, "excitation_hz": a.excitation, "margin": a.margin,
                 "ok": a.ok, "amplification": a.amplification}
                for a in self.approaches
            ],
        }


def check_resonance(frequencies: np.ndarray, kinds: list[str],
                    excitations: tuple[Excitation, ...] | list[Excitation],
                    required: float = DEFAULT_MARGIN,
                    amplification: Callable[[float], float] | None = None) -> ResonanceVerdict:
    """Separation margin of every mode from every harmonic of every source;
    `amplification(f)`: the response's amplification at frequency f (Hz), if known."""
    out = []
    for exc in excitations:
        for k in exc.orders:
            fk = k * exc.frequency
            amp = None if amplification is None else amplification(fk)
            for i, (f, kind) in enumerate(zip(frequencies, kinds)):
                out.append(Approach(mode=i + 1, frequency=float(f), kind=kind, source=exc.name,
                                    order=k, excitation=fk, margin=float(abs(f - fk) / fk),
                                    required=required, amplification=amp))
    out.sort(key=lambda a: a.margin)
    return ResonanceVerdict(approaches=out, required=required)


# API 684: no margin below this amplification factor (a critically damped mode) ...
AF_CRITICALLY_DAMPED = CRITICALLY_DAMPED_AF
# ... and this much more for a critical speed above the operating speed.
API684_ABOVE = 0.10


def api684_margin(amplification_factor: float, above: bool = False) -> float:
    """API 684's separation margin (fraction) for a mode of amplification factor AF:
    none below AF = 2.5, else 0.17 (1 - 1 / (AF - 1.5)), and 0.10 more for a critical
    speed above the operating speed (`above`). An infinite AF (no damping) needs 0.17."""
    if amplification_factor < AF_CRITICALLY_DAMPED:
        return 0.0
    return 0.17 * (1 - 1 / (amplification_factor - 1.5)) + (API684_ABOVE if above else 0.0)


def check_result(result: ModalResult, required: float | None = None) -> ResonanceVerdict | None:
    """The modes of a run against its scene's excitations (None if it has none); the
    required margin (fraction) defaults to the scene's: its flat margin, or with
    criterion "api684" the margin of the modal damping's amplification factor
    AF = 1 / (2 zeta) (the half-power bandwidth's f / (f2 - f1) of every mode)."""
    scene = result.scene
    if not scene.excitations:
        return None
    if required is None:
        required = (api684_margin(1 / (2 * scene.damping_ratio)) if scene.criterion == "api684"
                    else scene.required_margin)
    v = check_resonance(result.modes.frequencies, result.modes.kinds, scene.excitations,
                        required, _lateral_amplification(result))
    return replace(v, free_free=not scene.held,
                   free_free_intended=scene.free_free_intended or scene.hanging_free)


def _lateral_amplification(result: ModalResult) -> Callable[[float], float] | None:
    """f (Hz) -> transmissibility for lateral base motion, for a shaft in supports."""
    if result.installed is None or not result.scene.held:
        return None
    from shaftfem.fem.response import base_response, modal_basis

    basis = modal_basis(result)
    return lambda f: float(base_response(result, np.array([f]), "x",
                                         basis=basis).transmissibility[0])
