"""A design sweep: every combination of the file's axes, each a full modal run, on two
local Dask worker processes. Run again with the same folder, it resumes.

    python examples/sweep.py
"""

from pathlib import Path

import shaftfem.runtime

shaftfem.runtime.configure_threads()

from shaftfem.workflows.sweep import run_sweep  # noqa: E402
from shaftfem.workflows.sweep_file import load_sweep  # noqa: E402

if __name__ == "__main__":  # Dask starts worker processes that import this file
    sweep = load_sweep(Path(__file__).with_name("length_sweep.toml"))
    rows = run_sweep(sweep, Path("out/length_sweep/results.csv"), workers=2)
    print("length (mm)  diameter (mm)  mode 1 (Hz)  status")
    for r in rows:  # as results.csv holds them: text, in the file's units
        print(f"{float(r['shaft.length_mm']):11.0f}  {float(r['shaft.diameter_mm']):13.0f}  "
              f"{float(r['f1_hz']):11.2f}  {r['status']}")
