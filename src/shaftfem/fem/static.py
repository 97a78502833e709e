"""The installed shaft under its static loads: its weight and its parts' (gravity), and
radial forces on cross-sections. K u = f on the installed pencil, then:

* the deflection line: the mass-weighted mean (x, y) displacement of the shaft's
  slices along z;
* each support's reaction on the shaft: the force its seat band takes from the shaft's
  own equations, r = K_shaft u - f summed over the band's nodes (the springs, holds and
  clamps alike), checked against the loads: the reactions and the loads balance.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SceneError, SolverError
from shaftfem.fem.response import inertia_load

if TYPE_CHECKING:
    from shaftfem.fem.assembly import System
    from shaftfem.fem.installation import Installed
    from shaftfem.scene.model import Scene

# A shaft its supports leave free (axially, about its axis) is solved shifted by this
# share of its largest stiffness, in this many steps.
SHIFT = 1e-8
STEPS = 4
# the most steps a solve to a tolerance takes
MAX_STEPS = 200
# ... and the tolerance the static loads' solve is taken to
CONVERGED = 1e-13
# The deflection line is drawn on this many slices along the shaft.
SLICES = 200
# The reactions balance the loads to this share of the loads (else a SolverError).
BALANCE = 1e-6
# A load on the motions the supports leave free above this share of it has nothing to
# hold it (below it: a mesh's own asymmetry, a torque of round-off about the axis).
UNHELD = 1e-4


@dataclass(frozen=True)
class Reaction:
    """A support's force on the shaft, N, and where: its name and position (m)."""

    name: str
    position: float
    force: np.ndarray   # (3,)


@dataclass(frozen=True)
class StaticSolution:
    """The shaft under its static loads: the deflection line (z, x, y in m, along the
    slices), the displacement of every node (3 n,), each support's reaction (N) and the
    loads' resultant (N)."""

    z: np.ndarray
    x: np.ndarray
    y: np.ndarray
    u: np.ndarray
    reactions: tuple[Reaction, ...]
    load: np.ndarray

    def deflection_at(self, z: float) -> tuple[float, float]:
        """The deflection line at z (m), (x, y) m, linear between slices."""
        return float(np.interp(z, self.z, self.x)), float(np.interp(z, self.z, self.y))


def elastic_solve(K, M, R: np.ndarray, f: np.ndarray, shift: float, steps: int,
                  until: float | None = None) -> np.ndarray:
    """K u = f (loads as columns of f) on the elastic motions of the pencil (K, M), its
    free rigid motions R taken out of the loads and of u: (K + s M) u_k+1 = f + s M u_k,
    each step gaining about s / (lowest elastic eigenvalue); one factorisation, every
    load at once where the back-end takes them. Without free motions, K u = f. With
    `until`, at least `steps` steps and then on until a step moves u by less than that
    share of it (soft supports gain less per step)."""
    from shaftfem.fem.factor import factorise

    if not R.shape[1]:
        shift, steps = 0.0, 1
    one, backend = factorise((K + shift * M).tocsr() if shift else K.tocsr())

    def solve(b: np.ndarray) -> np.ndarray:
        if backend in ("pardiso", "superlu"):
            return one(b)
        return np.column_stack([one(np.ascontiguousarray(col)) for col in b.T])

    if R.shape[1]:
        lam, V = np.linalg.eigh(R.T @ (M @ R))
        R = R @ (V / np.sqrt(lam))               # M-orthonormal
        f = f - M @ (R @ (R.T @ f))
    u = np.zeros_like(f)
    for k in range(MAX_STEPS if until is not None else steps):
        new = solve(f + shift * (M @ u))
        if R.shape[1]:
            new = new - R @ (R.T @ (M @ new))
        moved = float(np.abs(new - u).max())
        u = new
        if until is not None and k + 1 >= steps and moved <= until * float(np.abs(u).max()):
            break
    return u


def loads(scene: Scene, system: System, inst: Installed) -> tuple[np.ndarray, np.ndarray]:
    """The static loads in the installed coordinates (N): gravity on the shaft and every
    part, and each [[force]] on its cross-section's mean motion; and their resultant
    (3,), N."""
    g = np.array(scene.gravity)
    f_q = sum(g[i] * inertia_load(system, inst, d)[0] for i, d in enumerate("xyz"))
    mass = float(system.mass_scalar.sum()) + sum(a.mass for a in scene.attachments)
    resultant = mass * g + sum((np.array([f.fx, f.fy, 0.0]) for f in scene.forces),
                               np.zeros(3))
    return np.asarray(f_q, dtype=float) + inst.T.T @ forces_on_nodes(scene, system), resultant


def forces_on_nodes(scene: Scene, system: System) -> np.ndarray:
    """The [[force]] tables on the shaft's nodes (3 n,), N: each (its radial force and
    its bending moment) on its cross-section's mean motion, q = C u, as C^T F."""
    from shaftfem.fem.supports import section_means

    nodal = np.zeros(system.n_dofs)
    for force in scene.forces:
        c = section_means(system.nodes, system.mass_scalar.diagonal(), force.position)
        nodal[c.dofs] += c.C[:2].T @ np.array([force.fx, force.fy])
        if force.mx or force.my:
            nodal[c.dofs] += c.C[3:5].T @ np.array([force.mx, force.my])
    return nodal


