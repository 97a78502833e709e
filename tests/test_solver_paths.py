"""Every factorisation path offered gives the same ten frequencies."""

import numpy as np

from shaftfem.factor import available_factorizers
from shaftfem.modal import modal_analysis


def test_all_solver_paths_agree_to_1e8(paper):
    s = paper.system
    paths = available_factorizers()
    assert "superlu" in paths  # the pure-SciPy path is always there
    freqs = {p: modal_analysis(s.K, s.M, s.nodes, s.mass_scalar, factorizer=p).frequencies
             for p in paths}
    for p, f in freqs.items():
        assert np.max(np.abs(f / freqs["superlu"] - 1)) < 1e-8, p
    # the pipeline's run, whose PARDISO ordering was computed while K and M were filled
    assert np.max(np.abs(paper.modes.frequencies / freqs["superlu"] - 1)) < 1e-8
