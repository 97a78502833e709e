"""The films' heating on a bore of pads: each pad's temperature from the film's energy
equation and its viscosity from the oil's ISO VG grade, solved in turn with its
pressure (a thermohydrodynamic film), and the peak pad temperature.

On each pad the oil's bulk temperature T (the one its flow carries) is solved in the
film's plane. The pads are adiabatic. The journal is isothermal at T_j, the films'
mean temperature over the pads' area (the shaft also sheds heat to the grooves' oil and
along its length, so it runs cooler than the thin films' balance alone would hold it:
ross 3.1's default, its `averaged_film_temperature`). In the film's nondimensional variables
(parts.pads) the energy equation reads

    qbar . grad T = dT_ref phi - kappa (T - T_j) / H,
    dT_ref = mu_s omega (R / c_b)^2 / (rho c_p),   kappa = Nu k / (rho c_p omega c_b^2),
    qbar_theta = H / 2 - (H^3 / 12 m) dP/dtheta,   qbar_Z = -(H^3 / 12 m) dP/dZ,
    phi = m / H + (H^3 / 12 m) |grad P|^2   (Couette and Poiseuille shear),

where m = mu(T) / mu_s is the viscosity over the supply oil's (the flows are omega R c_b
qbar per unit width), and Nu and the pad surface's temperature come from the profile
across the film (NUSSELT, SURFACE). The film's heat is carried along it, and
conduction along it is negligible beside that (a Peclet number of thousands). So T is
marched along theta from the pad's leading edge, and upwind across Z from the
mid-plane out to the ends.

Each pad's leading edge takes the oil that left the pad before it: a share
`carry_over` of that flow at its mean temperature. Supply oil makes up the rest of the
flow (hot-oil carry-over, Ettles):

    Q_in T_in = lambda Q_out,prev T_out,prev + (Q_in - lambda Q_out,prev) T_s.

The heat grows the parts, closing the clearance (a hot clearance, `grown`). The
clearances are declared with the whole bearing at one temperature, and the housing that
holds the pivots stays at the supply's. The journal, at T_j, grows by alpha R (T_j -
T_s). A tilting pad, adiabatic, is at its face's mean temperature T_p through its
thickness t; it grows about its pivot: its face there moves in by alpha t (T_p - T_s)
and its radius of curvature grows by alpha (R + c_p) (T_p - T_s). A fixed pad is the
housing's bore and keeps its size. So

    c_b' = c_b - alpha R (T_j - T_s) - alpha t (T_p - T_s)      (t = 0: a fixed pad)
    c_p' = c_p - alpha R (T_j - T_s) + alpha (R + c_p) (T_p - T_s)   (tilting)

with alpha a steel's (EXPANSION) for the shaft, the pads' backs and the housing, and the
pad's film over c_b at its pivot (Pad.gap) c_b' / c_b, its preload 1 - c_b' / c_p'. This
is the thermal part of ross 3.1's pads' and shaft's deformation (its deform_type
"pad_mechanical_thermal_shaft_shell_thermal", the shell at the supply's temperature),
without the pads' bending under their pressure and their heat's gradient through them.

A pad's pressure (its film with its viscosity, pads.pad_state) and its temperature are
solved in turn until the temperatures settle; the journal's place and the pads' tilts
are those of the heated film, on its grown parts.

References: Ettles (1969), hot oil carry-over in thrust bearings; Fillon, Bligoud and
Frene (1992), J. Tribology 114, a tilting-pad bearing's measured and computed pad
temperatures (docs/journal-bearing.md, "The film's heating").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.parts import oil, pads
from shaftfem.parts.heat import CARRY_OVER, HOTTEST, SPECIFIC_HEAT
from shaftfem.scene.model import JournalBearing, condensed

if TYPE_CHECKING:
    from shaftfem.parts.journal import Operating, SpeedTable

# Across the film, heated evenly (Couette shear), from the isothermal journal (xi = 0)
# to the adiabatic pad (xi = 1): T = T_j + A (xi - xi^2 / 2), the journal taking k A / h.
# The flow u = U (1 - xi) carries its bulk temperature T_j + A / 4, the one the march
# transports: so the journal takes Nu k (T - T_j) / h with Nu = 4 on it, and the pad's
# surface runs at T_j + A / 2, twice the bulk's excess over the journal.
NUSSELT = 4.0
SURFACE = 2.0
CONDUCTIVITY = 0.13   # W/(m K), a mineral oil's
# the temperatures have settled when no node lies further than this (K) from where the
# rounds converge to (a round's largest move m, its ratio r to the round before's: the
# rounds converge linearly, so the rest of the way is m r / (1 - r))
SETTLED = 0.02
# each round moves the temperatures this share of the way to the new ones (1 overshoots:
# the viscosity's and the journal's feedback makes the loop stiff)
RELAX = 0.5
ROUNDS = 60
# ... and until they move by less than this (K), the film's equilibrium is solved to a
# looser tolerance
ROUGH = 0.5
# a steel's linear thermal expansion (1/K): the journal, the pads (a thin babbitt on a
# steel back) and the housing
EXPANSION = 11.5e-6
# a tilting pad's radial thickness over the journal's diameter where none is given
# (0.12 to 0.2 on the bearings of ross 3.1's examples and literature cases): its
# growth moves the peak pad temperature by about 0.3 K per 10 mm on Fillon's bearing
THICKNESS = 0.15


@dataclass(frozen=True)
class PadsHeat:
    """A bore of pads' heated film: its state (pads.BoreState, the forces on the supply
    oil's viscosity's scale), each pad's nodal temperatures (C) and relative viscosity,
    each pad's inlet and mean outlet temperature (C) and inlet flow (m^3/s), the peak
    temperature over the pads (C) and which pad has it, and the friction power (W):
    2 mu_s omega^2 R^4 / c_b times the sum of the pads' int phi dtheta dZ (the whole
    length's)."""

    state: pads.BoreState
    temperature: tuple[np.ndarray, ...]
    surface: tuple[np.ndarray, ...]
    viscosity: tuple[np.ndarray, ...]
    inlet: tuple[float, ...]
    outlet: tuple[float, ...]
    journal: float
    flow: tuple[float, ...]
    peak: float
    hottest: int
    power: float = 0.0   # W, the films' shear at their own viscosity, over all pads
    journal_power: float = 0.0   # W, of it what the films give the journal
    fresh: float = 0.0   # m^3/s, the supply oil the pads' leading edges draw
    # m, each pad's film at its pivot with the journal centred, grown (c_b')
    clearance: tuple[float, ...] = ()
    bore: pads.Bore | None = None   # the pads grown, as the state's film has them


