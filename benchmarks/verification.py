"""The bounds' verification matrix: each solid at two or three mesh sizes, free-free and
installed, its printed interval [f (1 - bound), f (1 + upward)] against an independent
reference (NGSolve at high order on netgen's mesh of the exported STEP, stored in
tests/data/verification/ by benchmarks/verification_reference.py in NGSolve's own venv).

    .venv/bin/python benchmarks/verification.py --write    # the tables of docs/verification.md
    .venv/bin/python benchmarks/verification.py --steps    # the profiles' STEP files
    .venv-ngsolve/bin/python benchmarks/verification_reference.py \
        tests/data/verification/cases/CASE.json              # each reference, in its venv

`--steps` writes out/verification/steps/SCENE.step, which the cases' inputs name.
The true error is f / f_ref - 1; the effectivity is the bound on the side the truth lies
(the downward bound, or the upward allowance when the reference lies above f) over |error|.
"""

from __future__ import annotations

import json
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "verification"
SCENES = DATA / "scenes"


@dataclass(frozen=True)
class Case:
    name: str            # the reference's name (tests/data/verification/NAME.json)
    scene: str           # a scene file under tests/data/verification/scenes, or a shipped scene
    what: str
    sizes: tuple[float, ...]


CASES = (
    Case("stepped_free", "stepped.toml", "stepped 25/35/30/25 mm, 1 mm fillets", (8, 12, 16)),
    Case("keyed_free", "keyed.toml", "the same, keyway with sharp floor corners", (8, 12, 16)),
    Case("keyed_rounded_free", "keyed_rounded.toml",
         "the same, keyway with 1 mm floor corners", (8, 12, 16)),
    Case("cone_tube_free", "cone_tube.toml", "journal, cone, 16 mm bore, fillet, chamfers",
         (8, 12, 16)),
    Case("stepped_installed", "stepped_installed.toml",
         "the stepped shaft on two rigid seats", (8, 12)),
    Case("cross_hole_free", "cross_hole.toml",
         "STEP: 30 mm bar, 6 mm cross hole, ring groove with sharp floor", (8, 12, 16)),
    Case("paper2018_free", "paper2018", "the paper's shaft: helical grooves, round roots", (8,)),
    Case("paper2018_sharp_free", "paper2018_sharp.toml",
         "the paper's shaft, sharp groove roots", (8,)),
)


def reference(case: Case) -> tuple[np.ndarray, float, str]:
    """The case's reference frequencies (Hz), their largest relative change from the order
    below (nan with one order), and how they were made."""
    data = json.loads((DATA / f"{case.name}.json").read_text())
    orders = data["orders"]
    top, below = (elastic(o) for o in (orders[-1], orders[max(len(orders) - 2, 0)]))
    change = (float(np.max(np.abs(below / top - 1)))
              if len(orders) > 1 else float(data.get("change_from_order_below", np.nan)))
    how = (f"{data['program']}, order {orders[-1]['order']}, {orders[-1]['dofs']:,} DOFs"
           + (f", {data['hp_levels']} hp layers" if data.get("hp_levels") else ""))
    return top, change, how


def elastic(order: dict) -> np.ndarray:
    """An order's frequencies above 1 Hz (Hz): a shaft in its seats still turns freely
    about its axis, a rigid motion shaftfem counts apart."""
    f = np.array(order["frequencies_hz"])
    return f[f > 1.0]


def scene_of(case: Case):
    from shaftfem.scene.load import load_scene

    path = SCENES / case.scene
    return load_scene(path if path.exists() else case.scene)


@dataclass(frozen=True)
class Row:
    case: Case
    size: float
    dofs: int
    f: np.ndarray
    error: np.ndarray       # f / f_ref - 1
    bound: np.ndarray
    upward: np.ndarray

    @property
    def holds(self) -> np.ndarray:
        return (-self.upward <= self.error) & (self.error <= self.bound)

    @property
    def effectivity(self) -> np.ndarray:
        side = np.where(self.error >= 0, self.bound, self.upward)
        return side / np.maximum(np.abs(self.error), 1e-300)


