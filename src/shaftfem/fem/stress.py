"""The stress cycle at every point of the installed shaft's surface under its duty.

By linearity four static solves give the whole cycle over a turn, for a shaft of
revolution or not (keyways, grooves, STEP):

* A: the standing radial loads (the [[force]] tables' radial parts, gravity across the
  shaft) as they stand; B: the same turned 90 degrees about the axis. Turned by theta,
  the shaft sees the loads turned by -theta: sigma(theta) = cos(theta) sigma_A -
  sin(theta) sigma_B, a fully reversed cycle at every material point;
* T: the torques; Z: the axial forces (and gravity along the axis): steady.

A torque at a keyway (a keyed part's, a coupling's) enters through the key: a pressure
on the flank the key drives, along the key's bearing length, the hub's bore taking its
net force (key_loads); the keyway's floor, fillets and ends are then judged as any notch.
Every other load enters as a body force spread over its band (a part's hub, or a slice a
quarter of a diameter wide on either side of a bare position): a body force is finite,
so the stress it makes is too, and the hot spots are the notches', not a load's point.
The stresses are the P2 (P1) field's at each element's vertices, averaged over the
elements that share a vertex (the nodal recovery of any FE post-processor).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.static import CONVERGED, SHIFT, STEPS, UNHELD, elastic_solve

if TYPE_CHECKING:
    from shaftfem.fem.assembly import System
    from shaftfem.fem.installation import Installed
    from shaftfem.scene.model import Keyway, Scene

CASES = ("A", "B", "T", "Z")
# the angles a turn is sampled at for the largest equivalent amplitude
ANGLES = np.linspace(0.0, np.pi, 37)


@dataclass(frozen=True)
class Band:
    """Where a load enters: z0 to z1 (m)."""

    z0: float
    z1: float


@dataclass(frozen=True)
class SurfaceStress:
    """The four cases' stress tensors at the surface vertices: points (n, 3) m, outward
    normals (n, 3), stresses (4, n, 3, 3) Pa in CASES' order; and the nodal-averaged
    stresses of every vertex of the mesh (4, N, 3, 3), with the P1 basis on its vertices,
    to read the field inside (the stress gradient)."""

    vertices: np.ndarray      # indices of the surface vertices among the mesh's points
    points: np.ndarray
    normals: np.ndarray
    stress: np.ndarray
    all_stress: np.ndarray
    p1_basis: Any   # scikit-fem CellBasis
    edge: np.ndarray          # the longest surface edge at each surface vertex, m
    facets: np.ndarray        # the surface's triangles (m, 3), indices into `points`


@dataclass(frozen=True)
class KeyBearing:
    """A key carrying `torque` (N m) into its keyway: it bears on the flank on the
    `side` (+1: +width/2 across the keyway's own frame) from z0 to z1 (m) along the
    axis, and from `foot` (m from the axis, along the keyway's centre line) to the
    surface: a key's chamfer clears the floor's corner (DIN 6885: the key's chamfer is
    larger than the keyway's corner radius), here by one corner radius, at least a tenth
    of the depth."""

    keyway: Keyway
    z0: float
    z1: float
    side: float
    torque: float
    foot: float
    source: int     # the torque's index among the scene's


def key_bearings(scene: Scene) -> list[KeyBearing]:
    """The keys the scene's torques enter through: a torque (not a travelling one) at a
    position inside keyways' spans is shared among them equally. A positive torque
    turns the shaft towards +y at a keyway on +x: its key drives the flank at +width/2."""
    from shaftfem.cad.outline import key_bearing

    out = []
    for i, q in enumerate(scene.torques):
        if q.travel is not None or q.torque == 0:
            continue
        keys = [k for k in scene.shaft.keyways if k.start <= q.position <= k.end]
        for k in keys:
            radius = scene.shaft.radius_at(0.5 * (k.start + k.end))
            if radius is None:
                continue
            z0, z1 = key_bearing(k, radius)
            if z1 - z0 < 0.1 * k.width:   # a round hole: no flank to bear on
                continue
            foot = radius - k.depth + k.corner_radius + max(k.corner_radius, 0.1 * k.depth)
            out.append(KeyBearing(k, z0, z1, float(np.sign(q.torque)), q.torque / len(keys),
                                  foot, i))
    return out


def key_loads(skmesh, element, key: KeyBearing, band: Band, n_dofs: int) -> np.ndarray:
    """The nodal loads (3 n,) of the torque a key carries: a uniform pressure on the
    driven flank's boundary facets (above the key's foot, over z0..z1), t = tau e
    with e the keyway's across direction and tau = T / int x_k dA (x_k: the distance
    from the axis along the keyway's centre line), so that int (x - p) x t = (., ., T);
    and the hub's bore taking the pressure's net force and its bending moment about p (a
    body force over the band, band_loads): the whole has no net force, a moment T about
    the axis and none across it, exactly on the mesh."""
    from skfem import FacetBasis, Functional, LinearForm, MeshTet

    from shaftfem.cad.outline import keyway_frame

    k = key.keyway
    c, s = math.cos(k.angle), math.sin(k.angle)
    # the flank is plane: integrated on the straight-sided mesh of the same elements (the
    # same DOFs), whose affine map needs no Newton search for the facets' points
    nv = int(skmesh.t.max()) + 1
    flat = MeshTet(np.ascontiguousarray(skmesh.p[:, :nv]), skmesh.t)
    boundary = flat.boundary_facets()
    corners = flat.p[:, flat.facets[:, boundary]]            # (3, 3, m)
    mid = corners.mean(axis=1)
    xk, yk = keyway_frame(k, mid[0], mid[1])
    normal = np.cross((corners[:, 1] - corners[:, 0]).T, (corners[:, 2] - corners[:, 0]).T)
    across = np.abs(-s * normal[:, 0] + c * normal[:, 1]) / np.linalg.norm(normal, axis=1)
    tol = 1e-3 * k.width
    on = ((np.abs(yk - key.side * k.width / 2) < tol) & (across > 0.99)
          & (xk > key.foot)
          & (mid[2] >= key.z0 - tol) & (mid[2] <= key.z1 + tol))
    if not on.any():
        raise SceneError(f"the keyway at {k.start * 1e3:g}-{k.end * 1e3:g} mm: no flank "
                         "found on the mesh for its key to bear on")
    basis = FacetBasis(flat, element, facets=boundary[on], intorder=4)
    e = np.array([-s, c, 0.0])
    lever = Functional(lambda w: c * w.x[0] + s * w.x[1]).assemble(basis)   # int x_k dA
    area = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(basis)
    zbar = Functional(lambda w: w.x[2]).assemble(basis)
    tau = key.torque / lever
    pz = 0.5 * (band.z0 + band.z1)
    # the flank's pressure: force tau A e; moment about p: (z - pz) e_z x tau e + T e_z
    force = tau * area * e
    arm = zbar - pz * area
    moment = tau * arm * np.array([-e[1], e[0], 0.0])
    one = LinearForm(lambda v, w: v).assemble(basis)
    out = np.zeros(n_dofs)
    for i in range(2):
        out[i::3] += tau * e[i] * one
    return out + band_loads(skmesh, element, band, -force, 0.0, n_dofs,
                            (-float(moment[0]), -float(moment[1])))


def load_band(z: float, width: float, nodes: np.ndarray) -> Band:
    """The band a load at z (m) enters through: its hub's width, or a slice a quarter of
    the local diameter to either side of a bare position."""
    if width > 0:
        return Band(z - width / 2, z + width / 2)
    near = np.abs(nodes[:, 2] - z) < 0.02 * max(float(np.ptp(nodes[:, 2])), 1e-9)
    radius = float(np.hypot(nodes[near, 0], nodes[near, 1]).max()) if near.any() else 0.01
    return Band(z - radius / 2, z + radius / 2)


def band_loads(skmesh, element, band: Band, force: np.ndarray, torque: float,
               n_dofs: int, moment: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The nodal loads (3 n,) of a force (3,) N at the band's middle on the axis, p, a
    torque about the axis (N m) and a bending moment (m_x, m_y; N m), spread as a body
    force over the elements whose centroids lie in the band: b = F / V + mu x (x - c),
    with V their volume and c their centroid, mu from their inertia about c so that the
    moment about p is (m_x, m_y, T): int b = F and int (x - p) x b = M exactly on the
    mesh. A set of elements is never quite symmetric about the axis, and F / V alone
    adds the moment (c - p) x F: a 20 kN pull on a 30 mm bar's 8 mm elements bent it by
    2.6 N m, 3.5 % of its stress. On a symmetric band this is F / V, T (-y, x) / J for
    a torque, and a bending moment's linear b_z with its couple of shear across the
    band's width (the least body force, in L2, with these resultants)."""
    from skfem import Basis, Functional, LinearForm

    zc = skmesh.p[2, skmesh.t].mean(axis=0)
    inside = np.flatnonzero((zc >= band.z0) & (zc <= band.z1))
    if inside.size == 0:   # a band thinner than the elements: the elements it cuts
        lo, hi = skmesh.p[2, skmesh.t].min(axis=0), skmesh.p[2, skmesh.t].max(axis=0)
        inside = np.flatnonzero((lo <= band.z1) & (hi >= band.z0))
    basis = Basis(skmesh, element, elements=inside, intorder=4)
    volume = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(basis)
    c = np.array([Functional(lambda w, i=i: w.x[i]).assemble(basis) for i in range(3)]) / volume
    S = np.array([[Functional(lambda w, i=i, j=j: (w.x[i] - c[i]) * (w.x[j] - c[j])
                              ).assemble(basis) for j in range(3)] for i in range(3)])
    inertia = np.trace(S) * np.eye(3) - S       # int r x (mu x r) = inertia mu, r = x - c
    p = np.array([0.0, 0.0, 0.5 * (band.z0 + band.z1)])
    wanted = np.array([moment[0], moment[1], torque]) - np.cross(c - p, force)
    mu = np.linalg.solve(inertia, wanted)
    # b_k = F_k / V + (mu x r)_k, r = x - c: each component's nodal loads from int v and
    # int r_j v
    one = LinearForm(lambda v, w: v).assemble(basis)
    arm = [LinearForm(lambda v, w, j=j: (w.x[j] - c[j]) * v).assemble(basis) for j in range(3)]
    out = np.zeros(n_dofs)
    for k in range(3):
        i, j = (k + 1) % 3, (k + 2) % 3          # (mu x r)_k = mu_i r_j - mu_j r_i
        out[k::3] += force[k] / volume * one + mu[i] * arm[j] - mu[j] * arm[i]
    return out


def duty_loads(scene: Scene, system: System, inst: Installed, skmesh, element
               ) -> tuple[np.ndarray, np.ndarray]:
    """The four cases' loads in the installed coordinates (columns A, B, T, Z) and their
    resultants (4, 3) N: gravity on the shaft and its parts (fem.static.loads), the
    [[force]] and [[torque]] tables spread over their bands."""
    from shaftfem.fem.static import loads

    g = np.array(scene.gravity)
    radial, axial = np.array([g[0], g[1], 0.0]), np.array([0.0, 0.0, g[2]])
    turned = np.array([-g[1], g[0], 0.0])
    cols, resultants = [], []
    n = system.n_dofs
    for case, gravity in zip(CASES, (radial, turned, np.zeros(3), axial)):
        f_q, resultant = loads(replace(scene, gravity=tuple(gravity), forces=()), system, inst)
        nodal = np.zeros(n)
        for f in scene.forces:
            band = load_band(f.position, f.width, system.nodes)
            vector = {"A": np.array([f.fx, f.fy, 0.0]), "B": np.array([-f.fy, f.fx, 0.0]),
                      "T": np.zeros(3), "Z": np.array([0.0, 0.0, f.fz])}[case]
            # a standing moment (a gear's thrust off the axis) bends as the radial loads
            moment = {"A": (f.mx, f.my), "B": (-f.my, f.mx)}.get(case, (0.0, 0.0))
            if vector.any() or any(moment):
                nodal += band_loads(skmesh, element, band, vector, 0.0, n, moment)
                resultant = resultant + vector
        if case == "T":
            keys = key_bearings(scene)
            for i, q in enumerate(scene.torques):
                band = load_band(q.position, q.width, system.nodes)
                mine = [kb for kb in keys if kb.source == i]
                for kb in mine:
                    nodal += key_loads(skmesh, element, kb, band, n)
                if not mine:
                    nodal += band_loads(skmesh, element, band, np.zeros(3), q.torque, n)
        cols.append(f_q + inst.T.T @ nodal)
        resultants.append(resultant)
    return np.column_stack(cols), np.array(resultants)


def solve_cases(scene: Scene, system: System, inst: Installed, F: np.ndarray,
                resultants: np.ndarray) -> np.ndarray:
    """The four cases' displacements of the shaft's nodes (3 n, 4), m. A load along a
    motion the supports leave free is refused (an axial force with no axial stiffness)."""
    from shaftfem.fem.static import without_drive_torque

    R = inst.rigid
    if R.shape[1]:
        lam, V = np.linalg.eigh(R.T @ (inst.M @ R))
        R = R @ (V / np.sqrt(lam))
        reach = np.abs(np.asarray(inst.T @ R)).max(axis=0)
        scale = max(float(np.abs(resultants).max()), float(np.abs(F).max()), 1e-300)
        for k, case in enumerate(CASES):
            col = F[:, k]
            if case in "AB":
                col = without_drive_torque(system, inst, R, col)
                F[:, k] = col
            if np.abs((R / reach).T @ col).max() > UNHELD * scale:
                what = {"A": "the radial loads", "B": "the radial loads",
                        "T": "the torques", "Z": "the axial loads"}[case]
                raise SceneError(f"{scene.source}: {what} push the shaft along a motion its "
                                 f"supports leave free ({', '.join(inst.free)}): nothing holds "
                                 "it there; give a support an axial stiffness (a locating "
                                 "bearing) or balance the loads")
    q = elastic_solve(inst.K, inst.M, inst.rigid, F,
                      SHIFT * float(inst.K.diagonal().max()), STEPS, until=CONVERGED)
    return np.asarray(inst.T @ q)


def surface_stress(skmesh, element, lame: tuple[float, float], U: np.ndarray
                   ) -> SurfaceStress:
    """Each case's stress (Hooke's law on the displacement gradient) at every element's
    vertices, averaged over the elements that share the vertex; the surface's vertices,
    their outward normals and their longest edges."""
    from skfem import Basis, ElementTetP1, MeshTet

    lam, mu = lame
    corners = np.array([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    basis = Basis(skmesh, element, quadrature=(corners, np.full(4, 1.0 / 24)))
    t = skmesh.t
    nv = int(t.max()) + 1
    count = np.bincount(t.ravel(), minlength=nv).astype(float)
    out = np.zeros((U.shape[1], nv, 3, 3))
    for k in range(U.shape[1]):
        grad = np.stack([basis.interpolate(U[c::3, k]).grad for c in range(3)])  # (3,3,E,4)
        eps = 0.5 * (grad + grad.transpose(1, 0, 2, 3))
        sigma = 2 * mu * eps
        trace = np.einsum("iiev->ev", eps)
        for i in range(3):
            sigma[i, i] += lam * trace
        for i in range(3):
            for j in range(3):
                out[k, :, i, j] = np.bincount(t.ravel(), sigma[i, j].T.ravel(), nv) / np.maximum(
                    count, 1)
    boundary = skmesh.boundary_facets()
    facets = skmesh.facets[:, boundary]
    verts = np.unique(facets)
    p = skmesh.p[:, :nv].T
    a, b, c = (p[facets[i]] for i in range(3))
    normal = np.cross(b - a, c - a)
    # outward: away from the centroid of the element the facet bounds
    owner = p[t[:, skmesh.f2t[0, boundary]]].mean(axis=0)
    sign = np.sign(np.einsum("ij,ij->i", normal, (a + b + c) / 3 - owner))
    normal *= sign[:, None]
    vn = np.zeros((nv, 3))
    for i in range(3):
        np.add.at(vn, facets[i], normal)
    vn = vn[verts] / np.linalg.norm(vn[verts], axis=1)[:, None]
    edge = np.zeros(nv)
    for i, j in ((0, 1), (1, 2), (2, 0)):
        length = np.linalg.norm(p[facets[i]] - p[facets[j]], axis=1)
        np.maximum.at(edge, facets[i], length)
        np.maximum.at(edge, facets[j], length)
    local = np.full(nv, -1)
    local[verts] = np.arange(verts.size)
    return SurfaceStress(vertices=verts, points=p[verts], normals=vn,
                         stress=out[:, verts], all_stress=out,
                         p1_basis=Basis(MeshTet(np.ascontiguousarray(p.T), t), ElementTetP1()),
                         edge=edge[verts], facets=local[facets].T)


def on_surface(points: np.ndarray, facets: np.ndarray, values: np.ndarray,
               at: np.ndarray) -> float:
    """A surface field (values at `points`) at the point `at` (3,): linear on the
    surface triangle nearest to it, at the foot of the perpendicular (kept inside the
    triangle). The vertices lie on the true surface, so a coarse mesh read at a fine
    mesh's point has no bias from its straight edges."""
    near = np.argsort(np.linalg.norm(points - at, axis=1))[:8]
    tris = facets[np.isin(facets, near).any(axis=1)]
    best, value = np.inf, float(values[near[0]])
    for tri in tris:
        a, b, c = points[tri]
        e0, e1 = b - a, c - a
        G = np.array([[e0 @ e0, e0 @ e1], [e0 @ e1, e1 @ e1]])
        try:
            u, v = np.linalg.solve(G, np.array([e0 @ (at - a), e1 @ (at - a)]))
        except np.linalg.LinAlgError:
            continue
        u, v = max(u, 0.0), max(v, 0.0)
        if u + v > 1:
            u, v = u / (u + v), v / (u + v)
        foot = a + u * e0 + v * e1
        d = float(np.linalg.norm(at - foot))
        if d < best:
            best = d
            value = float((1 - u - v) * values[tri[0]] + u * values[tri[1]] + v * values[tri[2]])
    return value


def von_mises(s: np.ndarray) -> np.ndarray:
    """The von Mises equivalent of stress tensors (..., 3, 3), Pa."""
    d = s - np.eye(3) * (np.trace(s, axis1=-2, axis2=-1) / 3)[..., None, None]
    return np.sqrt(1.5 * np.einsum("...ij,...ij->...", d, d))


def cycle(stress: np.ndarray, turning: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The equivalent amplitude, signed mean and peak over a turn (Pa) of the four
    cases' stresses (4, ..., 3, 3): amplitude max over theta of vM(cos sigma_A - sin
    sigma_B); mean vM(sigma_T + sigma_Z) with the sign of its trace (FKM's signed von
    Mises: a compressive mean helps); peak max over theta of vM(mean + cycle). A shaft
    that does not turn sees A as it stands: no amplitude."""
    A, B, T, Z = stress
    mean = T + Z
    if not turning:
        mean = mean + A
        A = np.zeros_like(A)
        B = np.zeros_like(B)
    c, s = np.cos(ANGLES), np.sin(ANGLES)
    amplitude = np.zeros(A.shape[:-2])
    peak = von_mises(mean)
    for ci, si in zip(c, s):
        alt = ci * A - si * B
        amplitude = np.maximum(amplitude, von_mises(alt))
        peak = np.maximum(peak, np.maximum(von_mises(mean + alt), von_mises(mean - alt)))
    trace = np.trace(mean, axis1=-2, axis2=-1)
    vm = von_mises(mean)
    # a trace small beside the equivalent stress (shear, as a steady torque gives, whose
    # trace the discretisation leaves a few percent off zero) counts as positive: the
    # mean stress factor then takes it as tension, on the safe side
    signed = np.where(trace < -0.1 * vm, -vm, vm)
    return amplitude, signed, peak
