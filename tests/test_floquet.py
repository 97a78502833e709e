"""The periodic rotor (fem.floquet): a shaft stiffer across one diameter than across
the other, in supports that differ along x and y, written in the frame turning with
the shaft, where its coefficients have period pi / Omega.

- The asymmetric Jeffcott rotor (disk m on a shaft of stiffness k1, k2 along its two
  principal axes) on isotropic supports is unstable exactly between its two critical
  speeds sqrt(k1 / m) and sqrt(k2 / m).
- On supports kx != ky its instability zones move; each zone's edges against a direct
  time integration of the rotor's equations in the stationary frame, written here.
- Hill's method and the monodromy matrix agree; a round rotor in anisotropic supports
  solved by Floquet in the turning frame has the stationary frame's roots.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfem.fem.floquet import any_roots as roots
from shaftfem.fem.floquet import apart, converged_hill, multipliers, routes_apart
from shaftfem.fem.rotor import (
    BearingModal,
    RotorModel,
    deviatoric_parts,
    isotropic_part,
    part_matrices,
)
from shaftfem.scene.model import BearingCoefficients

M, K1, K2, C = 2.0, 2.0e5, 3.0e5, 4.0   # kg, N/m, N/m, N s/m


def jeffcott(kx: float, ky: float, c: float = C, k1: float = K1, k2: float = K2
             ) -> RotorModel:
    """The disk's two translations, mass-normalised (q = sqrt(m) u), in the frame turning
    with the shaft: the shaft's springs k1, k2 constant there, the supports kx, ky and
    damping c on the disk in the stationary frame (a bearing of the model)."""
    G, K = part_matrices(M, 0.0, 0.0, "rotating")
    G, K = G[:2, :2] / M, K[:2, :2] / M
    beta = np.eye(2) / math.sqrt(M)
    support = BearingCoefficients(speeds=(), kxx=(kx,), kxy=(0.0,), kyx=(0.0,), kyy=(ky,),
                                  cxx=(c,), cxy=(0.0,), cyx=(0.0,), cyy=(c,))
    eye = np.eye(2)
    return RotorModel("rotating", np.array([k1 / M, k2 / M]), G, K,
                      (BearingModal("support", beta, support, (0.0, 0.0)),),
                      eye, 1j * (np.outer(eye[0], eye[1]) - np.outer(eye[1], eye[0])),
                      ("bending", "bending"))


def growth(model: RotorModel, omega: float) -> float:
    """The fastest growth rate (1/s) of the rotor at the spin omega: its roots'."""
    r = roots(model, omega)
    g = float(np.max(r.lam.real)) if r.lam.size else -math.inf
    return max(g, r.divergence) if r.divergence > 0 else g


def stationary_multipliers(kx: float, ky: float, c: float, omega: float) -> np.ndarray:
    """The same rotor written directly in the stationary frame, x'' = -(K_s(t) x + c x')
    / m with the shaft's K_s(t) = R(Omega t) diag(k1, k2) R(Omega t)^T: its multipliers,
    integrated over one period pi / Omega from each unit state (scipy's DOP853)."""
    from scipy.integrate import solve_ivp

    def rhs(t: float, s: np.ndarray) -> np.ndarray:
        X = s.reshape(4, 4)
        a = omega * t
        R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        Ks = R @ np.diag([K1, K2]) @ R.T + np.diag([kx, ky])
        A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Ks / M, -c / M * np.eye(2)]])
        return (A @ X).ravel()

    sol = solve_ivp(rhs, (0.0, math.pi / omega), np.eye(4).ravel(), method="DOP853",
                    rtol=1e-12, atol=1e-14)
    return np.linalg.eigvals(sol.y[:, -1].reshape(4, 4))


def stationary_growth(kx: float, ky: float, c: float, omega: float) -> float:
    """The largest ln |mu| / T of stationary_multipliers."""
    mu = stationary_multipliers(kx, ky, c, omega)
    return float(np.max(np.log(np.abs(mu)))) / (math.pi / omega)


def edges(g, lo: float, hi: float, n: int = 240) -> list[float]:
    """Where g changes sign on [lo, hi]: scanned, then bisected to 1e-7."""
    from scipy.optimize import brentq

    xs = np.linspace(lo, hi, n)
    ys = [g(x) for x in xs]
    out = []
    for a, b, ya, yb in zip(xs[:-1], xs[1:], ys[:-1], ys[1:]):
        if ya * yb < 0:
            out.append(float(brentq(g, a, b, xtol=1e-7 * b)))
    return out


def test_the_deviatoric_part_turns_at_twice_the_angle():
    rng = np.random.default_rng(3)
    A = rng.normal(size=(2, 2))
    d, d2 = deviatoric_parts(A)
    np.testing.assert_allclose(isotropic_part(A) + d, A, atol=1e-14)
    for theta in (0.3, 1.1, 2.9):
        R = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
        np.testing.assert_allclose(R.T @ A @ R, isotropic_part(A) + d * math.cos(2 * theta)
                                   + d2 * math.sin(2 * theta), atol=1e-13)


def test_an_asymmetric_jeffcott_rotor_is_unstable_exactly_between_its_criticals():
    """Isotropic supports (kx = ky = 0 here: the shaft alone, undamped): the turning
    frame's equations are constant and a root diverges between sqrt(k1/m) and
    sqrt(k2/m), within 1e-4."""
    model = jeffcott(0.0, 0.0, c=0.0)
    w1, w2 = math.sqrt(K1 / M), math.sqrt(K2 / M)
    found = edges(lambda w: roots(model, w).divergence - 1e-6, 0.5 * w1, 1.5 * w2)
    assert len(found) == 2
    assert found[0] == pytest.approx(w1, rel=1e-4) and found[1] == pytest.approx(w2, rel=1e-4)


@pytest.mark.slow
def test_on_anisotropic_supports_every_zone_meets_a_direct_time_integration():
    """kx = 0.5 k1, ky = 1.5 k1, lightly damped: the periodic rotor's zones of growth
    from its Floquet exponents (Hill's method), their edges within 0.5 % in speed of
    those of the equations integrated in time in the stationary frame."""
    kx, ky = 0.5 * K1, 1.5 * K1
    model = jeffcott(kx, ky)
    lo, hi = 50.0, 1.6 * math.sqrt((K2 + ky) / M)
    ours = edges(lambda w: growth(model, w), lo, hi)
    theirs = edges(lambda w: stationary_growth(kx, ky, C, w), lo, hi)
    assert ours, "the rotor should have zones of growth to compare"
    assert len(ours) == len(theirs)
    np.testing.assert_allclose(ours, theirs, rtol=5e-3)


