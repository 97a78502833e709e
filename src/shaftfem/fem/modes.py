"""The shaft's modes read from the pencil's eigenpairs: the rigid motions checked,
the elastic modes normalised, their quality measured and their kind named.

Free (no seats): (K, M) of one free body, its six rigid motions given to the
solver. Installed: the reduced pencil of shaftfem.fem.supports, with the rigid
motions its seats leave free; the shapes come back as displacements of every node.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from shaftfem.errors import SolverError
from shaftfem.fem.eigen import (
    MECHANISM_FACTOR,
    RIGID_BODY_MODES,
    RIGID_FACTOR,
    SHIFT_FACTOR,
    EigenSolution,
    SolverSettings,
    one_norm,
    solve_modes,
)
from shaftfem.fem.installation import Installed
from shaftfem.fem.ritz import Ritz
from shaftfem.fem.supports import n_bodies, rigid_body_modes
from shaftfem.scene.model import ModeRequest

if TYPE_CHECKING:
    from shaftfem.fem.assembly import System


@dataclass(frozen=True)
class Modes:
    """The first elastic modes of the shaft, lowest first.

    frequencies in Hz; shapes (n_dofs, n) mass-normalised (x^T M x = 1, in
    m / sqrt(kg)); residuals ||K x - w^2 M x|| / ||K x||; backward_errors the
    same residual over (||K|| + w^2 ||M||) ||x|| (1-norms); kinds 'bending',
    'torsion', 'axial' or 'mixed'; energy (n, 3): kinetic-energy fractions in
    axial, radial and tangential (about the shaft axis) motion.
    """

    frequencies: np.ndarray
    shapes: np.ndarray
    residuals: np.ndarray
    backward_errors: np.ndarray
    kinds: list[str]
    energy: np.ndarray
    rigid_frequencies: np.ndarray
    orthonormality_error: float
    shift: float
    n_dofs: int
    factoriser: str
    # The inertia of K - s M counted `inertia_count` eigenvalues (rigid ones included)
    # below s = inertia_shift (rad^2/s^2), as many as the solver found: none was skipped.
    inertia_count: int = 0
    inertia_shift: float = 0.0
    # the coupled machines' turns in each mode (m, n), rad / sqrt(kg m^2): the shaft's
    # shapes do not hold them (fem.installation, coupled_inertia_kg_m2)
    trains: np.ndarray | None = None
    # the further pairs the solver proved below inertia_shift, in its own coordinates
    # (the installed shaft's reduced ones): kept with the shapes as the next solve's start
    beyond: np.ndarray | None = field(default=None, repr=False)

    @property
    def inertia_shift_hz(self) -> float:
        """The counting shift as a frequency, Hz."""
        return math.sqrt(self.inertia_shift) / (2 * math.pi)

    @property
    def n_rigid(self) -> int:
        return len(self.rigid_frequencies)

    @property
    def count(self) -> int:
        return len(self.frequencies)

    def lowest(self, n: int) -> Modes:
        """The lowest n of these modes, with their proof: the inertia count below
        inertia_shift holds for any of them (the further pairs left out)."""
        from dataclasses import replace

        return replace(self, frequencies=self.frequencies[:n], shapes=self.shapes[:, :n],
                       residuals=self.residuals[:n], backward_errors=self.backward_errors[:n],
                       kinds=self.kinds[:n], energy=self.energy[:n],
                       trains=None if self.trains is None else self.trains[:, :n],
                       beyond=None)


def modal_analysis(system: System, wanted: ModeRequest = ModeRequest(),
                   settings: SolverSettings = SolverSettings(),
                   installed: Installed | None = None,
                   shift_hint: float | None = None, start: np.ndarray | None = None,
                   ceiling: tuple[float, int] | None = None) -> Modes:
    """Solve, separate the rigid-body modes, check and classify the elastic ones: the
    lowest `wanted.count`, or every one below `wanted.max_frequency` (at least one).
    `shift_hint`, `start`: see eigen.solve_modes (a Modes' inertia_shift and shapes from
    an earlier solve of the same free system); `ceiling`: the (inertia_shift,
    inertia_count) of a space that contains this one."""
    K, M, rigid, what = _pencil(system, installed)
    sol = solve_modes(K, M, wanted, rigid=rigid, settings=settings, shift_hint=shift_hint,
                      start=start, ceiling=ceiling)
    n_given = rigid.shape[1]
    _check_zero_modes(sol, n_given, what)
    lam = sol.eigenvalues
    is_rigid = np.arange(lam.size) < n_given   # the given motions come first
    n_modes = wanted.count
    if wanted.max_frequency is not None:
        n_modes = max(1, int(np.sum(lam[~is_rigid] < (2 * math.pi * wanted.max_frequency) ** 2)))
    elastic = sol.pairs.select(~is_rigid).first(n_modes)
    # M-normalise explicitly (the Ritz vectors are, up to round-off)
    elastic = elastic.scaled(1 / np.sqrt(np.einsum("ij,ij->j", elastic.X, elastic.MX)))
    expand = (lambda X: X) if installed is None else installed.expand
    elastic = fixed_basis(elastic, expand(elastic.X), system.mass_scalar)
    shapes = expand(elastic.X)
    energy = energy_split(shapes, system.nodes, system.mass_scalar, system.constant)
    return Modes(frequencies=np.sqrt(elastic.lam) / (2 * math.pi), shapes=shapes,
                 residuals=elastic.relative_residuals(),
                 backward_errors=backward_errors(K, M, elastic),
                 kinds=[classify(e) for e in energy], energy=energy,
                 rigid_frequencies=np.sqrt(np.abs(lam[is_rigid])) / (2 * math.pi),
                 orthonormality_error=float(np.max(np.abs(elastic.X.T @ elastic.MX
                                                          - np.eye(elastic.X.shape[1])))),
                 shift=-SHIFT_FACTOR * sol.scale, n_dofs=K.shape[0], factoriser=sol.factoriser,
                 inertia_count=sol.inertia_count, inertia_shift=sol.inertia_shift,
                 trains=elastic.X[elastic.X.shape[0] - installed.trains:]
                 if installed is not None and installed.trains else None,
                 beyond=sol.beyond)


# Eigenvalues closer than this (relative) are one within the solver's tolerance: the
# solver's basis of such a pair is any, so it is rotated to a fixed one.
DEGENERATE_SPLIT = 1e-8


def fixed_basis(pairs: Ritz, shapes: np.ndarray, mass_scalar: sp.csr_matrix) -> Ritz:
    """The pairs with every degenerate cluster (eigenvalues within DEGENERATE_SPLIT)
    rotated to its principal directions of x motion: the first mode of a bending pair
    moves in x alone, the second in y alone. Each vector's sign is fixed as well (its
    largest entry positive), so the same scene gives the same shapes whatever the
    solver's start or shift. `shapes`: the vectors as displacements of every node."""
    n = pairs.lam.size
    Q = np.eye(n)
    rotated = False
    i = 0
    while i < n:
        j = i + 1
        while j < n and pairs.lam[j] - pairs.lam[i] <= DEGENERATE_SPLIT * abs(pairs.lam[j]):
            j += 1
        if j - i > 1 and shapes.shape[0] == 3 * mass_scalar.shape[0]:
            ux = shapes[0::3, i:j]
            _, V = np.linalg.eigh(ux.T @ (mass_scalar @ ux))
            Q[i:j, i:j] = V[:, ::-1]   # most x motion first
            rotated = True
        i = j
    out = pairs.rotated(Q) if rotated else pairs
    full = shapes @ Q
    # the sign: the largest motion positive; among motions as large as it to 1e-6 (a
    # torsion mode's at every node of the rim), the first DOF's, so that round-off in
    # the solve does not choose
    size = np.abs(full)
    first = np.argmax(size >= (1 - 1e-6) * size.max(axis=0), axis=0)
    biggest = full[first, np.arange(n)]
    return out.scaled(np.where(biggest < 0, -1.0, 1.0))


