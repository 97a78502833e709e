"""Bad scene input: a one-line error naming the key, exit code 2, no traceback."""

import re

import pytest

from shaftfem.cli import main
from shaftfem.errors import SceneError
from shaftfem.scene import GEOMETRY_DIR, load_scene

PAPER = (GEOMETRY_DIR / "paper2018.toml").read_text()


def _edit(text: str, key: str, value: str) -> str:
    new, n = re.subn(rf"(?m)^{re.escape(key)}\s*=.*$", f"{key} = {value}", text)
    assert n == 1, key
    return new


CASES = [
    ("length_mm", "0", "shaft.length_mm"),
    ("diameter_mm", "-32", "shaft.diameter_mm"),
    ("depth_mm", "-1", "grooves.depth_mm"),
    ("depth_mm", "16", "grooves.depth_mm"),            # as deep as the radius
    ("width_mm", "41", "grooves.width_mm"),            # wider than half the pitch
    ("grooved_length_mm", "600", "grooves.grooved_length_mm"),
    ("poisson_ratio", "0.5", "material.poisson_ratio"),
    ("poisson_ratio", "-1.0", "material.poisson_ratio"),
    ("youngs_modulus_mpa", '"steel"', "material.youngs_modulus_mpa"),  # wrong type
    ("element_size_mm", "0", "mesh.element_size_mm"),
    ("order", "3", "mesh.order"),
    ("hands", '["right", "right"]', "grooves.hands"),
    ("power_kw", "0", "sizing.power_kw"),
]


@pytest.mark.parametrize("key,value,named", CASES)
def test_bad_value_names_the_key(tmp_path, capsys, key, value, named):
    f = tmp_path / "bad.toml"
    f.write_text(_edit(PAPER, key, value))
    with pytest.raises(SceneError, match=re.escape(named)):
        load_scene(f)
    assert main(["modes", str(f), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and named in err and "Traceback" not in err


def test_unknown_key_is_named(tmp_path, capsys):
    f = tmp_path / "bad.toml"
    f.write_text(PAPER.replace("depth_mm = 3.0", "depth_mm = 3.0\ndepht_mm = 3.0"))
    assert main(["modes", str(f)]) == 2
    err = capsys.readouterr().err
    assert "grooves.depht_mm" in err and "unknown key" in err


def test_unknown_table_is_named(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text(PAPER + "\n[bearings]\ncount = 2\n")
    with pytest.raises(SceneError, match="bearings"):
        load_scene(f)


def test_missing_scene_file(capsys):
    assert main(["modes", "no_such_scene"]) == 2
    assert "no_such_scene" in capsys.readouterr().err


def test_invalid_toml(tmp_path, capsys):
    f = tmp_path / "bad.toml"
    f.write_text("[shaft\nlength_mm = 3")
    assert main(["modes", str(f)]) == 2
    assert "not valid TOML" in capsys.readouterr().err


def test_both_shipped_scenes_load():
    for name in ("paper2018", "plain_cylinder"):
        s = load_scene(name)
        assert s.shaft.diameter == pytest.approx(0.032)
    assert load_scene("plain_cylinder").grooves is None
