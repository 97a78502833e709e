"""Every factorisation path offered gives the same ten frequencies."""

import numpy as np
import pytest

from shaftfem.fem.eigen import SolverSettings
from shaftfem.fem.factor import available_factorisers
from shaftfem.fem.modes import modal_analysis


@pytest.fixture(scope="module")
def short_grooved(_fresh_shape_cache):
    """The paper's shaft cut to 200 mm with two turns of its grooves (about 30k DOFs):
    the same grooves and mesh sizes, a SuperLU solve a fifth as long."""
    from shaftfem.runtime import RunOptions
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes

    return run_modes(load_scene("paper2018", overrides={
        "shaft.length_mm": 200.0, "grooves.grooved_length_mm": 120.0}), RunOptions(factoriser="pardiso"))


def _agree(result):
    s = result.system
    paths = available_factorisers()
    assert "superlu" in paths  # the pure-SciPy path is always there
    freqs = {p: modal_analysis(s, settings=SolverSettings(p)).frequencies
             for p in paths}
    for p, f in freqs.items():
        assert np.max(np.abs(f / freqs["superlu"] - 1)) < 1e-8, p
    # the pipeline's run, whose PARDISO ordering was computed while K and M were filled
    assert result.modes.factoriser == "pardiso"
    assert np.max(np.abs(result.modes.frequencies / freqs["superlu"] - 1)) < 1e-8


@pytest.mark.slow
def test_all_solver_paths_agree_to_1e8(short_grooved):
    _agree(short_grooved)


@pytest.mark.slow
def test_all_solver_paths_agree_to_1e8_on_the_paper_shaft(paper):
    _agree(paper)
