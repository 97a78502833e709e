"""How far each frequency is from converged: a posteriori estimates from the solved meshes.

For a conforming discretisation and a mass-normalised eigenvector u_h of
eigenvalue lambda_h = w_h^2 (Babuska-Osborn),

    lambda_h - lambda = ||u - u_h||_a^2 - lambda ||u - u_h||_M^2 <= ||u - u_h||_a^2,

so the relative frequency error is about ||u - u_h||_a^2 / (2 lambda_h): half the
squared relative energy error of the mode. Two estimates of it are combined:

* recovery (Zienkiewicz-Zhu): the stress sigma_h of the mode is projected (L2) onto
  continuous elements of the mesh's order, and eta^2 = int (sigma* - sigma_h) :
  C^-1 : (sigma* - sigma_h) dx estimates ||u - u_h||_a^2, element by element. It
  is close to the truth where the mesh resolves the stress, and falls short where
  it does not (groove fillets spanned by one element: half the true error);
* two meshes: a coarser mesh's frequency f_c, never below the truth, shows that
  the coarser error is at least D = f_c - f. If the recovery estimate falls short
  of the truth by the same factor on both meshes, the finer mesh's error is
  D rho / (1 - rho), rho = eta_fine^2 / eta_coarse^2: the recovery estimate gives
  the ratio of the errors, the frequencies give their scale. No convergence rate is
  assumed anywhere.

Each frequency's bound is SAFETY times the larger of the two, plus the relative
difference between the mesh's volume and the solid's (analytic) volume: the curved
P2 faces only approximate the CAD surfaces, which moves frequencies by about as
much and is invisible to both estimates (on an adapted cylinder mesh it was as
large as the discretisation error). Where the two meshes
contradict each other (the coarse frequency is lower, or its recovery estimate is
not larger) the bound is the recovery estimate alone, and is said to be so.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

if TYPE_CHECKING:
    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.cad.solid import ShaftShape
    from shaftfem.fem.modes import Modes
    from shaftfem.scene.model import Material, Shaft

# On the larger estimate. Measured effectivities (estimate / true error) before it:
# 1.25-1.9 on the paper's shaft (two-mesh, against an independent NGSolve order-3
# reference), 1.1-1.9 on the cylinder's torsion modes (recovery, exact c_t / 2L), and
# about 0.9 on its fourth bending pair at 8 mm, where the coarse mesh's faceted circle
# also lowers the frequency: 1.5 keeps all of them above 1 and the first two below 3.
SAFETY = 1.5
# How far the recovery estimate may fall short of the true error, on each mode, on an
# unstructured P2 mesh: measured 0.36-0.42 times the error on the paper's shaft (against
# NGSolve order 3), 0.31-0.57 on a stepped shaft with 1 mm fillets under 4 mm elements and
# on the same shaft with a sharp-floored keyway (against NGSolve order 4), where the
# fillets, unresolved, act as corners and the two meshes converge too slowly for their
# drop to show it. No bound is below SAFETY times this times the recovery estimate. On a
# plain bar, whose mesh is one sector's copied round the axis, the recovery is 1-3 times
# the true error instead (ten torsion modes against c_t / 2L): there the factor is 1.
RECOVERY_SHORTFALL = 3.0
RHO_MAX = 0.9        # above: the coarser mesh's estimate is not clearly larger
# On the rate-based estimate of three nested orders. Measured on the paper's shaft at order 4
# (10/5/5 mm, 447k DOFs) it is 0.86-1.31 times the true error against the NGSolve
# reference, which may itself be 0.05 % high (then 0.5-0.7 times): 2 keeps the bound above
# the truth either way, and below 3 times it.
HIERARCHY_SAFETY = 2.0
CLUSTER = 1e-3       # relative gap below which modes share one bound (bending pairs)


@dataclass(frozen=True)
class Recovery:
    """Recovery estimates of one mesh's modes.

    relative: (n,) estimated relative frequency error of each mode (no safety);
    elements: (n, n_elements) each element's share of it; volume: the mesh's, m^3.
    """

    relative: np.ndarray
    elements: np.ndarray
    volume: float


@dataclass(frozen=True)
class ErrorEstimate:
    """Per mode: a bound on the relative frequency error and how it was made.

    relative_error is the bound (fraction of the frequency); recovery the finer
    mesh's recovery estimate; two_mesh the two-mesh estimate (nan where the meshes
    disagree); geometry the allowance for the mesh's curved faces; reliable False
    where only the recovery estimate was left (`notes` says why).
    """

    relative_error: np.ndarray
    recovery: np.ndarray
    two_mesh: np.ndarray
    reliable: np.ndarray
    coarse_dofs: int
    method: str
    geometry: float = 0.0   # the mesh's relative volume difference from the solid
    notes: tuple[str, ...] = ()
    # each mode's allowance for the straightened elements' faces (None: none straightened)
    straightening: np.ndarray | None = None
    seconds: float = 0.0    # wall time the bound took after the run's own solve (0: not timed)

    @property
    def upward(self) -> np.ndarray:
        """Per mode, how far (fraction) the true frequency may lie above the computed one:
        only the geometry allowances, which move it either way. The discretisation error
        is one-sided (the computed frequencies converge from above), so the bound
        `relative_error` holds downwards alone."""
        up = np.full(self.relative_error.shape, self.geometry)
        return up if self.straightening is None else up + self.straightening

    def interval(self, frequencies: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(low, high), Hz: where each true frequency lies, f (1 - bound) to
        f (1 + upward)."""
        f = np.asarray(frequencies, float)
        return f * (1 - self.relative_error), f * (1 + self.upward)


