"""Grid independence of the critical speeds: every example and verification rotor's
crossings on the Campbell diagram's default speeds against those on a grid ten times
finer, on the same standstill basis (one solve each).

    .venv/bin/python benchmarks/crossing_grids.py

Prints one Markdown table: the rotor, its frame and bearings, the crossings counted on
each grid, and the largest relative difference of matched speeds; a row whose counts
differ, or whose difference exceeds 1e-3, fails (exit 1).
"""

import math
import sys
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).parent))
sys.path.insert(0, str(ROOT / "tests"))
import numpy as np  # noqa: E402

from _common import machine  # noqa: E402


def rotors() -> dict:
    """name -> scene data (or a path), each with its [rotor]."""
    import test_rotor as t
    import test_rotor_verdict as v

    table = np.linspace(0.0, 2000.0, 21)
    return {
        "overhung spindle (example)": ROOT / "examples" / "overhung_spindle.toml",
        "motor and fan (example)": ROOT / "examples" / "motor_fan.toml",
        "Friswell 5.9.1": t.friswell(t.ends(kxx_n_per_mm=1000.0), t.two_disks(),
                                     {"speed_rpm": 4000.0}),
        "Friswell 5.9.2, anisotropic": t.friswell(
            t.ends(kxx_n_per_mm=1000.0, kyy_n_per_mm=800.0), t.two_disks(),
            {"speed_rpm": 4000.0}),
        "Friswell 5.9.9, overhung": t.friswell(
            [t.bearing(1.0, "left", kxx_n_per_mm=10_000.0),
             t.bearing(1000.0, "right", kxx_n_per_mm=10_000.0)],
            [{**t.disk(1465.0, 0.35, "disk"), "position_mm": 1499.0, "width_mm": 2.0}],
            {"speed_rpm": 600.0, "max_speed_rpm": 1500.0}),
        "Friswell 5.9.1, anisotropic damped": t.friswell(
            t.ends(kxx_n_per_mm=1000.0, kyy_n_per_mm=500.0, cxx_n_s_per_mm=0.5),
            t.two_disks(), {"speed_rpm": 1200.0, "max_speed_rpm": 1500.0}),
        "Friswell 5.9.1, 1x 2x 7x": t.friswell(
            t.ends(kxx_n_per_mm=1000.0), t.two_disks(),
            {"speed_rpm": 1500.0, "max_speed_rpm": 3000.0},
            excitation=[{"name": "vane pass", "speed_rpm": 1500.0, "orders": [1, 2, 7]}]),
        "Friswell 5.9.1, cross-coupled": t.friswell(
            t.ends(kxx_n_per_mm=1000.0, cxx_n_s_per_mm=0.5, speeds_rpm=list(table * 30 / math.pi),
                   kxy_n_per_mm=list(0.15 * table), kyx_n_per_mm=list(-0.15 * table)),
            t.two_disks(), {"speed_rpm": 2000.0, "max_speed_rpm": 5000.0}),
        "stepped rotor, damped": t.stepped_rotor("auto"),
        "pulley rotor": v.pulley_rotor(),
        "keyed shaft, rotating frame": v.keyed_rotor(),
    }


def main() -> int:
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.campbell import campbell_of, turning

    print(f"{machine()}; the default grid ([rotor] campbell_points, 31) against ten times "
          "as many speeds")
    print("| rotor | frame | crossings, default | crossings, 10x | largest difference |")
    print("|---|---|---|---|---|")
    bad = 0
    for name, data in rotors().items():
        scene = load_scene(data)
        result, model, why = turning(scene)
        rotor = scene.rotor
        assert rotor is not None
        coarse = campbell_of(scene, result, model, why)
        fine_grid = np.linspace(0.0, rotor.max_speed * 30 / math.pi, 10 * rotor.points)
        fine = campbell_of(replace(scene, rotor=rotor), result, model, why, fine_grid)
        a = sorted((cs.order, cs.speed_rpm) for cs in coarse.critical_speeds)
        b = sorted((cs.order, cs.speed_rpm) for cs in fine.critical_speeds)
        diff = max((abs(x[1] / y[1] - 1) for x, y in zip(a, b)), default=0.0)
        ok = len(a) == len(b) and all(x[0] == y[0] for x, y in zip(a, b)) and diff <= 1e-3
        bad += not ok
        print(f"| {name} | {model.frame} | {len(a)} | {len(b)} | {diff:.1e}"
              f"{'' if ok else ' (DIFFERS)'} |")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
