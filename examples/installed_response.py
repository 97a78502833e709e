"""The paper's shaft in its two bearings with its gear: modes, effective masses for
base excitation, and the transmissibility at the engine's harmonics.

    python examples/installed_response.py
"""

import shaftfem.runtime

shaftfem.runtime.configure_threads()

import numpy as np  # noqa: E402

import shaftfem  # noqa: E402
from shaftfem.fem.response import base_response, modal_basis, participation  # noqa: E402

# 12 mm elements: a quick look (about 1 % from converged); drop with_mesh for the
# scene's own mesh
scene = shaftfem.with_mesh(shaftfem.load_scene("paper2018_installed"), size_mm=12.0)
result = shaftfem.run_modes(scene)
modes = result.modes

p = participation(modal_basis(result))
lateral = p.effective[:, 0] / p.total[0]         # base motion along x, share of the mass
print("mode  frequency  kind      lateral effective mass")
for i, (f, kind, share) in enumerate(zip(modes.frequencies, modes.kinds, lateral), start=1):
    print(f"{i:4d}  {f:7.1f} Hz  {kind:8s}  {100 * share:5.1f} %")

engine = [60.0, 120.0]                           # 3600 r/min and its second harmonic, Hz
curve = base_response(result, np.array(engine), direction="x")
for f, t in zip(engine, curve.transmissibility):
    print(f"transmissibility |u / u_base| at {f:5.1f} Hz: {t:.3f}")
