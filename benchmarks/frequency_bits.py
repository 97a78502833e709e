"""Every frequency of three shipped scenes to the last bit (hex), from a fresh cache.

Run it on two commits to show that a change leaves the numbers untouched:

    git worktree add /tmp/before COMMIT
    MKL_CBWR=AUTO PYTHONPATH=/tmp/before/src .venv/bin/python benchmarks/frequency_bits.py > before.txt
    MKL_CBWR=AUTO .venv/bin/python benchmarks/frequency_bits.py > after.txt
    diff before.txt after.txt

MKL_CBWR=AUTO makes MKL PARDISO's threaded solves repeat to the last bit (without
it they differ between runs by about 1e-12 relative).
"""

import os
import tempfile

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # what shaftfem.runtime does (older commits lack it)
os.environ["SHAFTFEM_CACHE"] = tempfile.mkdtemp()

from shaftfem.scene.load import load_scene  # noqa: E402
from shaftfem.workflows.pipeline import run_modes  # noqa: E402

for name in ("paper2018", "plain_cylinder", "paper2018_installed"):
    for f in run_modes(load_scene(name)).modes.frequencies:
        print(name, float(f).hex(), repr(float(f)))
