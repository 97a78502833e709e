"""What the shaft's spin Omega (rad/s, about +z) adds to M q'' + K q = 0, on a basis
of its undamped standstill modes Phi (mass-normalised: Phi^T M Phi = I,
Phi^T K Phi = diag(w^2)):

    q'' + (Omega G + C_b) q' + (diag(w^2) + Omega^2 K_2 + dK_b + Omega K_c) q = 0.

Stationary frame (a shaft of revolution: the material flows through a mesh that
does not move, and the bearings may be anisotropic). With d_theta = x d/dy - y d/dx,
the velocity of the material is u_t + Omega d_theta u, whose kinetic energy gives

    G = Phi^T (A - A^T) Phi,   A = int rho N^T d_theta N dV        (the solid)

and, for a rigid part, I_p on its tilts (I_d th_x'' + Omega I_p th_y' = 0); the
same energy's (Omega d_theta u)^2 softens, K_2 = Phi^T (K_sigma - B) Phi with
B = int rho d_theta N^T d_theta N dV and K_sigma the stiffening by the stress of
the spin itself (its centrifugal load, statically): on a rigid tilt or turn of a
solid of revolution the two cancel, as they must.

Rotating frame (any shaft, coordinates turning with it; isotropic bearings):

    G = 2 Phi^T (M_s x S) Phi,   K_2 = Phi^T (K_sigma - M_s x P) Phi   (the solid)

with S = [e]x, P = I - e e^T, and for a rigid part 2 m S and -m P on its
translations, (I_p - 2 I_d) S and (I_p - I_d) on its tilts (its Euler equations in
the turning frame). A bearing's damping seen from the turning shaft adds
Omega C_b S to the stiffness.

Bearings: K_b(Omega) and C_b(Omega) act on each seat's mean radial motion
(q_x, q_y) = (c_x . u, c_y . u) (fem.supports); the standstill modes already hold
kxx(0) and kyy(0), dK_b is the rest. A seal's added mass M_b there makes the mass
I + beta^T M_b beta (turning with the shaft, M_b (q'' + 2 Omega S q' - Omega^2 q)).

Tilting pads (stationary frame): each pad's tilt phi is a coordinate of its own, s =
R phi (m), and the film's K, C act on (q_x, q_y, s_1, ...). The pads' equations,
m_p s'' + K_pj u + K_pp s + C_pj u' + C_pp s' = 0 (m_p = I_p / R^2; zero: massless, a
first-order state), close the rotor's; condensed at a whirl w they give back the 2x2
Z_jj - Z_jp Z_pp^-1 Z_pj of Z = K + i w C, which `reduced` uses at w = Omega for every
whirl (the synchronously reduced coefficients other tools give).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from shaftfem.errors import SolverError
from shaftfem.scene.model import Attachment, BearingCoefficients, coupled

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult

FRAMES = ("stationary", "rotating")
# The rotating-frame skew of the xy plane: S q = e x q for q = (q_x, q_y).
S2 = np.array([[0.0, -1.0], [1.0, 0.0]])


@dataclass(frozen=True)
class BearingModal:
    """One bearing on the modal basis: its seat's mean radial motions in each mode
    (2, N), m / sqrt(kg), its coefficients, and what the standstill modes hold of
    them (kxx(0), kyy(0), N/m)."""

    name: str
    beta: np.ndarray
    coefficients: BearingCoefficients
    standstill: tuple[float, float]


@dataclass(frozen=True)
class RotorModel:
    """The turning shaft on N standstill modes (see the module's equation): each
    mode's w^2 (rad^2/s^2), G per rad/s, K_2 per (rad/s)^2, the bearings, the
    whirl forms (the xy kinetic energy `lateral` and its turning part `turning`:
    the whirl index of a complex shape y is y^H turning y / y^H lateral y) and each
    mode's kind."""

    frame: str
    omega2: np.ndarray
    G: np.ndarray
    K2: np.ndarray
    bearings: tuple[BearingModal, ...]
    lateral: np.ndarray
    turning: np.ndarray
    kinds: tuple[str, ...]
    shapes: np.ndarray | None = None   # the basis as nodal shapes (3 n, N), if kept
    residual: int = 0   # the last columns: the bearings' residual modes (residual_modes)
    # the bearings' static shapes in the basis' coordinates (N, m): what a truncated
    # basis keeps exactly
    static: np.ndarray | None = None
    # the modal forces of a unit acceleration along x and along y of the whole shaft and
    # its parts (its weight per m/s^2), (2, N), kg / sqrt(kg)
    weight: np.ndarray | None = None
    # the speeds (rad/s) a periodic rotor runs at, where Hill's method may take more
    # harmonics (fem.floquet.HILL_WIDE), and how many of its lowest Floquet forms must
    # settle there (those reported)
    wide: tuple[float, ...] = ()
    wide_forms: int = 0
    # tilting pads' bearings take their synchronously reduced 2x2 (see the module's
    # equation), not their tilts as coordinates
    reduced: bool = False

    @property
    def size(self) -> int:
        return self.omega2.size

    @property
    def tilting(self) -> bool:
        """Whether the pads' tilts are coordinates of this model: a bearing of tilting
        pads, in the stationary frame, not `reduced`."""
        return (self.frame == "stationary" and not self.reduced
                and any(b.coefficients.pads is not None for b in self.bearings))

    def truncated(self, n: int) -> RotorModel:
        """The same rotor on its first n modes and, where it has residual modes, the
        bearings' static shapes as the rest of the basis leaves them (its residual modes
        made again for the n modes: a Rayleigh-Ritz of this model)."""
        import scipy.linalg

        kept = min(n, self.size - self.residual)
        if kept == self.size - self.residual:
            return self
        E = np.eye(self.size)[:, :kept]
        if self.residual and self.static is not None:
            S = self.static.copy()
            S[:kept] = 0.0                        # the static shapes beyond the kept modes
            m, V = np.linalg.eigh(S.T @ S)
            keep = m > RESIDUAL_RANK * m.max()
            B = S @ (V[:, keep] / np.sqrt(m[keep]))
            w2, U = scipy.linalg.eigh(B.T @ (self.omega2[:, None] * B))
            P = B @ U
            static = np.vstack([self.static[:kept], P.T @ self.static])
        else:
            P, w2, static = np.zeros((self.size, 0)), np.zeros(0), None
        V = np.hstack([E, P])
        turning = V.T @ self.turning @ V
        return replace(self, omega2=np.concatenate([self.omega2[:kept], w2]),
                       G=V.T @ self.G @ V, K2=V.T @ self.K2 @ V,
                       bearings=tuple(replace(b, beta=b.beta @ V) for b in self.bearings),
                       lateral=V.T @ self.lateral @ V, turning=0.5 * (turning + turning.conj().T),
                       kinds=self.kinds[:kept] + ("bending",) * P.shape[1],
                       shapes=None if self.shapes is None else self.shapes @ V,
                       residual=P.shape[1], static=static,
                       weight=None if self.weight is None else self.weight @ V)

    def matrices(self, omega: float, pads: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """(D, K) of M q'' + D q' + K q = 0 at the spin omega (rad/s); in the rotating
        frame their mean over a turn, the bearings' isotropic parts (what differs along
        x and y turns at 2 omega there: periodic_parts). Tilting pads' bearings give
        their synchronously reduced 2x2, or with `pads` their film's block on the seat
        alone (what `augmented` couples to the tilts)."""
        D = omega * self.G
        K = np.diag(self.omega2) + omega**2 * self.K2
        for b in self.bearings:
            if pads and b.coefficients.pads is not None:
                Kb, Cb = (A[:2, :2] for A in b.coefficients.pad_film(omega))
            else:
                Kb = np.array(b.coefficients.stiffness(omega))
                Cb = np.array(b.coefficients.damping(omega))
            if self.frame == "rotating" and omega != 0.0:   # at rest the frames are one
                Kb, Cb = isotropic_part(Kb), isotropic_part(Cb)
            D = D + b.beta.T @ Cb @ b.beta
            K = K + b.beta.T @ (Kb - np.diag(b.standstill)) @ b.beta
            if self.frame == "rotating":
                K = K + omega * (b.beta.T @ (Cb @ S2) @ b.beta)
                if b.coefficients.has_mass:
                    # a seal's fluid mass seen turning: M (q'' + 2 Omega S q' - Omega^2 q)
                    Mb = np.array(b.coefficients.mass(omega))
                    D = D + 2 * omega * (b.beta.T @ (Mb @ S2) @ b.beta)
                    K = K - omega**2 * (b.beta.T @ Mb @ b.beta)
        return D, K

    def periodic(self, omega: float) -> bool:
        """Whether the equations are periodic in time at the spin omega: the rotating
        frame, and a bearing that differs along x and y there."""
        if self.frame != "rotating" or omega == 0.0:
            return False
        return any(anisotropic(np.array(A)) for b in self.bearings
                   for A in (b.coefficients.stiffness(omega), b.coefficients.damping(omega)))

    def periodic_parts(self, omega: float) -> tuple[np.ndarray, ...]:
        """(D_c, D_s, K_c, K_s): in the rotating frame, where the bearings differ along
        x and y, D(t) = D + D_c cos 2 omega t + D_s sin 2 omega t and so K, (D, K) from
        `matrices`. A bearing's deviatoric part A_d (K_s and C_s in the stationary
        frame, less their isotropic part) is seen from the turning shaft as
        R^T A_d R = A_d cos 2 theta + A_d' sin 2 theta, theta = omega t; its damping
        adds omega R^T C R S to the stiffness."""
        N = self.size
        Dc, Ds, Kc, Ks = (np.zeros((N, N)) for _ in range(4))
        for b in self.bearings:
            Kb = np.array(b.coefficients.stiffness(omega))
            Cb = np.array(b.coefficients.damping(omega))
            if b.coefficients.has_mass:
                if anisotropic(np.array(b.coefficients.mass(omega))):
                    raise SolverError(f"{b.name}: an added mass that differs along x and y "
                                      "is not taken on a shaft that is not of revolution")
            (kc, ks), (cc, cs) = deviatoric_parts(Kb), deviatoric_parts(Cb)
            B = b.beta
            Dc += B.T @ cc @ B
            Ds += B.T @ cs @ B
            Kc += B.T @ (kc + omega * cc @ S2) @ B
            Ks += B.T @ (ks + omega * cs @ S2) @ B
        return Dc, Ds, Kc, Ks

    def augmented(self, omega: float) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                np.ndarray]:
        """(M, D, K) on the N modal coordinates and then every loaded tilting pad's s =
        R phi (the module's equation), and which coordinates have no mass (massless
        pads: first-order). Without tilting pads, the N-coordinate model. A pad whose
        film carries nothing at this speed floats, and is left out."""
        if not self.tilting:
            D, K = self.matrices(omega)
            return self.mass(omega), D, K, np.zeros(self.size, dtype=bool)
        D, K = self.matrices(omega, pads=True)
        M = self.mass(omega)
        blocks = []
        for b in self.bearings:
            if b.coefficients.pads is None:
                continue
            Kf, Cf = b.coefficients.pad_film(omega)
            # the pads the synchronous reduction keeps (scene.model.condensed)
            loaded = coupled(Kf + 1j * omega * Cf)
            inertia = b.coefficients.pads.masses or (0.0,) * (Kf.shape[0] - 2)
            blocks.append((b.beta, Kf, Cf, loaded, [inertia[i - 2] for i in loaded]))
        n, P = self.size, sum(len(x[3]) for x in blocks)
        Ma, Da, Ka = (np.zeros((n + P, n + P)) for _ in range(3))
        Ma[:n, :n], Da[:n, :n], Ka[:n, :n] = M, D, K
        at = n
        for beta, Kf, Cf, loaded, inertia in blocks:
            p = np.arange(at, at + len(loaded))
            for A, Af in ((Ka, Kf), (Da, Cf)):
                A[:n, p] = beta.T @ Af[:2, loaded]
                A[p, :n] = Af[loaded, :2] @ beta
                A[np.ix_(p, p)] = Af[np.ix_(loaded, loaded)]
            Ma[p, p] = inertia
            at += len(loaded)
        massless = np.zeros(n + P, dtype=bool)
        massless[n:] = np.diag(Ma)[n:] == 0.0
        return Ma, Da, Ka, massless

    def dynamic(self, omega: float, w: float) -> np.ndarray:
        """The dynamic stiffness K - w^2 M + i w D (N, N) at the spin omega for a
        motion at w (rad/s), the pads' tilts condensed out exactly at w."""
        M, D, K, _ = self.augmented(omega)
        Z = K - w * w * M + 1j * w * D
        n = self.size
        if Z.shape[0] == n:
            return Z
        return Z[:n, :n] - Z[:n, n:] @ np.linalg.solve(Z[n:, n:], Z[n:, :n])

    def mass(self, omega: float) -> np.ndarray:
        """M of M q'' + D q' + K q = 0 at the spin omega (rad/s): the identity on the
        mass-normalised modes, with the seals' added mass on their seats."""
        M = np.eye(self.size)
        for b in self.bearings:
            if b.coefficients.has_mass:
                M = M + b.beta.T @ np.array(b.coefficients.mass(omega)) @ b.beta
        return M


# A bearing whose deviatoric part is below this share of its largest coefficient is
# isotropic (round-off of a table written as kxx = kyy).
ANISOTROPY = 1e-12


def isotropic_part(A: np.ndarray) -> np.ndarray:
    """The part of a bearing's 2x2 coefficient that every angle about the axis sees
    alike: a I + b S, a = (A_xx + A_yy) / 2, b = (A_yx - A_xy) / 2."""
    a, b = 0.5 * (A[0, 0] + A[1, 1]), 0.5 * (A[1, 0] - A[0, 1])
    return a * np.eye(2) + b * S2


def anisotropic(A: np.ndarray) -> bool:
    """Whether a bearing's 2x2 coefficient differs along x and y (its deviatoric part
    beyond ANISOTROPY of its largest entry)."""
    return bool(np.abs(A - isotropic_part(A)).max() > ANISOTROPY * max(np.abs(A).max(), 1e-300))


def deviatoric_parts(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The rest, A_d = [[p, q], [q, -p]], and A_d' = [[q, -p], [-p, -q]]: seen from a
    frame turned by theta, R^T A_d R = A_d cos 2 theta + A_d' sin 2 theta."""
    p, q = 0.5 * (A[0, 0] - A[1, 1]), 0.5 * (A[0, 1] + A[1, 0])
    return np.array([[p, q], [q, -p]]), np.array([[q, -p], [-p, -q]])


@dataclass(frozen=True)
class Roots:
    """The complex modes at one spin: eigenvalues lam (s^-1, Im > 0: one of each
    conjugate pair, ascending in Im) and their modal coordinates y (N, m)."""

    lam: np.ndarray
    y: np.ndarray
    divergence: float = 0.0   # the largest growth rate of a non-oscillating root, 1/s
    # a periodic rotor's Floquet forms: each one's share of its motion in the harmonics
    # d = -SIDES..SIDES from its dominant one (at lam + i 2 d Omega), and their whirl
    # indices, (2 SIDES + 1, m); None for a constant rotor
    sides: np.ndarray | None = None
    side_index: np.ndarray | None = None
    # ... and those harmonics' coefficients (2 SIDES + 1, N, m), zero outside Hill's range
    side_forms: np.ndarray | None = None


def roots(model: RotorModel, omega: float) -> Roots:
    """The eigenvalues of q'' + D q' + K q = 0 at the spin omega (rad/s) of a rotor whose
    coefficients are constant there (fem.floquet.any_roots takes periodic ones too), from its
    first-order form [[0, I], [-M^-1 K, -M^-1 D]]: the oscillating ones (Im lam > 0), lowest
    frequency first. Real ones (overdamped, or a divergence) are left out, the fastest
    growth among them kept (a shaft stiffer across one diameter than across the other
    diverges in the frame that turns with it between its pair's frequencies)."""
    n = model.size
    if model.tilting:
        A = state_matrix(*model.augmented(omega))
    else:
        D, K = model.matrices(omega)
        if any(b.coefficients.has_mass for b in model.bearings):
            X = np.linalg.solve(model.mass(omega), np.hstack([D, K]))
            D, K = X[:, :n], X[:, n:]
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -D]])
    lam, V = np.linalg.eig(A)
    scale = math.sqrt(max(float(np.max(np.abs(model.omega2))), 1.0))
    still = (np.abs(lam.imag) <= 1e-9 * scale) | still_seen(model, omega, lam, V[:n])
    keep = (lam.imag > 1e-9 * scale) & ~still
    divergence = float(max(0.0, lam.real[still].max())) if still.any() else 0.0
    lam, V = lam[keep], V[:n, keep]
    order = np.argsort(lam.imag)
    return Roots(lam=lam[order], y=V[:, order],
                 divergence=divergence if divergence > 1e-9 * scale else 0.0)


