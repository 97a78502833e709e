"""An independent 1D Floquet model of a shaft that is not round, in bearings that differ
along x and y, against shaftfem's 3D solid.

Nothing of shaftfem's is used here but its scene reader for the numbers (the model is
built from the scene file's keys, in SI): a Timoshenko beam of linear elements (shear at
one point, so no locking; 2 mm elements), in the stationary frame, where the shaft's
bending stiffness turns with it,

    EJ(t) = E R(t) diag(I_1, I_2) R(t)^T = E (J_m I + J_d [[cos 2Wt, sin 2Wt],
                                                          [sin 2Wt, -cos 2Wt]]),

so that M q'' + (C + W G) q' + (K_0 + K_c cos 2Wt + K_s sin 2Wt) q = 0 has period
T = pi / W. Its Floquet multipliers are the eigenvalues of the monodromy matrix,
integrated over one period by the fourth-order Magnus method on the lowest standstill
modes of the mean shaft (their count doubled until the answers hold; a step a radian of
their highest frequency at most). The rotor grows
where a multiplier lies outside the unit circle: the zones of growth, their edges by
bisection. A 1x crossing is a multiplier on the negative real axis (a Floquet exponent
seen at W, modulo 2 W), lightly damped, of a mode whose mean frequency lies near W.
The section's rotary inertia is taken at its mean (its asymmetry turns with the shaft
too; its share here is under 1e-4 of the frequencies) and its shear area as the round
section's.

    python benchmarks/floquet_1d.py [scene.toml]   (default: the slotted rotor on
                                                    bearings four times softer along y)

prints the zones, the 1x crossings and the growth above the last zone from both, and
their differences. docs/verification.md quotes its table.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np
import scipy.linalg as sl

RPM = math.pi / 30
ROOT = Path(__file__).resolve().parent.parent


# --------------------------------------------------------------------------------------
# the section: a round bar less its slots (keyways), by quadrature across it

def section(diameter: float, slots: list[tuple[float, float, float]]
            ) -> tuple[float, float, float]:
    """Area, I_1 = int xi^2 dA and I_2 = int eta^2 dA (m^2, m^4) of a round section of
    `diameter` less slots (width, depth, angle) whose angles are 0 or pi (along the body
    axis xi): each removes {xi > R - depth, |eta| < width / 2} of the disc."""
    R = 0.5 * diameter
    edges = sorted({-R, R, *(s * w / 2 for w, _, _ in slots for s in (-1, 1))})
    A = I1 = I2 = 0.0
    for a, b in zip(edges, edges[1:]):
        t, wt = np.polynomial.legendre.leggauss(400)
        # eta = R sin(phi) spreads the points where the chord's square root turns
        pa, pb = math.asin(a / R), math.asin(b / R)
        phi = 0.5 * (pb - pa) * t + 0.5 * (pb + pa)
        w = 0.5 * (pb - pa) * wt * R * np.cos(phi)
        eta = R * np.sin(phi)
        chord = np.sqrt(np.maximum(R * R - eta * eta, 0.0))
        hi = chord.copy()
        lo = -chord.copy()
        for width, depth, angle in slots:
            inside = np.abs(eta) < width / 2
            if abs(math.cos(angle) - 1) < 1e-9:
                hi = np.where(inside, np.minimum(hi, R - depth), hi)
            else:
                lo = np.where(inside, np.maximum(lo, -(R - depth)), lo)
        A += float(np.sum(w * (hi - lo)))
        I1 += float(np.sum(w * (hi**3 - lo**3) / 3))
        I2 += float(np.sum(w * eta**2 * (hi - lo)))
    return A, I1, I2


# --------------------------------------------------------------------------------------
# the beam

class Beam:
    """The shaft as linear Timoshenko elements: per node (ux, uy, sx, sy), s the
    section's slope vector (its rotation about y is sx, about x is -sy)."""

    def __init__(self, scene, h: float = 0.002):
        self.scene = scene
        E, nu, rho = (scene.material.youngs_modulus, scene.material.poisson_ratio,
                      scene.material.density)
        G = E / (2 * (1 + nu))
        kappa = 6 * (1 + nu) / (7 + 6 * nu)         # a round section's shear coefficient
        L = scene.shaft.length
        marks = {0.0, L}
        for k in scene.shaft.keyways:
            marks |= {k.start, k.start + k.length}
        z = 0.0
        for s in scene.shaft.sections:
            z += s.length
            marks.add(z)
        for p in [*scene.supports, *scene.attachments]:
            marks.add(p.position)
        marks = sorted(m for m in marks if 0 <= m <= L)
        nodes = [0.0]
        for a, b in zip(marks, marks[1:]):
            n = max(1, math.ceil((b - a) / h))
            nodes += list(np.linspace(a, b, n + 1)[1:])
        self.z = np.array(nodes)
        n = self.z.size
        N = 4 * n
        self.N = N
        parts: dict[str, list] = {k: [] for k in ("K0", "Kc", "Ks", "M", "G")}
        sections: dict[tuple, tuple[float, float, float]] = {}
        for e in range(n - 1):
            a, b = self.z[e], self.z[e + 1]
            le = b - a
            mid = 0.5 * (a + b)
            d = self._diameter(mid)
            slots = [(k.width, k.depth, k.angle) for k in scene.shaft.keyways
                     if k.start <= mid <= k.start + k.length]
            key = (d, tuple(slots))
            if key not in sections:
                sections[key] = section(d, slots)
            A, I1, I2 = sections[key]
            Jm, Jd = 0.5 * (I1 + I2), 0.5 * (I1 - I2)
            idx = np.r_[4 * e:4 * e + 8]
            ux, uy, sx, sy = (np.array([i, 4 + i]) for i in range(4))
            # bending: (E / le) (s2 - s1)^T J (s2 - s1)
            B = np.array([[1.0, -1.0], [-1.0, 1.0]]) * E / le
            kb0 = np.zeros((8, 8))
            kbc = np.zeros((8, 8))
            kbs = np.zeros((8, 8))
            for (p, q, m0, mc, ms) in ((sx, sx, Jm, Jd, 0.0), (sy, sy, Jm, -Jd, 0.0),
                                       (sx, sy, 0.0, 0.0, Jd), (sy, sx, 0.0, 0.0, Jd)):
                kb0[np.ix_(p, q)] += m0 * B
                kbc[np.ix_(p, q)] += mc * B
                kbs[np.ix_(p, q)] += ms * B
            # shear at the element's middle: gamma = (d2 - d1) / le - (s1 + s2) / 2
            ks = np.zeros((8, 8))
            for u, s in ((ux, sx), (uy, sy)):
                g = np.zeros(8)
                g[u] = [-1 / le, 1 / le]
                g[s] = [-0.5, -0.5]
                ks += kappa * G * A * le * np.outer(g, g)
            m = np.zeros((8, 8))
            c = np.array([[2.0, 1.0], [1.0, 2.0]]) * le / 6
            for u in (ux, uy):
                m[np.ix_(u, u)] += rho * A * c
            for s in (sx, sy):
                m[np.ix_(s, s)] += rho * Jm * c
            gy = np.zeros((8, 8))
            gy[np.ix_(sx, sy)] += rho * 2 * Jm * c      # polar: I_1 + I_2 = 2 J_m
            gy[np.ix_(sy, sx)] -= rho * 2 * Jm * c
            for name, block in (("K0", kb0 + ks), ("Kc", kbc), ("Ks", kbs), ("M", m),
                                ("G", gy)):
                parts[name].append((idx, block))

        def assembled(name: str) -> np.ndarray:
            out = np.zeros((N, N))
            for idx, block in parts[name]:
                out[np.ix_(idx, idx)] += block
            return out

        K0, Kc, Ks, M, Gy = (assembled(k) for k in ("K0", "Kc", "Ks", "M", "G"))
        C = np.zeros((N, N))
        for sup in scene.supports:
            i = 4 * self.node(sup.position)
            b = sup.bearing
            K0[i, i] += b.kxx[0]
            K0[i + 1, i + 1] += b.kyy[0]
            K0[i, i + 1] += b.kxy[0]
            K0[i + 1, i] += b.kyx[0]
            C[i, i] += b.cxx[0]
            C[i + 1, i + 1] += b.cyy[0]
        for part in scene.attachments:   # distributing: on the section's mean motion
            i = 4 * self.node(part.position)
            M[i, i] += part.mass
            M[i + 1, i + 1] += part.mass
            M[i + 2, i + 2] += part.diametral_inertia
            M[i + 3, i + 3] += part.diametral_inertia
            Gy[i + 2, i + 3] += part.polar_inertia
            Gy[i + 3, i + 2] -= part.polar_inertia
        self.K0, self.Kc, self.Ks, self.M, self.G, self.C = K0, Kc, Ks, M, Gy, C

    def _diameter(self, z: float) -> float:
        at = 0.0
        for s in self.scene.shaft.sections:
            if z <= at + s.length:
                return s.diameter_start
            at += s.length
        return self.scene.shaft.sections[-1].diameter_start

    def node(self, z: float) -> int:
        return int(np.argmin(np.abs(self.z - z)))


