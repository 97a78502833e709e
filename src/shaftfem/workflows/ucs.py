"""The undamped critical speed map (API 684): the shaft's undamped critical speeds
against the stiffness of its bearings, all alike, isotropic and undamped, over decades
of stiffness (as ross's `run_ucs` and MESYS's critical speeds against bearing
stiffness). With the scene's own bearings' stiffness against speed drawn on it, their
crossings with the branches are the critical speeds the bearings give.

A critical speed is where the whirl meets the shaft's own speed, so the map is
synchronous by default: at each stiffness, the speeds Omega at which a forward (or,
asked, backward) whirl at omega = Omega is free, gyroscopic moments included,

    (K(k) - Omega^2 (M -+ i G)) a = 0,

a linear eigenproblem in Omega^2 (fem.tracking.order_roots). Its bearing crossings are
then the Campbell diagram's undamped 1x critical speeds (of the rotor crossing_scene
builds). A shaft that is not a solid of revolution is solved in the frame turning with
it, where its isotropic bearings are constant and a synchronous forward whirl stands
still: a root at zero frequency there, one per principal plane. The standstill map
(ross's `run_ucs` default: natural frequencies at rest) is kept as kind "standstill".

One standstill solve with the bearings at the range's geometric mean, the bearings'
residual modes beside the modes (fem.rotor): a bearing's stiffness k then enters
exactly as diag(w^2) + sum_b beta_b^T (k - k_ref) beta_b on the basis, every stiffness
one small eigenproblem, and the map is checked on two thirds of the basis. It is the
one study with a basis of its own: its bearings range over four decades about their
mean, the rotor's basis holds the rotor's own bearings; it is solved on the rotor's
mesh (uniform_bearings keeps its cuts). Seals are left out (they hold nothing at
standstill), as in ross.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.whirl import BearingCurve, UcsMap
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import BearingCoefficients, Scene

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult
    from shaftfem.fem.rotor import RotorModel

# Branches drawn (each a pair of lateral modes on a shaft of revolution), and the
# stiffnesses of the default range: four decades about the scene's bearings, 40 of them.
BRANCHES = 4
POINTS = 40
DECADES = 4.0
# the map may move by this much (relative) on two thirds of the basis; above, the
# basis is doubled
TRUNCATION = 1e-3
BASIS_MIN = 24
# a branch of a shaft not of revolution goes on in the root at the next stiffness whose
# shape is at least this like its own (MAC)
FOLLOW = 0.5


def default_range(scene: Scene) -> np.ndarray:
    """POINTS stiffnesses (N/m) over DECADES about the geometric mean of the scene's
    bearings' direct stiffness (at the highest operating speed where it changes), or
    about 10^7 N/m where none has one."""
    ks = []
    top = scene.rotor.top_speed if scene.rotor is not None else 0.0
    for s in scene.supports:
        if s.kind == "seal":
            continue
        if s.bearing is not None:
            (kxx, _), (_, kyy) = s.bearing.stiffness(top)
            ks += [kxx, kyy]
        elif s.kind in ("springs",) and s.radial > 0:
            ks.append(s.radial)
    ks = [k for k in ks if k > 0]
    centre = math.exp(sum(math.log(k) for k in ks) / len(ks)) if ks else 1e7
    return np.logspace(math.log10(centre) - DECADES / 2, math.log10(centre) + DECADES / 2,
                       POINTS)


def uniform_bearings(scene: Scene, k: float) -> Scene:
    """The scene with every support but its seals an isotropic undamped bearing of radial
    stiffness k (N/m) on its seat's mean motion, free to tilt; its axial hold kept; on
    the scene's mesh."""
    if not scene.held:
        raise SceneError(f"{scene.source}: no [[support]]: the critical speed map varies the "
                         "bearings' stiffness; give the bearings' seats")
    const = BearingCoefficients(speeds=(), kxx=(k,), kxy=(0.0,), kyx=(0.0,), kyy=(k,),
                                cxx=(0.0,), cxy=(0.0,), cyx=(0.0,), cyy=(0.0,))
    supports = tuple(
        replace(s, kind="bearing", bearing=const, journal=None, coupling="distributing",
                radial=0.0, tilting=0.0,
                axial=s.axial if s.kind not in ("rigid", "clamped") else 1e3 * k)
        for s in scene.supports if s.kind != "seal")
    # on the scene's own mesh: its seals' seats, unbalances and probes cut it still
    return replace(scene, supports=supports, rotor=None, unbalances=(),
                   mesh_cuts=scene.seat_cuts())