def state_matrix(M: np.ndarray, D: np.ndarray, K: np.ndarray, massless: np.ndarray
                 ) -> np.ndarray:
    """The first-order form z' = A z of M s'' + D s' + K s = 0 where some coordinates
    (b, `massless`) have no mass: z = (s_a, s_a', s_b), their rows D_b. s' + K_b. s = 0
    solved for s_b' (a massless pad's tilt follows its film's damping). The first
    entries of z are the first coordinates of s."""
    a, b = np.flatnonzero(~massless), np.flatnonzero(massless)
    if b.size == 0:
        X = np.linalg.solve(M, np.hstack([D, K]))
        return np.block([[np.zeros_like(M), np.eye(a.size)], [-X[:, a.size:], -X[:, :a.size]]])
    Kaa, Kab, Kba, Kbb = K[np.ix_(a, a)], K[np.ix_(a, b)], K[np.ix_(b, a)], K[np.ix_(b, b)]
    Daa, Dab, Dba, Dbb = D[np.ix_(a, a)], D[np.ix_(a, b)], D[np.ix_(b, a)], D[np.ix_(b, b)]
    # s_b' = -Dbb^-1 (Dba s_a' + Kba s_a + Kbb s_b)
    X = np.linalg.solve(Dbb, np.hstack([Kba, Dba, Kbb]))
    Sa, Va, Sb = X[:, :a.size], X[:, a.size:2 * a.size], X[:, 2 * a.size:]
    R = np.linalg.solve(M[np.ix_(a, a)], np.hstack([-Kaa + Dab @ Sa, -Daa + Dab @ Va,
                                                    -Kab + Dab @ Sb]))
    na, nb = a.size, b.size
    return np.block([[np.zeros((na, na)), np.eye(na), np.zeros((na, nb))],
                     [R[:, :na], R[:, na:2 * na], R[:, 2 * na:]],
                     [-Sa, -Va, -Sb]])


