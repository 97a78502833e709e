"""The rotors of Friswell et al., *Dynamics of Rotating Machines* (section 5.9), solved
with ross-rotordynamics 2.3, an independent 1D Timoshenko rotor model: the reference
values the rotating-shaft tests compare the 3D solid with (tests/data/ross_rotors.json).

ross is not one of shaftfem's dependencies (it needs plotly < 6 and brings about 1 GB
of packages): run this in an environment of its own,

    python3 -m venv .venv-ross && .venv-ross/bin/pip install "ross-rotordynamics==2.3.*" "plotly<6"
    .venv-ross/bin/python benchmarks/ross_reference.py tests/data/ross_rotors.json
    .venv-ross/bin/python benchmarks/ross_reference.py --journals \
        tests/data/journal_591.json tests/data/ross_rotors.json
    .venv-ross/bin/python benchmarks/ross_reference.py --journals \
        tests/data/journal_591_tight.json tests/data/ross_rotors.json "5.9.1 journals, tight"
    .venv-ross/bin/python benchmarks/ross_reference.py --cylindrical tests/data/ross_rotors.json
    .venv-ross/bin/python benchmarks/ross_reference.py --seal tests/data/ross_rotors.json
    .venv-ross/bin/python benchmarks/ross_reference.py --ucs tests/data/ross_rotors.json
    .venv-ross/bin/python benchmarks/ross_reference.py --level1 tests/data/ross_rotors.json
    .venv-ross/bin/python benchmarks/ross_reference.py --runup tests/data/ross_rotors.json

Every rotor is written as ross's own tests write it (ross/tests/test_examples.py), on
48 shaft elements; speeds are rad/s, frequencies rad/s (ross's units).
"""

from __future__ import annotations

import json
import sys

import numpy as np

N_EL = 48
RPM = np.pi / 30
# The cross-coupled stiffness kxy = -kyx grows with speed at this rate, N s/m.
SLOPE = 150.0


def shaft(rs, steel, length=1.5):
    return [rs.ShaftElement(L=length / N_EL, material=steel, n=i, idl=0, odl=0.05)
            for i in range(N_EL)]


def disk(rs, steel, node, od):
    return rs.DiskElement.from_geometry(n=node, material=steel, width=0.07, i_d=0.05, o_d=od)