# --------------------------------------------------------------------------
# Recovery


def _operators(skmesh, order: int):
    """Values and gradients of the scalar basis at the quadrature points as sparse
    matrices (n_elements * n_points, n_nodes), and the quadrature weights."""
    from skfem import Basis

    from shaftfem.fem.assembly import POSITIVE_INTORDER, _element

    basis = Basis(skmesh, _element(order), intorder=POSITIVE_INTORDER[order])
    ne, nq = basis.dx.shape
    rows = np.arange(ne * nq).reshape(ne, nq)
    shape = (ne * nq, basis.N)

    def matrix(vals) -> sp.csr_matrix:
        r = np.concatenate([rows.ravel()] * len(vals))
        c = np.concatenate([np.repeat(basis.element_dofs[j], nq) for j in range(len(vals))])
        return sp.csr_matrix((np.concatenate([v.ravel() for v in vals]), (r, c)), shape=shape)

    phis = [basis.basis[j][0] for j in range(basis.Nbfun)]
    value = matrix([np.asarray(p) for p in phis])
    grads = [matrix([p.grad[d] for p in phis]) for d in range(3)]
    return value, grads, basis.dx


def recovery_estimate(mesh: ShaftMesh, material: Material, modes: Modes,
                      chunk: int = 4) -> Recovery:
    """Zienkiewicz-Zhu estimate of each mode's relative frequency error, per element."""
    from shaftfem.fem.factor import factorise

    lam, mu = material.lame
    value, grads, dx = _operators(mesh.to_skfem(), mesh.order)
    ne, nq = dx.shape
    w = dx.ravel()
    solve, _ = factorise((value.T @ sp.diags(w) @ value).tocsc(), "auto")
    X = modes.shapes
    n = X.shape[1]
    omega2 = (2 * np.pi * modes.frequencies) ** 2
    elements = np.empty((n, ne))
    pairs = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))
    for start in range(0, n, chunk):
        cols = slice(start, min(n, start + chunk))
        u = [X[c::3, cols] for c in range(3)]
        g = [[grads[d] @ u[c] for d in range(3)] for c in range(3)]   # du_c / dx_d
        div = g[0][0] + g[1][1] + g[2][2]
        sigma = [mu * (g[a][b] + g[b][a]) + (lam * div if a == b else 0.0)  # C : eps(u)
                 for a, b in pairs]
        rhs = np.hstack([value.T @ (w[:, None] * s) for s in sigma])
        smooth = value @ np.asarray(solve(rhs)).reshape(rhs.shape)
        m = sigma[0].shape[1]
        d = [smooth[:, k * m:(k + 1) * m] - sigma[k] for k in range(6)]
        # complementary energy density of the stress error, C^-1 for isotropy
        dd = d[0]**2 + d[1]**2 + d[2]**2 + 2 * (d[3]**2 + d[4]**2 + d[5]**2)
        tr = d[0] + d[1] + d[2]
        energy = (dd - lam / (3 * lam + 2 * mu) * tr**2) / (2 * mu)
        per_element = (w[:, None] * energy).reshape(ne, nq, m).sum(axis=1).T
        elements[cols] = per_element / (2 * omega2[cols, None])
    return Recovery(relative=elements.sum(axis=1), elements=elements, volume=float(w.sum()))


