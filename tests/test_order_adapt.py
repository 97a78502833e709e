"""Element orders adapted on one mesh: every round's space lies between uniform order 2
and the full order (so its frequencies do too), it is conforming and free of strain under
rigid motions, the run stays within its budget, its bounds fall round by round, its
torsion frequency lies inside its bound of c_t/2L, and a warm run (an accuracy asked of
an order-3 scene) takes the cached orders."""

import numpy as np
import pytest

from references import torsion_hz

SIZE_MM = 16.0
pytestmark = pytest.mark.usefixtures("own_cache")   # its fixture starts cold


@pytest.fixture(scope="module")
def adapted(cylinder):
    from shaftfem.runtime import RunOptions
    from shaftfem.workflows.bounded import run_bounded, with_accuracy
    from shaftfem.workflows.order_adapt import run_order_adaptive
    from shaftfem.workflows.pipeline import with_mesh

    scene = with_mesh(cylinder.scene, SIZE_MM, order=3)
    # a target below the 16 mm circle's geometric floor: the run ends on its budget
    cold = run_order_adaptive(scene, 1e-5, 20_000, RunOptions(use_cache=True))
    # what the modal commands run for --accuracy 0.001 --order 3, counting its numeric
    # factorisations and recoveries
    from shaftfem.fem import factor
    from shaftfem.workflows import order_adapt

    counts = {"factorisations": 0, "solves": 0, "recoveries": 0}
    run, recover = factor.Pardiso._run, order_adapt.recovery_estimate

    def counted_run(self, phase, *args, **kwargs):
        counts["factorisations"] += phase == 22
        counts["solves"] += phase == 33
        return run(self, phase, *args, **kwargs)

    def counted_recovery(*args, **kwargs):
        counts["recoveries"] += 1
        return recover(*args, **kwargs)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(factor.Pardiso, "_run", counted_run)
        mp.setattr(order_adapt, "recovery_estimate", counted_recovery)
        warm = run_bounded(with_accuracy(scene, 1e-3, 20_000), options=RunOptions(use_cache=True))
    return scene, cold, warm.adapted, counts


@pytest.fixture(scope="module")
def uniform(cylinder):
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    return {p: run_modes(with_mesh(cylinder.scene, SIZE_MM, order=p)) for p in (2, 3)}


def test_adapted_space_lies_between_uniform_orders(adapted, uniform):
    """Nested spaces: f(order 2) >= f(adapted) >= f(order 3) mode by mode, and the
    adapted space is strictly larger than order 2 and smaller than order 3."""
    from shaftfem.fem.estimate import matched

    _, cold, _, _ = adapted
    m = cold.result.modes
    f2 = matched(m.kinds, uniform[2].modes.kinds, uniform[2].modes.frequencies)
    f3 = matched(m.kinds, uniform[3].modes.kinds, uniform[3].modes.frequencies)
    assert np.all(f2 >= m.frequencies * (1 - 1e-9))
    assert np.all(m.frequencies >= f3 * (1 - 1e-9))
    assert uniform[2].modes.n_dofs < m.n_dofs < uniform[3].modes.n_dofs
    assert len(cold.rounds) >= 3
    assert all(a.dofs < b.dofs for a, b in zip(cold.rounds, cold.rounds[1:]))


def test_adapted_space_is_conforming_and_rigid_free(adapted):
    """K t = 0 for the three translations of the adapted space (its constant field), and
    the solver found exactly six rigid modes."""
    _, cold, _, _ = adapted
    s = cold.result.system
    for c in range(3):
        t = np.zeros(s.n_dofs)
        t[c::3] = s.constant
        assert np.linalg.norm(s.K @ t) < 1e-9 * abs(s.K).max() * np.linalg.norm(t)
    assert cold.result.modes.n_rigid == 6


def test_bounds_fall_round_by_round(adapted):
    """From the second round (the first bounded one) on, each round's largest bound is
    below the last's."""
    _, cold, _, _ = adapted
    bounds = [r.max_bound for r in cold.rounds[1:]]
    assert all(b < a for a, b in zip(bounds, bounds[1:])), bounds


def test_budget_and_torsion_bound(adapted, cylinder):
    """The run ends within its DOF budget, saying why, and its first torsion frequency
    lies inside its bound of c_t/2L."""
    scene, cold, _, _ = adapted
    assert not cold.reached and "budget" in cold.why
    assert cold.result.modes.n_dofs <= 20_000
    m, mat = cold.result.modes, scene.material
    i = m.kinds.index("torsion")
    exact = torsion_hz(1, scene.shaft.length, mat.youngs_modulus, mat.poisson_ratio, mat.density)
    assert abs(m.frequencies[i] / exact - 1) <= cold.estimate.relative_error[i]


def test_warm_run_takes_the_cached_orders(adapted):
    """The second run solves the cached space once, factorising once at the cached
    shift, refining the cached shapes (at most REFINE_DAVIDSON block solves, where a
    Lanczos search takes 20 or more) and taking the last round's recovery from the
    cache: same DOFs, frequencies and bound."""
    from shaftfem.fem.eigen import REFINE_DAVIDSON

    _, cold, warm, counts = adapted
    assert counts["factorisations"] == 1 and counts["recoveries"] == 0
    assert counts["solves"] <= REFINE_DAVIDSON
    assert warm.from_cache and not cold.from_cache
    assert warm.result.modes.n_dofs == cold.result.modes.n_dofs
    assert np.allclose(warm.result.modes.frequencies, cold.result.modes.frequencies, rtol=1e-9)
    assert np.allclose(warm.estimate.relative_error, cold.estimate.relative_error, rtol=1e-6)
    assert [r.dofs for r in warm.rounds] == [r.dofs for r in cold.rounds]
