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
low, high = run.estimate.interval(modes.frequencies)
for i, (f, kind, lo, hi) in enumerate(zip(modes.frequencies, modes.kinds, low, high), start=1):
    # the computed frequencies converge from above: the bound reaches mostly downwards;
    # upwards only the geometry allowances (the mesh's volume, straightened faces)
    print(f"mode {i:2d}  {f:9.2f} Hz  {kind:8s}  true frequency in [{lo:.2f}, {hi:.2f}] Hz")