def mesh_volume(mesh: ShaftMesh) -> float:
    """The mesh's volume, m^3, by the quadrature recovery_estimate integrates with (the
    same value, without its projection)."""
    from skfem import Basis, ElementTetP0

    from shaftfem.fem.assembly import POSITIVE_INTORDER

    return float(Basis(mesh.to_skfem(), ElementTetP0(),
                       intorder=POSITIVE_INTORDER[mesh.order]).dx.ravel().sum())


# --------------------------------------------------------------------------
# Straightened elements


@dataclass(frozen=True)
class Straightening:
    """What straightening folded elements did to the mesh's boundary, per mode.

    relative: (n,) bound on each frequency's shift (fraction); shift: (n,) the shift
    itself to first order, f(CAD faces) / f - 1; layer: the volume between the
    straightened faces and the faces they had on the CAD surfaces, m^3 (positive: the
    straightening removed material)."""

    relative: np.ndarray
    shift: np.ndarray
    layer: float


# the reference tetrahedron's vertices and its faces (scikit-fem's order)
_VERTICES = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
_FACES = ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3))


def straightening(mesh: ShaftMesh, material: Material, modes: Modes) -> Straightening:
    """Each frequency's shift from the straightened elements' faces back to the CAD, by
    the shape derivative of a free boundary (Hadamard):

        d lambda = int (sigma(u) : eps(u) - lambda rho u.u) V_n dA,

    V_n the normal distance from a straightened face out to where it was curved (on the
    CAD surface), u the mass-normalised mode. The bound sums |...| over the faces (no
    cancellation between them), halved for the frequency, times SAFETY for what the
    first order leaves out: SAFETY sum |.| / (2 lambda). (Straightening a third of the
    cylinder's P2 faces, sagitta 0.5 mm, moved its frequencies 0.32-1.47 %; the first
    order was within 4 % of that: tests/test_error_estimate.py.)"""
    from skfem import Basis
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTri

    from shaftfem.fem.assembly import _element

    n = modes.frequencies.size
    if mesh.unfolded is None:
        return Straightening(relative=np.zeros(n), shift=np.zeros(n), layer=0.0)
    final, cells = mesh.to_skfem(), mesh.element_cells
    moved = np.flatnonzero(np.any(mesh.unfolded != mesh.points, axis=1))
    touched = np.any(np.isin(cells, moved), axis=1)
    back = mesh.unfolded - mesh.points     # each node's way back to the CAD
    geometry = final.elem()                # the map's basis: local node k is cells' column k
    faces = final.boundary_facets()
    faces = faces[touched[final.f2t[0, faces]]]
    owners = final.f2t[0, faces]
    local = np.argmax(final.t2f[:, owners] == faces, axis=0)
    qx, qw = get_quadrature(RefTri, min(2 * mesh.order + 2, 12))
    lam, mu = material.lame
    omega2 = (2 * np.pi * modes.frequencies) ** 2
    total, signed = np.zeros(n), np.zeros(n)
    layer = 0.0
    for j, (a, b, c) in enumerate(_FACES):
        elements = owners[local == j]
        if elements.size == 0:
            continue
        va, vb, vc = _VERTICES[[a, b, c]]
        X = va[:, None] + np.outer(vb - va, qx[0]) + np.outer(vc - va, qx[1])
        on = Basis(final, _element(mesh.order), quadrature=(X, qw), elements=elements)
        J = on.mapping.DF(X, tind=elements)
        normal = np.cross(np.einsum("ijeq,j->ieq", J, vb - va),
                          np.einsum("ijeq,j->ieq", J, vc - va), axis=0)
        opposite = _VERTICES[6 - a - b - c] - va          # into the element
        inward = np.einsum("ieq,ieq->eq", normal, np.einsum("ijeq,j->ieq", J, opposite))
        normal *= -np.sign(inward)                         # outward, times the area ratio
        phi_map = np.array([geometry.lbasis(X, k)[0] for k in range(cells.shape[1])])
        shift = np.einsum("kq,ekd->deq", phi_map, back[cells[elements]])
        vn_da = np.einsum("ieq,ieq->eq", shift, normal) * qw
        layer += float(vn_da.sum())
        phi = np.array([on.basis[j][0].value for j in range(on.Nbfun)])   # (nb, e, q)
        dphi = np.array([on.basis[j][0].grad for j in range(on.Nbfun)])  # (nb, 3, e, q)
        # every mode at once: coef (nb, e, 3, n)
        coef = modes.shapes.reshape(-1, 3, n)[on.element_dofs]
        u = np.einsum("jein,jeq->ieqn", coef, phi, optimize=True)
        grad = np.einsum("jein,jdeq->ideqn", coef, dphi, optimize=True)  # du_i / dx_d
        eps = 0.5 * (grad + grad.transpose(1, 0, 2, 3, 4))
        div = eps[0, 0] + eps[1, 1] + eps[2, 2]
        energy = lam * div**2 + 2 * mu * np.einsum("ijeqn,ijeqn->eqn", eps, eps)
        density = energy - omega2 * material.density * np.einsum("ieqn,ieqn->eqn", u, u)
        total += np.abs(density * vn_da[..., None]).sum(axis=(0, 1))
        signed += (density * vn_da[..., None]).sum(axis=(0, 1))
    return Straightening(relative=SAFETY * total / (2 * omega2), shift=signed / (2 * omega2),
                         layer=layer)