@pytest.mark.parametrize("rpm", [900.0, 2500.0, 4800.0])
def test_hill_and_the_monodromy_agree(rpm):
    """Both routes' exponents, each growth rate and its frequency modulo 2 Omega."""
    model = jeffcott(0.5 * K1, 1.5 * K1)
    omega = rpm * math.pi / 30
    assert routes_apart(model, omega) < 1e-7
    h = converged_hill(model, omega)
    mu = multipliers(model, omega)
    np.testing.assert_allclose(np.sort(np.abs(np.exp(h.lam * math.pi / omega))),
                               np.sort(np.abs(mu)), rtol=1e-7)


def test_a_round_rotor_in_anisotropic_supports_has_the_stationary_frame_s_roots():
    """k1 = k2: the stationary frame's equations are constant. Each of their roots
    lam_s is a Floquet exponent of the turning frame's periodic ones, lam_s - i Omega
    (modulo i 2 Omega), within 1e-8."""
    kx, ky = 0.4 * K1, 1.3 * K1
    model = jeffcott(kx, ky, k1=K1, k2=K1)
    for rpm in (700.0, 3100.0):
        omega = rpm * math.pi / 30
        A = np.block([[np.zeros((2, 2)), np.eye(2)],
                      [-(np.diag([kx, ky]) + K1 * np.eye(2)) / M, -C / M * np.eye(2)]])
        stationary = np.linalg.eigvals(A)
        h = converged_hill(model, omega)
        d = apart(stationary - 1j * omega, h.lam, omega)
        scale = float(np.abs(stationary).max())
        assert d.min(axis=1).max() < 1e-8 * scale


# --------------------------------------------------------------------------------------
# On the 3D solid


def stepped(frame: str) -> dict:
    """A stepped shaft (28/40/28 mm) with a wheel between two damped bearings stiffer
    along x than along y."""
    from test_rotor import STEEL

    brg = {"kind": "bearing", "width_mm": 14.0, "kxx_n_per_mm": 1.2e5, "kyy_n_per_mm": 6e4,
           "cxx_n_s_per_mm": 0.3, "cyy_n_s_per_mm": 0.2}
    return {"name": "stepped", "material": STEEL, "mesh": {"element_size_mm": 9.0},
            "section": [{"length_mm": 60.0, "diameter_mm": 28.0},
                        {"length_mm": 200.0, "diameter_mm": 40.0},
                        {"length_mm": 60.0, "diameter_mm": 28.0}],
            "support": [{**brg, "name": "left", "position_mm": 30.0},
                        {**brg, "name": "right", "position_mm": 290.0}],
            "attachment": [{"name": "wheel", "position_mm": 160.0, "width_mm": 30.0,
                            "mass_kg": 6.0, "polar_inertia_kg_m2": 0.02,
                            "diametral_inertia_kg_m2": 0.011, "joint": "distributing"}],
            "modes": {"count": 4},
            "rotor": {"speed_rpm": 6000.0, "max_speed_rpm": 24000.0, "campbell_points": 9,
                      "frame": frame}}


