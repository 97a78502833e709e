"""The installed shaft shaken through its supports: participation factors, effective
modal masses and the harmonic response to base motion, by modal superposition.

Base motion u_g(t) in direction d moves the supports and, rigidly, everything with
them: u = r u_g + u_rel, with r the rigid motion along d (a unit translation along
x, y or z, or a unit turn about the axis). The relative motion obeys

    M_r q'' + C q' + K_r q = -L u_g'',    L = T^T M r (+ the parts' m r),

so mode i (M-normalised, w_i) is driven by its participation factor G_i = x_i^T L
(kg^1/2, or kg^1/2 m for the turn) and carries the effective mass G_i^2; over all
modes of a shaft that every mode moves, the effective masses add up to r^T M r, the
mass (or polar inertia) of shaft and parts. With modal damping zeta and harmonic
base motion U e^{i W t}, each modal coordinate is

    eta_i = G_i W^2 U / (w_i^2 - W^2 + 2 i zeta w_i W),

and the displacement at a point is r U + sum_i x_i eta_i. The modes the seats leave
free (w = 0, a turn about the axis in two bearings) take their share as rigid motion.
The modes solved are the lowest ones: above the last, the response is truncated.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.supports import part_mass, rigid_body_modes

if TYPE_CHECKING:
    from shaftfem.fem.assembly import System
    from shaftfem.fem.installation import Installed
    from shaftfem.fem.result import ModalResult

# Base-motion directions: unit translations and the turn about the shaft axis.
DIRECTIONS = ("x", "y", "z", "rz")
DIRECTION_NAMES = {"x": "x (lateral)", "y": "y (lateral)", "z": "z (axial)",
                   "rz": "turn about the axis"}


def influence(nodes: np.ndarray, n_parts: int, direction: str) -> tuple[np.ndarray, np.ndarray]:
    """r for the nodes (3 n,) and for each part's (U, Theta) at its centre on the axis
    (n_parts, 6): a unit translation along x, y, z, or a unit turn about z (rad)."""
    column = {"x": 0, "y": 1, "z": 2, "rz": 5}[direction]
    r = rigid_body_modes(nodes, np.zeros(3))[:, column]
    parts = np.zeros((n_parts, 6))
    parts[:, column] = 1.0           # each part's centre lies on the axis
    return r, parts


@dataclass(frozen=True)
class Participation:
    """Per direction (DIRECTIONS) and elastic mode: factors G (n_modes, 4), effective
    masses G^2 (kg; kg m^2 for the turn), the share the free rigid motions take, and
    the total r^T M r of shaft and parts."""

    factors: np.ndarray
    effective: np.ndarray
    rigid: np.ndarray      # (4,) effective mass of the modes the seats leave free
    total: np.ndarray      # (4,)

    @property
    def cumulative(self) -> np.ndarray:
        """(n_modes, 4): fraction of the total reached up to each mode, rigid share
        included."""
        return (self.rigid + np.cumsum(self.effective, axis=0)) / self.total


@dataclass(frozen=True)
class ModalBasis:
    """Everything the superposition needs, in the solved (reduced) coordinates: the
    elastic modes X (n_q, m) with w^2, the free rigid modes (M-normalised), the load
    vectors L (n_q, 4) per direction and their totals r^T M r."""

    lam: np.ndarray
    X: np.ndarray
    rigid: np.ndarray
    loads: np.ndarray
    totals: np.ndarray


def inertia_load(system: System, inst: Installed, direction: str) -> tuple[np.ndarray, float]:
    """The load (reduced coordinates, N) of a unit acceleration of the shaft and its parts
    along `direction` (DIRECTIONS: rad/s^2 for the turn), M r, and r^T M r (kg)."""
    M = system.M if inst.M_carried is None else system.M + inst.M_carried
    r, rp = influence(system.nodes, len(inst.tied), direction)
    Mr = M @ r
    L = np.asarray(inst.T.T @ Mr).ravel()
    total = float(r @ Mr)
    first = inst.parts_from
    for k, a in enumerate(inst.parts):
        m6 = part_mass(a)
        L[first + 6 * k:first + 6 * k + 6] += m6 @ rp[k]
        total += float(rp[k] @ m6 @ rp[k])
    return L, total


def modal_basis(result: ModalResult) -> ModalBasis:
    """The result's modes in reduced coordinates with the base-motion loads."""
    inst, system = result.installed, result.system
    if inst is None or not result.scene.held:
        raise SceneError(f"{result.scene.source}: no [[support]] holds the shaft: base "
                         "motion needs supports to come through")
    X = result.reduced_shapes()
    loads, totals = zip(*(inertia_load(system, inst, d) for d in DIRECTIONS))
    R = inst.rigid
    if R.shape[1]:
        G = R.T @ (inst.M @ R)
        R = R @ np.linalg.inv(np.linalg.cholesky(G)).T       # M-orthonormal
    lam = (2 * math.pi * result.modes.frequencies) ** 2
    return ModalBasis(lam=lam, X=X, rigid=R, loads=np.column_stack(loads),
                      totals=np.array(totals))