# --------------------------------------------------------------------------
# Combining two meshes


def clusters(frequencies: np.ndarray, gap: float = CLUSTER) -> list[list[int]]:
    """Groups of modes whose frequencies lie within `gap` (relative) of each other."""
    out: list[list[int]] = []
    for i, f in enumerate(frequencies):
        if out and f - frequencies[out[-1][-1]] <= gap * f:
            out[-1].append(i)
        else:
            out.append([i])
    return out


def combine(fine_f: np.ndarray, fine_eta: np.ndarray, coarse_f: np.ndarray,
            coarse_eta: np.ndarray, coarse_dofs: int, method: str,
            geometry: float = 0.0, shortfall: float = RECOVERY_SHORTFALL,
            shifts: tuple[np.ndarray, np.ndarray] | None = None) -> ErrorEstimate:
    """The bound of each fine-mesh frequency from both meshes' frequencies and recovery
    estimates (coarse values matched to the fine modes; nan where a mode has none), and
    the fine mesh's relative volume difference from the solid, `geometry`; no bound below
    SAFETY `shortfall` times the recovery estimate.

    `shifts`: each mesh's frequency shift back from its straightened faces to the CAD's
    (Straightening.shift; fine, coarse matched), taken out of the drop between them so
    that it measures the discretisation alone: on a cone with a 16 mm bore at 12 mm, the
    coarser mesh's 37 straightened elements lowered its frequencies by up to 0.22 % and
    turned the drops of six modes negative."""
    fine_f, fine_eta = np.asarray(fine_f, float), np.asarray(fine_eta, float)
    coarse_f, coarse_eta = np.asarray(coarse_f, float), np.asarray(coarse_eta, float)
    if shifts is None:
        drop = coarse_f / fine_f - 1
    else:
        drop = coarse_f * (1 + shifts[1]) / (fine_f * (1 + shifts[0])) - 1
    rho = fine_eta / coarse_eta
    ok = np.isfinite(drop) & (drop > 0) & np.isfinite(rho) & (rho > 0) & (rho < RHO_MAX)
    two = np.where(ok, drop * rho / np.where(ok, 1 - rho, 1.0), np.nan)
    floor = shortfall * fine_eta
    raw = np.where(ok, np.fmax(two, floor), floor)
    bound = SAFETY * raw + abs(geometry)
    reliable = ok.copy()
    for group in clusters(fine_f):
        bound[group] = bound[group].max()
        reliable[group] = reliable[group].all()
    notes = []
    bad = [i + 1 for i in range(len(fine_f)) if not ok[i]]
    if bad:
        notes.append(
            f"mode(s) {', '.join(map(str, bad))}: the coarser mesh does not confirm the "
            "recovery estimate (its frequency is not higher, or its estimate not larger), so "
            "the bound rests on the recovery estimate alone, which falls short where the "
            "mesh does not resolve the stress; refine to confirm it")
    return ErrorEstimate(relative_error=bound, recovery=fine_eta, two_mesh=two,
                         reliable=reliable, coarse_dofs=coarse_dofs, method=method,
                         geometry=abs(geometry), notes=tuple(notes))


