"""How the paper shaft's frequencies converge with the element size at the grooves.

    .venv/bin/python benchmarks/sizes_for_0_1.py [GROOVE_SIZES_MM, e.g. 4,3,2.5,2,1.6] [ROOT_RADIUS_MM]

Each run keeps 8 mm away from the grooves (6 mm there changes nothing: +0.1 Hz
on mode 1) and sets the groove-face and floor-edge sizes to the given value.
Per mode, the table gives the frequencies, each run's distance from the
finest run, and f(h) = f0 + c h^p fitted to the sequence (p and f0 shown only
where 0.3 <= p <= 6). Meshes are not nested, so p is an observed order with the
noise of re-meshing, and f0 is only as good as the fit.
"""

import json
import sys
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import numpy as np  # noqa: E402

from _common import in_fresh_process, machine, peak_mb  # noqa: E402


def one(groove_mm: float, root_radius_mm: float | None) -> dict:
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes

    scene = replace(load_scene("paper2018"), max_dofs=20_000_000)  # research runs
    if root_radius_mm is not None:
        scene = replace(scene, grooves=replace(scene.grooves, root_radius=root_radius_mm * 1e-3))
    h = groove_mm * 1e-3
    scene = replace(scene, mesh=replace(scene.mesh, groove_size=h, edge_size=h))
    r = run_modes(scene)
    return {"h": groove_mm, "dofs": r.modes.n_dofs, "total_s": r.timings.total,
            "peak_mb": peak_mb(), "f": r.modes.frequencies.tolist()}


def fit(h: np.ndarray, f: np.ndarray) -> tuple[float, float, float]:
    from scipy.optimize import curve_fit

    (f0, c, p), _ = curve_fit(lambda x, f0, c, p: f0 + c * x**p, h, f,
                              p0=[f[-1], (f[0] - f[-1]) / (h[0] - h[-1]), 1.0], maxfev=20000)
    return f0, c, p


def main() -> None:
    sizes = [float(x) for x in (sys.argv[1] if len(sys.argv) > 1 else "4,3,2.5,2,1.6").split(",")]
    rr = float(sys.argv[2]) if len(sys.argv) > 2 else None
    runs = [in_fresh_process(one, h, rr) for h in sizes]
    h = np.array([r["h"] for r in runs])
    F = np.array([r["f"] for r in runs])
    print(f"machine: {machine()}; paper2018, P2, 8 mm away from the grooves"
          + (f", root radius {rr:g} mm" if rr is not None else "") + "\n")
    print("| groove size (mm) | DOFs | total (s) | peak memory (MB) |")
    print("|---|---|---|---|")
    for r in runs:
        print(f"| {r['h']:g} | {r['dofs']} | {r['total_s']:.1f} | {r['peak_mb']:.0f} |")
    print("\n| mode | " + " | ".join(f"f at {x:g} mm (Hz)" for x in h)
          + " | " + " | ".join(f"{x:g} mm vs {h[-1]:g} mm" for x in h[:-1])
          + " | fitted p | f0 (Hz) |")
    print("|---" * (2 * len(h) + 3) + "|")
    for k in range(F.shape[1]):
        f0, _, p = fit(h, F[:, k])
        sane = 0.3 <= p <= 6
        print(f"| {k + 1} | " + " | ".join(f"{x:.2f}" for x in F[:, k]) + " | "
              + " | ".join(f"{100 * (x / F[-1, k] - 1):+.2f} %" for x in F[:-1, k])
              + (f" | {p:.2f} | {f0:.1f} |" if sane else " | - | - |"))
    print("\n" + json.dumps({"h_mm": h.tolist(), "dofs": [r["dofs"] for r in runs],
                             "f_hz": F.tolist()}))


if __name__ == "__main__":
    main()
