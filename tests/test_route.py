"""--accuracy alone chooses the discretisation: the quickest route the measured model
says reaches the bound, and a clear stop when none does within the budget."""

import time

import numpy as np
import pytest

from shaftfem.cli import main
from shaftfem.errors import SceneError
from shaftfem.scene.load import load_scene
from shaftfem.workflows.route import choose_route

# NGSolve order 4 at 541k DOFs on the paper's shaft (docs/verification.md)
REFERENCE_HZ = np.array([432.345, 443.605, 1194.718, 1223.043, 2334.896, 2382.666, 2733.028,
                         3816.800, 3885.261, 4450.090])


@pytest.fixture(scope="module")
def paper():
    return load_scene("paper2018")


def test_an_accuracy_beyond_the_budget_stops_before_any_computation(capsys, tmp_path,
                                                                    monkeypatch):
    monkeypatch.setenv("SHAFTFEM_CACHE", str(tmp_path))
    t = time.perf_counter()
    assert main(["modes", "paper2018", "--accuracy", "0.1", "-q"]) == 2
    assert time.perf_counter() - t < 10
    err = capsys.readouterr().err
    assert "--accuracy 0.1" in err and "400,000 DOFs" in err and "--max-dofs" in err
    assert "Traceback" not in err
    assert not any(tmp_path.rglob("*.npz"))      # nothing meshed or solved
    # what it says can be asked for is not refused, with this budget or a smaller one
    floor = float(err.split("Ask for ")[1].split(" %")[0])
    assert choose_route(load_scene("paper2018"), floor / 100, 400_000) is not None
    with pytest.raises(SceneError) as small:
        choose_route(load_scene("paper2018"), 0.004, 100_000)
    floor = float(str(small.value).split("Ask for ")[1].split(" %")[0])
    assert choose_route(load_scene("paper2018"), floor / 100, 100_000) is not None


def test_a_larger_budget_takes_the_same_target(paper):
    with pytest.raises(SceneError):
        choose_route(paper, 0.003, 400_000)
    r = choose_route(paper, 0.003, 500_000)
    assert r.adaptive and 400_000 < r.dofs <= 500_000


def test_each_target_gets_the_quickest_route_whose_measured_bound_reaches_it(paper):
    loose = choose_route(paper, 0.05, 400_000)
    assert not loose.adaptive and loose.scene.mesh.order == 2 and loose.bound <= 0.05
    mid = choose_route(paper, 0.01, 400_000)
    assert not mid.adaptive and mid.scene.mesh.order == 5
    assert mid.scene.mesh.geometry_order == 3 and mid.bound <= 0.01
    tight = choose_route(paper, 0.0045, 400_000)
    assert tight.bound <= 0.0045 and tight.dofs > mid.dofs
    assert choose_route(paper, 0.004, 400_000).adaptive     # below every fixed route's


def test_a_shaft_outside_the_measured_family_adapts_at_order_2():
    for name in ("plain_cylinder", "examples/stepped_shaft.toml"):
        r = choose_route(load_scene(name), 0.001, 400_000)
        assert r.adaptive and r.scene.mesh.order == 2 and "no cost model" in r.why


@pytest.mark.slow
def test_the_chosen_route_reaches_its_target_and_the_bound_holds(capsys, paper):
    """--accuracy 1 on the paper's shaft: the chosen route's own bounds are below 1 %,
    and each holds against the NGSolve reference."""
    from shaftfem.workflows.bounded import run_bounded, with_accuracy

    b = run_bounded(with_accuracy(paper, 1.0), choose=True)
    assert b.adapted is not None and b.adapted.reached and b.adapted.chosen
    f = b.result.modes.frequencies
    error = f / REFERENCE_HZ - 1
    assert np.all(b.estimate.relative_error < 0.01)
    assert np.all(b.estimate.relative_error >= error)
