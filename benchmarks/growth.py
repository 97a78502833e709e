"""How time and memory grow with the number of DOFs (plain cylinder, P2), per factoriser.

    .venv/bin/python benchmarks/growth.py [SIZES_MM, e.g. 10,8,6,5,4,3]
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import in_fresh_process, machine, peak_mb  # noqa: E402


def one(size_mm: float, factoriser: str) -> dict:
    from dataclasses import replace

    from shaftfem.runtime import RunOptions
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    scene = replace(load_scene("plain_cylinder"), max_dofs=20_000_000)  # research runs
    r = run_modes(with_mesh(scene, size_mm), RunOptions(factoriser=factoriser))
    return {"dofs": r.modes.n_dofs, "s": dict(r.timings.items()), "peak_mb": peak_mb(),
            "f": r.modes.frequencies}


def main() -> None:
    sizes = [float(x) for x in (sys.argv[1] if len(sys.argv) > 1 else "10,8,6,5,4,3").split(",")]
    from shaftfem.fem.factor import available_factorisers

    print(f"machine: {machine()}\n")
    print("| factoriser | size (mm) | DOFs | assembly (s) | solve (s) "
          "| total (s) | peak memory (MB) |")
    print("|---|---|---|---|---|---|---|")
    for fac in available_factorisers():
        for h in sizes:
            if fac == "superlu" and h < 4:
                continue  # minutes and GBs: see the trial notes
            r = in_fresh_process(one, h, fac)
            s = r["s"]
            print(f"| {fac} | {h:g} | {r['dofs']} | {s['assembly']:.1f} | {s['solve']:.1f} "
                  f"| {s['total']:.1f} | {r['peak_mb']:.0f} |", flush=True)


if __name__ == "__main__":
    main()
