"""A fast subset of the bounds' verification matrix (benchmarks/verification.py): each
solid's printed interval [f (1 - bound), f (1 + upward)] holds the frequency of an
independent reference, NGSolve at order 4 on netgen's own mesh of the exported STEP
(tests/data/verification/CASE.json, written by benchmarks/verification_reference.py)."""

import json
from pathlib import Path

import numpy as np
import pytest

DATA = Path(__file__).parent / "data" / "verification"

FAST = [("stepped_free", "stepped.toml", 12.0),
        ("keyed_free", "keyed.toml", 12.0),
        ("keyed_rounded_free", "keyed_rounded.toml", 16.0),
        ("cone_tube_free", "cone_tube.toml", 12.0),
        ("stepped_installed", "stepped_installed.toml", 12.0)]


def reference(name: str) -> tuple[np.ndarray, float]:
    """The reference's frequencies (Hz) and their largest change from the order below."""
    orders = json.loads((DATA / f"{name}.json").read_text())["orders"]
    # above 1 Hz: a shaft in its seats still turns about its axis, which shaftfem counts apart
    top, below = (np.array([f for f in o["frequencies_hz"] if f > 1.0])
                  for o in (orders[-1], orders[-2]))
    return top, float(np.max(np.abs(below / top - 1)))


@pytest.mark.parametrize("name,scene,size", [c for c in FAST if (DATA / f"{c[0]}.json").exists()])
def test_every_bound_holds_against_an_independent_reference(name, scene, size):
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.bounded import estimate_errors
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    f_ref, change = reference(name)
    # the reference converged well beyond the bounds it checks (0.3-1 % at 12 mm)
    assert change < 5e-4, change
    r = run_modes(with_mesh(load_scene(DATA / "scenes" / scene), size))
    est = estimate_errors(r)
    low, high = est.interval(r.modes.frequencies)
    n = f_ref.size
    assert r.modes.count >= n
    assert np.all((low[:n] <= f_ref) & (f_ref <= high[:n])), (
        r.modes.frequencies[:n] / f_ref - 1, est.relative_error[:n], est.upward[:n])
