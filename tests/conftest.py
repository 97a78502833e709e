import os
import sys
from pathlib import Path

# As the CLI does: one OpenBLAS thread, set before NumPy loads (shaftfem.runtime).
import shaftfem.runtime  # noqa: E402

shaftfem.runtime.configure_threads()
if "PYTEST_XDIST_WORKER" in os.environ:
    # one worker per core: MKL's threads in each would only fight the other worker's, and
    # so would work put beside a run (shaftfem.aside), as in a sweep's Dask workers: it
    # runs in line there (the tests of the work beside a run turn it back on)
    os.environ.setdefault("MKL_NUM_THREADS", "1")
    os.environ.setdefault("SHAFTFEM_ASIDE", "0")

import pytest

sys.path.insert(0, str(Path(__file__).parent))  # tests/references.py


@pytest.fixture(scope="session", autouse=True)
def _fresh_shape_cache(tmp_path_factory):
    """Every test session builds its CAD from scratch (the volume checks run), into one
    cache that its workers share, as a sweep's Dask workers do: what one worker built,
    the other reads (its entries are written whole and renamed into place)."""
    base = tmp_path_factory.getbasetemp()
    shared = base.parent if "PYTEST_XDIST_WORKER" in os.environ else base
    os.environ["SHAFTFEM_CACHE"] = str(shared / "cache")


@pytest.fixture(scope="module")
def own_cache(tmp_path_factory):
    """A cache of the module's own, for the module's tests: for a module whose fixture
    must start cold, as no other worker's run of that fixture may have warmed it."""
    before = os.environ["SHAFTFEM_CACHE"]
    os.environ["SHAFTFEM_CACHE"] = str(tmp_path_factory.mktemp("own_cache"))
    yield
    os.environ["SHAFTFEM_CACHE"] = before


@pytest.fixture(scope="session")
def cylinder(_fresh_shape_cache):
    """The plain 32 x 550 mm cylinder, P2 at 8 mm (4-fold symmetric mesh)."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes

    return run_modes(load_scene("plain_cylinder"))


@pytest.fixture(scope="session")
def paper(_fresh_shape_cache):
    """The paper's grooved shaft with its default mesh."""
    from shaftfem.scene.load import load_scene
    from shaftfem.workflows.pipeline import run_modes

    return run_modes(load_scene("paper2018"))
