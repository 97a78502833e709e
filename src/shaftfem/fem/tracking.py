"""Whirl curves as mode families, and their crossings with the excitation order lines.

Each root of the turning shaft (fem.rotor) is followed from speed to speed by its shape:
the correlation (MAC) of its modal coordinates with those at the speed before, the
pairs assigned as a whole (linear_sum_assignment), and the step halved where a
followed curve's correlation falls below MAC_MIN (two curves veer or cross). Neither
its rank nor its whirl label is used, so a curve keeps its identity through crossings
and may change its label along the way.

In the rotating frame a root at signed frequency f_s (Hz) with whirl index w moves as
two circular components seen from the housing: forward at f_s + n, carrying
(1 + w) / 2 of its motion, and backward at f_s - n, carrying (1 - w) / 2 (n the spin,
Hz). A root and its conjugate are one motion, (f_s, y, w) ~ (-f_s, conj y, -w): along
a curve the form continuous with the speed before is kept, so f_s passes through zero
at a rotating-frame critical speed instead of jumping. In the stationary frame each
root is one line at f_s > 0.

Crossings are found twice. On the curves: every sign change of |v| - k n along every
component v that carries at least SHARE_MIN of the motion, refined by root finding on
the model. And, for bearings whose coefficients are constant and undamped, directly:
a root at lambda = i m Omega of q'' + Omega G q' + (K_0 + Omega^2 K_2) q = 0 solves

    K_0 a = Omega^2 (m^2 I - i m G - K_2) a,

a linear eigenproblem in Omega^2 (m = k in the stationary frame; m = k - 1 for the
forward component and m = k + 1 for the backward one in the rotating frame; at k = 1
the root m = 0 stands still in the turning frame, a static critical speed).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from shaftfem.fem.floquet import any_roots, periodic_order_roots
from shaftfem.fem.rotor import RotorModel, whirl_index
from shaftfem.fem.whirl import FORWARD, RPM, WHIRLING, Curve, seen

# A step along the diagram is halved while a followed curve's shape correlation with
# the speed before is below this ...
MAC_MIN = 0.8
# ... at most this many times (a step of 1/256 of the grid's).
MAX_HALVINGS = 8
# Below this correlation a root is not the same mode: a curve ends, another starts.
MAC_NEW = 0.1
# A component carrying less of the motion than this is not judged as a crossing (the
# companion of a circular rotating-frame mode on a shaft of revolution carries 0).
SHARE_MIN = 0.05
# Two bending roots closer than this (relative) are a double pair (split by the mesh).
PAIR = 1e-3
# How far a curve's frequency may move per Hz of spin from its straight continuation.
REACH = 2.0
# A root followed into a stretch where it stops oscillating: at most this many halvings.
FOLLOW_STEPS = 40
# ... to this share of the speed (the edge of a stretch is where two roots meet: a
# square-root point, which no model places closer than this)
FOLLOW_TOL = 1e-8
# Crossings of one curve with one order closer than this (relative) are one.
SAME = 1e-6


@dataclass(frozen=True)
class Spectrum:
    """The roots at one spin: signed frequency (Hz), decay rate (1/s), whirl index,
    kind, unit modal coordinates (N, m), and the largest non-oscillating growth rate."""

    omega: float
    f: np.ndarray
    decay: np.ndarray
    index: np.ndarray
    kinds: tuple[str, ...]
    y: np.ndarray
    divergence: float
    # a periodic rotor's: each form's harmonics beside its dominant one, scaled as y
    # (fem.rotor.Roots.side_forms); None for a constant rotor
    side_forms: np.ndarray | None = None


def spectrum(model: RotorModel, omega: float) -> Spectrum:
    """The roots at the spin omega (rad/s). Two bending roots within PAIR of each other
    (a shaft of revolution's double pair, split only by its mesh) have any pair of
    shapes in their plane: they are taken as the two circular orbits there, forward and
    backward, so a pair double at standstill starts as two curves of known whirl."""
    from shaftfem.fem.rotor import dominant_kinds

    r = any_roots(model, omega)
    norm = np.linalg.norm(r.y, axis=0)
    y = r.y / norm
    sides = None if r.side_forms is None else r.side_forms / norm
    f, decay = r.lam.imag / (2 * math.pi), -r.lam.real
    kinds = dominant_kinds(model, y)
    for j in range(f.size - 1):
        if (abs(f[j + 1] - f[j]) <= PAIR * abs(f[j + 1]) and kinds[j] in WHIRLING
                and kinds[j + 1] in WHIRLING):
            c = circular(model, y[:, j:j + 2])
            y[:, j:j + 2] = y[:, j:j + 2] @ c
            if sides is not None:
                sides[:, :, j:j + 2] = sides[:, :, j:j + 2] @ c
    return Spectrum(omega, f, decay, whirl_index(model, y), tuple(kinds), y, r.divergence,
                    sides)


def circular(model: RotorModel, y: np.ndarray) -> np.ndarray:
    """The combination (2, 2) of the shapes y (N, 2) whose whirl indices are extreme:
    y @ it are the forward and the backward orbit of their plane (unit norm)."""
    import scipy.linalg

    T = y.conj().T @ model.turning @ y
    L = y.conj().T @ model.lateral @ y
    if np.linalg.eigvalsh(0.5 * (L + L.conj().T)).min() <= 1e-12 * max(np.abs(L).max(), 1e-300):
        return np.eye(2, dtype=complex)
    _, c = scipy.linalg.eigh(0.5 * (T + T.conj().T), 0.5 * (L + L.conj().T))
    c = c / np.linalg.norm(y @ c, axis=0)
    z = y @ c
    # each orbit to the root it is most of (a pair split by the gyroscopic moments is
    # circular already: its roots keep their own)
    fit = np.abs(y.conj().T @ z) ** 2
    return c[:, ::-1] if fit[0, 1] + fit[1, 0] > fit[0, 0] + fit[1, 1] else c


@dataclass(eq=False)
class _Track:
    """A curve being followed: its points, and its shape at the last (in the form kept)."""

    omega: list[float]
    f: list[float]
    decay: list[float]
    index: list[float]
    kinds: list[str]
    ys: list[np.ndarray]
    gaps: list[int] = field(default_factory=list)   # steps i -> i + 1 that span one
    # why it starts after the first speed or ends before the last (Curve.began, .ended)
    began: str = ""
    ended: str = ""

    def add(self, s: Spectrum, j: int, flip: bool) -> None:
        sign = -1.0 if flip else 1.0
        self.omega.append(s.omega)
        self.f.append(sign * float(s.f[j]))
        self.decay.append(float(s.decay[j]))
        self.index.append(sign * float(s.index[j]))
        self.kinds.append(s.kinds[j])
        self.ys.append(s.y[:, j].conj() if flip else s.y[:, j])


def match(y: np.ndarray, f: np.ndarray, s: Spectrum, frame: str, reach: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Which root of `s` continues each shape y[:, i], expected near the signed
    frequency f[i] (Hz) give or take reach[i]: the rows and columns assigned, whether
    the root is taken conjugate (rotating frame), and each pair's score, its shape
    correlation less up to a half for a frequency beyond reach (in the rotating frame a
    root's conjugate can have the shape of another root: only the frequency tells)."""
    from scipy.optimize import linear_sum_assignment

    def score(mac: np.ndarray, fj: np.ndarray) -> np.ndarray:
        off = np.abs(fj[None, :] - f[:, None]) / reach[:, None]
        return mac - 0.5 * np.minimum(1.0, off)

    direct = score(np.abs(y.conj().T @ s.y) ** 2, s.f)
    if frame == "rotating":
        conj = score(np.abs(y.T @ s.y) ** 2, -s.f)
        flip = conj > direct
        total = np.where(flip, conj, direct)
    else:
        flip, total = np.zeros_like(direct, dtype=bool), direct
    rows, cols = linear_sum_assignment(-total)
    return rows, cols, flip[rows, cols], total[rows, cols]


def predicted(live: list[_Track], omega: float) -> tuple[np.ndarray, np.ndarray]:
    """Each followed curve's signed frequency (Hz) at the spin omega, extrapolated from
    its last two points, and how far from it a root may lie: REACH times the spin's
    change in Hz (a whirl frequency moves at most a few times as fast as the spin) plus
    a thousandth of the frequency."""
    f = np.empty(len(live))
    reach = np.empty(len(live))
    for i, t in enumerate(live):
        step = abs(omega - t.omega[-1]) / (2 * math.pi)
        f[i] = t.f[-1]
        if len(t.f) > 1 and t.omega[-1] > t.omega[-2]:
            f[i] += (t.f[-1] - t.f[-2]) / (t.omega[-1] - t.omega[-2]) * (omega - t.omega[-1])
        reach[i] = REACH * step + 1e-3 * abs(t.f[-1]) + 1e-9
    return f, reach


# why a curve starts or ends mid-range: two real roots meet and whirl as a pair from
# there (or, ending, split into two real roots: the pair decays without whirling), or
# the root's shape changed beyond the match between two speeds, the step halved as far
# as it goes (MAX_HALVINGS): a new curve carries it on
PAIR_MET, PAIR_SPLIT, SHAPE_LOST = "pair", "split", "shape"


def track(model: RotorModel, grid: np.ndarray, watch: int) -> list[Curve]:
    """Every root followed over the speeds `grid` (rad/s, ascending from any speed),
    the step halved where one of the `watch` lowest curves (by the frequency seen)
    correlates less than MAC_MIN with its shape before; the curves numbered from 1 by
    their first speed, then by their frequency there."""
    frame = model.frame
    first = spectrum(model, float(grid[0]))
    live = [_Track([], [], [], [], [], []) for _ in range(first.f.size)]
    for j, t in enumerate(live):
        t.add(first, j, False)
    done: list[_Track] = []

    missing: list[_Track] = []

    def step(t0: float, t1: float, depth: int) -> None:
        nonlocal live, done, missing
        s = spectrum(model, t1)
        y = np.column_stack([t.ys[-1] for t in live]) if live else np.zeros((model.size, 0))
        f, reach = predicted(live, t1)
        rows, cols, flips, score = match(y, f, s, frame, reach)
        n0 = t0 / (2 * math.pi)
        heard = seen(f, np.array([t.index[-1] for t in live]), n0, frame)
        watched = set(np.argsort(heard)[:watch].tolist())
        worst = min((sc for r, sc in zip(rows, score) if r in watched), default=1.0)
        if worst < MAC_MIN and depth < MAX_HALVINGS:
            mid = 0.5 * (t0 + t1)
            step(t0, mid, depth + 1)
            step(mid, t1, depth + 1)
            return
        kept, taken = [], set()
        for r, c, fl, sc in zip(rows, cols, flips, score):
            if sc < MAC_NEW:
                continue
            live[r].add(s, int(c), bool(fl))
            kept.append(live[r])
            taken.add(int(c))
        ended = [t for t in live if all(t is not k for k in kept)]
        done.extend(ended)
        for t in ended:
            t.ended = PAIR_SPLIT if s.f.size < len(live) else SHAPE_LOST
        if s.f.size < len(live):
            # fewer roots oscillate: those lost met at zero frequency and may come back
            missing.extend(ended)
        spare = [j for j in range(s.f.size) if j not in taken]
        if spare and missing:
            # a root back from a stretch where it did not oscillate: the curve it left
            # goes on, with a gap (its shape may have turned there)
            sub = Spectrum(s.omega, s.f[spare], s.decay[spare], s.index[spare],
                           tuple(s.kinds[j] for j in spare), s.y[:, spare], s.divergence)
            f, reach = predicted(missing, t1)
            reach = reach + np.abs(f)   # it left near zero frequency
            back = np.column_stack([t.ys[-1] for t in missing])
            # one lost and one back: the same root, however far its shape turned
            alone = len(missing) == 1 and len(spare) == 1
            for r, c, fl, sc in zip(*match(back, f, sub, frame, reach)):
                if sc >= MAC_NEW or alone:
                    missing[r].gaps.append(len(missing[r].omega) - 1)
                    missing[r].add(s, spare[c], bool(fl))
                    kept.append(missing[r])
                    taken.add(spare[c])
            done = [t for t in done if all(t is not k for k in kept)]
            missing = [t for t in missing if all(t is not k for k in kept)]
        for j in range(s.f.size):
            if j not in taken:
                t = _Track([], [], [], [], [], [])
                t.add(s, j, False)
                t.began = PAIR_MET if s.f.size > len(live) else SHAPE_LOST
                kept.append(t)
        for t in kept:
            if t.ended:   # back from a stretch where it did not oscillate
                t.ended = ""
        live = kept

    for a, b in zip(grid[:-1], grid[1:]):
        step(float(a), float(b), 0)
    tracks = sorted(done + live, key=lambda t: (t.omega[0], abs(t.f[0])))
    # a double pair's two curves in a fixed order, backward first (their frequencies
    # differ only by the mesh's own asymmetry)
    for i in range(len(tracks) - 1):
        a, b = tracks[i], tracks[i + 1]
        if (a.omega[0] == b.omega[0] and abs(abs(a.f[0]) - abs(b.f[0])) <= PAIR * abs(b.f[0])
                and a.index[0] > b.index[0]):
            tracks[i], tracks[i + 1] = b, a
    return [Curve(number=i + 1, frame=frame, speeds_rpm=np.array(t.omega) / RPM,
                  signed_hz=np.array(t.f), decay=np.array(t.decay), index=np.array(t.index),
                  kinds=tuple(t.kinds), shapes=np.column_stack(t.ys), gaps=tuple(t.gaps),
                  began=t.began, ended=t.ended)
            for i, t in enumerate(tracks)]


def reported(curves: list[Curve], count: int, order: int = 0, within: int = 0
             ) -> list[Curve]:
    """The curves among the `count` lowest (by the frequency seen) at some speed of the
    diagram, the modes the basis check vouches for; and, so that no crossing with the
    highest `order` line is missed, those among the lowest `within` at a speed where
    they lie below that line."""
    speeds = sorted({float(s) for c in curves for s in c.speeds_rpm})
    keep: set[int] = set()
    for s in speeds:
        here = sorted((float(np.interp(s, c.speeds_rpm, c.seen_hz)), c.number) for c in curves
                      if c.speeds_rpm[0] <= s <= c.speeds_rpm[-1])
        keep.update(number for _, number in here[:count])
        keep.update(number for f, number in here[:within] if f <= order * s / 60.0)
    return [c for c in curves if c.number in keep]


def reach(curves: list[Curve], within: int, speed_rpm: float) -> float:
    """The frequency (Hz) of the `within`-th lowest curve at a speed: how high the
    crossings are searched there."""
    here = sorted(float(np.interp(speed_rpm, c.speeds_rpm, c.seen_hz)) for c in curves
                  if c.speeds_rpm[0] <= speed_rpm <= c.speeds_rpm[-1])
    return here[min(within, len(here)) - 1] if here else 0.0


@dataclass(frozen=True)
class Crossing:
    """A curve meeting an order line: the order, the curve, the component ("" in the
    stationary frame, "forward" or "backward" in the rotating), the speed (rad/s), and
    the curve's whirl there, its whirl index, log decrement and the component's share."""

    order: int
    curve: int
    component: str
    omega: float
    whirl: str
    index: float
    log_dec: float
    share: float


def _at(model: RotorModel, omega: float, y: np.ndarray, f: float, reach: float
        ) -> tuple[float, float, float, float]:
    """The root continuing shape y (expected near the signed frequency f, Hz, give or
    take reach) at the spin omega: its signed frequency (Hz), decay (1/s), whirl index
    (in the form kept) and score."""
    s = spectrum(model, omega)
    if s.f.size == 0:
        return 0.0, 0.0, 0.0, -1.0
    _, cols, flips, score = match(y[:, None], np.array([f]), s, model.frame,
                                  np.array([reach]))
    j, sign = int(cols[0]), (-1.0 if flips[0] else 1.0)
    return sign * float(s.f[j]), float(s.decay[j]), sign * float(s.index[j]), float(score[0])


def _shape_at(model: RotorModel, omega: float, y: np.ndarray, f: float, reach: float
              ) -> np.ndarray:
    """The shape (in the form kept) of the root _at finds."""
    s = spectrum(model, omega)
    _, cols, flips, _ = match(y[:, None], np.array([f]), s, model.frame, np.array([reach]))
    j = int(cols[0])
    return s.y[:, j].conj() if flips[0] else s.y[:, j]


def component_lines(c: Curve) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """A curve's lines as the housing sees them: (component, signed value v in Hz whose
    magnitude is seen, share of the motion). A curve that never orbits (torsion, axial)
    is seen at its own frequency in either frame."""
    if c.frame == "stationary" or not c.whirling:
        return [("", c.signed_hz, np.ones_like(c.signed_hz))]
    n = c.speeds_rpm / 60.0
    return [("forward", c.signed_hz + n, 0.5 * (1 + c.index)),
            ("backward", c.signed_hz - n, 0.5 * (1 - c.index))]


# a periodic rotor's side harmonic crosses an order line where it holds this share
SIDE_SHARE_MIN = 0.05


def side_lines(c: Curve) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """A periodic rotor's curve's other lines, its Floquet form's harmonics beside the
    dominant one (d != 0, at signed_hz + 2 d n in the turning frame), as the housing sees
    them: (component, signed value v in Hz, share of the whole motion), as
    component_lines gives the dominant harmonic's."""
    return [(comp, v, share) for comp, v, share, _ in _sides(c)]


def _sides(c: Curve) -> list[tuple[str, np.ndarray, np.ndarray, int]]:
    if c.sides is None or c.side_index is None or not c.whirling:
        return []
    n = c.speeds_rpm / 60.0
    S = (c.sides.shape[0] - 1) // 2
    out = []
    for r, d in enumerate(range(-S, S + 1)):
        if d == 0:
            continue
        f = c.signed_hz + 2 * d * n
        share, index = c.sides[r], c.side_index[r]
        out += [("forward", f + n, share * 0.5 * (1 + index), d),
                ("backward", f - n, share * 0.5 * (1 - index), d)]
    return out


def component_whirl(component: str, v: float, index: float) -> str:
    """The whirl of a component seen at |v|: in the stationary frame the root's own by
    its index; in the rotating frame circular, its sense flipped where v < 0."""
    if component == "":
        return "forward" if index > FORWARD else "backward" if index < -FORWARD else "mixed"
    forward = (component == "forward") == (v > 0)
    return "forward" if forward else "backward"


def curve_crossings(model: RotorModel, curves: list[Curve], orders: tuple[int, ...]
                    ) -> list[Crossing]:
    """Every crossing of every curve's components with every order line, on the curves'
    own (refined) speeds, each refined by root finding on the model."""
    from scipy.optimize import brentq

    out: list[Crossing] = []
    for c in curves:
        if not any(k in WHIRLING for k in c.kinds):
            continue
        # a periodic rotor's form also crosses with its other harmonics (d != 0), seen
        # at its dominant one's frequency + 2 d n: found as the dominant one is
        lines = [(comp, v, share, 0) for comp, v, share in component_lines(c)] + [
            x for x in _sides(c) if float(np.max(x[2])) >= SIDE_SHARE_MIN]
        for comp, v, share, d in lines:
            for k in orders:
                g = np.abs(v) - k * c.speeds_rpm / 60.0
                changes = set(np.flatnonzero((g[:-1] > 0) & (g[1:] <= 0)
                                             | (g[:-1] < 0) & (g[1:] >= 0)).tolist())
                if d:
                    changes = {i for i in changes if min(share[i], share[i + 1]) >= SIDE_SHARE_MIN}
                if comp and k == 1 and not d:
                    # a stretch where the root stands at zero frequency in the turning
                    # frame: both its ends meet 1x, whether or not its sign came back
                    for i in c.gaps:
                        ends = _gap_crossings(model, c, i, comp, k)
                        if ends is not None:
                            changes.discard(i)
                            out += ends
                for i in sorted(changes):
                    if max(share[i], share[i + 1]) < SHARE_MIN or c.speeds_rpm[i + 1] <= 0:
                        continue
                    y0 = c.shapes[:, i]
                    lo, hi = c.speeds_rpm[i] * RPM, c.speeds_rpm[i + 1] * RPM
                    f0, f1 = float(c.signed_hz[i]), float(c.signed_hz[i + 1])
                    reach = REACH * (hi - lo) / (2 * math.pi) + 1e-3 * max(abs(f0), abs(f1))

                    def near(om: float, y0: np.ndarray = y0, f0: float = f0, f1: float = f1,
                             lo: float = lo, hi: float = hi, reach: float = reach
                             ) -> tuple[float, float, float, float]:
                        return _at(model, om, y0, f0 + (f1 - f0) * (om - lo) / (hi - lo), reach)

                    def gap(om: float, k: int = k, comp: str = comp, near=near,
                            d: int = d) -> float:
                        fs, _, _, sc = near(om)
                        if sc < MAC_MIN:   # the root does not oscillate here: at zero
                            fs = 0.0
                        n = om / (2 * math.pi)
                        fs += 2 * d * n
                        val = fs if comp == "" else fs + n if comp == "forward" else fs - n
                        return abs(val) - k * n

                    try:
                        om = brentq(gap, lo, hi, xtol=1e-12 * hi) if gap(lo) * gap(hi) < 0 else (
                            hi if g[i + 1] == 0 else lo - g[i] * (hi - lo) / (g[i + 1] - g[i]))
                    except ValueError:
                        om = lo - g[i] * (hi - lo) / (g[i + 1] - g[i])
                    fs, decay, index, sc = near(om)
                    if d:
                        # a side harmonic: its share there, its sense by its own index
                        t = (om - lo) / (hi - lo)
                        n = om / (2 * math.pi)
                        val = fs + 2 * d * n + (n if comp == "forward" else -n)
                        part = float((1 - t) * share[i] + t * share[i + 1])
                        row = (c.sides.shape[0] - 1) // 2 + d if c.sides is not None else 0
                        idx = (float((1 - t) * c.side_index[row, i] + t * c.side_index[row, i + 1])
                               if c.side_index is not None else 0.0)
                        wd = 2 * math.pi * abs(val)
                        out.append(Crossing(k, c.number, comp, float(om),
                                            component_whirl(comp, val, idx), idx,
                                            float(2 * math.pi * decay / wd) if wd > 0 else 0.0,
                                            part))
                        continue
                    if sc < MAC_MIN:
                        # the root meets zero frequency here (a conjugate pair passing
                        # through it): its state just beside, where it oscillates
                        side = [near(om * (1 + e)) for e in (-1e-7, 1e-7)]
                        if min(x[3] for x in side) >= MAC_MIN:
                            fs, decay, index = (0.5 * (a + b) for a, b in
                                                zip(side[0][:3], side[1][:3]))
                        else:
                            # the curve does not oscillate over part of the step (two roots
                            # met at zero frequency): its ends there are the crossings
                            ends = _gap_crossings(model, c, int(i), comp, k, inside=om)
                            if ends is None:   # it oscillates throughout: only just lost
                                t = (om - lo) / (hi - lo)
                                fs, decay, index = (
                                    (1 - t) * float(a[i]) + t * float(a[i + 1])
                                    for a in (c.signed_hz, c.decay, c.index))
                            else:
                                out += ends
                                continue
                    n = om / (2 * math.pi)
                    val = fs if comp == "" else fs + n if comp == "forward" else fs - n
                    wd = 2 * math.pi * float(seen(np.array([fs]), np.array([index]), n,
                                                  model.frame)[0])
                    part = 1.0 if comp == "" else 0.5 * (1 + index if comp == "forward"
                                                         else 1 - index)
                    out.append(Crossing(k, c.number, comp, float(om),
                                        component_whirl(comp, val, index), float(index),
                                        float(2 * math.pi * decay / wd) if wd > 0 else 0.0,
                                        float(part)))
    return dedupe(out)


def _follow(model: RotorModel, om: float, y: np.ndarray, f: float, end: float
            ) -> tuple[float, float, float, float]:
    """Follow one root from the spin om (shape y, signed frequency f) towards `end`, by
    bisection, to the last spin where it still oscillates (its shape found among the
    roots): that spin (rad/s) and the root's signed frequency, decay and whirl index."""
    reach = REACH * abs(end - om) / (2 * math.pi) + abs(f) + 1.0   # the shape decides
    fs, decay, index, sc = _at(model, end, y, f, reach)
    if sc >= MAC_MIN:
        return end, fs, decay, index
    good, bad = om, end
    fs, decay, index = f, 0.0, 0.0
    for _ in range(FOLLOW_STEPS):
        if abs(bad - good) <= FOLLOW_TOL * abs(end):
            break
        mid = 0.5 * (good + bad)
        f_mid, d, w, sc = _at(model, mid, y, fs, reach)
        if sc >= MAC_MIN:
            y = _shape_at(model, mid, y, fs, reach)
            good, fs, decay, index = mid, f_mid, d, w
        else:
            bad = mid
    return good, fs, decay, index


def _gap_crossings(model: RotorModel, c: Curve, i: int, comp: str, k: int,
                   inside: float | None = None) -> list[Crossing] | None:
    """The crossings at a stretch of the step i -> i + 1 where the curve does not
    oscillate (its roots meet at zero frequency in the turning frame, where the forward
    and backward components both stand at 1x): the last speeds the curve reaches from
    either side, each a crossing of the 1x line; None where it reaches across (no such
    stretch: a conjugate pair passing through zero at one speed). `inside`: a spin
    (rad/s) in the step where the curve is known not to oscillate; each side is followed
    towards it (a stretch narrower than the step has oscillating roots at both of the
    step's ends, each like the other's). A stretch narrower than PAIR is one crossing:
    a round shaft's pair, split by its mesh, stands still over some 1e-5 of the speed."""
    lo, hi = c.speeds_rpm[i] * RPM, c.speeds_rpm[i + 1] * RPM
    to_left, to_right = (hi, lo) if inside is None else (inside, inside)
    left = _follow(model, lo, c.shapes[:, i], float(c.signed_hz[i]), to_left)
    right = _follow(model, hi, c.shapes[:, i + 1], float(c.signed_hz[i + 1]), to_right)
    if left[0] == to_left or right[0] == to_right:
        return None
    if inside is not None and right[0] - left[0] <= PAIR * inside:
        # narrower than the split a mesh gives a round shaft's pair: one crossing
        return None
    out = []
    for om, fs, decay, index in (left, right):
        n = om / (2 * math.pi)
        val = fs + n if comp == "forward" else fs - n
        wd = 2 * math.pi * float(seen(np.array([fs]), np.array([index]), n, model.frame)[0])
        part = 0.5 * (1 + index if comp == "forward" else 1 - index)
        if part >= SHARE_MIN:
            out.append(Crossing(k, c.number, comp, float(om), component_whirl(comp, val, index),
                                float(index), float(2 * math.pi * decay / wd) if wd > 0 else 0.0,
                                float(part)))
    return out


def dedupe(found: list[Crossing]) -> list[Crossing]:
    """One crossing per curve, order and speed (a rotating-frame root at f_s = 0 meets
    1x with both its components): the one of the larger share."""
    out: list[Crossing] = []
    for x in sorted(found, key=lambda x: -x.share):
        if not any(o.curve == x.curve and o.order == x.order
                   and abs(o.omega - x.omega) <= SAME * max(o.omega, x.omega) for o in out):
            out.append(x)
    return sorted(out, key=lambda x: (x.omega, x.order))


def direct_applies(model: RotorModel) -> str | None:
    """None where the direct route applies, else why not."""
    if any(len(b.coefficients.speeds) for b in model.bearings):
        return "the bearing coefficients change with speed"
    if any(np.any(np.array(b.coefficients.damping(0.0))) for b in model.bearings):
        return ("the bearings damp: a damped root meets an order line at a speed no "
                "undamped eigenproblem gives")
    return None


@dataclass(frozen=True)
class Direct:
    """A crossing found directly: order, speed (rad/s), the component, whirl index."""

    order: int
    omega: float
    component: str
    index: float


def order_roots(model: RotorModel, m: int, top: float = math.inf, every: bool = False
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The undamped whirling roots that meet the line f = m n (n the spin) up to the spin
    `top` (rad/s): the speeds Omega (rad/s, ascending), their whirl indices and modal
    shapes (N, found), from the linear eigenproblem in Omega^2 of the module's
    docstring (constant, undamped bearings; torsion and axial modes meet the lines as
    at standstill and are left out). m = 1 in the stationary frame: the synchronous
    critical speeds, gyroscopic moments at Omega = omega. `every`: torsion and axial
    roots kept too (a mode followed as it takes on their motion)."""
    import scipy.linalg

    from shaftfem.fem.rotor import dominant_kinds

    K0 = np.diag(model.omega2).astype(complex)
    for b in model.bearings:
        K0 = K0 + b.beta.T @ (np.array(b.coefficients.stiffness(0.0)) - np.diag(b.standstill)
                              ) @ b.beta
    lam, A = scipy.linalg.eig(K0, m * m * model.mass(0.0) - 1j * m * model.G - model.K2)
    ok = (np.isfinite(lam) & (np.abs(lam.imag) <= 1e-8 * np.abs(lam)) & (lam.real > 0)
          & (lam.real <= top**2 * (1 + 1e-9)))
    if not every:
        ok[ok] = [k in WHIRLING for k in dominant_kinds(model, A[:, ok])]
    order = np.argsort(lam.real[ok])
    A = A[:, ok][:, order]
    return np.sqrt(lam.real[ok][order]), whirl_index(model, A), A


def one_of_each_pair(speeds: np.ndarray) -> np.ndarray:
    """Of roots standing still in the turning frame (ascending speeds), the indices of one
    of each group met at one speed (within 1e-6): a conjugate pair met at zero is a null
    space of two shapes on a shaft of revolution (x and y), so a group of two or three is
    one crossing; a root alone is its own (a keyway splits the pair)."""
    keep: list[int] = []
    start = 0
    for i in range(1, speeds.size + 1):
        if i == speeds.size or speeds[i] > speeds[start] * (1 + 1e-6):
            keep += range(start, start + max(1, (i - start) // 2))
            start = i
    return np.array(keep, dtype=int)


def direct_crossings(model: RotorModel, orders: tuple[int, ...], top: float) -> list[Direct]:
    """Every undamped crossing with each order line up to the spin `top` (rad/s), from
    the linear eigenproblem in Omega^2 of the module's docstring (constant, undamped
    bearings only: see direct_applies); of a periodic rotor, each Floquet component's
    from Hill's equations at the crossing (fem.floquet.periodic_order_roots)."""

    periodic = model.periodic(1.0)

    def solve(m: int) -> tuple[np.ndarray, np.ndarray]:
        if periodic:   # a Floquet form's component at m n: its dominant one or a side one
            speeds, share, index, kinds = periodic_order_roots(model, m, top)
            met = (share >= SIDE_SHARE_MIN) & np.array([k in WHIRLING for k in kinds], dtype=bool)
            return speeds[met], index[met]
        return order_roots(model, m, top)[:2]

    out = []
    for k in orders:
        if model.frame == "stationary":
            speeds, index = solve(k)
            out += [Direct(k, float(om), "", float(w)) for om, w in zip(speeds, index)]
            continue
        for m, comp, sign in ((k - 1, "forward", 1.0), (k + 1, "backward", -1.0)):
            speeds, index = solve(m)
            found = [Direct(k, float(om), comp, float(w)) for om, w in zip(speeds, index)
                     if m == 0 or 0.5 * (1 + sign * w) >= SHARE_MIN]
            if m == 0:
                # a root standing still in the turning frame is a conjugate pair met at
                # zero: each of its crossings is a null space of two shapes on a shaft
                # of revolution (x and y), of one where the shaft is stiffer one way
                found = sorted(found, key=lambda d: d.omega)
                found = [found[i] for i in one_of_each_pair(np.array([d.omega for d in found]))]
            out += found
    if periodic:
        # one crossing met by two components of one form (a form of two equal circular
        # whirls, as a round shaft's in bearings that differ along x and y: its forward
        # and backward components meet the line at the same speed) is one crossing
        kept: list[Direct] = []
        for d in sorted(out, key=lambda d: (d.order, d.omega)):
            if not (kept and kept[-1].order == d.order
                    and d.omega <= kept[-1].omega * (1 + 1e-7)):
                kept.append(d)
        out = kept
    return out