def grown(pad: pads.Pad, radius: float, clearance: float, journal_rise: float,
          pad_rise: float, thickness: float, expansion: float = EXPANSION) -> pads.Pad:
    """The pad as the heat grows the parts (module docstring): the journal of `radius`
    (m) `journal_rise` (K) above the supply, the pad (of `thickness`, m, if it tilts)
    `pad_rise`; its gap and preload on the cold clearance c_b (m). A ValueError where
    the journal would fill the bore."""
    c_p = clearance / (1 - pad.preload)
    journal = expansion * radius * journal_rise
    face = expansion * thickness * pad_rise if pad.tilts else 0.0
    curve = expansion * (radius + c_p) * pad_rise if pad.tilts else 0.0
    c_b, c_p = clearance - journal - face, c_p - journal + curve
    if c_b <= 0.05 * clearance:
        raise ValueError(f"the journal, {journal_rise:.0f} K above the supply, and the "
                         f"pads, {pad_rise:.0f} K, grow through the clearance "
                         f"({clearance * 1e6:.1f} um cold, {c_b * 1e6:.1f} um hot)")
    return replace(pad, gap=c_b / clearance, preload=1 - c_b / c_p)


@dataclass(frozen=True)
class _Grid:
    """A pad film's nodes on its tensor grid: each node's theta and Z index, the grid's
    theta and Z."""

    i: np.ndarray
    j: np.ndarray
    theta: np.ndarray
    Z: np.ndarray