def participation(basis: ModalBasis) -> Participation:
    """Participation factors and effective masses (kg; kg m^2 for the turn about the
    axis) of every elastic mode for base motion along x, y, z and the turn, with the
    totals they add up to; `participation(modal_basis(result))`."""
    G = basis.X.T @ basis.loads
    rigid = np.sum((basis.rigid.T @ basis.loads) ** 2, axis=0) if basis.rigid.size else (
        np.zeros(len(DIRECTIONS)))
    return Participation(factors=G, effective=G**2, rigid=rigid, total=basis.totals)


@dataclass(frozen=True)
class FrequencyResponse:
    """Transmissibility |u . e_d| / U at one point for base motion U along d, over
    `frequencies` (Hz), with modal damping ratio `damping`."""

    frequencies: np.ndarray
    transmissibility: np.ndarray
    direction: str
    point: np.ndarray           # the node's position, m
    damping: float

    def at(self, f: float) -> float:
        """The transmissibility at frequency f (Hz), interpolated on the curve."""
        return float(np.interp(f, self.frequencies, self.transmissibility))


def modal_coordinates(basis: ModalBasis, direction: str, omega: np.ndarray,
                      zeta: float) -> np.ndarray:
    """eta (n_modes, n_freq) per unit base motion along `direction`, at angular
    frequencies omega (rad/s)."""
    G = basis.X.T @ basis.loads[:, DIRECTIONS.index(direction)]
    w = np.sqrt(basis.lam)[:, None]
    W = np.asarray(omega, dtype=float)[None, :]
    return G[:, None] * W**2 / (w**2 - W**2 + 2j * zeta * w * W)


def base_response(result: ModalResult, frequencies: np.ndarray, direction: str = "x",
                  point: float | None = None, zeta: float | None = None,
                  basis: ModalBasis | None = None) -> FrequencyResponse:
    """The transmissibility, amplitude of u over u_base, at the node nearest the axis at z = point (m;
    default the scene's response point, else mid-span) for harmonic base motion along
    `direction` ('x', 'y', 'z') at `frequencies` (Hz), with modal damping ratio `zeta`
    (a fraction; default the scene's)."""
    scene = result.scene
    basis = basis or modal_basis(result)
    zeta = scene.damping_ratio if zeta is None else zeta
    z = point if point is not None else (scene.response_point if scene.response_point
                                         is not None else scene.shaft.length / 2)
    if direction not in ("x", "y", "z"):
        raise SceneError(f"response direction {direction!r}: must be x, y or z")
    nodes = result.system.nodes
    node = int(np.argmin(np.hypot(nodes[:, 0], nodes[:, 1]) + np.abs(nodes[:, 2] - z)))
    comp = 3 * node + "xyz".index(direction)
    r, _ = influence(nodes, 0, direction)
    assert result.installed is not None  # modal_basis has refused a shaft without seats
    T = result.installed.T
    row = np.asarray(T[comp].toarray()).ravel()
    omega = 2 * math.pi * np.asarray(frequencies, dtype=float)
    eta = modal_coordinates(basis, direction, omega, zeta)
    u = r[comp] + (row @ basis.X) @ eta
    if basis.rigid.size:
        Gr = basis.rigid.T @ basis.loads[:, DIRECTIONS.index(direction)]
        u = u - (row @ basis.rigid) @ Gr * np.ones_like(omega)   # w = 0: eta = -G U
    return FrequencyResponse(frequencies=np.asarray(frequencies, dtype=float),
                             transmissibility=np.abs(u), direction=direction,
                             point=nodes[node].copy(), damping=zeta)


def response_sweep(result: ModalResult, direction: str = "x", n: int = 1200,
                   basis: ModalBasis | None = None) -> FrequencyResponse:
    """The response over 0..1.2 x the highest frequency solved, on a grid that also
    lands on every natural frequency (where the peaks are)."""
    top = 1.2 * float(result.modes.frequencies[-1])
    # linear for the excitation band, logarithmic for a log axis down to 1e-4 x top
    grid = np.union1d(np.union1d(np.linspace(0.0, top, n), np.geomspace(1e-4 * top, top, n)),
                      result.modes.frequencies)
    return base_response(result, grid, direction, basis=basis)