def crossing_scene(scene: Scene, curve: BearingCurve, direction: str = "x") -> Scene:
    """The rotor a bearing curve's crossings stand for: every bearing on that curve's
    stiffness against speed (its kxx, or with `direction` "y" its kyy), isotropic and
    undamped, seated as the map seats them; seals left out. Its Campbell diagram's 1x
    critical speeds are the curve's crossings on the map."""
    k = curve.kxx if direction == "x" else curve.kyy
    rpm = np.asarray(curve.speeds_rpm, dtype=float)
    if np.all(k == k[0]):
        k, rpm = k[:1], np.empty(0)
    zeros = (0.0,) * len(k)
    table = BearingCoefficients(speeds=tuple(rpm * math.pi / 30), kxx=tuple(map(float, k)),
                                kxy=zeros, kyx=zeros, kyy=tuple(map(float, k)), cxx=zeros,
                                cxy=zeros, cyx=zeros, cyy=zeros)
    alike = uniform_bearings(scene, float(k[0]))
    return replace(alike, supports=tuple(replace(s, bearing=table) for s in alike.supports),
                   rotor=scene.rotor)


# The maps: synchronous forward (the default), synchronous backward, standstill.
KINDS = ("forward", "backward", "standstill")


def at_stiffness(model: RotorModel, k: float) -> RotorModel:
    """The model with every bearing isotropic, undamped, of radial stiffness k (N/m)."""
    const = BearingCoefficients(speeds=(), kxx=(k,), kxy=(0.0,), kyx=(0.0,), kyy=(k,),
                                cxx=(0.0,), cxy=(0.0,), cyx=(0.0,), cyy=(0.0,))
    return replace(model, bearings=tuple(replace(b, coefficients=const)
                                         for b in model.bearings))


def lateral_frequencies(model: RotorModel, k: float, count: int
                        ) -> tuple[np.ndarray, np.ndarray]:
    """The lowest `count` lateral branches (Hz) at the bearing stiffness k (N/m): one of
    each pair of lateral modes at standstill, and their modal coordinates (N, count)."""
    from shaftfem.fem.rotor import dominant_kinds

    K = at_stiffness(model, k).matrices(0.0)[1]
    lam, V = np.linalg.eigh(0.5 * (K + K.T))
    kinds = dominant_kinds(model, V)
    keep = [i for i, kind in enumerate(kinds) if kind not in ("torsion", "axial")][::2][:count]
    return np.sqrt(np.maximum(lam[keep], 0.0)) / (2 * math.pi), V[:, keep]


