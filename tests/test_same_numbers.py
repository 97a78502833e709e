"""benchmarks/same_numbers.py's comparison, which vouches that a rebuild changed no number:
it must find a change of the physics, and not call round-off one."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parents[1] / "benchmarks"))
from same_numbers import differences  # noqa: E402


def modes(mass_z_first: float, f_first: float = 24.87, bound: float = 0.0274451681,
          residual: float = 2e-12) -> dict:
    return {"mass_orthonormality_error": residual,
            "modes": [{"frequency_hz": f_first, "effective_mass_z_kg": mass_z_first,
                       "effective_mass_x_kg": 0.4, "error_bound_percent": bound,
                       "residual": residual},
                      {"frequency_hz": 718.56, "effective_mass_z_kg": 5.2,
                       "effective_mass_x_kg": 0.0, "error_bound_percent": 0.03,
                       "residual": residual}]}


def test_round_off_is_not_a_difference():
    before = modes(1e-25)
    # a bending mode's axial effective mass is round-off of a quantity that reaches 5.2 kg;
    # residuals measure round-off; a bound moved by 3e-12 of its frequency
    after = modes(3e-25, bound=0.0274451684, residual=1e-11)
    assert differences(before, after, "", 1e-9) == []


def test_a_change_of_the_physics_is_found():
    # a frequency is its own size, however high the list's others
    found = differences(modes(1e-25), modes(1e-25, f_first=24.87 * (1 + 1e-8)), "", 1e-9)
    assert [f.split(":")[0] for f in found] == [".modes[0].frequency_hz"]
    # a quantity that is not round-off on any mode: its own size counts
    assert len(differences(modes(0.1), modes(0.1 * (1 + 1e-6)), "", 1e-9)) == 1
    assert differences({"a": [1.0, 2.0]}, {"a": [1.0]}, "", 1e-9) == [
        ".a: 2 items before, 1 after"]
    assert differences({"a": 1.0}, {"b": 1.0}, "", 1e-9) == [".a: only in before",
                                                              ".b: only in after"]