def with_straightening(est: ErrorEstimate, frequencies: np.ndarray,
                       straightened: np.ndarray) -> ErrorEstimate:
    """`est` with each mode's straightening allowance (`straightening(...).relative`)
    added to its bound; modes of one cluster share the largest."""
    if not np.any(straightened):
        return est
    bound = est.relative_error + straightened
    for group in clusters(np.asarray(frequencies, float)):
        bound[group] = bound[group].max()
    return replace(est, relative_error=bound, straightening=np.asarray(straightened, float))


def measured_rate(dofs: tuple[float, float, float], ratio: float) -> float:
    """The exponent b of e = C N^-b that makes (e_1 - e_2) / (e_0 - e_1) = `ratio` for three
    nested spaces of `dofs` N_0 < N_1 < N_2 (nan when no positive b does)."""
    n0, n1, n2 = dofs

    def r(b: float) -> float:
        return (n1**-b - n2**-b) / (n0**-b - n1**-b)

    lo, hi = 1e-3, 20.0
    if not np.isfinite(ratio) or not r(hi) < ratio < r(lo):
        return float("nan")
    for _ in range(100):       # r falls as b rises
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if r(mid) > ratio else (lo, mid)
    return 0.5 * (lo + hi)


def hierarchy_estimate(f: tuple[np.ndarray, np.ndarray, np.ndarray],
                       dofs: tuple[int, int, int], recovery: np.ndarray,
                       geometry: float = 0.0) -> ErrorEstimate:
    """The bound of the highest of three nested orders' frequencies f = (f_(p-2), f_(p-1),
    f_p) on one mesh (lower orders matched to order p's modes; nan where none is).

    The drops D_(p-2) = f_(p-2) - f_(p-1) and D_(p-1) = f_(p-1) - f_p are never negative
    and are lower bounds of the lower orders' errors. Their ratio measures the rate b
    of e = C N^-b in this run, per mode; then e_p = D_(p-1) / ((N_p / N_(p-1))^b - 1).
    The bound is HIERARCHY_SAFETY times that, plus the geometry allowance. A mode whose drops do
    not fall (no rate measured) keeps the recovery estimate, and is said to."""
    lo2, lo1, top = (np.asarray(x, float) for x in f)
    d2, d1 = (lo2 - lo1) / top, (lo1 - top) / top
    est = np.full(top.size, np.nan)
    for i in range(top.size):
        if d2[i] > 0 and d1[i] > 0:
            b = measured_rate((float(dofs[0]), float(dofs[1]), float(dofs[2])), d1[i] / d2[i])
            if np.isfinite(b):
                est[i] = d1[i] / ((dofs[2] / dofs[1]) ** b - 1)
    return _rate_bound(top, est, recovery, geometry, int(dofs[1]),
                       "three nested orders on one mesh, their measured rate",
                       "the lower orders' frequencies do not fall towards this one at a "
                       "measurable rate")


