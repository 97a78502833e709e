"""The work-precision study on the plain cylinder."""

import numpy as np
import pytest

from references import torsion_hz
from shaftfem.scene.load import load_scene
from shaftfem.workflows.study import run_study, study_reference, study_table


@pytest.mark.slow
def test_study_recovers_torsion_and_order_four():
    scene = load_scene("plain_cylinder")
    runs = run_study(scene, {2: [12.0, 9.0, 6.75], 1: [12.0]})
    ref, est = study_reference(runs, singular=False)
    kinds = [r for r in runs if r.order == 2][-1].kinds
    i = kinds.index("torsion")
    ft = torsion_hz(1, 0.55, 2.11e11, 0.277, 7870)
    finest = min((r for r in runs if r.order == 2), key=lambda r: r.size_mm)
    # the extrapolated torsion frequency is within the estimated error of the exact one
    assert abs(ref[i] / ft - 1) <= est.relative_error[i]
    assert abs(finest.frequencies[i] / ft - 1) <= est.relative_error[i]
    # smooth problem, P2: eigenvalue errors fall as h^4
    p = est.observed_order[np.isfinite(est.observed_order)]
    assert 3.0 < np.median(p) < 5.5, p
    rows = study_table(runs, ref, kinds)
    assert {r["element"] for r in rows} == {"P1", "P2"}
    assert all(r["peak_memory_mb"] > 0 and r["dofs"] > 0 for r in rows)
    # P1 on a coarse mesh is far worse than P2 on the same mesh size
    p1 = [r for r in rows if r["element"] == "P1"][0]
    p2 = [r for r in rows if r["element"] == "P2" and r["size_mm"] == 12.0][0]
    assert p1["max_rel_error"] > 10 * p2["max_rel_error"]
