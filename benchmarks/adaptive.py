"""Work against precision on the paper's shaft: uniform groove meshes against adaptive ones.

    .venv/bin/python benchmarks/adaptive.py [GROOVE_SIZES_MM, e.g. 4,3,2] [TARGETS_PERCENT, e.g. 1,0.5]

Each run is a fresh process with an empty cache (cold: CAD, meshing and every
adaptive round); the adaptive runs are then repeated warm (adapted mesh cached).
True errors are against an independent reference: NGSolve, H1 order 4 on netgen's
own curved mesh of the exported STEP, 541k DOFs (benchmarks/ngsolve_reference.py;
_common.PAPER_REFERENCE_HZ: its order 3 -> 4 change was 0.04-0.08 %).
Writes docs/images/adaptive.png and prints a Markdown table.
"""

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import numpy as np  # noqa: E402

from _common import PAPER_REFERENCE_HZ, in_fresh_process, machine, peak_mb  # noqa: E402

REFERENCE_HZ = np.array(PAPER_REFERENCE_HZ)


def uniform(groove_mm: float, cache: str) -> dict:
    import os
    import time
    from dataclasses import replace

    os.environ["SHAFTFEM_CACHE"] = cache
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.bounded import run_bounded

    t0 = time.perf_counter()
    scene = load_scene("paper2018")
    h = groove_mm * 1e-3
    scene = replace(scene, mesh=replace(scene.mesh, groove_size=h, edge_size=h))
    b = run_bounded(scene)
    r, est = b.result, b.estimate
    return {"kind": f"uniform {groove_mm:g} mm", "dofs": r.modes.n_dofs,
            "seconds": time.perf_counter() - t0, "peak_mb": peak_mb(),
            "f": r.modes.frequencies.tolist(), "bound": est.relative_error.tolist()}


def adaptive(target_percent: float, cache: str) -> dict:
    import os
    import time

    os.environ["SHAFTFEM_CACHE"] = cache
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.bounded import run_bounded, with_accuracy

    t0 = time.perf_counter()
    b = run_bounded(with_accuracy(load_scene("paper2018"), target_percent))
    r, est, a = b.result, b.estimate, b.adapted
    return {"kind": f"adaptive {target_percent:g} %{'' if a.reached else ' (budget)'}"
                    f"{' warm' if a.from_cache else ''}",
            "dofs": r.modes.n_dofs, "seconds": time.perf_counter() - t0, "peak_mb": peak_mb(),
            "f": r.modes.frequencies.tolist(), "bound": est.relative_error.tolist()}


def main() -> None:
    sizes = [float(x) for x in (sys.argv[1] if len(sys.argv) > 1 else "4,3,2").split(",")]
    targets = [float(x) for x in (sys.argv[2] if len(sys.argv) > 2 else "1,0.5").split(",")]
    rows = []
    for h in sizes:
        with tempfile.TemporaryDirectory() as cache:
            rows.append(in_fresh_process(uniform, h, cache))
    for t in targets:
        with tempfile.TemporaryDirectory() as cache:
            rows.append(in_fresh_process(adaptive, t, cache))
            rows.append(in_fresh_process(adaptive, t, cache))
    print(f"machine: {machine()}\n")
    print("| run | DOFs | time (s) | peak memory (MB) | largest true error | largest bound "
          "| effectivity (bound / true) |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        true = np.array(r["f"]) / REFERENCE_HZ - 1
        eff = np.array(r["bound"]) / true
        r["true"] = float(true.max())
        print(f"| {r['kind']} | {r['dofs']} | {r['seconds']:.1f} | {r['peak_mb']:.0f} | "
              f"{100 * true.max():.3f} % | {100 * max(r['bound']):.3f} % | "
              f"{eff.min():.2f}-{eff.max():.2f} |")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for kind, marker in (("uniform", "o-"), ("adaptive", "s-")):
        sel = [r for r in rows if r["kind"].startswith(kind) and "warm" not in r["kind"]]
        for ax, x in zip(axes, ("dofs", "seconds")):
            ax.loglog([r[x] for r in sel], [100 * r["true"] for r in sel], marker, label=kind)
    for ax, label in zip(axes, ("DOFs", "cold run time (s)")):
        ax.set_xlabel(label)
        ax.set_ylabel("largest true error of 10 frequencies (%)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("paper's shaft: error against an NGSolve order-4 reference")
    fig.tight_layout()
    out = Path(__file__).parent.parent / "docs" / "images" / "adaptive.png"
    fig.savefig(out, dpi=100)
    print(f"\nwrote {out}")


if __name__ == "__main__":
    main()