def example_591(rs, steel, c=0.0, cross=None):
    """5.9.1: 1 MN/m bearings at the ends, disks at 0.5 and 1.0 m; `c` bearing damping
    (N s/m); `cross` (speeds rad/s, kxy N/m) a cross-coupled stiffness against speed."""
    kw = {}
    if cross is not None:
        speeds, kxy = cross
        kw = dict(kxx=[1e6] * len(speeds), kyy=[1e6] * len(speeds), kxy=list(kxy),
                  kyx=[-k for k in kxy], cxx=[c] * len(speeds), cyy=[c] * len(speeds),
                  frequency=list(speeds))
    else:
        kw = dict(kxx=1e6, kyy=1e6, cxx=c, cyy=c)
    return rs.Rotor(shaft(rs, steel), [disk(rs, steel, N_EL // 3, 0.28),
                                       disk(rs, steel, 2 * N_EL // 3, 0.35)],
                    [rs.BearingElement(n=0, **kw), rs.BearingElement(n=N_EL, **kw)])


def example_592(rs, steel):
    """5.9.2: 5.9.1 with kyy = 0.8 MN/m."""
    return rs.Rotor(shaft(rs, steel), [disk(rs, steel, N_EL // 3, 0.28),
                                       disk(rs, steel, 2 * N_EL // 3, 0.35)],
                    [rs.BearingElement(n=0, kxx=1e6, kyy=8e5, cxx=0, cyy=0),
                     rs.BearingElement(n=N_EL, kxx=1e6, kyy=8e5, cxx=0, cyy=0)])


def example_599(rs, steel):
    """5.9.9, overhung: 10 MN/m bearings at 0 and 1.0 m, the 350 mm disk at 1.5 m."""
    return rs.Rotor(shaft(rs, steel), [disk(rs, steel, N_EL, 0.35)],
                    [rs.BearingElement(n=0, kxx=10e6, kyy=10e6, cxx=0, cyy=0),
                     rs.BearingElement(n=2 * N_EL // 3, kxx=10e6, kyy=10e6, cxx=0, cyy=0)])


def journal_591(rs, steel, table: dict):
    """5.9.1 on the two journal bearings of `table` (benchmarks/journal_tables.py: their
    coefficients against speed, as shaftfem's film gives them) at nodes 1 and 47."""
    keys = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")
    bearings = [rs.BearingElement(n=node, frequency=list(b["speeds"]),
                                  **{k: list(b[k]) for k in keys})
                for node, b in zip((1, N_EL - 1), table["bearings"])]
    return rs.Rotor(shaft(rs, steel), [disk(rs, steel, N_EL // 3, 0.28),
                                       disk(rs, steel, 2 * N_EL // 3, 0.35)], bearings)


def journal_reference(rs, steel, table: dict) -> dict:
    """5.9.1 on journals: the whirl and log decrements at 1,000, 3,000 and 6,000 r/min,
    where the first forward mode's log decrement falls through zero, and where the
    first two lightly damped modes (log decrement below 1) meet 1x (bisection), rad/s."""
    rotor = journal_591(rs, steel, table)
    out: dict = {}
    for rpm in (1000, 3000, 6000):
        wd, dirs, ld = whirl(rotor, rpm * RPM, 6)
        out[str(rpm)] = {"wd": list(map(float, wd)), "whirl": dirs,
                         "log_dec": list(map(float, ld))}

    def logdec(speed):
        wd, dirs, ld = whirl(rotor, speed, 6)
        return min(v for v, d in zip(ld, dirs) if d == "Forward")

    lo, hi = 1000 * RPM, 6000 * RPM
    assert logdec(lo) > 0 > logdec(hi), (logdec(lo), logdec(hi))
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if logdec(mid) > 0 else (lo, mid)
    out["onset_speed"] = 0.5 * (lo + hi)

    def lightly_damped(speed, k):
        """The k-th lowest whirl frequency among the modes with a log decrement below 1
        (the films' overdamped modes left out), rad/s."""
        wd, _, ld = whirl(rotor, speed, 8)
        return sorted(w for w, d in zip(wd, ld) if d < 1.0)[k]

    out["critical_1x"] = {}
    for k, name in ((0, "first"), (1, "second")):
        lo, hi = 60.0, 200.0
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if lightly_damped(mid, k) > mid else (lo, mid)
        out["critical_1x"][name] = 0.5 * (lo + hi)
    return out


def whirl(rotor, speed, n=8):
    m = rotor.run_modal(speed, num_modes=2 * n + 4)
    return m.wd[:n], list(m.whirl_direction()[:n]), m.log_dec[:n]


def first_of(rotor, speed, direction):
    wd, dirs, _ = whirl(rotor, speed)
    return next(w for w, d in zip(wd, dirs) if d == direction)


def critical(rotor, direction, lo, hi):
    """The speed (rad/s) where the first `direction` whirl meets 1x, by bisection."""
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if first_of(rotor, mid, direction) > mid:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def lateral_wd(rotor, speed, n):
    """The first n lateral damped frequencies (rad/s) at a speed, ascending."""
    m = rotor.run_modal(speed, num_modes=2 * n + 8)
    return np.array([w for w, d in zip(m.wd, m.whirl_direction()) if d != "None"][:n])


def every_crossing(rotor, orders, top, n, points=81):
    """Every speed (rad/s) where one of the first n lateral frequencies meets an order
    line, up to `top`: sign changes on a grid, then bisection. The k-th lowest
    frequencies are the union of the curves, so their crossings are the curves'."""
    grid = np.linspace(top / points, top, points)
    wd = np.array([lateral_wd(rotor, w, n) for w in grid])
    out = []
    for order in orders:
        for k in range(n):
            g = wd[:, k] - order * grid
            for i in np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0):
                lo, hi = grid[i], grid[i + 1]
                for _ in range(45):
                    mid = 0.5 * (lo + hi)
                    if (lateral_wd(rotor, mid, n)[k] - order * mid) * g[i] > 0:
                        lo = mid
                    else:
                        hi = mid
                out.append({"order": order, "curve": k + 1, "speed": 0.5 * (lo + hi)})
    return sorted(out, key=lambda x: (x["speed"], x["order"]))


def major_peaks(rotor, node, unbalance, speeds):
    """The peaks (speed rad/s, major semi-axis m) of a node's unbalance orbit."""
    def major(w):
        r = rotor.run_unbalance_response(node, unbalance, 0.0, w)
        x, y = r.forced_resp[6 * node], r.forced_resp[6 * node + 1]
        return 0.5 * (np.abs(x + 1j * y) + np.abs(x - 1j * y))

    a = major(speeds)
    peaks = []
    for i in np.flatnonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:])) + 1:
        fine = np.linspace(speeds[i - 1], speeds[i + 1], 801)
        af = major(fine)
        j = int(np.argmax(af))
        peaks.append({"speed": float(fine[j]), "major_m": float(af[j])})
    return peaks


def main(path: str) -> None:
    import ross as rs
    from ross.materials import steel

    out: dict = {"source": "ross-rotordynamics " + rs.__version__ + ", " + str(N_EL)
                 + " shaft elements; rad/s"}
    r1 = example_591(rs, steel)
    r2 = example_592(rs, steel)
    for name, rotor in (("5.9.1", r1), ("5.9.2", r2)):
        out[name] = {}
        for rpm in (0, 4000):
            wd, dirs, _ = whirl(rotor, rpm * RPM)
            out[name][str(rpm)] = {"wd": list(map(float, wd)), "whirl": dirs}
    r9 = example_599(rs, steel)
    wd, dirs, _ = whirl(r9, 4000 * RPM)
    out["5.9.9"] = {"4000": {"wd": list(map(float, wd)), "whirl": dirs},
                    "critical_1x": {"backward": critical(r9, "Backward", 10.0, 200.0),
                                    "forward": critical(r9, "Forward", 10.0, 200.0)}}
    # Unbalance response of 5.9.1 with 500 N s/m in each bearing: 100 g mm at the 350 mm
    # disk, the response of that disk's node along x
    c = 500.0
    rd = example_591(rs, steel, c=c)
    speeds = np.linspace(60.0, 120.0, 601)
    resp = rd.run_unbalance_response(2 * N_EL // 3, 1e-4, 0.0, speeds)
    x = np.abs(resp.forced_resp[6 * (2 * N_EL // 3)])
    i = int(np.argmax(x))
    fine = np.linspace(speeds[max(i - 2, 0)], speeds[min(i + 2, len(speeds) - 1)], 401)
    xf = np.abs(rd.run_unbalance_response(2 * N_EL // 3, 1e-4, 0.0, fine)
                .forced_resp[6 * (2 * N_EL // 3)])
    j = int(np.argmax(xf))
    out["5.9.1 unbalance"] = {"bearing_damping_n_s_per_m": c, "unbalance_kg_m": 1e-4,
                              "node_z_m": 1.0, "peak_speed": float(fine[j]),
                              "peak_amplitude_m": float(xf[j])}
    # Cross-coupled stiffness growing with speed, kxy = -kyx = 150 N s/m x speed, with
    # 500 N s/m of damping: the first forward mode's log decrement falls to zero
    table = np.linspace(0.0, 2000.0, 21)
    rc = example_591(rs, steel, c=c, cross=(table, SLOPE * table))

    def logdec(speed):
        wd, dirs, ld = whirl(rc, speed)
        return next(v for v, d in zip(ld, dirs) if d == "Forward")

    lo, hi = 1.0, 1990.0
    assert logdec(lo) > 0 > logdec(hi), (logdec(lo), logdec(hi))
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if logdec(mid) > 0 else (lo, mid)
    out["5.9.1 cross-coupled"] = {"bearing_damping_n_s_per_m": c, "kxy_per_speed": SLOPE,
                                  "onset_speed": 0.5 * (lo + hi)}
    # 5.9.2's anisotropic bearings (kyy = kxx / 2 here) with 500 N s/m of damping:
    # every 1x crossing of the first four curves, and the unbalance peaks (major
    # semi-axis) of the 350 mm disk's node, 100 g mm there
    ra = rs.Rotor(shaft(rs, steel), [disk(rs, steel, N_EL // 3, 0.28),
                                     disk(rs, steel, 2 * N_EL // 3, 0.35)],
                  [rs.BearingElement(n=b, kxx=1e6, kyy=5e5, cxx=c, cyy=c)
                   for b in (0, N_EL)])
    out["anisotropic damped"] = {
        "kxx": 1e6, "kyy": 5e5, "c": c, "unbalance_kg_m": 1e-4,
        "crossings": every_crossing(ra, (1,), 1500 * RPM, 4),
        "peaks": major_peaks(ra, 2 * N_EL // 3, 1e-4, np.linspace(20.0, 160.0, 281))}
    # 5.9.1 undamped with a pump's orders 1x, 2x and 7x (vane pass) up to 3,000 r/min
    out["orders 1 2 7"] = {"orders": [1, 2, 7],
                           "crossings": every_crossing(r1, (1, 2, 7), 3000 * RPM, 6)}
    # The examples: the grinding spindle and the motor shaft with its fan
    # (examples/overhung_spindle.toml, examples/motor_fan.toml), on 10 mm elements
    for name, (length, od, brgs, k, (node, m, ip, idm), rpm, top) in {
            "overhung_spindle": (0.5, 0.04, (5, 35), 2e8, (48, 7.4, 0.037, 0.019), 9000, 15000),
            "motor_fan": (0.42, 0.035, (6, 30), 1e8, (40, 4.0, 0.03, 0.016), 2950, 30000),
    }.items():
        n = round(length / 0.01)
        elements = [rs.ShaftElement(L=length / n, material=steel, n=i, idl=0, odl=od)
                    for i in range(n)]
        rotor = rs.Rotor(elements, [rs.DiskElement(n=node, m=m, Id=idm, Ip=ip)],
                         [rs.BearingElement(n=b, kxx=k, kyy=k, cxx=0, cyy=0) for b in brgs])
        wd, dirs, _ = whirl(rotor, rpm * RPM, 4)
        out[name] = {str(rpm): {"wd": list(map(float, wd)), "whirl": dirs},
                     "critical_1x": {"backward": critical(rotor, "Backward", 10.0, top * RPM),
                                     "forward": critical(rotor, "Forward", 10.0, top * RPM)}}
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps(out, indent=1))


def cylindrical(path: str) -> None:
    """Add "cylindrical bearing" to the reference file at `path`: ross's
    CylindricalBearing (the short-bearing closed form) on a bearing of L/D = 0.1 (its
    docstring's bearing, 10 mm long), at 1,500 and 2,000 r/min; N/m, N s/m."""
    import ross as rs
    from ross.units import Q_

    b = rs.CylindricalBearing(n=0, speed=Q_([1500, 2000], "RPM"), weight=525,
                              bearing_length=Q_(10, "mm"), journal_diameter=Q_(100, "mm"),
                              radial_clearance=Q_(0.1, "mm"), oil_viscosity=0.1)
    entry = {"speed_rpm": [1500, 2000], "load_n": 525.0, "length_m": 0.01, "diameter_m": 0.1,
             "clearance_m": 1e-4, "viscosity_pa_s": 0.1,
             "eccentricity": [float(e) for e in b.eccentricity]}
    for k in ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"):
        entry[k] = [float(v) for v in getattr(b, k)]
    with open(path) as f:
        out = json.load(f)
    out["cylindrical bearing"] = entry
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps(entry, indent=1))


# 5.9.1 with a water seal at mid-span (tests/test_seal.py): 25 mm long on the 50 mm shaft,
# 150 um clearance, 1 MPa across it at 3,000 r/min; speeds up to 4,000 r/min
SEAL = {"length_m": 0.025, "diameter_m": 0.05, "clearance_m": 150e-6,
        "pressure_drop_pa": 1e6, "rated_rpm": 3000.0, "density_kg_m3": 998.0,
        "viscosity_pa_s": 1e-3, "top_rpm": 4000.0}


def seal(path: str) -> None:
    """Add "5.9.1 seal" to the reference file at `path`: 5.9.1 with 2,000 N s/m in each
    bearing and the seal SEAL at node 24 (0.75 m), its coefficients against speed as
    shaftfem's seal model gives them (shaftfem.parts.seal, pure Python, read from src/),
    in ross's SealElement; the whirl and log decrements at 1,000, 3,000 and 4,000 r/min."""
    from pathlib import Path

    import ross as rs
    from ross.materials import steel

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src" / "shaftfem" / "parts"))
    import seal as model  # shaftfem.parts.seal on its own: it imports nothing of shaftfem

    s = model.AnnularSeal(length=SEAL["length_m"], diameter=SEAL["diameter_m"],
                          clearance=SEAL["clearance_m"], pressure_drop=SEAL["pressure_drop_pa"],
                          rated=SEAL["rated_rpm"] * RPM, density=SEAL["density_kg_m3"],
                          viscosity=SEAL["viscosity_pa_s"])
    speeds, states = model.speed_table(s, SEAL["top_rpm"] * RPM)
    table = {"speeds": [0.0, *speeds]}
    for name, key, sign in (("kxx", "K", 1), ("kyy", "K", 1), ("kxy", "k", 1), ("kyx", "k", -1),
                            ("cxx", "C", 1), ("cyy", "C", 1), ("cxy", "c", 1), ("cyx", "c", -1),
                            ("mxx", "M", 1), ("myy", "M", 1)):
        table[name] = [0.0, *(sign * getattr(x, key) for x in states)]
    c = 2000.0
    element = rs.SealElement(n=N_EL // 2, frequency=table["speeds"],
                             **{k: v for k, v in table.items() if k != "speeds"})
    rotor = rs.Rotor(shaft(rs, steel), [disk(rs, steel, N_EL // 3, 0.28),
                                        disk(rs, steel, 2 * N_EL // 3, 0.35)],
                     [rs.BearingElement(n=0, kxx=1e6, kyy=1e6, cxx=c, cyy=c),
                      rs.BearingElement(n=N_EL, kxx=1e6, kyy=1e6, cxx=c, cyy=c), element])
    entry: dict = {"seal": SEAL, "bearing_damping_n_s_per_m": c, "table": table}
    for rpm in (1000, 3000, 4000):
        wd, dirs, ld = whirl(rotor, rpm * RPM, 6)
        entry[str(rpm)] = {"wd": list(map(float, wd)), "whirl": dirs,
                           "log_dec": list(map(float, ld))}
    with open(path) as f:
        out = json.load(f)
    out["5.9.1 seal"] = entry
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps({k: v for k, v in entry.items() if k != "table"}, indent=1))


def ucs(path: str) -> None:
    """Add "ucs" and "ucs_synchronous" to the reference file at `path`: ross's run_ucs
    (standstill, and synchronous=True; 4 branches) of 5.9.1 and of 5.9.9 (overhung) over
    1e5 to 1e9 N/m, 20 stiffnesses; rad/s."""
    import ross as rs
    from ross.materials import steel

    out_ucs = {"stiffness_n_per_m": [float(k) for k in np.logspace(5, 9, 20)]}
    synchronous = dict(out_ucs)
    for name, rotor in (("5.9.1", example_591(rs, steel)), ("5.9.9", example_599(rs, steel))):
        r = rotor.run_ucs(stiffness_range=(5, 9), num=20, num_modes=16)
        out_ucs[name] = [[float(v) for v in row] for row in np.asarray(r.wn)]
        # the synchronous map: gyroscopic moments at Omega = omega (forward branches)
        r = rotor.run_ucs(stiffness_range=(5, 9), num=20, num_modes=16, synchronous=True)
        synchronous[name] = [[float(v) for v in row] for row in np.asarray(r.wn)]
    with open(path) as f:
        out = json.load(f)
    out["ucs"] = out_ucs
    out["ucs_synchronous"] = synchronous
    out_ucs = {"standstill": out_ucs, "synchronous": synchronous}
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps(out_ucs, indent=1))


def level1(path: str) -> None:
    """Add "level1" to the reference file at `path`: ross's run_level1 on 5.9.1 with 500
    N s/m in each bearing at 3,000 r/min, the cross-coupling Q at mid-span (node 24): the
    first forward mode's log decrement at five Q, and Q_0 where it is zero, found by
    bisection on the same construction (ross's run_level1 gives the curve only)."""
    import ross as rs
    from ross.materials import steel

    speed, node = 3000 * RPM, N_EL // 2
    rotor = example_591(rs, steel, c=500.0)
    rotor.rated_w = speed

    def logdec(q: float) -> float:
        b = [*rotor.bearing_elements, rs.BearingElement(n=node, kxx=0, cxx=0, kxy=q, kyx=-q)]
        modal = rs.Rotor(rotor.shaft_elements, rotor.disk_elements, b).run_modal(speed=speed)
        return float(modal.log_dec[modal.whirl_direction() != "Backward"][0])

    lo, hi = 0.0, 1e5
    assert logdec(lo) > 0 > logdec(hi)
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if logdec(mid) > 0 else (lo, mid)
    q0 = 0.5 * (lo + hi)
    qs = [0.0, 0.15 * q0, 0.3 * q0, 0.45 * q0, 0.6 * q0]   # log decs well off zero
    r = rotor.run_level1(n=node, stiffness_range=(qs[0], qs[-1]), num=5)
    entry = {"speed_rpm": 3000.0, "bearing_damping_n_s_per_m": 500.0, "at_m": 0.75,
             "q_n_per_m": [float(q) for q in r.stiffness_range],
             "log_dec": [float(v) for v in r.log_dec], "q0_n_per_m": q0}
    with open(path) as f:
        out = json.load(f)
    out["level1"] = entry
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps(entry, indent=1))


def runup(path: str) -> None:
    """Add "runup" to the reference file at `path`: 5.9.1 with 2,000 N s/m in each
    bearing run from 500 to 1,300 r/min at 100 r/min per s, 100 g mm at the 350 mm disk
    (node 32), integrated by ross's Newmark (run_time_response with the speed against
    time): the largest orbit radius at that node in each turn, its peak and the speed
    there."""
    import ross as rs
    from ross.materials import steel

    rotor = example_591(rs, steel, c=2000.0)
    start, stop, accel = 500 * RPM, 1300 * RPM, 100 * RPM
    duration = (stop - start) / accel
    n = int(np.ceil(duration / (2 * np.pi / stop / 100)))
    t = np.linspace(0.0, duration, n + 1)
    speed = start + accel * t
    phi = start * t + 0.5 * accel * t**2
    me, node = 1e-4, 2 * N_EL // 3
    F = np.zeros((t.size, rotor.ndof))
    F[:, rotor.number_dof * node + 0] = me * (speed**2 * np.cos(phi) + accel * np.sin(phi))
    F[:, rotor.number_dof * node + 1] = me * (speed**2 * np.sin(phi) - accel * np.cos(phi))
    response = rotor.run_time_response(speed, F, t)
    x = response.yout[:, rotor.number_dof * node + 0]
    y = response.yout[:, rotor.number_dof * node + 1]
    turn = np.floor(phi / (2 * np.pi)).astype(int)
    r = np.hypot(x, y)
    peaks = np.zeros(turn.max() + 1)
    np.maximum.at(peaks, turn, r)
    mean = np.bincount(turn, speed) / np.bincount(turn)
    peaks, mean = peaks[:-1], mean[:-1]
    i = int(np.argmax(peaks))
    entry = {"bearing_damping_n_s_per_m": 2000.0, "start_rpm": 500.0, "stop_rpm": 1300.0,
             "accel_rpm_per_s": 100.0, "unbalance_kg_m": me, "node_z_m": 1.0,
             "steps": int(n), "peak_speed_rpm": float(mean[i] / RPM),
             "peak_radius_m": float(peaks[i])}
    with open(path) as f:
        out = json.load(f)
    out["runup"] = entry
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps(entry, indent=1))


def journals(table_path: str, path: str, key: str = "5.9.1 journals") -> None:
    """Add `key` ("5.9.1 journals", or a tolerance case's) to the reference file at
    `path`, from the bearings of `table_path`."""
    import ross as rs
    from ross.materials import steel

    with open(table_path) as f:
        table = json.load(f)
    with open(path) as f:
        out = json.load(f)
    out[key] = journal_reference(rs, steel, table)
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps(out[key], indent=1))


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--journals":
        journals(*sys.argv[2:5])
    elif len(sys.argv) > 1 and sys.argv[1] == "--cylindrical":
        cylindrical(sys.argv[2])
    elif len(sys.argv) > 1 and sys.argv[1] == "--seal":
        seal(sys.argv[2])
    elif len(sys.argv) > 1 and sys.argv[1] == "--ucs":
        ucs(sys.argv[2])
    elif len(sys.argv) > 1 and sys.argv[1] == "--level1":
        level1(sys.argv[2])
    elif len(sys.argv) > 1 and sys.argv[1] == "--runup":
        runup(sys.argv[2])
    else:
        main(sys.argv[1] if len(sys.argv) > 1 else "ross_rotors.json")
