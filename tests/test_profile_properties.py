"""Random profiles, valid and invalid (hypothesis): sections, cones, bores, fillets,
chamfers, keyways, seats. Every one the scene checks accept builds, meshes and solves
into positive, finite frequencies with small residuals; every one they refuse is refused
as one line naming the file; no OpenCASCADE or gmsh error reaches the user as anything
but shaftfem's own one-line error.

A short run of 40 profiles is in the suite; `pytest -m slow` runs 400 more.
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from shaftfem.errors import SceneError, ShaftfemError
from shaftfem.scene.load import SceneText, load_scene

MATERIAL = """
[material]
youngs_modulus_mpa = 210000.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0
"""

@st.composite
def profiles(draw) -> str:
    """A scene file's text: one to three sections, maybe a keyway, a helical groove and
    seats. Many are invalid on purpose (fillets and chamfers beyond their steps, bores
    through the next section, keyways too deep or across a shoulder, grooves and seats
    across a shoulder or over a keyway)."""
    n = draw(st.integers(1, 3))
    lines = ['name = "drawn"']
    sections = []
    for _ in range(n):
        length = draw(st.sampled_from([30.0, 45.0, 60.0, 90.0]))
        d0 = draw(st.sampled_from([20.0, 25.0, 30.0, 35.0, 40.0]))
        cone = draw(st.booleans()) and draw(st.integers(0, 3)) == 0
        d1 = d0 + draw(st.sampled_from([-5.0, 5.0])) if cone else d0
        bore = draw(st.sampled_from([0.0, 0.0, 0.0, 10.0, 16.0, 22.0]))
        fillet = draw(st.sampled_from([0.0, 0.0, 1.0, 2.0, 3.0]))
        chamfer = draw(st.sampled_from([0.0, 0.0, 0.5, 1.0, 2.5]))
        sections.append((length, d0, d1, bore))
        lines.append("[[section]]")
        lines.append(f"length_mm = {length}")
        if cone:
            lines += [f"diameter_start_mm = {d0}", f"diameter_end_mm = {d1}"]
        else:
            lines.append(f"diameter_mm = {d0}")
        if bore:
            lines.append(f"bore_mm = {bore}")
        if fillet:
            lines.append(f"fillet_mm = {fillet}")
        if chamfer:
            lines.append(f"chamfer_mm = {chamfer}")
    total = sum(s[0] for s in sections)
    if draw(st.booleans()):
        lines += ["[shaft]", f"end_chamfer_mm = {draw(st.sampled_from([0.5, 1.0, 6.0]))}"]
    for _ in range(draw(st.integers(0, 1))):
        pos = draw(st.floats(15.0, total - 15.0)) if total > 30 else total / 2
        lines += ["[[keyway]]", f"position_mm = {pos:.1f}",
                  f"length_mm = {draw(st.sampled_from([12.0, 20.0, 28.0]))}",
                  f"form = \"{draw(st.sampled_from(['rounded', 'sled']))}\"",
                  f"angle_deg = {draw(st.sampled_from([0.0, 45.0, 200.0]))}"]
        if draw(st.booleans()):
            lines.append(f"depth_mm = {draw(st.sampled_from([3.0, 5.0, 9.0]))}")
    if draw(st.integers(0, 3)) == 0:   # a helical groove, maybe across a shoulder
        start = draw(st.sampled_from([0.0, 5.0, 30.0, 50.0]))
        lines += ["[grooves]", 'hands = ["right"]', "pitch_mm = 40.0", "width_mm = 6.0",
                  f"depth_mm = {draw(st.sampled_from([2.0, 4.0]))}", "root_radius_mm = 1.0",
                  f"grooved_length_mm = {draw(st.sampled_from([20.0, 40.0]))}",
                  f"start_mm = {start}"]
    for k in range(draw(st.integers(0, 2))):
        pos = draw(st.floats(6.0, total - 6.0))
        lines += ["[[support]]", f"position_mm = {pos:.1f}", "width_mm = 10.0",
                  f"kind = \"{'rigid' if k == 0 else 'rigid-radial'}\""]
    lines += ["[mesh]", "element_size_mm = 12.0", "groove_element_size_mm = 4.0",
              "[modes]", "count = 4"]
    return "\n".join(lines) + "\n" + MATERIAL


def check(text: str) -> None:
    from shaftfem.workflows.pipeline import run_modes

    try:
        scene = load_scene(SceneText(text=text, source="drawn.toml"))
    except SceneError as exc:   # refused: one line, naming the file
        message = str(exc)
        assert "\n" not in message and message.startswith("drawn.toml: "), message
        return
    try:
        result = run_modes(scene)
    except ShaftfemError as exc:  # accepted by the checks, so it must build and solve
        raise AssertionError(f"a valid profile failed: {exc}\n{text}") from exc
    m = result.modes
    assert m.count == 4 and np.all(np.isfinite(m.frequencies)) and m.frequencies[0] > 0
    assert np.all(m.residuals < 1e-6)


@pytest.mark.slow
@settings(max_examples=40, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(profiles())
def test_random_profiles_build_or_are_refused(text):
    check(text)


@pytest.mark.slow
@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(profiles())
def test_many_random_profiles_build_or_are_refused(text):
    check(text)