class Reduced:
    """The beam on the lowest `count` standstill modes of its mean shaft."""

    def __init__(self, beam: Beam, count: int):
        import scipy.sparse as sp
        import scipy.sparse.linalg as sla

        w2, V = sla.eigsh(sp.csc_matrix(beam.K0), k=count, M=sp.csc_matrix(beam.M),
                          sigma=0.0)
        order = np.argsort(w2)
        w2, V = w2[order], V[:, order]
        V = V / np.sqrt(np.einsum("ij,ij->j", V, beam.M @ V))   # unit modal masses
        self.w2 = w2
        self.k0 = V.T @ beam.K0 @ V
        self.kc = V.T @ beam.Kc @ V
        self.ks = V.T @ beam.Ks @ V
        self.g = V.T @ beam.G @ V
        self.c = V.T @ beam.C @ V
        self.n = count

    def A(self, omega: float, t: float) -> np.ndarray:
        n = self.n
        K = self.k0 + self.kc * math.cos(2 * omega * t) + self.ks * math.sin(2 * omega * t)
        return np.block([[np.zeros((n, n)), np.eye(n)], [-K, -(self.c + omega * self.g)]])

    def multipliers(self, omega: float) -> np.ndarray:
        """The Floquet multipliers over one period pi / omega (fourth-order Magnus, a step
        a radian of the basis' highest frequency at most: coarser steps alias it and
        make growth that is not there)."""
        T = math.pi / omega
        steps = max(96, math.ceil(math.sqrt(self.w2.max()) * T))
        h = T / steps
        Phi = np.eye(2 * self.n)
        r = math.sqrt(3) / 6
        for k in range(steps):
            t = k * h
            A1, A2 = self.A(omega, t + (0.5 - r) * h), self.A(omega, t + (0.5 + r) * h)
            W = 0.5 * h * (A1 + A2) + math.sqrt(3) / 12 * h * h * (A2 @ A1 - A1 @ A2)
            Phi = sl.expm(W) @ Phi
        return np.linalg.eigvals(Phi)

    def growth(self, omega: float) -> float:
        """The fastest growth rate, 1/s (negative: every motion decays)."""
        mu = self.multipliers(omega)
        return float(np.max(np.log(np.abs(mu)))) * omega / math.pi

    def mean_frequencies(self, omega: float) -> np.ndarray:
        """The mean shaft's whirl frequencies at the spin (Hz): what tells a 1x crossing
        from a 3x one."""
        n = self.n
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-self.k0, -(self.c + omega * self.g)]])
        lam = np.linalg.eigvals(A)
        return np.sort(np.abs(lam.imag[lam.imag > 0])) / (2 * math.pi)


