"""Every modal command's entry point: the modes with an error bound for each frequency.

A scene with a target error is solved on meshes adapted to it (workflows.adapt).
Otherwise its fixed mesh is solved and, when asked, bounded by its recovery
estimate confirmed on the same scene solved on a mesh COARSER times coarser
(fem.estimate says how the two combine).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene

if TYPE_CHECKING:
    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.fem.result import ModalResult
    from shaftfem.workflows.adapt import Adapted

COARSER = 1.5        # size ratio of the coarser mesh behind a fixed mesh's estimate


@dataclass(frozen=True)
class Bounded:
    """A modal run with its bounds: the result, each frequency's bound (None when not
    asked for), and how the mesh was adapted (None on the scene's fixed mesh)."""

    result: ModalResult
    estimate: ErrorEstimate | None
    adapted: Adapted | None = None


def run_bounded(scene: Scene, estimate: bool = True,
                options: RunOptions = RunOptions()) -> Bounded:
    """The modes with their error bounds (`Bounded.estimate.relative_error`, fractions
    of each frequency): on a mesh adapted to the scene's target_error when it has one,
    else on its fixed mesh (bounded when `estimate`)."""
    if scene.target_error is not None:
        from shaftfem.workflows.adapt import run_adaptive

        a = run_adaptive(scene, scene.target_error, scene.max_dofs, options)
        return Bounded(a.result, a.estimate, a)
    from shaftfem.workflows.pipeline import run_modes

    result = run_modes(scene, options)
    return Bounded(result, estimate_errors(result, options) if estimate else None)


def estimate_errors(result: ModalResult, options: RunOptions = RunOptions(),
                    ratio: float = COARSER) -> ErrorEstimate:
    """The bound of a fixed mesh's frequencies: its recovery estimate, confirmed by the
    same scene solved on a mesh `ratio` times coarser (cached like any solve, unless
    the options say not to)."""
    from shaftfem.fem.estimate import combine, matched, recovery_estimate, volume_difference
    from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes

    scene, m = result.scene, result.modes
    size_mm = scene.mesh.size * 1e3 * ratio
    options.say(f"error estimate: recovery on this mesh, and a coarser mesh ({size_mm:.3g} mm)")
    fine = recovery_estimate(result.mesh, scene.material, m)
    # the same modes, counted (a frequency limit could select others on a coarse mesh)
    coarse_scene = with_modes(with_mesh(scene, size_mm), count=m.count)
    coarse = run_modes(coarse_scene, replace(options, progress=None))
    ceta = recovery_estimate(coarse.mesh, scene.material, coarse.modes).relative
    return combine(m.frequencies, fine.relative,
                   matched(m.kinds, coarse.modes.kinds, coarse.modes.frequencies),
                   matched(m.kinds, coarse.modes.kinds, ceta), coarse.modes.n_dofs,
                   method=f"recovery, confirmed on a {ratio:g}x coarser mesh",
                   geometry=volume_difference(fine.volume, result.shape, scene.shaft))


def with_accuracy(scene: Scene, percent: float | None = None, max_dofs: int | None = None,
                  fixed: bool = False) -> Scene:
    """The scene asking for another bound (`percent`, %) and DOF budget; `fixed`: on
    its fixed mesh (the target is dropped unless one is given here)."""
    target = scene.target_error
    if fixed:
        target = None
    if percent is not None:
        target = percent / 100
    return replace(scene, target_error=target,
                   max_dofs=scene.max_dofs if max_dofs is None else max_dofs)