def _pencil(system: System, installed: Installed | None
            ) -> tuple[sp.csr_matrix, sp.csr_matrix, np.ndarray, str]:
    """(K, M, the rigid motions given to the solver, what they are) of a free body or
    of the shaft in its seats."""
    if installed is not None:
        return installed.K, installed.M, installed.rigid, (
            f"the supports leave {installed.n_rigid} rigid-body modes "
            f"({', '.join(installed.free) or 'none'})")
    bodies = n_bodies(system.K)
    if bodies != 1:
        raise SolverError(
            f"the mesh has {bodies} disconnected parts; a free body must be one piece "
            f"(it would have {RIGID_BODY_MODES * bodies} rigid-body modes)")
    return (system.K, system.M, rigid_body_modes(system.nodes, constant=system.constant),
            f"one free body has {RIGID_BODY_MODES} rigid-body modes")


def _check_zero_modes(sol: EigenSolution, n_given: int, what: str) -> None:
    """No negative eigenvalue, and no zero one beside the given rigid motions."""
    lam, scale = sol.eigenvalues, sol.scale
    if lam[0] < -RIGID_FACTOR * scale:
        raise SolverError(
            f"a negative eigenvalue w^2 = {lam[0]:.3g} rad^2/s^2: K is not positive "
            "semi-definite (an inverted element or a bad material)"
        )
    zero = (np.arange(lam.size) >= n_given) & (lam < MECHANISM_FACTOR * scale)
    if zero.any():
        raise SolverError(
            f"found {int(zero.sum())} zero-frequency modes (below "
            f"{math.sqrt(MECHANISM_FACTOR * scale) / (2 * math.pi):.2g} Hz) beside the "
            f"{n_given} rigid-body modes, where {what}: a mechanism, a nearly "
            "disconnected part or a support far too soft")