def either_frame(element_mm: float, first_pair: float) -> None:
    """stepped()'s rotor on `element_mm` elements solved in the stationary frame
    (constant coefficients) and in the turning frame (periodic, Floquet): the whirl at
    the running speed within 5e-4 (the first pair within `first_pair`), its log
    decrements within 2e-3 of themselves, the 1x critical speeds within 1e-4."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.campbell import run_campbell

    still, turning = (stepped(frame) for frame in ("stationary", "rotating"))
    for d in (still, turning):
        d["mesh"]["element_size_mm"] = element_mm
    still, turning = run_campbell(load_scene(still)), run_campbell(load_scene(turning))
    assert "Floquet" in turning.why
    a = sorted((w.frequency_hz, w.log_dec) for w in still.operating)
    b = sorted((w.frequency_hz, w.log_dec) for w in turning.operating)
    np.testing.assert_allclose([f for f, _ in b], [f for f, _ in a], rtol=5e-4)
    np.testing.assert_allclose([f for f, _ in b][:2], [f for f, _ in a][:2], rtol=first_pair)
    np.testing.assert_allclose([d for _, d in b], [d for _, d in a], rtol=2e-3, atol=1e-6)
    x = sorted(cs.speed_rpm for cs in still.critical_speeds if cs.order == 1)
    y = sorted(cs.speed_rpm for cs in turning.critical_speeds if cs.order == 1)
    assert x and len(x) == len(y)
    np.testing.assert_allclose(y, x, rtol=1e-4)
    seen_alike(still, turning)


def seen_alike(still, turning) -> None:
    """The housing sees one whirl whichever frame solved it: each mode's whirl and
    index (within 0.01), and its orbit at the wheel (its own whirl index, the forward
    less the backward circle's square over their sum, within 0.01; the direction of its
    major axis within 1 deg). The stationary frame's ellipse
    is its constant mode's own; the turning frame's is what its Floquet form's harmonics
    show the housing (fem.rotor.seen_shape)."""
    from shaftfem.outputs.whirl_files import complex_shapes

    a, b = still.operating, turning.operating
    assert [w.whirl for w in b] == [w.whirl for w in a]
    np.testing.assert_allclose([w.whirl_index for w in b], [w.whirl_index for w in a],
                               atol=0.01)
    pts = still.result.mesh.points
    at = (np.abs(pts[:, 2] - 0.160) < 0.004) & (np.hypot(pts[:, 0], pts[:, 1]) < 0.008)
    assert at.sum() >= 3

    def ellipse(u):
        x, y = u[at, 0].mean(), u[at, 1].mean()
        f, g = 0.5 * (x + 1j * y), 0.5 * np.conj(x - 1j * y)     # z = f e^it + g e^-it
        return ((abs(f) ** 2 - abs(g) ** 2) / (abs(f) ** 2 + abs(g) ** 2),
                (0.5 * (np.angle(f) + np.angle(g))) % math.pi)

    for k, w in enumerate(a):
        if w.kind != "bending":
            continue
        (ra, ta), (rb, tb) = ellipse(complex_shapes(still, 0)[k]), ellipse(
            complex_shapes(turning, 0)[k])
        assert rb == pytest.approx(ra, abs=0.01), (w, ra, rb)
        gap = abs(ta - tb) % math.pi
        assert min(gap, math.pi - gap) < math.radians(1.0), (w, ta, tb)


@pytest.mark.slow
def test_a_round_shaft_in_anisotropic_bearings_is_one_answer_in_either_frame():
    """On 9 mm elements the first pair agrees within 1e-5; the second, the wheel's
    gyroscopic pair, differs by 2.5e-4 and 4.6e-4 on any basis, 18 or 40 modes."""
    either_frame(9.0, 1e-5)


@pytest.mark.slow
def test_a_round_shaft_in_anisotropic_bearings_is_one_answer_in_either_frame_coarse():
    """The fast twin: on 12 mm elements the first pair agreed within 5e-5 (the frames'
    bases resolve it less alike), the rest as on 9 mm (2.3e-4, 4e-4 and 4e-5 measured)."""
    either_frame(12.0, 1e-4)


@pytest.mark.parametrize("rpm", [1500.0, 2900.0, 3800.0, 6000.0])
def test_the_unbalance_response_by_harmonic_balance_meets_the_stationary_closed_form(rpm):
    """A round Jeffcott rotor on supports kx != ky, damped: its unbalance response solved
    in the turning frame (periodic: harmonic balance) is the stationary frame's steady
    ellipse, (K_s - Omega^2 m + i Omega c) X = m e Omega^2 (1, -i) exp(i phi): its x
    amplitude and phase and its major semi-axis within 1e-8."""
    from shaftfem.fem.floquet import any_unbalance_response as unbalance_response
    from shaftfem.fem.rotor import orbit

    kx, ky = 0.4 * K1, 1.3 * K1
    model = jeffcott(kx, ky, k1=K1, k2=K1)
    omega = rpm * math.pi / 30
    me, phi = 2e-5, 0.7
    beta = np.eye(2) / math.sqrt(M)
    y = unbalance_response(model, omega, [(beta, me * np.exp(1j * phi))])
    A = np.diag([kx + K1, ky + K1]) - omega**2 * M * np.eye(2) + 1j * omega * C * np.eye(2)
    X, Y = np.linalg.solve(A, me * omega**2 * np.exp(1j * phi) * np.array([1.0, -1j]))
    amp_x, major, phase_x, amp_y, _ = orbit(model, beta, y)
    assert amp_x == pytest.approx(abs(X), rel=1e-8)
    assert amp_y == pytest.approx(abs(Y), rel=1e-8)
    assert math.cos(phase_x - np.angle(X)) == pytest.approx(1.0, abs=1e-10)
    assert major == pytest.approx(0.5 * (abs(X + 1j * Y) + abs(X - 1j * Y)), rel=1e-8)


def keyed(kyy_share: float, depth_mm: float | None = 2.0, kxx: float = 2e4) -> dict:
    """stepped()'s shaft with a 10 mm wide keyway under the wheel's side (depth_mm deep;
    None: no keyway), in bearings kxx and kyy = kyy_share kxx (N/mm), damped alike."""
    d = stepped("auto")
    for s in d["support"]:
        s.update(kxx_n_per_mm=kxx, kyy_n_per_mm=kyy_share * kxx,
                 cyy_n_s_per_mm=s["cxx_n_s_per_mm"])
    if depth_mm is not None:
        d["keyway"] = [{"position_mm": 200.0, "length_mm": 60.0, "width_mm": 10.0,
                        "depth_mm": depth_mm}]
    return d


def first_criticals(d: dict) -> tuple[list[float], str]:
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.campbell import run_campbell

    c = run_campbell(load_scene(d))
    return sorted(cs.speed_rpm for cs in c.critical_speeds if cs.order == 1), c.why


@pytest.mark.slow
def test_one_percent_of_anisotropy_moves_a_keyed_shaft_s_criticals_by_little():
    """A keyed shaft in bearings kyy = 0.99 kxx (periodic: Floquet) against the same
    shaft in kyy = kxx (constant in the turning frame): each 1x critical speed within
    0.5 % (the 1 % softer diameter moves them by about 0.1-0.2 %)."""
    iso, why_iso = first_criticals(keyed(1.0))
    near, why = first_criticals(keyed(0.99))
    assert "Floquet" in why and "Floquet" not in why_iso
    assert iso and len(near) == len(iso)
    np.testing.assert_allclose(near, iso, rtol=5e-3)
    assert all(a <= b for a, b in zip(near, iso))   # softer bearings, lower criticals


@pytest.mark.slow
def test_a_keyway_shrinking_towards_nothing_tends_to_the_round_shaft():
    """In bearings kyy = kxx / 2, a keyway 2, 0.5 and 0.1 mm deep (periodic: Floquet in
    the turning frame) against the round shaft (constant: stationary frame): the first
    1x critical speed's distance falls with the depth, and within 0.01 % at 0.1 mm."""
    round_, why = first_criticals(keyed(0.5, None, kxx=1.2e5))
    assert "Floquet" not in why and round_
    gaps = []
    for depth in (2.0, 0.5, 0.1):
        crit, why = first_criticals(keyed(0.5, depth, kxx=1.2e5))
        assert "Floquet" in why
        gaps.append(abs(crit[0] - round_[0]) / round_[0])
    assert gaps[0] > gaps[1] > gaps[2]
    assert gaps[2] < 1e-4


