"""Where each printed interval puts the true frequency, against the NGSolve references of
docs/verification.md, on the paper's shaft at orders 2 to 5 (the table in
docs/accuracy.md, "How far each frequency is from converged").

    .venv/bin/python benchmarks/bound_intervals.py

Runs `shaftfem modes --json` with its bound for: P2 and order 3 on the default mesh
(8/4/4 mm), orders 4 and 5 on cubic geometry at 16/12/12 mm (a scene of those sizes
written next to the paper's). Each interval is [f (1 - bound), f (1 + upper)]: the
discretisation error is one-sided, the geometry allowances count both ways. Prints a
Markdown table.
"""

import json
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import PAPER_REFERENCE_HZ  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
# NGSolve on its own curved mesh of the exported STEP (docs/verification.md)
REFERENCES = {"order 4, 541k DOFs": list(PAPER_REFERENCE_HZ)}


def held(modes: list[dict], reference: list[float]) -> int:
    """How many reference frequencies lie inside their mode's interval."""
    return sum(x["true_frequency_low_hz"] <= f <= x["true_frequency_high_hz"]
               for x, f in zip(modes, reference))


def coarse_scene(folder: Path, tree: Path = ROOT) -> Path:
    """The paper's scene of the source tree `tree` with 16/12/12 mm elements, in `folder`."""
    text = (tree / "geometry" / "paper2018.toml").read_text()
    for key, value in (("element_size_mm", 16.0), ("groove_element_size_mm", 12.0),
                       ("edge_element_size_mm", 12.0)):
        lines = [f"{key} = {value}" if line.split("=")[0].strip() == key else line
                 for line in text.splitlines()]
        text = "\n".join(lines) + "\n"
    path = folder / "paper2018_16_12_12.toml"
    path.write_text(text)
    return path


def main() -> None:
    with tempfile.TemporaryDirectory() as d:
        coarse = str(coarse_scene(Path(d)))
        cases = [("P2, 8/4/4 (the default)", ["paper2018"]),
                 ("order 3, 8/4/4", ["paper2018", "--order", "3"]),
                 ("order 4, cubic 16/12/12", [coarse, "--order", "4", "--geometry-order", "3"]),
                 ("order 5, cubic 16/12/12", [coarse, "--order", "5", "--geometry-order", "3"])]
        print("| run | DOFs | mode 1: f, interval (Hz) | widest upward allowance | "
              "references inside the interval | f against the order-4 reference |")
        print("|---|---|---|---|---|---|")
        for name, args in cases:
            out = Path(d) / "modes.json"
            subprocess.run([sys.executable, "-m", "shaftfem", "modes", *args, "-q", "--json",
                            str(out)], check=True, capture_output=True)
            r = json.loads(out.read_text())
            m = r["modes"]
            inside = ", ".join(f"{held(m, ref)}/10 ({which})" for which, ref in REFERENCES.items())
            off = [100 * (x["frequency_hz"] / f - 1)
                   for x, f in zip(m, REFERENCES["order 4, 541k DOFs"])]
            print(f"| {name} | {r['dofs']:,} | {m[0]['frequency_hz']:.2f}, "
                  f"[{m[0]['true_frequency_low_hz']:.2f}, {m[0]['true_frequency_high_hz']:.2f}] | "
                  f"{max(x['error_bound_upper_percent'] for x in m):.2g} % | {inside} | "
                  f"{min(off):+.3f} to {max(off):+.3f} % |", flush=True)


if __name__ == "__main__":
    main()
