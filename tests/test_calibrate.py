"""Calibration recovers parameters that the toolkit itself used to make the targets."""

import numpy as np
import pytest

from shaftfem.workflows.calibrate import Calibration, calibrate
from shaftfem.workflows.sweep import run_variant


@pytest.mark.slow  # about 70 s: a 3x3 grid and a least-squares fit, each a modal run
def test_recovers_hidden_length_and_diameter(tmp_path):
    hidden = {"shaft.length_mm": 537.0, "shaft.diameter_mm": 31.2}
    row = run_variant("plain_cylinder", hidden, 16.0)
    targets = np.array([row[f"f{i}_hz"] for i in range(1, 7)])
    cal = Calibration(base="plain_cylinder", mesh_size_mm=16.0,
                      unknowns={"shaft.length_mm": (500.0, 600.0),
                                "shaft.diameter_mm": (28.0, 36.0)},
                      targets=targets, sigma=targets * 0.001, grid=3)
    res = calibrate(cal, tmp_path, workers=2)
    for k, v in hidden.items():
        # within the stated uncertainty (3 standard deviations) and close in absolute terms
        assert abs(res.parameters[k] - v) <= 3 * res.std[k] + 1e-9, (k, res.parameters[k], res.std[k])
        assert abs(res.parameters[k] / v - 1) < 0.01
    assert res.chi2 < len(targets)  # the fit is as good as the stated uncertainty
