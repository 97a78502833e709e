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
    how = (f"order {orders[-1]['order']}, {orders[-1]['dofs'] / 1e3:.0f}k DOFs"
           + (f", hp {data['hp_levels']}" if data.get("hp_levels") else ""))
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
    f_ref: np.ndarray
    bound: np.ndarray
    upward: np.ndarray

    @property
    def error(self) -> np.ndarray:
        """f / f_ref - 1."""
        return self.f / self.f_ref - 1

    @property
    def side(self) -> np.ndarray:
        """The bound on the side where the reference lies (downward, or the upward
        allowance where the reference lies above f)."""
        return np.where(self.error >= 0, self.bound, self.upward)

    @property
    def holds(self) -> np.ndarray:
        return (-self.upward <= self.error) & (self.error <= self.bound)

    @property
    def effectivity(self) -> np.ndarray:
        return self.side / np.maximum(np.abs(self.error), 1e-300)


def solve(case: Case, size: float, f_ref: np.ndarray) -> Row:
    from shaftfem.workflows.bounded import estimate_errors
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    r = run_modes(with_mesh(scene_of(case), size))
    est = estimate_errors(r)
    n = min(r.modes.count, f_ref.size)
    return Row(case, size, r.modes.n_dofs, r.modes.frequencies[:n], f_ref[:n],
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
    references = {case.name: reference(case) for case in CASES
                  if (DATA / f"{case.name}.json").exists()}
    rows = [solve(case, size, references[case.name][0]) for case in CASES
            if case.name in references for size in case.sizes]
    text = tables(rows, {name: (change, how) for name, (_, change, how) in references.items()})
    if "--write" in argv:
        doc = ROOT / "docs" / "verification.md"
        head, rest = doc.read_text().split(BEGIN, 1)
        doc.write_text(f"{head}{BEGIN}\n{text}{END}{rest.split(END, 1)[1]}")
    else:
        print(text, end="")


BEGIN = "<!-- benchmarks/verification.py --write: from here -->"
END = "<!-- benchmarks/verification.py --write: to here -->"


def tables(rows: list[Row], references: dict[str, tuple[float, str]]) -> str:
    """The matrix's summary per solid and mesh, then every mode (Markdown); `references`:
    each case's reference's change from the order below, and how it was made."""
    out = ["| solid | NGSolve reference (change from the order below) | mesh (mm) | DOFs "
           "| bounds holding | effectivity | largest error | its bound |",
           "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        change, how = references[r.case.name]
        k = int(np.argmax(np.abs(r.error)))
        out.append(f"| {r.case.what} | {how} ({100 * change:.3f} %) | {r.size:g} | {r.dofs:,} "
                   f"| {int(r.holds.sum())} of {r.holds.size} | {r.effectivity.min():.2f}-"
                   f"{r.effectivity.max():.2f} | {100 * r.error[k]:+.3f} % | "
                   f"{100 * r.side[k]:.3f} % |")
    eff = np.concatenate([r.effectivity for r in rows])
    held = np.concatenate([r.holds for r in rows])
    out += ["", f"{int(held.sum())} of {held.size} bounds hold; effectivity at most 5 on "
            f"{100 * np.mean(eff <= 5):.0f} % of the modes, at most 3 on "
            f"{100 * np.mean(eff <= 3):.0f} %.", "",
            "| solid | mesh (mm) | mode | f (Hz) | reference (Hz) | true error | bound "
            "| effectivity | holds |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        error, side, eff, holds = r.error, r.side, r.effectivity, r.holds
        for i in range(r.f.size):
            out.append(f"| {r.case.name} | {r.size:g} | {i + 1} | {r.f[i]:.2f} | "
                       f"{r.f_ref[i]:.2f} | {100 * error[i]:+.4f} % | "
                       f"{'-' if error[i] >= 0 else '+'}{100 * side[i]:.4f} % | "
                       f"{eff[i]:.2f} | {'yes' if holds[i] else 'NO'} |")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    main(sys.argv[1:])
