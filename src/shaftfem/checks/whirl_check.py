"""The resonance check of a shaft that turns ([rotor]): its critical speeds against
its operating speeds, and its whirl at the operating speeds against every other
source's harmonics.

- A harmonic of the shaft's own speed (a source at an operating speed, 1x always) is
  met where a whirl curve crosses its order line: the critical speed N_c, with the
  speed margin |N_c - N| / N. At 1x an unbalance drives forward whirl only on a shaft
  of revolution in isotropic bearings, so there backward 1x crossings are not judged;
  elsewhere (anisotropic bearings, a shaft that is not of revolution) both are.
- Any other source's harmonic k f is met by the whirl frequencies at each operating
  speed, forward and backward, margin |f - k f| / (k f).
- Torsion and axial modes do not whirl: they meet every harmonic as at standstill.

The required margin is the scene's flat one, or with criterion "api684" that of each
mode's amplification factor AF = pi / log dec (none below AF 2.5; an undamped model
has none to give, and gets 17 % below and 27 % above the operating speed).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from shaftfem.checks.resonance import Approach, ResonanceVerdict, api684_margin

if TYPE_CHECKING:
    from shaftfem.fem.whirl import Campbell



def amplification(log_dec: float) -> float:
    """A mode's amplification factor from its log decrement, pi / delta (infinite
    undamped)."""
    return math.pi / log_dec if log_dec > 0 else math.inf


def check_whirl(c: Campbell, required: float | None = None) -> ResonanceVerdict | None:
    """The turning shaft's verdict (None when the scene has no excitation at all)."""
    scene = c.result.scene
    rotor = scene.rotor
    assert rotor is not None
    speeds = [om * 60 / (2 * math.pi) for om in rotor.speeds]
    own = [e for e in scene.excitations if any(abs(e.frequency * 60 - n) <= 1e-9 * n
                                               for n in speeds)]
    others = [e for e in scene.excitations if e not in own]
    api = scene.criterion == "api684" and required is None
    flat = required if required is not None else scene.required_margin
    isotropic = c.frame == "rotating" or all(
        s.bearing is None or s.bearing.isotropic for s in scene.held)
    judged = [cs for cs in c.critical_speeds
              if not (cs.order == 1 and cs.whirl == "backward" and scene.axisymmetric
                      and isotropic)]
    out = []
    for n in speeds:
        for cs in judged:
            below = cs.speed_rpm < n
            need = api684_margin(amplification(cs.log_dec), above=not below) if api else flat
            out.append(Approach(mode=cs.mode, frequency=cs.frequency_hz,
                                kind=f"{cs.whirl} whirl, critical at {cs.speed_rpm:,.0f} r/min",
                                source=f"shaft at {n:,.0f} r/min", order=cs.order,
                                excitation=cs.order * n / 60, margin=abs(cs.speed_rpm - n) / n,
                                required=need))
    rows = {n: [w for w in c.operating if abs(w.speed_rpm - n) <= 1e-9 * n] for n in speeds}
    for n, ws in rows.items():
        for w in ws:
            still = w.kind not in ("bending", "mixed")
            for e in others + (own if still else []):
                for k in e.orders:
                    fk = k * e.frequency
                    need = api684_margin(amplification(w.log_dec)) if api else flat
                    kind = w.kind if still else f"{w.kind}, {w.whirl} whirl at {n:,.0f} r/min"
                    out.append(Approach(mode=w.mode, frequency=w.frequency_hz, kind=kind,
                                        source=e.name, order=k, excitation=fk,
                                        margin=abs(w.frequency_hz - fk) / fk, required=need))
    if not scene.excitations and not c.critical_speeds:
        return None
    out.sort(key=lambda a: a.margin - a.required)
    basis = (f"the shaft turning at {', '.join(f'{n:,.0f}' for n in speeds)} r/min ({c.frame} "
             f"frame): critical speeds from 0 to {max(c.speeds_rpm):,.0f} r/min against the "
             "operating speed" + ("; whirl frequencies there against "
                                  + ", ".join(e.name for e in others) if others else "")
             + (" (backward 1x crossings left out: an unbalance drives forward whirl only on "
                "a shaft of revolution in isotropic bearings)" if scene.axisymmetric
                and isotropic and any(cs.whirl == "backward" and cs.order == 1
                                      for cs in c.critical_speeds) else "")
             + (". API 684 margins from each mode's log decrement" if api else "")
             + ("; no bearing damping, so no amplification factor: the margin is API 684's "
                "for a lightly damped mode" if api and not any(
                    s.bearing is not None for s in scene.held) else ""))
    return ResonanceVerdict(approaches=out, required=flat, free_free=not scene.held,
                            free_free_intended=scene.free_free_intended or scene.hanging_free,
                            turning=basis)
