"""A resonance check for CI: exit 0 when every mode keeps its margin from every
excitation harmonic, 1 when one does not, 4 when every margin holds but on a shaft that
nothing holds (a scene without [[support]]: its free-free modes lie above those in its
bearings).

    python examples/check_in_ci.py [SCENE.toml]

`shaftfem check SCENE.toml --mesh-size 10` does the same from the shell, with the
same exit codes (2 bad input, 3 a failure in the computation).
"""

import sys
from pathlib import Path

import shaftfem.runtime

shaftfem.runtime.configure_threads()

import shaftfem  # noqa: E402
from shaftfem.checks.resonance import check_result  # noqa: E402
from shaftfem.outputs.tables import verdict_text  # noqa: E402

scene_file = sys.argv[1] if len(sys.argv) > 1 else Path(__file__).with_name("my_shaft.toml")
# a coarse mesh is enough for a 15 % margin: the frequencies are within about 1 %
scene = shaftfem.with_mesh(shaftfem.load_scene(scene_file), size_mm=16.0)
result = shaftfem.run_modes(scene)
verdict = check_result(result, required=0.15)   # 15 % separation from every harmonic
print(verdict_text(verdict))
sys.exit(verdict.exit_status)