def still_seen(model: RotorModel, omega: float, lam: np.ndarray, y: np.ndarray
               ) -> np.ndarray:
    """Which roots (lam, s^-1; shapes y (N, m)) do not oscillate as the stationary frame
    sees them: in the rotating frame, a sideways root at Im lam = +-Omega whose circular
    component turns against it (an overdamped root of an oil film, seen from the turning
    shaft) is still in the stationary frame. Still within round-off of the largest
    frequency, or within 1e-3 of its own decay rate (a damping ratio within 5e-7 of 1:
    a form Hill's method need not settle)."""
    if model.frame != "rotating" or omega == 0.0 or lam.size == 0:
        return np.zeros(lam.size, dtype=bool)
    index = whirl_index(model, y)
    seen = np.where(index >= 0, lam.imag + omega, lam.imag - omega)
    scale = math.sqrt(max(float(np.max(np.abs(model.omega2))), 1.0))
    sideways = np.array([k not in ("axial", "torsion") for k in dominant_kinds(model, y)])
    return sideways & (np.abs(seen) <= np.maximum(1e-9 * scale, 1e-3 * np.abs(lam.real)))


def whirl_index(model: RotorModel, y: np.ndarray) -> np.ndarray:
    """Each complex shape's whirl index (m,): +1 a forward circular orbit (turning
    with the shaft), -1 backward, between for ellipses and mixed motion; the
    kinetic-energy-weighted share of the forward minus the backward component."""
    num = np.einsum("im,ij,jm->m", y.conj(), model.turning, y).real
    den = np.einsum("im,ij,jm->m", y.conj(), model.lateral, y).real
    return np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)