def contraction_estimate(f: Sequence[np.ndarray], dofs: Sequence[int], recovery: np.ndarray,
                         geometry: float = 0.0) -> ErrorEstimate:
    """The bound of the last of three or more successive rounds of an adaptive run on
    nested spaces, f = (f_1, ..., f_n) (earlier rounds matched to the last's modes), of
    `dofs` DOFs.

    Each three successive rounds' drops D_(j-1) and D_j measure how the rounds converge,
    per mode, read two ways: each round removing the same fraction q = D_j / D_(j-1) of
    what is left (as Doerfler marking does), and e = C N^-b over the rounds' DOFs. The
    last drop D_(n-1) then leaves D_(n-1) q / (1 - q), or D_(n-1) / ((N_n / N_(n-1))^b
    - 1). Each reading takes the slowest convergence the run has measured (the largest
    q, the smallest b, over every three rounds whose drops contract): a marking that
    takes the cheapest functions first makes the last rounds look faster than what is
    left converges (measured on the sharp-corner shaft: a rate of 3.6 over the last
    three rounds, 2.0 over the first). The first reading follows the rounds to the full
    space's frequencies, the second to the truth; the larger is kept. The bound is
    HIERARCHY_SAFETY times that plus the geometry allowance; a mode whose last drops do
    not contract keeps the recovery estimate, and is said to."""
    f = [np.asarray(x, float) for x in f]
    if len(f) < 3 or len(f) != len(dofs):
        raise ValueError("the contraction of a run takes three rounds or more, with their DOFs")
    top = f[-1]
    drops = [(a - b) / top for a, b in zip(f, f[1:])]
    est = np.full(top.size, np.nan)
    for i in range(top.size):
        d2, d1 = drops[-2][i], drops[-1][i]
        if not (d2 > 0 and 0 < d1 < d2):
            continue
        qs, rates = [], []
        for j in range(1, len(drops)):
            a, b = drops[j - 1][i], drops[j][i]
            if a > 0 and 0 < b < a:
                qs.append(b / a)
                rates.append(measured_rate((float(dofs[j - 1]), float(dofs[j]),
                                            float(dofs[j + 1])), b / a))
        q = max(qs)
        measured = [r for r in rates if np.isfinite(r)]
        per_dof = d1 / ((dofs[-1] / dofs[-2]) ** min(measured) - 1) if measured else 0.0
        est[i] = max(d1 * q / (1 - q), per_dof)
    return _rate_bound(top, est, recovery, geometry, int(dofs[-2]),
                       "successive rounds on nested spaces, their slowest convergence",
                       "the earlier rounds' frequencies do not fall towards this one by a "
                       "contracting series")