def test_the_weight_of_an_asymmetric_shaft_peaks_at_2x_near_half_its_critical_speed():
    """An asymmetric Jeffcott rotor (k1 != k2 along the shaft's principal axes) on round,
    damped supports under its own weight: seen from the shaft the weight turns backwards
    at Omega, and the shaft's asymmetry turns the sag into a 2x whirl, resonant where
    2 Omega meets the natural frequency (the "secondary critical" of slotted generator
    rotors). Its peak, by gravity_response (harmonic balance in the turning frame) and
    stationary_orders, against the closed form written here (the turning frame's 2x2
    equations at -Omega): speed and amplitude within 1 %; the peak lies within 5 % of
    half the critical speed sqrt((k_mean + k_s) / m)."""
    from shaftfem.fem.floquet import gravity_response, stationary_orders

    ks, c, g = 0.5 * K1, 20.0, 9.80665
    model = jeffcott(ks, ks, c)
    beta = np.eye(2) / math.sqrt(M)
    load = -1j * g * math.sqrt(M) * np.array([1.0, -1j])    # A (p_x - i p_y), A = -i g

    def ours(omega: float) -> float:
        c_ = stationary_orders(beta, gravity_response(model, omega, load))
        return abs(c_[1]) + abs(c_[-1])

    def closed(omega: float) -> float:
        s = -1j * omega
        Z = np.array([[M * s * s + c * s + K1 + ks - M * omega**2, -2 * M * omega * s - c * omega],
                      [2 * M * omega * s + c * omega, M * s * s + c * s + K2 + ks - M * omega**2]])
        X = np.linalg.solve(Z, -1j * M * g * np.array([1.0, -1j]))
        return abs(0.5 * (X[0].conjugate() + 1j * X[1].conjugate()))

    def peak(f) -> tuple[float, float]:
        from scipy.optimize import minimize_scalar

        grid = np.linspace(50.0, 400.0, 701)
        i = int(np.argmax([f(w) for w in grid]))
        r = minimize_scalar(lambda w: -f(w), bounds=(grid[i - 1], grid[i + 1]),
                            method="bounded", options={"xatol": 1e-8})
        return float(r.x), float(-r.fun)

    for w in (100.0, 200.0, 300.0):
        assert ours(w) == pytest.approx(closed(w), rel=1e-10)
    (w0, a0), (w1, a1) = peak(closed), peak(ours)
    assert w1 == pytest.approx(w0, rel=1e-2) and a1 == pytest.approx(a0, rel=1e-2)
    critical = math.sqrt((0.5 * (K1 + K2) + ks) / M)
    assert w0 == pytest.approx(critical / 2, rel=0.05)
    assert a0 > 5 * closed(0.25 * critical)   # a resonance, not a drift


