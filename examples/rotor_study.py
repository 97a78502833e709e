"""The rotordynamic study of a pump, from Python: the shaft on its journal bearings with
its wear ring and its coupled motor (examples/pump_on_journals.toml), turned at its
operating speed (whirl, critical speeds, stability), its undamped critical speed map,
and API 684's Level I stability screening with an anticipated cross-coupling.

    python examples/rotor_study.py
"""

import shaftfem.runtime

shaftfem.runtime.configure_threads()

from pathlib import Path  # noqa: E402

import shaftfem  # noqa: E402

HERE = Path(__file__).resolve().parent
# 30 mm elements: a quick look; drop with_mesh for the scene's own mesh
scene = shaftfem.with_mesh(shaftfem.load_scene(HERE / "pump_on_journals.toml"), size_mm=30.0)

# the shaft turning: the whirl at 3,000 r/min and the critical speeds up to 9,000 r/min
turning = shaftfem.campbell(scene)
c = turning.campbell
for w in c.operating:
    print(f"whirl at {w.speed_rpm:,.0f} r/min: {w.frequency_hz:7.2f} Hz {w.whirl:8s} "
          f"log dec {w.log_dec:6.3f} ({w.kind})")
for cs in turning.critical_speeds:
    if cs.order == 1 and cs.speed_rpm > 1000:
        print(f"critical speed: {cs.speed_rpm:,.0f} r/min ({cs.whirl}, 1x)")
for onset in c.onsets:
    print(f"unstable from {onset.speed_rpm:,.0f} r/min ({onset.whirl} whirl)")
turning.plot("campbell.png")

# the critical speeds against the bearings' stiffness; where the journals cross them
ucs = shaftfem.run_ucs(scene)
for b in ucs.bearings:
    for branch, direction, k, n in b.crossings:
        print(f"map: {b.name} k{direction}{direction} {k / 1e3:,.0f} N/mm meets branch "
              f"{branch + 1} at {n:,.0f} r/min")

# Level I: 2 N/mm anticipated at the impeller (no stage power given)
level1 = shaftfem.run_level1(scene, at_mm=600.0, qa_n_per_mm=2.0)
print(f"Level I: log dec {level1.log_dec_0:.3f} without Q, Q_0 {level1.q0 / 1e3:,.1f} N/mm, "
      f"Q_0 / Q_A {level1.ratio:.2f}, log dec at Q_A {level1.log_dec_a:.3f}: "
      + ("pass" if level1.passed else "Level II required"))
