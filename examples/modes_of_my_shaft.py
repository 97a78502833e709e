"""Modes of my own shaft: a scene file in, frequencies with their error bounds out.

    python examples/modes_of_my_shaft.py [SCENE.toml]

The same as `shaftfem modes my_shaft.toml`, as a library call you can build on.
"""

import sys
from pathlib import Path

import shaftfem.runtime

shaftfem.runtime.configure_threads()  # before NumPy loads: one OpenBLAS thread beside MKL

import shaftfem  # noqa: E402

scene_file = sys.argv[1] if len(sys.argv) > 1 else Path(__file__).with_name("my_shaft.toml")
scene = shaftfem.load_scene(scene_file)          # checked, converted to SI
run = shaftfem.run_bounded(scene)                # modes, and a bound on each one's error

modes = run.result.modes
print(f"{scene.name}: {modes.n_dofs} DOFs, first {len(modes.frequencies)} elastic modes")
for i, (f, kind, bound) in enumerate(zip(modes.frequencies, modes.kinds,
                                          run.estimate.relative_error), start=1):
    # the true frequency lies in [f (1 - bound), f]: the computed ones converge from above
    print(f"mode {i:2d}  {f:9.2f} Hz  {kind:8s}  +- {100 * bound:.2g} %")