def solve(case: Case, size: float) -> Row:
    from shaftfem.workflows.bounded import estimate_errors
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    f_ref, _, _ = reference(case)
    r = run_modes(with_mesh(scene_of(case), size))
    est = estimate_errors(r)
    f = r.modes.frequencies
    n = min(f.size, f_ref.size)
    return Row(case, size, r.modes.n_dofs, f[:n], f[:n] / f_ref[:n] - 1,
               est.relative_error[:n], est.upward[:n])


def export_steps() -> None:
    """Each profile case's solid as the STEP its reference reads (the reference's inputs:
    tests/data/verification/cases/CASE.json)."""
    import shutil
    import subprocess
    import tempfile

    steps = ROOT / "out" / "verification" / "steps"
    steps.mkdir(parents=True, exist_ok=True)
    for case in CASES:
        path = SCENES / case.scene
        if not path.exists() or "step_file" in path.read_text():
            continue
        with tempfile.TemporaryDirectory() as d:
            subprocess.run([sys.executable, "-m", "shaftfem", "export", str(path), "--out", d,
                            "--no-estimate", "-q"], check=True)
            shutil.copy(Path(d) / "shaft.step", steps / f"{path.stem}.step")


def main(argv: list[str]) -> None:
    if "--steps" in argv:
        export_steps()
        return
    rows = [solve(case, size) for case in CASES if (DATA / f"{case.name}.json").exists()
            for size in case.sizes]
    if "--write" in argv:
        import contextlib
        import io

        buffer = io.StringIO()
        with contextlib.redirect_stdout(buffer):
            tables(rows)
        doc = ROOT / "docs" / "verification.md"
        text = doc.read_text()
        head, rest = text.split(BEGIN, 1)
        tail = rest.split(END, 1)[1]
        doc.write_text(f"{head}{BEGIN}\n{buffer.getvalue()}{END}{tail}")
    else:
        tables(rows)


BEGIN = "<!-- benchmarks/verification.py --write: from here -->"
END = "<!-- benchmarks/verification.py --write: to here -->"


def tables(rows: list[Row]) -> None:
    """The matrix's summary per solid and mesh, then every mode."""
    print("| solid | reference (its change from the order below) | mesh (mm) | DOFs "
          "| bounds holding | effectivity | largest error | its bound |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        _, change, how = reference(r.case)
        k = int(np.argmax(np.abs(r.error)))
        print(f"| {r.case.what} | {how} ({100 * change:.3f} %) | {r.size:g} | {r.dofs:,} "
              f"| {int(r.holds.sum())} of {r.holds.size} | {r.effectivity.min():.2f}-"
              f"{r.effectivity.max():.2f} | {100 * r.error[k]:+.3f} % | "
              f"{100 * (r.bound[k] if r.error[k] >= 0 else r.upward[k]):.3f} % |")
    eff = np.concatenate([r.effectivity for r in rows])
    held = np.concatenate([r.holds for r in rows])
    print(f"\n{int(held.sum())} of {held.size} bounds hold; effectivity at most 5 on "
          f"{100 * np.mean(eff <= 5):.0f} % of the modes, at most 3 on "
          f"{100 * np.mean(eff <= 3):.0f} %.\n")
    print("| solid | mesh (mm) | mode | f (Hz) | reference (Hz) | true error | bound "
          "| effectivity | holds |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        f_ref, _, _ = reference(r.case)
        for i in range(r.f.size):
            side = r.bound[i] if r.error[i] >= 0 else r.upward[i]
            print(f"| {r.case.name} | {r.size:g} | {i + 1} | {r.f[i]:.2f} | {f_ref[i]:.2f} "
                  f"| {100 * r.error[i]:+.4f} % | {'-' if r.error[i] >= 0 else '+'}"
                  f"{100 * side:.4f} % | {r.effectivity[i]:.2f} | "
                  f"{'yes' if r.holds[i] else 'NO'} |")


if __name__ == "__main__":
    main(sys.argv[1:])