def seen_lines(shift: float, w_r: np.ndarray, S: int) -> tuple[np.ndarray, np.ndarray]:
    """The frequencies (rad/s, signed: + turning with the shaft) at which the housing sees
    a mode's harmonics d = -S..S: a form exp(i w_r t) sum_d q_d exp(i 2 d Omega t) in the
    frame turning at `shift` (Omega; 0 for the stationary frame) shows the housing each
    q_d's forward part (x + i y) at w_r + (2 d + 1) Omega and its backward part at
    -(w_r + (2 d - 1) Omega); each (2 S + 1, m) for w_r (m,)."""
    d = np.arange(-S, S + 1)[:, None]
    w = np.atleast_1d(w_r)[None, :]
    return w + (2 * d + 1) * shift, -(w + (2 * d - 1) * shift)


def seen_whirl_index(model: RotorModel, shift: float, w_r: np.ndarray,
                     forms: np.ndarray) -> np.ndarray:
    """Each mode's whirl index as the housing sees it (m,): the kinetic energy of the
    parts that turn with the shaft there less that of those turning against it, over
    the whole, summed over the harmonics forms (2 S + 1, N, m) at seen_lines. In the
    stationary frame (shift 0, S = 0) this is whirl_index."""
    L = np.einsum("dim,ij,djm->dm", forms.conj(), model.lateral, forms).real
    T = np.einsum("dim,ij,djm->dm", forms.conj(), model.turning, forms).real
    forward, backward = 0.5 * (L + T), 0.5 * (L - T)
    nu_f, nu_b = seen_lines(shift, w_r, (forms.shape[0] - 1) // 2)
    num = np.sum(np.sign(nu_f) * forward + np.sign(nu_b) * backward, axis=0)
    den = np.sum(L, axis=0)
    return np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)