def static_solution(scene: Scene, system: System, inst: Installed, skmesh) -> StaticSolution:
    """The installed shaft of `scene` under its static loads."""
    from shaftfem.fem.installation import seat_radius
    from shaftfem.fem.supports import band_nodes

    f_q, resultant = loads(scene, system, inst)
    R = inst.rigid
    if R.shape[1]:
        lam, V = np.linalg.eigh(R.T @ (inst.M @ R))
        R = R @ (V / np.sqrt(lam))
        f_q = without_drive_torque(system, inst, R, f_q)
        # each free motion scaled to move the shaft's farthest point by 1 m: what the
        # loads do along it is then a force, N
        reach = np.abs(np.asarray(inst.T @ R)).max(axis=0)
        if np.abs((R / reach).T @ f_q).max() > UNHELD * max(float(np.abs(resultant).max()),
                                                              1e-300):
            raise SceneError(f"{scene.source}: the static loads push the shaft along a motion "
                             f"its supports leave free ({', '.join(inst.free)}): nothing holds "
                             "it there; hold it (an axial stiffness, a rigid seat) or turn "
                             "[static] gravity_direction across the shaft")
    q = elastic_solve(inst.K, inst.M, inst.rigid, f_q[:, None],
                      SHIFT * float(inst.K.diagonal().max()), STEPS, until=CONVERGED)[:, 0]
    u = np.asarray(inst.T @ q)
    # what each band takes from the shaft: K_shaft u - f on its nodes
    nodal = loads_on_nodes(scene, system, inst)
    residual = system.K @ u - nodal
    reactions = []
    for s in scene.held:
        if s.kind == "seal":   # a seal carries no static load (its stiffness needs speed)
            continue
        radius = seat_radius(scene, system.nodes, s.seat)
        idx = band_nodes(system.nodes, radius, s.seat)
        force = np.array([residual[3 * idx + c].sum() for c in range(3)])
        reactions.append(Reaction(s.name, s.position, force))
    total = sum(r.force for r in reactions) + resultant
    if np.abs(total).max() > BALANCE * max(np.abs(resultant).max(), 1e-300):
        raise SolverError(f"the supports' reactions do not balance the static loads: "
                          f"{np.abs(total).max():.3g} N left of {np.abs(resultant).max():.3g} N")
    z, x, y = line(system, u)
    return StaticSolution(z=z, x=x, y=y, u=u, reactions=tuple(reactions), load=resultant)


def without_drive_torque(system: System, inst: Installed, R: np.ndarray, f_q: np.ndarray
                         ) -> np.ndarray:
    """The loads less their moment about the shaft's axis where the seats leave that turn
    free: a shaft that is not of revolution (a keyway, a groove) has its weight off the
    axis, and that small moment is the drive's to hold (the coupling, the motor), not the
    bearings'. R: the free rigid motions, M-orthonormal, reduced."""
    x, y = system.nodes[:, 0], system.nodes[:, 1]
    turn = np.zeros(system.n_dofs)
    turn[0::3], turn[1::3] = -y, x
    shapes = np.asarray(inst.T @ R)
    c, *_ = np.linalg.lstsq(shapes, turn, rcond=None)
    if np.linalg.norm(shapes @ c - turn) > 1e-6 * np.linalg.norm(turn):
        return f_q                                   # the seats hold the turn
    r = R @ c
    r = r / np.sqrt(r @ (inst.M @ r))
    return f_q - (inst.M @ r) * (r @ f_q)


def loads_on_nodes(scene: Scene, system: System, inst: Installed) -> np.ndarray:
    """The loads the shaft's own nodes carry (3 n,), N: its weight, the weight of the
    parts on distributing joints (through their sections' means), the forces."""
    M = system.M if inst.M_carried is None else system.M + inst.M_carried
    return M @ np.tile(np.array(scene.gravity), system.nodes.shape[0]) + forces_on_nodes(
        scene, system)


def line(system: System, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The deflection line: each slice's mass-weighted mean (x, y) displacement (m), at
    the slice's mass centre z (m)."""
    z = system.nodes[:, 2]
    edges = np.linspace(z.min(), z.max(), SLICES + 1)
    slot = np.clip(np.searchsorted(edges, z, side="right") - 1, 0, SLICES - 1)
    mass = system.mass_scalar.diagonal()
    m = np.bincount(slot, mass, SLICES)
    keep = m > 0
    zc = np.bincount(slot, mass * z, SLICES)[keep] / m[keep]
    x = np.bincount(slot, mass * u[0::3], SLICES)[keep] / m[keep]
    y = np.bincount(slot, mass * u[1::3], SLICES)[keep] / m[keep]
    return zc, x, y