def _grid(pad: pads.Pad, ratio: float) -> tuple[pads.PadFilm, _Grid]:
    f = pads.pad_film(pad.start, pad.arc, ratio, pads.cells_round(pad.arc), pads.Z_CELLS)
    x = f.basis.mesh.p
    theta, Z = np.unique(x[0].round(12)), np.unique(x[1].round(12))
    i = np.rint((x[0] - theta[0]) / (theta[-1] - theta[0]) * (theta.size - 1)).astype(int)
    j = np.rint(x[1] / Z[-1] * (Z.size - 1)).astype(int)
    return f, _Grid(i=i, j=j, theta=theta, Z=Z)


def _flows(H: np.ndarray, P: np.ndarray, m: np.ndarray, theta: np.ndarray, Z: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The film's flows qbar_theta and qbar_Z (downstream and out towards the ends only)
    and its dissipation phi on the pad's grid (module docstring)."""
    dP_t, dP_z = np.gradient(P, theta, Z)
    poiseuille = H**3 / (12 * m)
    q_t = np.maximum(0.5 * H - poiseuille * dP_t, 1e-3 * H)   # no flow back at the edge
    q_z = np.maximum(-poiseuille * dP_z, 0.0)                 # out towards the ends
    return q_t, q_z, m / H + poiseuille * (dP_t**2 + dP_z**2)


def _face(T: np.ndarray, journal: float) -> np.ndarray:
    """The pad's surface temperature under a film whose bulk is at T (C), the journal at
    `journal`: the adiabatic wall's (SURFACE)."""
    return journal + SURFACE * (T - journal)


def _on_grid(v: np.ndarray, g: _Grid) -> np.ndarray:
    """Nodal values v on the pad's grid (theta, Z)."""
    out = np.zeros((g.theta.size, g.Z.size))
    out[g.i, g.j] = v
    return out


def _over(v: np.ndarray, g: _Grid) -> float:
    """int v dtheta dZ over the pad's half film."""
    return float(np.trapezoid(np.trapezoid(v, g.Z, axis=1), g.theta))


def march(H: np.ndarray, P: np.ndarray, m: np.ndarray, theta: np.ndarray, Z: np.ndarray,
          inlet: float, rise: float, kappa: float = 0.0, journal: float = 0.0
          ) -> tuple[np.ndarray, np.ndarray]:
    """The film's temperature (C) on the pad's grid (theta, Z) of its thickness H,
    pressure P and relative viscosity m there (module docstring), its leading edge at
    `inlet` (C), dT_ref = `rise` (K); and the flow qbar_theta across each theta line
    (the grid's shape)."""
    q_t, q_z, phi = _flows(H, P, m, theta, Z)
    T = np.empty_like(H)
    T[0] = inlet
    dt, dz = np.diff(theta), np.diff(Z)
    for i in range(1, theta.size):
        a = q_t[i] / dt[i - 1]
        g = kappa / H[i]
        T[i, 0] = (a[0] * T[i - 1, 0] + rise * phi[i, 0] + g[0] * journal) / (a[0] + g[0])
        for j in range(1, Z.size):
            b = q_z[i, j] / dz[j - 1]
            T[i, j] = ((a[j] * T[i - 1, j] + b * T[i, j - 1] + rise * phi[i, j]
                        + g[j] * journal) / (a[j] + b + g[j]))
    return T, q_t


def heated(bore: pads.Bore, load: float, omega: float, radius: float, clearance: float,
           grade: int, supply: float, carry_over: float = CARRY_OVER,
           specific_heat: float = SPECIFIC_HEAT, thickness: float | None = None
           ) -> PadsHeat:
    """The bore's heated film carrying `load` (N, along -y) at the spin omega (rad/s), the
    journal's radius and the bearing's clearance c_b (m, cold), oil of ISO VG `grade`
    supplied at `supply` (C), the parts grown by the heat with tilting pads `thickness`
    thick (m; None: the parts keep their cold size); a ValueError where a film runs above
    parts.heat.HOTTEST, the parts grow through the clearance, or the temperatures do not
    settle."""
    cold = bore
    mu_s = oil.dynamic(grade, supply)
    rho_c = oil.density(supply) * specific_heat
    rise = mu_s * omega * (radius / clearance) ** 2 / rho_c
    W = load * clearance**2 / (mu_s * omega * radius**4)
    films = [_grid(p, bore.ratio) for p in bore.pads]
    def viscosity(t: np.ndarray) -> np.ndarray:
        return oil.dynamic(grade, np.minimum(t, HOTTEST)) / mu_s
    T = [np.full(f.basis.mesh.p.shape[1], supply) for f, _ in films]
    m = [np.ones_like(t) for t in T]
    inlets = [supply] * len(bore.pads)
    kappa = NUSSELT * CONDUCTIVITY / (oil.density(supply) * specific_heat * omega
                                      * clearance**2)
    journal = supply
    state = None
    n = len(bore.pads)
    moved = before = np.inf
    for _ in range(ROUNDS):
        # while the temperatures still move by degrees, the film's place need not be
        # exact: the last rounds settle it to the full tolerance
        tol = 1e-10 if moved < ROUGH else 1e-5
        used = bore
        state = pads.equilibrium(bore, np.array([0.0, -W]), tol=tol, start=state,
                                 viscosity=tuple(m))
        new, flows, outs, warm, grids = [], [], [], [], []
        for k, ((f, g), pad) in enumerate(zip(films, bore.pads)):
            q = state.q[bore.coordinates(k)]
            H = pads._film(pad, f.basis.mesh.p[0], q)[0]
            shape = (g.theta.size, g.Z.size)
            grid = np.zeros(shape), np.zeros(shape), np.ones(shape)
            for a, v in zip(grid, (H, state.pads[k].pressure, m[k])):
                a[g.i, g.j] = v
            Tk, q_t = march(*grid, g.theta, g.Z, inlets[k], rise, kappa, journal)
            grids.append((grid, Tk, g))
            new.append(Tk[g.i, g.j])
            # this pad's film temperature integrated over its area, and the area
            warm.append((_over(Tk, g), (g.theta[-1] - g.theta[0]) * g.Z[-1]))
            # the flow (qbar, whole length) and mean temperature at each edge
            q_in, q_out = 2 * np.trapezoid(q_t[0], g.Z), 2 * np.trapezoid(q_t[-1], g.Z)
            flows.append(q_in)
            outs.append((q_out, float(np.trapezoid(q_t[-1] * Tk[-1], g.Z)
                                      / np.trapezoid(q_t[-1], g.Z))))
        moved, before = max(float(np.abs(a - b).max()) for a, b in zip(new, T)), moved
        if max(float(t.max()) for t in new) > HOTTEST:
            raise ValueError(f"the pads' film would run above {HOTTEST:g} C (fed at "
                             f"{supply:g} C)")
        T = [RELAX * a + (1 - RELAX) * b for a, b in zip(new, T)]
        m = [viscosity(t) for t in T]
        # the journal turns through every film and runs at their mean
        marched_at = journal
        journal += RELAX * (sum(a for a, _ in warm) / sum(w for _, w in warm) - journal)
        if thickness is not None:
            # each pad's face's mean over the film's area
            faces = [_over(_on_grid(_face(t, journal), g), g) / a
                     for t, (_, g), (_, a) in zip(T, films, warm)]
            bore = pads.Bore(tuple(grown(p, radius, clearance, journal - supply, f - supply,
                                         thickness) for p, f in zip(cold.pads, faces)),
                             cold.ratio)
        fresh = 0.0
        for k in range(n):   # the pad before k in the journal's turn
            q_prev, t_prev = outs[(k - 1) % n]
            kept = min(carry_over * q_prev, flows[k])
            inlets[k] = (kept * t_prev + (flows[k] - kept) * supply) / flows[k]
            fresh += flows[k] - kept
        rate = min(moved / before, 0.99) if before < np.inf else 0.99
        if max(moved * rate / (1 - rate), moved) < SETTLED:
            surface = [_face(t, journal) for t in T]
            peaks = [float(t.max()) for t in surface]
            hot = int(np.argmax(peaks))
            # the friction (the films' dissipation) and what the journal takes, on this
            # round's films
            shear = sum(_over(_flows(*grid, g.theta, g.Z)[2], g) for grid, _, g in grids)
            sink = sum(_over(kappa * (Tk - marched_at) / grid[0], g) for grid, Tk, g in grids)
            return PadsHeat(clearance=tuple(p.gap * clearance for p in used.pads), bore=used,
                            state=state, temperature=tuple(T), surface=tuple(surface),
                            viscosity=tuple(m), inlet=tuple(inlets),
                            outlet=tuple(t for _, t in outs), journal=journal,
                            flow=tuple(omega * radius**2 * clearance * q for q in flows),
                            peak=peaks[hot], hottest=hot,
                            power=2 * mu_s * omega**2 * radius**4 / clearance * shear,
                            journal_power=2 * rho_c * omega * clearance * radius**2 * sink,
                            fresh=omega * radius**2 * clearance * fresh)
    raise ValueError(f"the pads' temperatures did not settle in {ROUNDS} rounds")


# the speeds a fed tilting-pad journal's heated film is solved at for its rotor model's
# coefficients, evenly in log(speed) over its speed table, besides its operating speeds
SAMPLES = 8


def settings() -> dict:
    """What a heated film's table depends on besides its bearing and its film table (a
    cache's key), as they stand now."""
    return {"heated_version": 1, "samples": SAMPLES, "expansion": EXPANSION,
            "thickness": THICKNESS, "nusselt": NUSSELT, "surface": SURFACE,
            "conductivity": CONDUCTIVITY, "settled": SETTLED, "relax": RELAX,
            "rounds": ROUNDS, "rough": ROUGH, "carry_over": CARRY_OVER,
            "specific_heat": SPECIFIC_HEAT, "hottest": HOTTEST}


def heated_at(b: JournalBearing, omega: float) -> PadsHeat:
    """A fed bore of pads' heated film at the spin omega (rad/s), its parts grown with
    tilting pads b.pad_thickness thick (THICKNESS of the diameter if not given), its
    pads from the first past the load's line in the journal's turn; in the frame of the
    load along -y, whatever its direction."""
    return _heated_at(replace(b, direction=(0.0, -1.0)), omega)


@lru_cache(maxsize=256)
def _heated_at(b: JournalBearing, omega: float) -> PadsHeat:
    assert b.bore is not None and b.oil_iso_vg is not None
    assert b.oil_supply_temperature is not None
    bore = pads.bore_of(b.bore, b.ratio)
    thickness = b.pad_thickness or THICKNESS * b.diameter
    return heated(bore, b.load, omega, b.diameter / 2, b.clearance, b.oil_iso_vg,
                  b.oil_supply_temperature, thickness=thickness)


def film_matrices(b: JournalBearing, h: PadsHeat, omega: float
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The heated film's K (N/m) and C (N s/m) on (x, y, R phi_1, ...[, each pivot's
    radial motion]), as parts.journal.operating gives the isoviscous film's."""
    from shaftfem.parts.journal import pad_matrices

    assert h.bore is not None and b.oil_iso_vg is not None
    assert b.oil_supply_temperature is not None
    blocks = [pads._on_pivot(p, s) for p, s in zip(h.bore.pads, h.state.pads) if p.tilts]
    Kp, Cp = np.array([k for k, _ in blocks]), np.array([c for _, c in blocks])
    # the film's forces are on the supply oil's viscosity's scale (heated)
    unit = (oil.dynamic(b.oil_iso_vg, b.oil_supply_temperature) * omega
            * (b.diameter / 2) ** 4 / b.clearance**3)
    return pad_matrices(b, Kp, Cp, unit, omega)


