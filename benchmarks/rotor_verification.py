"""The turning shaft against ross-rotordynamics 2.3 (a 1D Timoshenko rotor model, 48
elements): Friswell et al.'s rotors and the two example rotors, as tests/test_rotor.py
and tests/test_examples.py write them, against the values benchmarks/ross_reference.py
wrote into tests/data/ross_rotors.json.

    .venv/bin/python benchmarks/rotor_verification.py

Prints one Markdown table: each quantity, ross's value, ours, the difference.
"""

import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).parent))
sys.path.insert(0, str(ROOT / "tests"))
from _common import machine  # noqa: E402

RAD = math.pi / 30   # rad/s per r/min


def main() -> None:
    import numpy as np

    import test_rotor as t
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.campbell import run_campbell

    ross = json.loads((ROOT / "tests" / "data" / "ross_rotors.json").read_text())
    rows = []
    counts: list[tuple[str, int, int]] = []

    def row(what: str, theirs: float, ours: float, unit: str) -> None:
        rows.append(f"| {what} | {theirs:.6g} {unit} | {ours:.6g} {unit} | "
                    f"{(ours / theirs - 1) * 100:+.2f} % |")

    fixed = {"max_speed_rpm": 4000.0, "campbell_points": 2}
    for name, supports in (("5.9.1", t.ends(kxx_n_per_mm=1000.0)),
                           ("5.9.2", t.ends(kxx_n_per_mm=1000.0, kyy_n_per_mm=800.0))):
        c = run_campbell(load_scene(t.friswell(supports, t.two_disks(),
                                               {"speed_rpm": 4000.0, **fixed})))
        for rpm in (0, 4000):
            ours, theirs = t.lateral(c, rpm)[:6], t.ross_lateral(name, rpm)[:6]
            for k, (a, b) in enumerate(zip(theirs, ours)):
                row(f"{name}, {rpm} r/min, whirl {k + 1}", a, b, "rad/s")
            if rpm:
                for k in range(3):
                    row(f"{name}, {rpm} r/min, split of pair {k + 1}",
                        theirs[2 * k + 1] - theirs[2 * k], ours[2 * k + 1] - ours[2 * k], "rad/s")
    c = run_campbell(load_scene(t.friswell(
        [t.bearing(1.0, "left", kxx_n_per_mm=10_000.0),
         t.bearing(1000.0, "right", kxx_n_per_mm=10_000.0)],
        [{**t.disk(1465.0, 0.35, "disk"), "position_mm": 1499.0, "width_mm": 2.0}],
        {"speed_rpm": 600.0, "max_speed_rpm": 1500.0, "campbell_points": 16})))
    for whirl in ("backward", "forward"):
        first = min((cs for cs in c.critical_speeds if cs.whirl == whirl and cs.order == 1),
                    key=lambda cs: cs.speed_rpm)
        row(f"5.9.9, first 1x {whirl} critical speed", ross["5.9.9"]["critical_1x"][whirl],
            first.speed_rpm * RAD, "rad/s")
    ref = ross["5.9.1 unbalance"]
    c = run_campbell(load_scene(t.friswell(
        t.ends(kxx_n_per_mm=1000.0, cxx_n_s_per_mm=ref["bearing_damping_n_s_per_m"] / 1e3),
        t.two_disks(), {"speed_rpm": 1200.0, "max_speed_rpm": 1500.0, "campbell_points": 2},
        unbalance=[{"name": "disk 2", "position_mm": 1000.0,
                    "amount_g_mm": ref["unbalance_kg_m"] * 1e6}])))
    assert c.unbalance is not None
    peak = min((p for p in c.unbalance.peaks if p.probe == "disk 2"), key=lambda p: p.speed_rpm)
    row("5.9.1 unbalance, peak speed", ref["peak_speed"], peak.speed_rpm * RAD, "rad/s")
    row("5.9.1 unbalance, peak amplitude", ref["peak_amplitude_m"] * 1e6, peak.amplitude * 1e6,
        "um")
    ref = ross["5.9.1 cross-coupled"]
    table = np.linspace(0.0, 2000.0, 21)
    coefficients = {"kxx_n_per_mm": 1000.0,
                    "cxx_n_s_per_mm": ref["bearing_damping_n_s_per_m"] / 1e3,
                    "speeds_rpm": list(table / RAD),
                    "kxy_n_per_mm": list(ref["kxy_per_speed"] * table / 1e3),
                    "kyx_n_per_mm": list(-ref["kxy_per_speed"] * table / 1e3)}
    c = run_campbell(load_scene(t.friswell(t.ends(**coefficients), t.two_disks(),
                                           {"speed_rpm": 2000.0, "max_speed_rpm": 5000.0,
                                            "campbell_points": 11})))
    row("5.9.1 cross-coupled, instability onset", ref["onset_speed"], c.onsets[0].speed_rpm * RAD,
        "rad/s")
    if "anisotropic damped" in ross:
        ref = ross["anisotropic damped"]
        c = run_campbell(load_scene(t.friswell(
            t.ends(kxx_n_per_mm=ref["kxx"] / 1e3, kyy_n_per_mm=ref["kyy"] / 1e3,
                   cxx_n_s_per_mm=ref["c"] / 1e3),
            t.two_disks(), {"speed_rpm": 1200.0, "max_speed_rpm": 1500.0},
            unbalance=[{"name": "disk 2", "position_mm": 1000.0,
                        "amount_g_mm": ref["unbalance_kg_m"] * 1e6}])))
        ours = sorted(cs.speed_rpm * RAD for cs in c.critical_speeds if cs.order == 1)
        for k, x in enumerate(ref["crossings"]):
            near = min(ours, key=lambda n: abs(n - x["speed"]))
            row(f"anisotropic damped bearings, 1x crossing {k + 1}", x["speed"], near, "rad/s")
        assert c.unbalance is not None
        peaks = [p for p in c.unbalance.peaks if p.probe == "disk 2"]
        for k, x in enumerate(ref["peaks"]):
            p = min(peaks, key=lambda p: abs(p.speed_rpm * RAD - x["speed"]))
            row(f"anisotropic damped bearings, unbalance peak {k + 1}, speed", x["speed"],
                p.speed_rpm * RAD, "rad/s")
            row(f"anisotropic damped bearings, unbalance peak {k + 1}, major semi-axis",
                x["major_m"] * 1e6, p.amplitude * 1e6, "um")
        counts.append(("anisotropic damped bearings, 1x crossings up to 1,500 r/min",
                       len(ref["crossings"]), len(ours)))
    if "orders 1 2 7" in ross:
        ref = ross["orders 1 2 7"]
        scene = load_scene(t.friswell(
            t.ends(kxx_n_per_mm=1000.0), t.two_disks(),
            {"speed_rpm": 1500.0, "max_speed_rpm": 3000.0},
            excitation=[{"name": "vane pass", "speed_rpm": 1500.0, "orders": [1, 2, 7]}]))
        c = run_campbell(scene)
        used: set[int] = set()
        for x in ref["crossings"]:   # each of ours matched once, nearest first
            same = [(abs(cs.speed_rpm * RAD - x["speed"]), k) for k, cs in
                    enumerate(c.critical_speeds) if cs.order == x["order"] and k not in used]
            _, k = min(same)
            used.add(k)
            row(f"1x, 2x, 7x: {x['order']}x crossing of curve {x['curve']}", x["speed"],
                c.critical_speeds[k].speed_rpm * RAD, "rad/s")
        counts.append(("1x, 2x, 7x crossings up to 3,000 r/min", len(ref["crossings"]),
                       sum(1 for cs in c.critical_speeds
                           if cs.frequency_hz * 2 * math.pi
                           <= max(x["speed"] * x["order"] for x in ref["crossings"]) * 1.0001)))
    for name in ("overhung_spindle", "motor_fan"):
        if name not in ross:
            continue
        c = run_campbell(load_scene(ROOT / "examples" / f"{name}.toml"))
        rpm = next(k for k in ross[name] if k != "critical_1x")
        ours = [w.frequency_hz * 2 * math.pi for w in c.operating if w.kind == "bending"][:2]
        for k, (a, b) in enumerate(zip(ross[name][rpm]["wd"][:2], ours)):
            row(f"{name}, {rpm} r/min, whirl {k + 1}", a, b, "rad/s")
        for whirl in ("backward", "forward"):
            first = min((cs for cs in c.critical_speeds if cs.whirl == whirl and cs.order == 1),
                        key=lambda cs: cs.speed_rpm)
            row(f"{name}, first 1x {whirl} critical speed", ross[name]["critical_1x"][whirl],
                first.speed_rpm * RAD, "rad/s")
    print(f"{machine()}; ross-rotordynamics 2.3, 48 Timoshenko elements, against the 3D solid")
    print("| quantity | ross | shaftfem | difference |")
    print("|---|---|---|---|")
    print("\n".join(rows))
    if counts:
        print()
        print("| crossings counted | ross | shaftfem |")
        print("|---|---|---|")
        for what, a, b in counts:
            print(f"| {what} | {a} | {b} |")


if __name__ == "__main__":
    main()