def seen_orbit(shift: float, w_r: float, X: np.ndarray, Y: np.ndarray, t: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """The path (x, y), each (len(t), P), that P points trace as the housing sees them,
    undamped, whose harmonics' displacements along the frame's x and y are X and Y
    (2 S + 1, P), complex: z = x + i y = 1/2 sum_d [(X_d + i Y_d) exp(i nu_f t)
    + conj(X_d - i Y_d) exp(i nu_b t)], nu from seen_lines (the frames agree at t = 0)."""
    nu_f, nu_b = seen_lines(shift, np.array([w_r]), (X.shape[0] - 1) // 2)
    ef = np.exp(1j * np.outer(t, nu_f[:, 0]))                 # (T, 2 S + 1)
    eb = np.exp(1j * np.outer(t, nu_b[:, 0]))
    z = 0.5 * (ef @ (X + 1j * Y) + eb @ np.conj(X - 1j * Y))
    return z.real, z.imag


def seen_shape(shift: float, w_r: float, f: float, X: np.ndarray, Y: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """The complex shape (x, y), each (P,), that the housing sees at the frequency f
    (rad/s, > 0) of a mode whose harmonics' displacements are X and Y (2 S + 1, P): its
    motion there is Re(x exp(i f t)), Re(y exp(i f t)), from every part at +f (a_f) and
    at -f (a_b): x = a_f + conj(a_b), y = -i (a_f - conj(a_b)) (the filtered orbit)."""
    nu_f, nu_b = seen_lines(shift, np.array([w_r]), (X.shape[0] - 1) // 2)
    tol = 1e-6 * (abs(f) + abs(shift))
    parts = [(nu_f[:, 0], 0.5 * (X + 1j * Y)), (nu_b[:, 0], 0.5 * np.conj(X - 1j * Y))]
    a_f = sum(np.sum(c[np.abs(nu - f) <= tol], axis=0) for nu, c in parts)
    a_b = sum(np.sum(c[np.abs(nu + f) <= tol], axis=0) for nu, c in parts)
    return a_f + np.conj(a_b), -1j * (a_f - np.conj(a_b))


def dominant_kinds(model: RotorModel, y: np.ndarray) -> list[str]:
    """The kind of the standstill mode each complex shape holds most of."""
    return [model.kinds[int(np.argmax(np.abs(y[:, k])))] for k in range(y.shape[1])]


# --------------------------------------------------------------------------
# Building the model from a standstill modal run


def lateral_rigid(result: ModalResult) -> np.ndarray:
    """The rigid motions that move the shaft sideways (translations along x and y,
    tilts about x and y, about any point) and that its supports leave free: a shaft
    held by damping only, or not at all. As nodal shapes (3 n, r), mass-normalised in
    the run's pencil, like its modes."""
    import scipy.linalg

    from shaftfem.fem.supports import rigid_body_modes

    system, inst = result.system, result.installed
    nodes = system.nodes
    if inst is not None:
        if inst.n_rigid == 0:
            return np.zeros((3 * nodes.shape[0], 0))
        free_q, M = inst.rigid, inst.M
        free = np.asarray(inst.T @ free_q)
    else:
        free = rigid_body_modes(nodes)
        free_q, M = free, system.M
    sideways = rigid_body_modes(nodes, np.array([0.0, 0.0, nodes[:, 2].mean()]))[:, [0, 1, 3, 4]]
    Qf, Rf = np.linalg.qr(free)
    Ql = np.linalg.qr(sideways)[0]
    U, sv, _ = np.linalg.svd(Qf.T @ Ql)
    r = int(np.sum(sv > 1 - 1e-8))
    if r == 0:
        return np.zeros((free.shape[0], 0))
    q = free_q @ scipy.linalg.solve_triangular(Rf, U[:, :r])
    lam, V = np.linalg.eigh(q.T @ (M @ q))
    q = q @ (V / np.sqrt(lam))
    return np.asarray(inst.T @ q) if inst is not None else q


def rotor_model(result: ModalResult, frame: str, rigid: bool = False, residual: bool = True
                ) -> RotorModel:
    """The turning shaft of `result` (an order-1 or order-2 modal run, its elastic
    modes the basis) in `frame` ("stationary" or "rotating"); with `rigid`, the basis
    also holds the sideways rigid motions the supports leave free (lateral_rigid), at
    zero frequency: what a forced response needs of a shaft its bearings do not hold.
    With `residual` (and bearings), the basis also holds their residual modes
    (residual_modes), last: the bearings' coefficients at any speed then enter exactly
    to first order, whatever the standstill modes held of them."""
    from shaftfem.fem.modes import classify, energy_split

    if frame not in FRAMES:
        raise ValueError(f"frame {frame!r}: one of {FRAMES}")
    system, modes = result.system, result.modes
    if system.order > 2:
        raise SolverError("the turning shaft takes element orders 1 and 2")
    free = lateral_rigid(result) if rigid else np.zeros((modes.shapes.shape[0], 0))
    seats = seat_loads(result) if residual else np.zeros((system.n_dofs, 0))
    q = static_shapes(result, np.column_stack([spin_load(result), seats]), reduced=True)
    inst = result.installed
    spin_u = inst.T @ q[:, 0] if inst is not None else q[:, 0]
    res = residual_modes(result, q[:, 1:])
    extra, w2 = res.shapes, res.omega2
    Phi = np.hstack([free, modes.shapes, extra])   # (3 n, N)
    Ms = system.mass_scalar
    X, Y = Phi[0::3], Phi[1::3]
    MX, MY = Ms @ X, Ms @ Y
    Mxy = X.T @ MY
    lateral = X.T @ MX + Y.T @ MY
    turning = 1j * (Mxy - Mxy.T)
    basis = spin_basis(result)
    Ksig, B = spin_stiffness(result, basis, with_flow=frame == "stationary", u=spin_u)
    components = (X, Y, Phi[2::3])
    K2 = sum(P.T @ (Ksig @ P) for P in components)
    if frame == "stationary":
        A = spin_derivative(result, basis)
        AP = [A @ P for P in components]
        G = sum(P.T @ Q - Q.T @ P for P, Q in zip(components, AP))
        K2 = K2 - sum(P.T @ (B @ P) for P in components)
    else:
        G = 2.0 * (Y.T @ MX - X.T @ MY)
        K2 = K2 - lateral
    weight = np.vstack([MX.sum(axis=0), MY.sum(axis=0)])
    for psi, part in part_motions(result, Phi):
        Gp, Kp = part_matrices(part.mass, part.polar_inertia, part.diametral_inertia, frame)
        G = G + psi.T @ Gp @ psi
        K2 = K2 + psi.T @ Kp @ psi
        weight = weight + part.mass * psi[:2]
    omega2 = np.concatenate([np.zeros(free.shape[1]), (2 * math.pi * modes.frequencies) ** 2,
                             w2])
    kinds = tuple(classify(e) for e in energy_split(extra, system.nodes, Ms))
    return RotorModel(frame=frame, omega2=omega2, G=0.5 * (G - G.T), K2=0.5 * (K2 + K2.T),
                      bearings=bearing_modal(result, Phi), lateral=lateral,
                      turning=0.5 * (turning + turning.conj().T),
                      kinds=("rigid",) * free.shape[1] + tuple(modes.kinds) + kinds, shapes=Phi,
                      residual=extra.shape[1],
                      static=np.vstack([np.zeros((free.shape[1], res.on_modes.shape[1])),
                                        res.on_modes, res.on_residual]), weight=weight)


def seat_loads(result: ModalResult) -> np.ndarray:
    """A unit force on each bearing's seat along x and along y, as its mean motion reads
    it (the force c with q = c . u), (3 n, 2 b) N; no columns without bearings."""
    from shaftfem.fem.installation import seat_radius
    from shaftfem.fem.supports import seat_restraints, surface_weights

    scene, system = result.scene, result.system
    cols = []
    for s in scene.held:
        if s.bearing is None:
            continue
        radius = seat_radius(scene, system.nodes, s.seat)
        w = surface_weights(result.mesh.to_skfem(), system.order, radius, s.seat)
        unit = replace(s, kind="springs", radial=1.0, axial=0.0, tilting=0.0, bearing=None,
                       journal=None, seal=None, rolling=None)
        for r in seat_restraints(unit, system.nodes, w)[:2]:
            f = np.zeros(system.n_dofs)
            f[r.dofs] = r.coeffs
            cols.append(f)
    return np.column_stack(cols) if cols else np.zeros((system.n_dofs, 0))


@dataclass(frozen=True)
class Residual:
    """The bearings' residual modes (residual_modes): their shapes (3 n, r) and w^2
    (r,), and the static shapes they come from in the basis' coordinates: on the
    standstill modes (N, m) and on the residual modes (r, m)."""

    shapes: np.ndarray
    omega2: np.ndarray
    on_modes: np.ndarray
    on_residual: np.ndarray


def residual_modes(result: ModalResult, static: np.ndarray) -> Residual:
    """What the bearings' static shapes `static` (reduced coordinates, as static_shapes
    gives them) hold beyond the standstill modes: their part M-orthogonal to the modes,
    diagonalised on its own, as pseudo-modes with their w^2. The modes are eigenvectors,
    so the two blocks are K- and M-orthogonal and the basis stays diagonal. With them
    any change of the bearings' coefficients is taken exactly to first order in
    (w / w_N)^2: a bearing's force on the shaft moves it along its seat's static shape,
    which is in the basis (MacNeal's residual flexibility)."""
    import scipy.linalg

    inst = result.installed
    n = result.modes.shapes.shape[1]
    if inst is None or static.shape[1] == 0:
        return Residual(np.zeros((result.system.n_dofs, 0)), np.zeros(0),
                        np.zeros((n, static.shape[1])), np.zeros((0, static.shape[1])))
    Q = result.reduced_shapes()
    A = Q.T @ (inst.M @ static)
    R = static - Q @ A
    R = R - Q @ (Q.T @ (inst.M @ R))                 # twice is enough
    Mr, Kr = R.T @ (inst.M @ R), R.T @ (inst.K @ R)
    m, V = np.linalg.eigh(0.5 * (Mr + Mr.T))
    keep = m > RESIDUAL_RANK * m.max()
    B = V[:, keep] / np.sqrt(m[keep])                # M-orthonormal combinations
    w2, U = scipy.linalg.eigh(B.T @ (0.5 * (Kr + Kr.T)) @ B)
    W = B @ U
    return Residual(inst.T @ (R @ W), w2, A, W.T @ (0.5 * (Mr + Mr.T)))


def spin_basis(result: ModalResult):
    """scikit-fem's scalar basis of the run's mesh at the mass's quadrature: what the
    spin's matrices are integrated on."""
    from skfem import Basis

    from shaftfem.fem.assembly import MASS_INTORDER
    from shaftfem.fem.elements import element

    return Basis(result.mesh.to_skfem(), element(result.system.order),
                 intorder=MASS_INTORDER[result.system.order])


def spin_derivative(result: ModalResult, basis) -> sp.csr_matrix:
    """A = int rho phi_a (x d/dy - y d/dx) phi_b dV on the scalar basis (kg / s per
    rad/s): the material's flow through the mesh of a shaft that turns."""
    from skfem import BilinearForm

    @BilinearForm
    def flow(u, v, w):
        return v * (w.x[0] * u.grad[1] - w.x[1] * u.grad[0])

    return (result.scene.material.density * flow.assemble(basis)).tocsr()


def spin_stiffness(result: ModalResult, basis, with_flow: bool, u: np.ndarray | None = None
                   ) -> tuple[sp.csr_matrix, sp.csr_matrix | None]:
    """Per (rad/s)^2, on the scalar basis: the stiffening by the stress of the shaft's
    own spin, int sigma_ij d_i phi_a d_j phi_b dV with sigma from K u = int rho P x
    (the centrifugal load of a unit spin, its rigid part taken out; `u` if given), and, with
    `with_flow`, the stationary frame's softening int rho d_theta phi_a d_theta phi_b
    dV. On a solid of revolution the two cancel on a rigid tilt or turn (the spin
    stress's virial is its centrifugal load's moment; see tied_cells for the slices
    under rigid parts)."""
    from skfem import BilinearForm

    u = static_shapes(result, spin_load(result)[:, None])[:, 0] if u is None else u
    grad = np.stack([basis.interpolate(u[c::3]).grad for c in range(3)])   # (3, 3, E, Q)
    eps = 0.5 * (grad + grad.transpose(1, 0, 2, 3))
    lam, mu = result.scene.material.lame
    sigma = 2 * mu * eps
    for i in range(3):
        sigma[i, i] += lam * (eps[0, 0] + eps[1, 1] + eps[2, 2])
    tied = tied_cells(result)
    if tied.any():
        # a slice tied to a rigid part moves as one body with it, unstrained (its part
        # holds its centrifugal load); it takes the stress whose virial a free spinning
        # body has, rho x_i x_j across the axis, which is all a rigid motion reads
        x = basis.global_coordinates().value[:, tied]          # (3, E_tied, Q)
        sigma[:, :, tied] = 0.0
        for i in range(2):
            for j in range(2):
                sigma[i, j, tied] = result.scene.material.density * x[i] * x[j]
    fields = {f"s{i}{j}": sigma[i, j] for i in range(3) for j in range(3)}

    @BilinearForm
    def prestress(u, v, w):
        return sum(w[f"s{i}{j}"] * u.grad[i] * v.grad[j] for i in range(3) for j in range(3))

    Ksig = prestress.assemble(basis, **fields).tocsr()
    if not with_flow:
        return Ksig, None

    @BilinearForm
    def flow(u, v, w):
        du = w.x[0] * u.grad[1] - w.x[1] * u.grad[0]
        dv = w.x[0] * v.grad[1] - w.x[1] * v.grad[0]
        return du * dv

    rho = result.scene.material.density
    return Ksig, (rho * flow.assemble(basis)).tocsr()


def tied_cells(result: ModalResult) -> np.ndarray:
    """Whether each cell of the mesh lies in a slice tied to a rigid part or ring."""
    t = result.mesh.to_skfem().t
    inst = result.installed
    tied = np.zeros(int(t.max()) + 1, dtype=bool)
    for idx in (*inst.tied, *inst.rings) if inst is not None else ():
        tied[idx[idx < tied.size]] = True
    return tied[t].all(axis=0)


# A bearing's static shape whose part beyond the modes has less than this share of the
# largest one's mass norm adds nothing new.
RESIDUAL_RANK = 1e-10

# The static solve of the spin load: shifted by this share of the lowest elastic
# eigenvalue and iterated (each step gains about this factor) ...
STATIC_SHIFT = 1e-2
# ... this many times.
STATIC_STEPS = 5


def spin_load(result: ModalResult) -> np.ndarray:
    """The centrifugal load of a unit spin on every DOF (N per (rad/s)^2): rho x, rho y."""
    system = result.system
    f = np.zeros(system.n_dofs)
    for c in (0, 1):
        f[c::3] = system.mass_scalar @ system.nodes[:, c]
    return f


def static_shapes(result: ModalResult, loads: np.ndarray, reduced: bool = False) -> np.ndarray:
    """The shaft's displacement (3 n, m) under each load (3 n, m; N on every DOF), its
    rigid motions taken out: (K + s M) u_k+1 = f + s M u_k from the run's pencil
    (installed or free), which converges to K u = f on the elastic modes without a
    singular factorisation; one factorisation for every load. With `reduced`, in the
    installed pencil's own coordinates."""
    from shaftfem.fem.static import elastic_solve
    from shaftfem.fem.supports import rigid_body_modes

    system, inst = result.system, result.installed
    if inst is not None:
        K, M, R, f = inst.K, inst.M, inst.rigid, inst.T.T @ loads
    else:
        K, M, R, f = system.K, system.M, rigid_body_modes(system.nodes), loads
    s = STATIC_SHIFT * (2 * math.pi * result.modes.frequencies[0]) ** 2
    u = elastic_solve(K, M, R, f, s, STATIC_STEPS)
    return inst.T @ u if inst is not None and not reduced else u


def part_matrices(mass: float, polar: float, diametral: float, frame: str
                  ) -> tuple[np.ndarray, np.ndarray]:
    """A rigid part's (G per rad/s, K_2 per (rad/s)^2) on its (U, Theta), 6x6."""
    G, K = np.zeros((6, 6)), np.zeros((6, 6))
    if frame == "stationary":
        G[3, 4], G[4, 3] = polar, -polar
        return G, K
    G[0, 1], G[1, 0] = -2 * mass, 2 * mass
    G[3, 4], G[4, 3] = polar - 2 * diametral, -(polar - 2 * diametral)
    K[0, 0] = K[1, 1] = -mass
    K[3, 3] = K[4, 4] = polar - diametral
    return G, K


def part_motions(result: ModalResult, Phi: np.ndarray | None = None
                 ) -> list[tuple[np.ndarray, Attachment]]:
    """Each part's (U, Theta) in each shape of Phi (default the run's modes), (6, N),
    and the part: on a distributing joint its section's means, on a rigid one the rigid
    motion its slice follows."""
    from shaftfem.fem.supports import tie_rows

    inst = result.installed
    if inst is None:
        return []
    Phi = result.modes.shapes if Phi is None else Phi
    out = [(c.C @ Phi[c.dofs], c.part) for c in inst.carried]
    nodes = result.system.nodes
    for idx, part in zip(inst.tied, inst.parts):
        B = tie_rows(nodes, idx, np.array([0.0, 0.0, part.position])).reshape(-1, 6)
        U = Phi[(3 * idx[:, None] + np.arange(3)).ravel()]
        out.append((np.linalg.lstsq(B, U, rcond=None)[0], part))
    return out


def bearing_modal(result: ModalResult, Phi: np.ndarray | None = None
                  ) -> tuple[BearingModal, ...]:
    """The scene's bearings (kind "bearing", "journal", "ball", "roller") and its stages'
    cross-couplings (Wachel, on their parts) on the shapes Phi (default the run's
    modes)."""
    from shaftfem.fem.installation import seat_radius
    from shaftfem.fem.supports import seat_restraints, surface_weights

    scene, system = result.scene, result.system
    out = []
    skmesh = None
    for s in scene.held:
        if s.awaits_part:
            raise SolverError(f"support {s.name!r}: its part was not asked for its "
                              "coefficients (workflows.equip)")
        if s.bearing is None:
            continue
        if skmesh is None:
            skmesh = result.mesh.to_skfem()
        radius = seat_radius(scene, system.nodes, s.seat)
        w = surface_weights(skmesh, system.order, radius, s.seat)
        unit = replace(s, kind="springs", radial=1.0, axial=0.0, tilting=0.0, bearing=None,
                       journal=None, seal=None, rolling=None)
        x, y = seat_restraints(unit, system.nodes, w)[:2]
        shapes = result.modes.shapes if Phi is None else Phi
        beta = np.vstack([x.coeffs @ shapes[x.dofs], y.coeffs @ shapes[y.dofs]])
        out.append(BearingModal(s.name, beta, s.bearing, s.radial_xy))
    # a stage's cross-coupling acts on its part's translations as a bearing would
    for psi, part in part_motions(result, Phi):
        if part.cross_coupling is not None:
            out.append(BearingModal(f"{part.name} (stage)", psi[:2], part.cross_coupling,
                                    (0.0, 0.0)))
    return tuple(out)


def section_motion(result: ModalResult, z: float, Phi: np.ndarray | None = None
                   ) -> np.ndarray:
    """The mean radial motion (x, y) of the shaft's cross-section at z (m) in each
    shape of Phi (default the run's modes), (2, N), m / sqrt(kg): where a beam model
    reads its node (the mesh follows the planes of the scene's parts and unbalances)."""
    from shaftfem.fem.supports import section_means

    system = result.system
    c = section_means(system.nodes, system.mass_scalar.diagonal(), z)
    return c.C[:2] @ (result.modes.shapes if Phi is None else Phi)[c.dofs]


def unbalance_response(model: RotorModel, omega: float, forces: list[tuple[np.ndarray, complex]]
                       ) -> np.ndarray:
    """The modal coordinates (N,) of the steady response to unbalances turning at omega
    (rad/s): each (beta, U) its plane's motion (2, N) and U = m e exp(i phase) (kg m).

    Stationary frame: the force m e omega^2 (cos(omega t + phase), sin(...)) is
    U omega^2 (1, -i) exp(i omega t), solved from (K - omega^2 I + i omega D) y = F.
    Rotating frame: it stands still there, omega^2 (Re U, Im U), and K y = F."""
    F = np.zeros(model.size, dtype=complex)
    for beta, U in forces:
        if model.frame == "stationary":
            F += omega**2 * U * (beta[0] - 1j * beta[1])
        else:
            F += omega**2 * (U.real * beta[0] + U.imag * beta[1])
    if model.frame == "stationary":
        return np.linalg.solve(model.dynamic(omega, omega), F)
    return np.linalg.solve(model.matrices(omega)[1].astype(complex), F)


def orbit(model: RotorModel, beta: np.ndarray, y: np.ndarray
          ) -> tuple[float, float, float, float, float]:
    """The orbit of a section (its motion beta, (2, N)) in the response y, 0-peak: the
    amplitude along x, the orbit's major semi-axis (m), the phase of x (rad), the
    amplitude along y (m) and its phase (rad). In the rotating frame the response
    stands still there: a forward circle in the stationary frame, of the radius of its
    displacement."""
    if y.ndim == 2:
        # a periodic rotor's harmonics q_k (N, 2 H + 1), turning frame: the section's
        # x_r + i y_r = sum (X_k + i Y_k) exp(i 2 k Omega t) is seen from the housing as
        # exp(i Omega t) times that: at 1x the forward a_f (k = 0) and backward a_b (k = -1)
        H = y.shape[1] // 2
        Xk, Yk = beta[0] @ y, beta[1] @ y
        a_f, a_b = Xk[H] + 1j * Yk[H], Xk[H - 1] + 1j * Yk[H - 1]
        X, Y = a_f + np.conj(a_b), -1j * a_f + 1j * np.conj(a_b)
        return (float(abs(X)), float(abs(a_f) + abs(a_b)), float(np.angle(X)), float(abs(Y)),
                float(np.angle(Y)))
    x, yv = beta[0] @ y, beta[1] @ y
    if model.frame == "rotating":
        r = float(math.hypot(abs(x), abs(yv)))
        angle = float(np.angle(x + 1j * yv))
        return r, r, angle, r, angle - math.pi / 2
    major = 0.5 * (abs(x + 1j * yv) + abs(x - 1j * yv))
    return float(abs(x)), float(major), float(np.angle(x)), float(abs(yv)), float(np.angle(yv))
