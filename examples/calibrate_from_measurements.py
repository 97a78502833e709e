"""Calibration: the scene values that reproduce measured frequencies, with their
uncertainty. A grid of modal runs on Dask workers, then SciPy's bounded least squares.

    python examples/calibrate_from_measurements.py
"""

from pathlib import Path

import shaftfem.runtime

shaftfem.runtime.configure_threads()

from shaftfem.workflows.calibrate import (  # noqa: E402
    calibrate,
    calibration_text,
    load_calibration,
)

if __name__ == "__main__":  # Dask starts worker processes that import this file
    cal = load_calibration(Path(__file__).with_name("hammer_test.toml"))
    fit = calibrate(cal, Path("out/hammer_test"), workers=2)
    print(calibration_text(fit, cal))
    length, sigma = fit.parameters["shaft.length_mm"], fit.std["shaft.length_mm"]
    print(f"\nthe bar is {length:.1f} +- {sigma:.1f} mm long")