def backward_errors(K: sp.csr_matrix, M: sp.csr_matrix, pairs: Ritz) -> np.ndarray:
    """Normwise backward error ||r|| / ((||K|| + w^2 ||M||) ||x||) per pair. The relative
    residual has a round-off floor of about eps * w_max^2 / w^2, which slender shafts
    (low modes, fine meshes) reach; the backward error has none."""
    r = np.linalg.norm(pairs.residual_vectors, axis=0)
    return r / ((one_norm(K) + pairs.lam * one_norm(M)) * np.linalg.norm(pairs.X, axis=0))


def energy_split(X: np.ndarray, nodes: np.ndarray, mass_scalar: sp.csr_matrix,
                 constant: np.ndarray | None = None) -> np.ndarray:
    """Kinetic-energy fractions of each mode in axial, radial and tangential motion.

    The shaft axis is z. Bending moves sections sideways (radial and tangential
    alike), torsion turns them (tangential only), axial modes stretch (z only). With a
    hierarchical basis (`constant` given) only the vertex functions are values at
    positions: the split is that of the modes' linear part, enough to tell the kinds.
    """
    if constant is not None:
        v = np.flatnonzero(constant > 0)
        dofs = (3 * v[:, None] + np.arange(3)).ravel()
        return energy_split(X[dofs], nodes[v], mass_scalar[v][:, v])
    r = np.hypot(nodes[:, 0], nodes[:, 1])
    safe = np.where(r > 0, r, 1.0)
    c, s = nodes[:, 0] / safe, nodes[:, 1] / safe
    out = np.empty((X.shape[1], 3))
    for k in range(X.shape[1]):
        ux, uy, uz = X[0::3, k], X[1::3, k], X[2::3, k]
        ur, ut = c * ux + s * uy, -s * ux + c * uy
        e = np.array([uz @ (mass_scalar @ uz), ur @ (mass_scalar @ ur), ut @ (mass_scalar @ ut)])
        out[k] = e / e.sum()
    return out


def classify(energy: np.ndarray) -> str:
    """'axial', 'torsion', 'bending' or 'mixed' from the energy fractions (z, r, t)."""
    axial, radial, tangential = energy
    if axial > 0.6:
        return "axial"
    if tangential > 0.75:
        return "torsion"
    if radial + tangential > 0.5 and radial > 0.2:
        return "bending"
    return "mixed"