def heated_operating(b: JournalBearing, h: PadsHeat, omega: float, op: Operating
                     ) -> Operating:
    """The journal's film at the spin omega as its heated film h on grown parts has it:
    its place, thinnest film and reduced K, C (the rotor model's at this speed,
    heated_table), and its Sommerfeld number at the films' mean temperature; the rest as
    `op`, the heat balance's (parts.journal.operating)."""
    K, C = film_matrices(b, h, omega)
    Z = condensed(K + 1j * omega * C)
    X, Y = h.state.q[:2]
    assert h.bore is not None and b.oil_iso_vg is not None
    mean = replace(b, viscosity=oil.dynamic(b.oil_iso_vg, h.journal))
    return replace(op, eccentricity=math.hypot(X, Y), attitude=math.atan2(X, -Y),
                   min_film=b.clearance * pads.thinnest(h.bore, h.state), K=Z.real,
                   C=Z.imag / omega, pad_K=K, pad_C=C, sommerfeld=mean.sommerfeld(omega))


def heated_table(b: JournalBearing, t: SpeedTable, at: tuple[float, ...] = ()
                 ) -> SpeedTable:
    """A fed tilting-pad journal's speed table (from its heat balance's one film
    temperature on the cold clearance) corrected to its heated film on grown parts: the
    difference of the two films' matrices, solved at SAMPLES speeds and at the
    operating speeds `at` (rad/s), spread over the table's speeds, monotone cubic in
    log(speed). Below the lowest speed the heated film settles at, the difference falls
    with the balance's temperature rise, to none where the film does not warm."""
    from scipy.interpolate import PchipInterpolator

    from shaftfem.parts import heat
    from shaftfem.parts.journal import operating

    if t.pad_K is None or t.pad_C is None or b.oil_supply_temperature is None:
        return t
    lo, top = float(t.speeds[0]), float(t.speeds[-1])
    speeds = sorted({*np.geomspace(lo, top, SAMPLES + 1)[1:].tolist(),
                     *(w for w in at if lo < w <= top)})
    xs, dK, dC = [], [], []
    for w in speeds:
        try:
            h = heated_at(b, w)
        except ValueError:   # a film the heated march does not settle: the balance's
            continue
        K, C = film_matrices(b, h, w)
        base = operating(heat.at_speed(b, w), w)
        assert base.pad_K is not None and base.pad_C is not None
        xs.append(math.log(w))
        dK.append(K - base.pad_K)
        dC.append(C - base.pad_C)
    if not xs:
        return t
    x = np.log(t.speeds)
    if len(xs) > 1:
        fK = PchipInterpolator(xs, np.array(dK), axis=0)
        fC = PchipInterpolator(xs, np.array(dC), axis=0)
        at_x = np.clip(x, xs[0], xs[-1])
        DK, DC = fK(at_x), fC(at_x)
    else:
        DK = np.repeat(dK[0][None], x.size, axis=0)
        DC = np.repeat(dC[0][None], x.size, axis=0)
    below = np.flatnonzero(x < xs[0])
    if below.size:
        supply = b.oil_supply_temperature
        def rise(w: float) -> float:
            return heat.heat_balance(b, w, supply).effective - supply
        first = rise(math.exp(xs[0]))
        for i in below:
            share = min(max(rise(float(t.speeds[i])) / first, 0.0), 1.0) if first > 0 else 0.0
            DK[i], DC[i] = share * DK[i], share * DC[i]
    pad_K, pad_C = t.pad_K + DK, t.pad_C + DC
    Z = [condensed(A + 1j * w * B) for w, A, B in zip(t.speeds, pad_K, pad_C)]
    return replace(t, K=np.array([z.real for z in Z]),
                   C=np.array([z.imag / w for z, w in zip(Z, t.speeds)]),
                   pad_K=pad_K, pad_C=pad_C)
