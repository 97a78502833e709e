"""Adaptive meshes: the bound falls round by round to the accuracy asked for, the result
is cached, and a budget too small for the accuracy is said plainly."""

import re

import numpy as np
import pytest

from references import torsion_hz
from shaftfem.cli import main
from shaftfem.scene.load import load_scene
from shaftfem.workflows.adapt import run_adaptive
from shaftfem.workflows.pipeline import with_mesh

TARGET = 1e-4
pytestmark = pytest.mark.usefixtures("own_cache")   # its fixture starts cold


@pytest.fixture(scope="module")
def coarse_cylinder():
    return with_mesh(load_scene("plain_cylinder"), 12.0)


@pytest.fixture(scope="module")
def adapted(coarse_cylinder):
    """Adapted from scratch (and so cached for the command line below)."""
    import shutil

    from shaftfem.store import cache_dir

    shutil.rmtree(cache_dir() / "adapted", ignore_errors=True)
    a = run_adaptive(coarse_cylinder, TARGET, 150_000)
    assert not a.from_cache
    return a


def test_adaptivity_reaches_the_accuracy_with_a_falling_bound(coarse_cylinder, adapted):
    target, a = TARGET, adapted
    bounds = [r.max_bound for r in a.rounds]
    assert len(bounds) >= 2 and a.reached and not a.why
    assert all(b2 < b1 for b1, b2 in zip(bounds, bounds[1:])), bounds
    assert np.max(a.estimate.relative_error) <= target
    dofs = [r.dofs for r in a.rounds]
    assert dofs == sorted(dofs) and dofs[-1] == a.result.modes.n_dofs <= 150_000
    # the torsion frequency is inside its bound of the exact c_t / 2L, from above
    s, m = coarse_cylinder.shaft, coarse_cylinder.material
    i = a.result.modes.kinds.index("torsion")
    exact = torsion_hz(1, s.length, m.youngs_modulus, m.poisson_ratio, m.density)
    f = a.result.modes.frequencies[i]
    assert 0 < f / exact - 1 <= a.estimate.relative_error[i]


def test_a_budget_too_small_says_so_and_fails_only_when_strict(capsys):
    args = ["modes", "plain_cylinder", "--mesh-size", "12", "--accuracy", "0.00001",
            "--max-dofs", "30000", "-q"]
    assert main(args) == 0
    err = capsys.readouterr().err
    assert "NOT reached" in err and "above the budget of 30000 DOFs" in err
    assert main(args + ["--strict-accuracy"]) == 1
    assert "NOT reached" in capsys.readouterr().err
    # every modal command honours it (the adapted mesh is cached by now)
    args[0] = "check"
    assert main(args) == 0 and main(args + ["--strict-accuracy"]) == 1


def test_a_warm_run_solves_the_cached_mesh_and_prints_every_bound(adapted, capsys):
    assert main(["modes", "plain_cylinder", "--mesh-size", "12", "--accuracy", "0.01",
                 "--max-dofs", "150000", "-q"]) == 0
    out = capsys.readouterr().out
    assert "adaptive mesh for bounds below 0.01 %: reached (from cache)" in out
    assert f"P2, {adapted.result.modes.n_dofs} DOFs" in out
    rows = [line for line in out.splitlines() if line.strip()[:2].strip().isdigit()
            and " Hz " in line]
    assert len(rows) == 10 and all(re.search(r" -[\d.e-]+ % \+[\d.e-]+ %\*? ", r) for r in rows)