def zones(red: Reduced, speeds_rpm: np.ndarray) -> list[tuple[float, float, float]]:
    """The zones of growth on `speeds_rpm` (edges bisected to 1e-7 of the speed) and
    their fastest growth met on the grid (1/s)."""
    g = [red.growth(n * RPM) for n in speeds_rpm]

    def edge(lo: float, hi: float, grows_high: bool) -> float:
        while hi - lo > 1e-7 * hi:
            mid = 0.5 * (lo + hi)
            if (red.growth(mid * RPM) > 0) == grows_high:
                hi = mid
            else:
                lo = mid
        return 0.5 * (lo + hi)

    out, start, fastest = [], None, 0.0
    for i, (n, gi) in enumerate(zip(speeds_rpm, g)):
        if gi > 0 and start is None:
            start = float(n) if i == 0 else edge(speeds_rpm[i - 1], n, True)
            fastest = gi
        elif gi > 0:
            fastest = max(fastest, gi)
        elif start is not None:
            out.append((start, edge(speeds_rpm[i - 1], n, False), fastest))
            start = None
    if start is not None:
        out.append((start, float(speeds_rpm[-1]), fastest))
    return out


def locked(red: Reduced, omega: float, light: float = 0.5) -> bool:
    """Whether a lightly damped motion (decaying by less than e^-light a period) is
    locked to the shaft's speed: a multiplier on the negative real axis, a Floquet
    exponent seen at the speed (modulo twice it), as a pair that met there."""
    mu = red.multipliers(omega)
    return bool(np.any((mu.real < 0) & (mu.imag == 0) & (np.abs(mu) > math.exp(-light))))


