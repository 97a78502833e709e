"""The modelling choices a scene makes by default, each flipped and solved again on the
same mesh: how far each frequency moves. A bound covers the discretisation of the model
as given; this shows what the model's own choices are worth beside it.

The choices: each part's joint (rigid: the seat moves with the part as one body;
distributing: the part rides on the section's mean motion, adding no stiffness) and each
held seat's coupling (distributing or rigid ring). Bearings with coefficients keep
theirs (their coupling is always distributing). All flips are solved on one mesh, with
the planes every variant needs, so a move is the model's alone: making a joint rigid
can only stiffen the shaft, and no frequency falls.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.fem.result import ModalResult, ModelMoves
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene

if TYPE_CHECKING:
    from shaftfem.fem.modes import Modes

OTHER = {"rigid": "distributing", "distributing": "rigid"}
FLIPPED_SUPPORTS = ("rigid", "rigid-radial", "springs")   # kinds whose coupling matters


def flips(scene: Scene) -> list[tuple[str, Scene]]:
    """Each default choice of the scene flipped: (what was flipped, the scene with it)."""
    out = []
    for i, a in enumerate(scene.attachments):
        parts = list(scene.attachments)
        parts[i] = replace(a, joint=OTHER[a.joint])
        out.append((f"{a.name}: joint {OTHER[a.joint]} (scene: {a.joint})",
                    replace(scene, attachments=tuple(parts))))
    for i, s in enumerate(scene.supports):
        if scene.hanging_free or s.kind not in FLIPPED_SUPPORTS:
            continue
        seats = list(scene.supports)
        seats[i] = replace(s, coupling=OTHER[s.coupling])
        out.append((f"{s.name}: coupling {OTHER[s.coupling]} (scene: {s.coupling})",
                    replace(scene, supports=tuple(seats))))
    return out


def _matched(base: Modes, other: Modes) -> np.ndarray:
    """other's frequency for each of base's modes: the j-th mode of a kind to the j-th of
    the same kind (a flip can move a bending pair past a torsion mode); NaN where other has
    too few of that kind."""
    by_kind: dict[str, list[float]] = {}
    for f, kind in zip(other.frequencies, other.kinds):
        by_kind.setdefault(kind, []).append(float(f))
    seen: dict[str, int] = {}
    out = np.full(len(base.frequencies), np.nan)
    for k, kind in enumerate(base.kinds):
        j = seen.get(kind, 0)
        seen[kind] = j + 1
        if j < len(by_kind.get(kind, [])):
            out[k] = by_kind[kind][j]
    return out


def sensitivity(result: ModalResult, options: RunOptions = RunOptions()) -> ModelMoves:
    """The run's frequencies' moves under each flip of flips(result.scene)."""
    from shaftfem.workflows import stages
    from shaftfem.workflows.pipeline import solve_mesh, with_modes

    scene = result.scene
    variants = flips(scene)
    n = len(result.modes.frequencies)
    if not variants:
        return ModelMoves(choices=(), moves=np.zeros((0, n)))
    cuts = tuple(sorted(set(scene.seat_cuts()).union(*(v.seat_cuts() for _, v in variants))))
    base = result
    if cuts != scene.seat_cuts():   # a part made distributing reads its centre's plane
        mesh = stages.mesh(result.shape, scene.shaft, scene.grooves, scene.mesh,
                           use_cache=options.use_cache, cuts=cuts, hubs=scene.hubs())
        base = solve_mesh(scene, result.shape, mesh, options)
    moves = []
    for label, variant in variants:
        options.say(f"sensitivity: {label}")
        other = solve_mesh(with_modes(variant, count=n + 4), result.shape, base.mesh, options)
        moves.append(_matched(base.modes, other.modes) / base.modes.frequencies - 1)
    return ModelMoves(choices=tuple(label for label, _ in variants), moves=np.array(moves))
