"""The record of one modal run: every step's product, how long each step took, and
what the run warns of. The typed hand-over from the chain to its readers (checks,
files, pictures, reports)."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np

    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.cad.solid import ShaftShape
    from shaftfem.fem.assembly import System
    from shaftfem.fem.installation import Installed
    from shaftfem.fem.modes import Modes
    from shaftfem.scene.model import Scene


@dataclass(frozen=True)
class Timings:
    """Wall time of each step of one modal run, s, as the workflow measured it."""

    cad: float = 0.0
    mesh: float = 0.0
    assembly: float = 0.0
    solve: float = 0.0   # factorisations, eigensolve and the inertia proof
    total: float = 0.0

    def items(self) -> Iterator[tuple[str, float]]:
        return ((f.name, getattr(self, f.name)) for f in fields(self))



@dataclass(frozen=True)
class ModalResult:
    """One modal run and what it made: the scene, the solid (`shape`), the mesh, K and M
    (`system`), the `modes`, the time of each step (`timings`, s), warnings about the
    run, and the seats and parts (`installed`; None for a free shaft)."""

    scene: Scene
    shape: ShaftShape
    mesh: ShaftMesh
    system: System
    modes: Modes
    timings: Timings
    warnings: tuple[str, ...] = ()
    installed: Installed | None = None  # the seats and parts (None: free-free)

    def reduced_shapes(self) -> np.ndarray:
        """The modes in the installed shaft's reduced coordinates (n_q, n): the shapes are
        T q exactly, and the coupled machines' turns are kept beside them."""
        import numpy as np

        assert self.installed is not None
        q = self.installed.shaft_coordinates(self.modes.shapes)
        return q if self.modes.trains is None else np.vstack([q, self.modes.trains])

    def shapes_at_points(self) -> np.ndarray:
        """Mode shapes at the mesh's points: (n_modes, n_points, 3), m / sqrt(kg)."""
        return self.system.at_points(self.modes.shapes)


@dataclass(frozen=True)
class ModelMoves:
    """How far each frequency moves when one modelling choice the scene makes by default
    is flipped (a part's joint, a seat's coupling) and the same mesh solved again:
    `choices` names each flip, `moves[c, k]` is mode k's relative move under flip c
    (f_flipped / f - 1; NaN where the flipped model has no mode of that kind to match)."""

    choices: tuple[str, ...]
    moves: np.ndarray

    def largest(self) -> list[tuple[float, str]]:
        """For each mode, its largest move (signed) and the choice behind it."""
        import numpy as np

        out = []
        for k in range(self.moves.shape[1]):
            col = np.nan_to_num(self.moves[:, k], nan=0.0)
            c = int(np.argmax(np.abs(col)))
            out.append((float(col[c]), self.choices[c]))
        return out