def synchronous_speeds(model: RotorModel, k: float, count: int, whirl: str = "forward",
                       every: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """The lowest `count` synchronous critical speeds of `whirl` (as Hz: Omega / 2 pi) at
    the bearing stiffness k (N/m), and their modal shapes (N, count); NaN where fewer
    exist (a backward branch of a disk whose polar inertia outweighs its diametral one
    has no synchronous crossing). In the turning frame (a shaft that is not a solid of
    revolution) a forward synchronous whirl stands still: the roots at zero frequency,
    one per principal plane (a keyed shaft has two criticals where a round one has a
    pair); a backward one turns at twice the spin there. `every`: the roots that are
    most of a torsion or axial mode kept too (fem.tracking.order_roots)."""
    from shaftfem.fem.tracking import SHARE_MIN, one_of_each_pair, order_roots
    from shaftfem.fem.whirl import FORWARD

    stiff = at_stiffness(model, k)
    if model.frame == "stationary":
        speeds, index, A = order_roots(stiff, 1)
        keep = np.flatnonzero(index > FORWARD if whirl == "forward" else index < -FORWARD)
    elif whirl == "forward":
        speeds, index, A = order_roots(stiff, 0, every=every)
        keep = one_of_each_pair(speeds)
    else:
        speeds, index, A = order_roots(stiff, 2, every=every)
        keep = np.flatnonzero(0.5 * (1 - index) >= SHARE_MIN)
    keep = keep[:count]
    out = np.full(count, np.nan)
    out[:keep.size] = speeds[keep] / (2 * math.pi)
    Y = np.zeros((A.shape[0], count), dtype=complex)
    Y[:, :keep.size] = A[:, keep]
    return out, Y


def branches_at(model: RotorModel, k: float, count: int, kind: str
                ) -> tuple[np.ndarray, np.ndarray]:
    """The map's `count` branches (Hz) at stiffness k and their shapes, of its kind."""
    if kind == "standstill":
        return lateral_frequencies(model, k, count)
    return synchronous_speeds(model, k, count, kind)


def _mac(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The modal assurance criterion between the columns of a (N, p) and b (N, q)."""
    num = np.abs(a.conj().T @ b) ** 2
    den = np.outer(np.sum(np.abs(a) ** 2, axis=0), np.sum(np.abs(b) ** 2, axis=0))
    return num / np.where(den > 0, den, 1.0)


def _matched(shapes: np.ndarray, candidates: np.ndarray) -> np.ndarray:
    """For each branch (its last shape, a column of `shapes`), the candidate root most
    like it (MAC at least FOLLOW), each root to one branch, the likest pairs first;
    -1 where none is."""
    mac = _mac(shapes, candidates)
    mac[~np.isfinite(mac)] = 0.0
    out = np.full(shapes.shape[1], -1)
    while mac.size and mac.max() >= FOLLOW:
        i, j = np.unravel_index(int(np.argmax(mac)), mac.shape)
        out[i] = j
        mac[i, :], mac[:, j] = 0.0, 0.0
    return out


def _candidates(model: RotorModel, k: float, count: int, kind: str
                ) -> tuple[np.ndarray, np.ndarray]:
    """The roots at stiffness k (N/m) a followed branch may go on in: the lowest 4 count
    of `kind`, torsion and axial ones too, and their shapes."""
    c, C = synchronous_speeds(model, k, 4 * count, kind, every=True)
    live = np.isfinite(c)
    return c[live], C[:, live]


def followed(model: RotorModel, ks: np.ndarray, count: int, kind: str
             ) -> tuple[np.ndarray, np.ndarray]:
    """The map's branches (Hz, (count, len(ks))) and their shapes at each stiffness
    ((len(ks), N, count)). In the turning frame a branch is followed by its shape from
    stiffness to stiffness (a keyed shaft's mode in one principal plane takes on torsion
    as its bearings stiffen, and the lowest roots of the next kind would take its place
    in a list by speed); where no root is like it any more it ends (NaN). A shaft of
    revolution's map, and the standstill map, list by speed (their pairs are double)."""
    first, Y = branches_at(model, float(ks[0]), count, kind)
    freqs, shapes = [first], [Y]
    follow = model.frame == "rotating" and kind != "standstill"
    for k in ks[1:]:
        if not follow:
            f, Y = branches_at(model, float(k), count, kind)
        else:
            c, C = _candidates(model, float(k), count, kind)
            pick = _matched(shapes[-1], C)
            found = pick >= 0
            f = np.full(count, np.nan)
            f[found] = c[pick[found]]
            Y = shapes[-1].copy()     # an ended branch keeps its last shape
            Y[:, found] = C[:, pick[found]]
        freqs.append(f)
        shapes.append(Y)
    return np.column_stack(freqs), np.array(shapes)


def run_ucs(scene: Scene, stiffness: np.ndarray | None = None,
            options: RunOptions = RunOptions(), branches: int | None = None,
            kind: str = "forward") -> UcsMap:
    """The scene's undamped critical speed map over `stiffness` (N/m; default
    default_range): synchronous forward (`kind` "forward", the default) or backward
    critical speeds, or the standstill natural frequencies ("standstill"); `branches`
    of them (default BRANCHES, twice that for a shaft that is not a solid of revolution,
    whose bending modes each split into two, one in each principal plane)."""
    if kind not in KINDS:
        raise SceneError(f"critical speed map of kind {kind!r}: one of {', '.join(KINDS)}")
    from shaftfem.fem.rotor import rotor_model
    from shaftfem.fem.static import line
    from shaftfem.workflows.pipeline import run_modes, with_modes
    from shaftfem.workflows.static import equipped

    if scene.mesh.order > 2:
        raise SceneError(f"{scene.source}: element order {scene.mesh.order}: the critical "
                         "speed map takes orders 1 and 2")
    if scene.rotor is not None:
        scene = equipped(scene, options)
    ks = default_range(scene) if stiffness is None else np.asarray(stiffness, dtype=float)
    if branches is None:
        branches = BRANCHES if scene.axisymmetric else 2 * BRANCHES
    reference = float(math.exp(np.log(ks).mean()))
    uniform = uniform_bearings(scene, reference)
    size = max(BASIS_MIN, 3 * (2 * branches + 2))
    while True:
        options.say(f"critical speed map: {size} standstill modes with the bearings at "
                    f"{reference / 1e3:.3g} N/mm")
        result = run_modes(with_modes(uniform, count=size), options)
        model = rotor_model(result, "stationary" if scene.axisymmetric else "rotating")
        freqs, shapes = followed(model, ks, branches, kind)
        smaller = model.truncated(2 * size // 3)
        check = followed(smaller, ks, branches, kind)[0]
        n = min(freqs.shape[0], check.shape[0])
        both = np.isfinite(freqs[:n]) & np.isfinite(check[:n])
        change = float(np.max(np.abs(check[:n][both] / freqs[:n][both] - 1))) if both.any() else 0.0
        if change <= TRUNCATION or size >= 96:
            break
        size *= 2
    z, soft, stiff = _end_lines(result, model, shapes, line)

    def branch_rpm(k: float, i: int) -> float:   # branch i at stiffness k, solved again
        if model.frame != "rotating" or kind == "standstill":
            return 60.0 * float(branches_at(model, k, branches, kind)[0][i])
        near = int(np.argmin(np.abs(np.log(ks) - math.log(k))))
        c, C = _candidates(model, k, branches, kind)
        mac = _mac(shapes[near][:, i:i + 1], C)[0]
        return 60.0 * float(c[int(np.argmax(mac))]) if mac.size else math.nan

    return UcsMap(scene=scene, stiffness=ks, frequencies=freqs, z=z, soft_lines=soft,
                  stiff_lines=stiff, bearings=_bearing_curves(scene, ks, freqs, branch_rpm),
                  reference=reference, basis=model.size, change=change, kind=kind)


def _end_lines(result: ModalResult, model: RotorModel, shapes: np.ndarray, line
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each branch's deflected line at the softest and the stiffest bearings (the
    orbit's major semi-axis along the shaft for a synchronous branch), from the
    branches' shapes at each stiffness (len(ks), N, branches)."""
    assert model.shapes is not None
    out = []
    for Y in (shapes[0], shapes[-1]):
        rows = []
        for j in range(Y.shape[1]):
            u = model.shapes @ Y[:, j]
            z, xr, yr = line(result.system, u.real)
            _, xi, yi = line(result.system, u.imag)
            x, y = xr + 1j * xi, yr + 1j * yi
            amp = 0.5 * (np.abs(x + 1j * y) + np.abs(x - 1j * y))
            rows.append(amp / max(float(amp.max()), 1e-300))
        out.append(np.array(rows))
    return z, out[0], out[1]


def _bearing_curves(scene: Scene, ks: np.ndarray, freqs: np.ndarray, branch_rpm=None
                    ) -> tuple[BearingCurve, ...]:
    """The scene's bearings' kxx and kyy against speed (over their table, or the rotor's
    range for a constant one), and where each meets a branch: the speed n at which the
    branch's critical speed at the bearing's k(n) is n itself; found between the map's
    stiffnesses, then solved on the model itself (`branch_rpm(k, i)`, r/min) so that it
    is the critical speed those bearings give, not an interpolation."""
    curves = []
    top = scene.rotor.max_speed if scene.rotor is not None else 0.0
    for s in scene.supports:
        b = s.bearing
        if s.kind == "seal" or (b is None and s.kind != "springs"):
            continue
        omegas = (np.asarray(b.speeds) if b is not None and b.speeds
                  else np.linspace(0.0, max(top, 1.0), 2))
        if b is not None:
            kxx = np.array([b.stiffness(w)[0][0] for w in omegas])
            kyy = np.array([b.stiffness(w)[1][1] for w in omegas])
        else:
            kxx = kyy = np.full(omegas.size, s.radial)
        rpm = omegas * 30 / math.pi
        found = []
        pairs = (("x", kxx),) if np.array_equal(kxx, kyy) else (("x", kxx), ("y", kyy))
        for direction, kd in pairs:
            for i in range(freqs.shape[0]):
                rough = _crossings(i, direction, ks, 60.0 * freqs[i], kd, rpm)
                found += [_refined(x, kd, rpm, branch_rpm) for x in rough]
        curves.append(BearingCurve(s.name, rpm, kxx, kyy, tuple(found)))
    return tuple(curves)


def _refined(x: tuple[int, str, float, float], kd: np.ndarray, rpm: np.ndarray, branch_rpm
             ) -> tuple[int, str, float, float]:
    """A crossing (branch, direction, k, n) solved on the model: the n where the branch
    at the bearing's k(n) (interpolated in its speed table) is n."""
    import scipy.optimize

    i, d, k, n = x
    if branch_rpm is None:
        return x
    if len(rpm) == 2 and kd[0] == kd[1]:   # a constant bearing: the branch at its k
        return i, d, k, branch_rpm(k, i)

    def k_at(m: float) -> float:
        return float(np.interp(m, rpm, kd))

    def gap(m: float) -> float:
        return branch_rpm(k_at(m), i) - m

    j = int(np.clip(np.searchsorted(rpm, n) - 1, 0, len(rpm) - 2))
    lo, hi = float(rpm[j]), float(rpm[j + 1])
    try:
        m = float(scipy.optimize.brentq(gap, lo, hi, xtol=1e-9 * hi))
    except ValueError:   # no sign change on the model: keep the map's crossing
        return x
    return i, d, k_at(m), m


def _crossings(branch: int, direction: str, ks: np.ndarray, branch_rpm: np.ndarray,
               kd: np.ndarray, rpm: np.ndarray) -> list[tuple[int, str, float, float]]:
    """Where the bearing's curve (kd against rpm) meets the branch (branch_rpm against
    ks, interpolated in log k): sign changes of branch(k(n)) - n along the curve."""
    logk = np.log(ks)

    def gap(k: float, n: float) -> float:
        return float(np.interp(math.log(k), logk, branch_rpm)) - n

    if len(rpm) == 2 and kd[0] == kd[1]:   # a constant bearing: its vertical line
        k = float(kd[0])
        if not ks[0] <= k <= ks[-1]:
            return []
        return [(branch, direction, k, float(np.interp(math.log(k), logk, branch_rpm)))]
    out = []
    inside = (kd >= ks[0]) & (kd <= ks[-1])
    for j in range(len(rpm) - 1):
        if not (inside[j] and inside[j + 1]):
            continue
        g0, g1 = gap(kd[j], rpm[j]), gap(kd[j + 1], rpm[j + 1])
        if g0 == 0.0 or g0 * g1 < 0:
            t = g0 / (g0 - g1) if g0 != g1 else 0.0
            out.append((branch, direction, float(kd[j] + t * (kd[j + 1] - kd[j])),
                        float(rpm[j] + t * (rpm[j + 1] - rpm[j]))))
    return out