def carried_estimate(before: ErrorEstimate, f_before: np.ndarray, f: np.ndarray,
                     recovery: np.ndarray, dofs: int) -> ErrorEstimate:
    """The bound of a space that contains one already bounded (`before`, its frequencies
    f_before matched to this one's modes f): its error is the earlier error less the drop
    between them, so (B f_before - (f_before - f)) / f bounds it wherever B did. An
    adaptive run's rounds take it where it is tighter than their own rates' bound, and
    alone where the budget cut a round's step short (its drops measure no rate).

    A drop larger than B f_before proves that B did not hold: that mode's bound is
    then SAFETY times its recovery estimate, marked unreliable, and a note says so."""
    prev, f_before, top = (np.asarray(x, float) for x in (before.relative_error, f_before, f))
    bound = (prev * f_before - (f_before - top)) / top
    broken = np.isfinite(bound) & ~(bound > 0)
    ok = np.isfinite(bound) & ~broken
    bound = np.where(ok, bound, SAFETY * np.asarray(recovery, float) + before.geometry)
    reliable = ok & before.reliable
    for group in clusters(top):
        bound[group] = bound[group].max()
        reliable[group] = reliable[group].all()
    notes = before.notes
    if broken.any():
        modes = ", ".join(str(i + 1) for i in np.flatnonzero(broken))
        notes += (f"mode(s) {modes}: the drop to this round exceeds the round before's "
                  "bound, which so did not hold; the bound here rests on the recovery "
                  "estimate alone",)
    return ErrorEstimate(relative_error=bound, recovery=np.asarray(recovery, float),
                         two_mesh=np.full(top.size, np.nan), reliable=reliable,
                         coarse_dofs=dofs, method="the round before's bound, less the drop "
                         "to this round", geometry=before.geometry, notes=notes)


def _rate_bound(top: np.ndarray, est: np.ndarray, recovery: np.ndarray, geometry: float,
                dofs: int, method: str, why: str) -> ErrorEstimate:
    """HIERARCHY_SAFETY times a rate-based estimate (SAFETY times the recovery estimate
    where it is nan) plus the geometry allowance, one bound per cluster of modes."""
    ok = np.isfinite(est)
    bound = np.where(ok, HIERARCHY_SAFETY * est, SAFETY * recovery) + abs(geometry)
    reliable = ok.copy()
    for group in clusters(top):
        bound[group] = bound[group].max()
        reliable[group] = reliable[group].all()
    bad = [i + 1 for i in range(top.size) if not ok[i]]
    notes = (f"mode(s) {', '.join(map(str, bad))}: {why}, so the bound rests on the "
             "recovery estimate alone; refine the mesh to confirm it",) if bad else ()
    return ErrorEstimate(relative_error=bound, recovery=np.asarray(recovery, float), two_mesh=est,
                         reliable=reliable, coarse_dofs=dofs, method=method,
                         geometry=abs(geometry), notes=notes)


def geometry_allowances(mesh: ShaftMesh, shape: ShaftShape, shaft: Shaft, material: Material,
                        modes: Modes, mesh_volume: float) -> tuple[float, Straightening]:
    """The mesh's allowances for the solid's shape: the relative volume difference from
    the solid of its faces as curved onto the CAD (before any straightening; the mesh
    itself holds `mesh_volume`, m^3), and each mode's shift from the straightened faces
    (straightening)."""
    s = straightening(mesh, material, modes)
    return volume_difference(mesh_volume + s.layer, shape, shaft), s


def volume_difference(mesh_volume: float, shape: ShaftShape, shaft: Shaft) -> float:
    """(V_mesh - V) / V against the solid's reference volume (ShaftShape)."""
    return mesh_volume / shape.reference_volume - 1


def matched(ref_kinds: list[str], kinds: list[str], values: np.ndarray) -> np.ndarray:
    """`values` (of modes `kinds`) reordered to correspond to the reference modes, in
    order within each kind, so that a torsion mode overtaking a bending pair on a
    coarse mesh is still compared with its own kind; nan where a mode has no match."""
    out = np.full(len(ref_kinds), np.nan)
    for kind in set(ref_kinds):
        mine = [i for i, k in enumerate(ref_kinds) if k == kind]
        theirs = [i for i, k in enumerate(kinds) if k == kind]
        for a, b in zip(mine, theirs):
            out[a] = values[b]
    return out