def lock_bands(red: Reduced, speeds_rpm: np.ndarray) -> list[tuple[float, float]]:
    """The bands (r/min) where a lightly damped motion locks to the speed: a 1x crossing
    of a rotor that is not round (its mode's forward and backward seen frequencies meet
    the 1x line there as one pair), a zone of growth where it grows; each with a mean
    frequency near the speed (a 3x band, near a third of it, is left out). Edges by
    bisection (1e-7 of the speed)."""
    on = [locked(red, n * RPM) if n > 0 else False for n in speeds_rpm]

    def edge(lo: float, hi: float, on_high: bool) -> float:
        while hi - lo > 1e-7 * hi:
            mid = 0.5 * (lo + hi)
            if locked(red, mid * RPM) == on_high:
                hi = mid
            else:
                lo = mid
        return 0.5 * (lo + hi)

    out, start = [], None
    for i, n in enumerate(speeds_rpm):
        if on[i] and start is None:
            start = edge(speeds_rpm[i - 1], n, True)
        elif not on[i] and start is not None:
            out.append((start, edge(speeds_rpm[i - 1], n, False)))
            start = None
    if start is not None:
        out.append((start, float(speeds_rpm[-1])))
    return [(a, b) for a, b in out
            if np.any(np.abs(red.mean_frequencies(0.5 * (a + b) * RPM) - (a + b) / 120)
                      < (a + b) / 360)]


def main(path: str) -> None:
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.campbell import run_campbell

    scene = load_scene(path)
    assert scene.rotor is not None
    top = scene.rotor.max_speed / RPM
    grid = np.linspace(top / 60, top, 60)
    t0 = time.perf_counter()
    beam = Beam(scene)
    runs = {}
    for count in (24, 48):
        red = Reduced(beam, count)
        runs[count] = (zones(red, grid), red)
    ours_zones, red = runs[48]
    moved = max((abs(a - b) / b for z1, z2 in zip(runs[24][0], ours_zones)
                 for a, b in zip(z1[:2], z2[:2])), default=0.0)
    ref_locks = lock_bands(red, grid)
    print(f"1D reference: {beam.z.size} nodes, {red.n} modes (24 modes move the zone "
          f"edges by {moved:.1e}), {time.perf_counter() - t0:.0f} s")
    t0 = time.perf_counter()
    c = run_campbell(scene)
    print(f"shaftfem: {time.perf_counter() - t0:.0f} s")
    print("\nzones of growth, r/min:")
    print(f"{'1D from':>10} {'1D to':>10} {'3D from':>10} {'3D to':>10} {'diff':>9}")
    for i in range(max(len(ours_zones), len(c.zones))):
        a = ours_zones[i] if i < len(ours_zones) else None
        b = c.zones[i] if i < len(c.zones) else None
        diff = (max(abs(a[0] / b.from_rpm - 1), abs(a[1] / b.to_rpm - 1))
                if a and b else float("nan"))
        print(f"{a[0] if a else float('nan'):>10,.1f} {a[1] if a else float('nan'):>10,.1f} "
              f"{b.from_rpm if b else float('nan'):>10,.1f} "
              f"{b.to_rpm if b else float('nan'):>10,.1f} {diff * 100:>8.3f}%")
    theirs = sorted(cs.speed_rpm for cs in c.critical_speeds if cs.order == 1)
    print("\n1x: the 1D model's bands locked to the speed (a 1x crossing of a rotor that "
          "is not round), r/min:", "; ".join(f"{a:,.1f}-{b:,.1f}" for a, b in ref_locks))
    print("    shaftfem's 1x critical speeds, r/min:", ", ".join(f"{n:,.1f}" for n in theirs))
    last = ours_zones[-1][1] if ours_zones else 0.0
    above = [n for n in grid if n > last * 1.001]
    print(f"\nabove the last zone ({last:,.0f} r/min): 1D fastest growth "
          f"{max((red.growth(n * RPM) for n in above), default=float('nan')):.3g} 1/s; "
          f"3D stable above {c.stable_above_rpm}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "benchmarks" / "data"
                                                    / "slotted_aniso.toml"))