@pytest.mark.slow
def test_a_keyed_shaft_s_weight_sags_it_by_statics_and_whirls_at_half_its_critical():
    """The keyed stepped shaft with its 6 kg wheel midway between round bearings
    (2e4 N/mm): its weight, seen turning backwards from the shaft (harmonic balance on
    the 3D model), sags each bearing seat by its reaction over its stiffness, the
    reactions from statics (each half the weight of shaft and wheel: the shaft is
    symmetric but for its 9 g of keyway) within 0.5 % (measured 0.07 and 0.12 %); and the
    2x whirl it drives peaks within 3 % of half the shaft's first forward 1x critical
    speed (measured 1e-5: the wheel's gyroscopic moments barely move that mode)."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.campbell import run_campbell
    from test_rotor import STEEL

    d = keyed(1.0)
    c = run_campbell(load_scene(d))
    assert c.frame == "rotating" and len(c.weight_2x) == 2
    rho, g = STEEL["density_kg_m3"], 9.80665
    shaft = rho * math.pi / 4 * (0.028**2 * 0.120 + 0.040**2 * 0.200)
    half = 0.5 * (shaft + 6.0) * g
    k = d["support"][0]["kxx_n_per_mm"] * 1e3
    for w in c.weight_2x:
        assert w.sag == pytest.approx(half / k, rel=5e-3)
    forward = min(cs.speed_rpm for cs in c.critical_speeds
                  if cs.order == 1 and cs.whirl == "forward")
    for w in c.weight_2x:
        assert w.speed_rpm == pytest.approx(forward / 2, rel=3e-2)
        assert w.amplitude > 3 * w.at_operating or w.speed_rpm > 0.9 * max(c.operating_rpm)


def test_a_run_up_in_the_turning_frame_meets_the_stationary_frame_s_integration():
    """The asymmetric Jeffcott rotor on anisotropic supports run up through its critical
    speeds and the zone between them with an unbalance, integrated in the frame turning
    with the shaft (workflows.runup: the bearings turned, the unbalance standing still,
    the Euler force of the acceleration) against its equations in the stationary frame
    written here (the shaft's stiffness turned, the unbalance's centripetal and
    tangential force; scipy's DOP853): the disk's motion as the housing sees it agrees
    within 1 % of its largest excursion at every step."""
    from scipy.integrate import solve_ivp

    from shaftfem.workflows.runup import newmark_run_up

    kx, ky = 0.5 * K1, 1.0 * K1
    model = jeffcott(kx, ky)
    U = 2e-5 * complex(math.cos(0.3), math.sin(0.3))      # kg m, at 0.3 rad
    beta = np.eye(2) / math.sqrt(M)
    start, stop, accel = 2500 * math.pi / 30, 5500 * math.pi / 30, 6000 * math.pi / 30
    times, speeds, (ours,) = newmark_run_up(model, start, stop, accel, [(beta, U)], [beta],
                                            steps_per_turn=400)

    def rhs(t: float, s: np.ndarray) -> np.ndarray:
        w, phi = start + accel * t, start * t + 0.5 * accel * t * t
        R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        Ks = R @ np.diag([K1, K2]) @ R.T + np.diag([kx, ky])
        c = U * complex(math.cos(phi), math.sin(phi))
        f = np.array([w * w * c.real + accel * c.imag, w * w * c.imag - accel * c.real])
        return np.concatenate([s[2:], (f - Ks @ s[:2] - C * s[2:]) / M])

    ref = solve_ivp(rhs, (0.0, float(times[-1])), np.zeros(4), method="DOP853",
                    t_eval=times, rtol=1e-10, atol=1e-14).y[:2]
    scale = float(np.abs(ref).max())
    assert scale > 0
    assert float(np.abs(ours - ref).max()) < 0.01 * scale


@pytest.mark.parametrize("side", [-1, 1])
def test_a_free_motion_integrated_in_time_grows_inside_every_zone_and_decays_outside(side):
    """A third route to the zones, beside Hill's method and the monodromy matrix: the
    free motion of the asymmetric Jeffcott rotor on anisotropic supports, integrated in
    the turning frame at a constant spin (workflows.runup.integrate) from a push, over
    200 periods: 1 % inside each edge of each zone Hill's method finds, the motion grows;
    1 % outside, it decays; where it grows, at the rate Hill's method gives within 3 %
    (measured over periods 150 to 200, when the other forms are spent)."""
    from shaftfem.workflows.runup import integrate

    model = jeffcott(0.5 * K1, 1.5 * K1)
    found = edges(lambda w: growth(model, w), 150.0, 700.0)
    assert len(found) >= 2
    beta = np.eye(2) / math.sqrt(M)
    for i, edge in enumerate(found):
        inside_above = growth(model, edge * 1.01) > 0
        omega = edge * (1 + side * 0.01)
        grows = (side > 0) == inside_above
        T = math.pi / omega
        times = np.linspace(0.0, 200 * T, 200 * 100 + 1)
        (xy,) = integrate(model, omega, 0.0, times, [], [beta], q0=np.array([1e-3, 1e-3]))
        r = np.hypot(xy[0], xy[1])
        # the largest excursion over periods 150-160 and 190-200 (the other forms spent)
        first, last = r[150 * 100:160 * 100].max(), r[-10 * 100:].max()
        rate = math.log(last / first) / (40 * T)
        assert (rate > 0) == grows, (i, edge, side, rate)
        if grows:
            assert rate == pytest.approx(growth(model, omega), rel=0.03)


def test_the_unbalance_s_1x_and_3x_by_harmonic_balance_meet_a_time_integration():
    """The asymmetric Jeffcott rotor on anisotropic supports under an unbalance at a speed
    outside its zones: its steady orbit by harmonic balance in the turning frame
    (periodic_unbalance, read at the housing by unbalance_orders) against its equations
    in the stationary frame integrated from rest until the start has died away (scipy's
    DOP853), Fourier coefficients over whole turns: the 1x within 1e-4 of it, the 3x
    (which the stiff and soft diameters in bearings that differ along x and y add)
    within 1 % of itself, and not small (above 1 % of the 1x)."""
    from scipy.integrate import solve_ivp

    from shaftfem.fem.floquet import periodic_unbalance, unbalance_orders

    kx, ky, c = 0.5 * K1, 1.5 * K1, 40.0
    model = jeffcott(kx, ky, c)
    omega = 260.0                                            # rad/s, below the zones
    assert growth(model, omega) < 0
    U = 2e-5 * complex(math.cos(0.3), math.sin(0.3))
    beta = np.eye(2) / math.sqrt(M)
    ours = unbalance_orders(beta, periodic_unbalance(model, omega, [(beta, U)]))

    def rhs(t: float, s: np.ndarray) -> np.ndarray:
        phi = omega * t
        R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        Ks = R @ np.diag([K1, K2]) @ R.T + np.diag([kx, ky])
        f = omega**2 * U * complex(math.cos(phi), math.sin(phi))
        return np.concatenate([s[2:], (np.array([f.real, f.imag]) - Ks @ s[:2] - c * s[2:]) / M])

    turn = 2 * math.pi / omega
    t0, turns = 30 * M / c * 2, 20          # the start decays by e^-30 first
    t = t0 + np.linspace(0.0, turns * turn, turns * 256, endpoint=False)
    sol = solve_ivp(rhs, (0.0, float(t[-1])), np.zeros(4), method="DOP853", t_eval=t,
                    rtol=1e-11, atol=1e-16)
    z = sol.y[0] + 1j * sol.y[1]

    def coefficient(m: int) -> complex:
        return complex(np.mean(z * np.exp(-1j * m * omega * t)))

    one = coefficient(1)
    assert abs(ours[1] - one) < 1e-4 * abs(one)
    for m in (3, -3, -1):
        assert abs(ours[m] - coefficient(m)) < 0.01 * abs(coefficient(m)) + 1e-6 * abs(one)
    assert abs(ours[3]) + abs(ours[-3]) > 0.01 * abs(one)


@pytest.mark.parametrize("rpm", [1500.0, 4000.0])
def test_the_receptance_of_a_round_rotor_seen_from_the_shaft_is_the_stationary_closed_form(rpm):
    """A round Jeffcott rotor (k1 = k2) on supports kx != ky, solved in the frame turning
    with it (the force turns backwards there, the supports turn at 2 Omega: harmonic
    balance), read at the housing: its receptance equals the stationary frame's closed
    form (K - w^2 m + i w c)^-1, K = diag(k1 + kx, k1 + ky), within 1e-9, across the
    resonances."""
    from shaftfem.fem.floquet import stationary_receptance

    kx, ky = 0.5 * K1, 1.5 * K1
    model = jeffcott(kx, ky, C, K1, K1)
    beta = np.eye(2) / math.sqrt(M)
    omega = rpm * math.pi / 30
    for f in (20.0, 79.0, 100.7, 140.0):
        w = 2 * math.pi * f
        closed = np.linalg.inv(np.diag([K1 + kx, K1 + ky]) - w * w * M * np.eye(2)
                               + 1j * w * C * np.eye(2))
        ours = stationary_receptance(model, omega, w, beta, beta)
        assert np.abs(ours - closed).max() < 1e-9 * np.abs(closed).max()


def test_the_receptance_of_an_asymmetric_rotor_meets_a_time_integration():
    """The asymmetric Jeffcott rotor on anisotropic supports at a speed outside its
    zones, forced along x at the housing at w: its motion at exp(i w t) by harmonic
    balance (stationary_receptance) against its stationary-frame equations integrated
    until the start has died away, read by a Fourier coefficient over a common period:
    within 1e-4."""
    from scipy.integrate import solve_ivp

    from shaftfem.fem.floquet import stationary_receptance

    kx, ky, c = 0.5 * K1, 1.5 * K1, 40.0
    model = jeffcott(kx, ky, c)
    omega = 260.0
    w = 1.5 * omega                  # the force's frequency: a common period 4 pi / omega
    ours = stationary_receptance(model, omega, w, np.eye(2) / math.sqrt(M),
                                 np.eye(2) / math.sqrt(M))

    def rhs(t: float, s: np.ndarray) -> np.ndarray:
        phi = omega * t
        R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        Ks = R @ np.diag([K1, K2]) @ R.T + np.diag([kx, ky])
        f = np.array([math.cos(w * t), 0.0])
        return np.concatenate([s[2:], (f - Ks @ s[:2] - c * s[2:]) / M])

    period = 4 * math.pi / omega
    t = 30 * M / c * 2 + np.linspace(0.0, 10 * period, 10 * 512, endpoint=False)
    sol = solve_ivp(rhs, (0.0, float(t[-1])), np.zeros(4), method="DOP853", t_eval=t,
                    rtol=1e-11, atol=1e-18)
    X = 2 * np.mean(sol.y[0] * np.exp(-1j * w * t))
    Y = 2 * np.mean(sol.y[1] * np.exp(-1j * w * t))
    assert abs(ours[0, 0] - X) < 1e-4 * abs(X)
    assert abs(ours[1, 0] - Y) < 1e-4 * abs(X)


def zones_on(points: int) -> tuple[list[float], list[float]]:
    """The zones of the rotor above (kx = 0.5 k1, ky = 1.5 k1) as a Campbell run finds
    them on a grid of `points` speeds from 150 to 700 rad/s, and as a scan of 240 speeds
    bisected finds them: their edges, rad/s."""
    from shaftfem.fem.tracking import track
    from shaftfem.workflows.campbell import RPM, divergent_bands, parametric_zones

    model = jeffcott(0.5 * K1, 1.5 * K1)
    lo, hi = 150.0, 700.0
    scanned = edges(lambda w: growth(model, w), lo, hi)
    grid = np.linspace(lo, hi, points)
    curves = track(model, grid, 4)
    bands = divergent_bands(model, grid)
    found = sorted([*(b[:3] for b in bands),
                    *(z[:3] for z in parametric_zones(model, grid, curves, bands))])
    assert all(g > 0 for _, _, g in found)
    return [w * RPM for z in found for w in z[:2]], scanned


@pytest.mark.parametrize("points", [4, 5, 6, 8, 10])
def test_a_coarse_grid_finds_true_zones_each_whole(points):
    """On grids of 4 to 10 speeds a zone between two speeds may be missed, but every
    zone found is one of the scan's, both its edges within 1e-6, never two run into one
    (the step between a growing speed and one that does not is tried at its quarters
    before its edge is bisected: it may hold another zone)."""
    ours, scanned = zones_on(points)
    assert ours, "some zone is found"
    pairs = list(zip(scanned[0::2], scanned[1::2]))
    for lo, hi in zip(ours[0::2], ours[1::2]):
        assert any(abs(lo / a - 1) <= 1e-6 and abs(hi / b - 1) <= 1e-6 for a, b in pairs), (
            (lo, hi), pairs)


@pytest.mark.parametrize("points", [7, 9, 11, 21, 40])
def test_the_campbell_run_finds_every_zone_whatever_its_grid(points):
    """The zones of the rotor above (kx = 0.5 k1, ky = 1.5 k1), as a Campbell run finds
    them on a grid of 7 to 40 speeds from 150 to 700 rad/s (workflows.campbell:
    divergence bands and parametric zones, the latter sought where two curves'
    frequencies meet 2 k n between the grid's speeds), against a scan of 240 speeds
    bisected: the same zones, their edges within 1e-6."""
    ours, scanned = zones_on(points)
    assert len(ours) == len(scanned), (ours, scanned)
    np.testing.assert_allclose(ours, scanned, rtol=1e-6)


@pytest.mark.parametrize("rpm", [700.0, 2600.0])
def test_every_harmonic_of_a_round_rotor_s_floquet_form_lies_on_a_stationary_frequency(rpm):
    """A round Jeffcott rotor on supports kx != ky, seen from the turning shaft, is a
    periodic rotor whose forms spread over harmonics 2 n apart (fem.floquet: Roots.sides,
    drawn thin on the Campbell diagram); seen from the housing it has just its two
    stationary frequencies. Every line a form shows there, its dominant harmonic's and
    its side harmonics' (turning frame f + 2 d n, seen at +-n), with a share of at least
    5 % of its motion, lies on one of them within 1e-6; the shares sum to 1."""
    from shaftfem.fem.floquet import floquet_roots

    kx, ky = 0.5 * K1, 1.5 * K1
    model = jeffcott(kx, ky, C, K1, K1)
    omega = rpm * math.pi / 30
    n = omega / (2 * math.pi)
    A = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [-np.diag([K1 + kx, K1 + ky]) / M, -C / M * np.eye(2)]])
    still = np.sort(np.abs(np.linalg.eigvals(A).imag))[::2] / (2 * math.pi)
    r = floquet_roots(model, omega)
    assert r.sides is not None and r.side_index is not None
    S = (r.sides.shape[0] - 1) // 2
    lines = 0
    for j in range(r.lam.size):
        f = r.lam[j].imag / (2 * math.pi)
        assert r.sides[:, j].sum() <= 1 + 1e-9
        for row, d in enumerate(range(-S, S + 1)):
            for v, part in ((f + 2 * d * n + n, 0.5 * (1 + r.side_index[row, j])),
                            (f + 2 * d * n - n, 0.5 * (1 - r.side_index[row, j]))):
                if r.sides[row, j] * part >= 0.05:
                    lines += 1
                    assert np.min(np.abs(still - abs(v))) < 1e-6 * abs(v), (v, still)
    assert lines >= 2


def test_a_round_rotor_seen_from_the_shaft_crosses_the_order_lines_at_its_stationary_criticals():
    """The round Jeffcott rotor on supports kx != ky solved in the turning frame (its
    forms hold two equal harmonics: the one kept must not flip from speed to speed),
    every component and side harmonic searched (workflows.campbell.critical_speeds):
    exactly its stationary frame's crossings, 1x at its damped frequencies along x and y
    and 2x at half of them, within 1e-6; no other."""
    from shaftfem.fem.tracking import track
    from shaftfem.workflows.campbell import RPM, critical_speeds, with_sides

    kx, ky = 0.5 * K1, 1.5 * K1
    model = jeffcott(kx, ky, C, K1, K1)
    grid = np.linspace(30.0, 700.0, 37)
    curves = [with_sides(model, c) for c in track(model, grid, 4)]
    found, _ = critical_speeds(model, curves, (1, 2), 700.0)
    # (the damped frequencies: sqrt(k / m - (c / 2 m)^2))
    wx, wy = (math.sqrt((K1 + k) / M - (C / (2 * M)) ** 2) for k in (kx, ky))
    expected = sorted([(1, wx), (1, wy), (2, wx / 2), (2, wy / 2)], key=lambda x: x[1])
    ours = sorted(((c.order, c.speed_rpm * RPM) for c in found), key=lambda x: x[1])
    assert [o for o, _ in ours] == [o for o, _ in expected]
    np.testing.assert_allclose([w for _, w in ours], [w for _, w in expected], rtol=1e-6)


def test_a_periodic_rotor_s_crossings_are_found_twice():
    """The direct route for a periodic rotor (fem.floquet.periodic_order_roots: Hill's
    equations at the crossing, linear in Omega^2): on the undamped round Jeffcott rotor
    on supports kx != ky, solved in the turning frame, exactly the stationary frame's
    crossings, 1x at sqrt((k + kx) / m) and sqrt((k + ky) / m) and 2x at half of them,
    within 1e-8, the same four on the curves followed by shape, none by one route only;
    on an asymmetric shaft on those supports (no closed form), each crossing found
    directly is one: at its speed Hill's method (the Floquet exponents, solved on their
    own) has an exponent i m Omega, m the component's order in the turning frame."""
    from shaftfem.fem.tracking import direct_crossings, track
    from shaftfem.workflows.campbell import critical_speeds, with_sides

    kx, ky = 0.5 * K1, 1.5 * K1
    model = jeffcott(kx, ky, 0.0, K1, K1)
    wx, wy = (math.sqrt((K1 + k) / M) for k in (kx, ky))
    direct = sorted((d.order, d.omega) for d in direct_crossings(model, (1, 2), 700.0))
    expected = sorted([(1, wx), (1, wy), (2, wx / 2), (2, wy / 2)])
    assert [o for o, _ in direct] == [o for o, _ in expected]
    np.testing.assert_allclose([w for _, w in direct], [w for _, w in expected], rtol=1e-8)
    curves = [with_sides(model, c) for c in track(model, np.linspace(30.0, 700.0, 37), 4)]
    found, check = critical_speeds(model, curves, (1, 2), 700.0)
    assert check.applies and len(found) == 4, check
    assert check.direct == 4 and check.direct_only == 0 and check.curves_only == 0, check
    assert check.largest_difference <= 1e-8
    model = jeffcott(kx, ky, 0.0, K1, K2)
    direct = direct_crossings(model, (1, 2), 700.0)
    assert len(direct) >= 4
    for d in direct:
        m = d.order - 1 if d.component == "forward" else d.order + 1
        lam = converged_hill(model, d.omega).lam
        near = apart(lam, np.array([1j * m * d.omega]), d.omega).min()
        assert near <= 1e-6 * d.omega, (d, near)


@pytest.mark.slow
def test_a_standing_stretch_inside_one_grid_step_gives_both_its_ends():
    """The keyed shaft on undamped isotropic bearings given as a speed table (so only the
    curves find its crossings): its pair stands at zero frequency in the turning frame
    over some 50 r/min, inside one step of the diagram's 3,000 r/min grid. Both ends of
    that stretch are 1x forward critical speeds, equal to those of the same bearings
    given as constants (there found directly too, an eigenproblem in the speed squared),
    within 1e-6."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.campbell import run_campbell

    def rotor(table: bool) -> dict:
        d = keyed(1.0)
        # 12 mm elements (9 mm elsewhere): the stretch is as narrow (49 r/min), the two
        # routes agreed within 4e-13 there, and the test takes half the time
        d["mesh"]["element_size_mm"] = 12.0
        for s in d["support"]:
            for key in ("cxx_n_s_per_mm", "cyy_n_s_per_mm"):
                s.pop(key, None)
            if table:
                s.update(speeds_rpm=[0.0, 24000.0], kxx_n_per_mm=[2e4, 2e4],
                         kyy_n_per_mm=[2e4, 2e4])
        return d

    def forward(d: dict) -> tuple[list[float], bool]:
        c = run_campbell(load_scene(d))
        applies = c.crossing_check is not None and c.crossing_check.applies
        return sorted(x.speed_rpm for x in c.critical_speeds
                      if x.order == 1 and x.whirl == "forward"), applies

    on_curves, direct = forward(rotor(True))
    both, applies = forward(rotor(False))
    assert not direct and applies
    assert len(on_curves) == len(both) >= 2
    np.testing.assert_allclose(on_curves, both, rtol=1e-6)


def test_a_curve_s_own_growth_past_its_onset_is_no_zone_of_its_own():
    """A zone of growth the diagram's end closes, starting a little above a curve's onset
    (its edge counts growth from a log decrement of -1e-4, so it lies above the onset by
    as much as the damping falls slowly: here 1.5e-4 of the speed), is that curve's own
    growth, not a parametric resonance; one that starts where every curve decays is a
    zone."""
    from dataclasses import replace

    from shaftfem.fem.whirl import Curve, Onset
    from shaftfem.workflows.campbell import _onset_s_own

    speeds = np.array([5000.0, 6000.0, 7000.0, 12000.0])
    decay = np.array([3.0, 1.0, -0.5, -6.0])        # 1/s: grows from 6,667 r/min
    curve = Curve(number=2, frame="rotating", speeds_rpm=speeds, signed_hz=np.full(4, 50.0),
                  decay=decay, index=np.ones(4), kinds=("bending",) * 4,
                  shapes=np.zeros((1, 4)))
    onset = [Onset(6666.7, "forward", 2, 55.7)]
    assert _onset_s_own(6667.7, onset, [curve])
    assert not _onset_s_own(5500.0, onset, [curve])       # below the onset: a zone
    recovering = replace(curve, decay=np.array([3.0, 1.0, -0.5, 2.0]))
    assert not _onset_s_own(9500.0, onset, [recovering])   # the curve decays there again


def test_each_rotor_keeps_its_own_roots_and_they_go_with_it():
    """Level I makes one rotor per applied Q, each freed before the next: every one's
    growth meets the stationary frame's integration, and its remembered solves go
    when it does (a memo keyed by a reused id would hand a new rotor an old one's
    roots)."""
    import gc
    from dataclasses import replace

    from shaftfem.fem import floquet

    base = jeffcott(1e4, 1.5e4)
    omega = math.sqrt((K1 + K2 + 5e4) / (2 * M))
    grown = []
    for kx in (1e4, 3e4, 6e4, 1e5):
        support = BearingCoefficients(speeds=(), kxx=(kx,), kxy=(0.0,), kyx=(0.0,),
                                      kyy=(1.5 * kx,), cxx=(C,), cxy=(0.0,), cyx=(0.0,),
                                      cyy=(C,))
        model = replace(base, bearings=(replace(base.bearings[0], coefficients=support),))
        g = growth(model, omega)
        assert g == pytest.approx(stationary_growth(kx, 1.5 * kx, C, omega), abs=1e-6)
        grown.append(g)
        key = id(model)
        assert key in floquet._MEMOS
        del model
        gc.collect()
        assert key not in floquet._MEMOS
    assert len(set(np.round(grown, 3))) == len(grown)   # four rotors, four answers



def test_a_periodic_rotor_s_1x_criticals_are_the_edges_of_its_bands_locked_to_the_speed():
    """An asymmetric Jeffcott rotor (k1 != k2) on supports kx != ky, damped: its 1x
    crossings are bands, not points, where a pair of multipliers (integrated in the
    stationary frame, apart from shaftfem) stands on the negative real axis: a motion
    locked to the speed. Its unbalance response peaks at the bands' edges, and those
    edges are the critical speeds shaftfem lists (within 1e-5), each once, none inside a
    band (the curves followed by shape met the line at 406 and 416 rad/s inside the
    first) and none elsewhere (the curves' jumps from root to root crossed it at 453, 459
    and 484 rad/s, where no exponent is seen at 1x)."""
    from shaftfem.fem.tracking import track
    from shaftfem.workflows.campbell import RPM, critical_speeds, with_sides

    kx, ky, c = 0.5 * K1, 1.5 * K1, 12.0

    def locked(omega: float) -> bool:
        mu = stationary_multipliers(kx, ky, c, omega)
        pair = mu[(mu.real < 0) & (np.abs(mu.imag) <= 1e-9 * np.abs(mu))]
        return pair.size >= 2 and float(np.ptp(np.abs(pair))) > 1e-9

    def edge(inside: float, outside: float) -> float:
        while abs(inside - outside) > 1e-8 * inside:
            mid = 0.5 * (inside + outside)
            inside, outside = (mid, outside) if locked(mid) else (inside, mid)
        return 0.5 * (inside + outside)

    grid = np.linspace(300.0, 650.0, 71)
    on = [locked(w) for w in grid]
    bands = []
    for i in range(1, len(grid)):
        if on[i] and not on[i - 1]:
            bands.append(edge(grid[i], grid[i - 1]))
        if on[i - 1] and not on[i]:
            bands.append(edge(grid[i - 1], grid[i]))
    assert len(bands) == 4, bands    # two bands
    model = jeffcott(kx, ky, c, K1, K2)
    curves = [with_sides(model, cv) for cv in track(model, np.linspace(30.0, 700.0, 60), 4)]
    found, _ = critical_speeds(model, curves, (1,), 700.0)
    ours = sorted(cs.speed_rpm * RPM for cs in found if 300.0 <= cs.speed_rpm * RPM <= 650.0)
    np.testing.assert_allclose(ours, bands, rtol=1e-5)


def stationary_whirl(kx: float, ky: float, c: float, omega: float) -> float:
    """The whirl index of the same rotor's motion locked to the speed, from its stationary
    frame alone: each of the pair of real negative multipliers' forms integrated over two
    periods (2 pi / Omega), its growth taken out, z = x + i y split by FFT into the
    orders turning with the shaft and against it: (forward - backward) / all of |c_m|^2,
    the two forms' mean."""
    from scipy.integrate import solve_ivp

    def rhs(t: float, s: np.ndarray) -> np.ndarray:
        a = omega * t
        R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        Ks = R @ np.diag([K1, K2]) @ R.T + np.diag([kx, ky])
        return np.concatenate([s[2:], -(Ks @ s[:2] + c * s[2:]) / M])

    T = math.pi / omega
    mono = solve_ivp(lambda t, s: np.stack([rhs(t, col) for col in s.reshape(4, 4).T], 1).ravel(),
                     (0.0, T), np.eye(4).ravel(), method="DOP853", rtol=1e-12, atol=1e-14)
    mu, vec = np.linalg.eig(mono.y[:, -1].reshape(4, 4))
    pair = np.flatnonzero((mu.real < 0) & (np.abs(mu.imag) <= 1e-9 * np.abs(mu)))
    assert pair.size == 2, mu
    n = 256
    t = np.arange(n) * 2 * T / n
    out = []
    for j in pair:
        sol = solve_ivp(rhs, (0.0, 2 * T), vec[:, j].real, method="DOP853", t_eval=t,
                        rtol=1e-12, atol=1e-14)
        z = (sol.y[0] + 1j * sol.y[1]) * np.exp(-math.log(abs(mu[j].real)) * t / T)
        cm = np.fft.fft(z) / n                       # order m at index m (mod n)
        m = np.fft.fftfreq(n, 1.0 / n)
        e = np.abs(cm) ** 2
        out.append(float((e[m > 0].sum() - e[m < 0].sum()) / e.sum()))
    return float(np.mean(out))


def test_a_periodic_rotor_s_critical_speeds_do_not_depend_on_the_speeds_its_curves_follow():
    """The same asymmetric Jeffcott rotor's 1x critical speeds, its curves followed on two
    grids (as two running speeds give the diagram): the same list, speed, whirl and log
    decrement, each locked band's edge whirling as its locked motion does in the
    stationary frame alone (the orbit's orders, stationary_whirl: +0.247, -0.238, -0.245,
    +0.240 at 401, 432, 514 and 538 rad/s; the index within 0.01; the code before
    labelled an edge by whichever curve led to its band, two of four wrong)."""
    from shaftfem.fem.floquet import line_pair
    from shaftfem.fem.tracking import track
    from shaftfem.workflows.campbell import RPM, critical_speeds, with_sides

    kx, ky, c = 0.5 * K1, 1.5 * K1, 12.0
    model = jeffcott(kx, ky, c, K1, K2)
    lists = []
    for grid in (np.linspace(30.0, 700.0, 60), np.union1d(np.linspace(30.0, 700.0, 45), [420.0])):
        curves = [with_sides(model, cv) for cv in track(model, grid, 4)]
        found, _ = critical_speeds(model, curves, (1,), 700.0)
        lists.append([(cs.order, cs.whirl, cs.speed_rpm * RPM, cs.log_dec) for cs in found
                      if 300.0 <= cs.speed_rpm * RPM <= 650.0])
    a, b = lists
    assert [x[:2] for x in a] == [x[:2] for x in b], (a, b)
    np.testing.assert_allclose([x[2:] for x in a], [x[2:] for x in b], rtol=1e-5, atol=1e-6)
    assert len(a) == 4, a
    senses = []
    for i, (_, whirl, w, _) in enumerate(a):
        inside = w * (1 + 1e-5 if i % 2 == 0 else 1 - 1e-5)   # the bands' edges, in pairs
        index = stationary_whirl(kx, ky, c, inside)
        assert abs(index) > 0.1, (w, index)
        assert abs(line_pair(model, w, 1)[0] - index) <= 0.01, (w, index)
        senses.append(("forward" if index > 0 else "backward", whirl))
    assert all(x == y for x, y in senses), senses
