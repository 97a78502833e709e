"""Scenes made in code (shaftfem.make_scene, the table objects, load_scene(dict), vary)
are the scenes their files give, are refused with the file route's messages, and write
themselves back as files that give them again."""

import dataclasses
import re
import tomllib

import pytest

import shaftfem as sf
from shaftfem.errors import SceneError
from shaftfem.scene.load import GEOMETRY_DIR, load_scene
from shaftfem.scene.schema import SCHEMA
from test_scene_errors import CASES, PAPER, _edit

EXAMPLES = GEOMETRY_DIR.parent / "examples"


def stepped_in_code() -> sf.Scene:
    """examples/stepped_shaft.toml, written in code."""
    return sf.make_scene(
        name="stepped_shaft",
        description="Stepped C45 shaft: 25 mm journals, 35 mm middle, keyed sprocket, two "
                    "6205 ball bearings",
        shaft=sf.Shaft(end_chamfer_mm=1.0,
                       sections=[sf.Section(length_mm=40, diameter_mm=25, fillet_mm=1,
                                            chamfer_mm=0.5),
                                 sf.Section(length_mm=220, diameter_mm=35, fillet_mm=1,
                                            chamfer_mm=0.5),
                                 sf.Section(length_mm=40, diameter_mm=25)],
                       keyways=[sf.Keyway(position_mm=150, length_mm=40)]),
        material=sf.Material(name="C45", youngs_modulus_mpa=210e3, poisson_ratio=0.3,
                             density_kg_m3=7850),
        mesh=sf.Mesh(element_size_mm=8, groove_element_size_mm=4),
        supports=[sf.Support(name="left bearing", position_mm=20, width_mm=15, kind="rigid"),
                  sf.Support(name="right bearing", position_mm=280, width_mm=15,
                             kind="rigid-radial")],
        attachments=[sf.Attachment(name="sprocket", position_mm=150, width_mm=40, mass_kg=1.2,
                                   polar_inertia_kg_m2=0.0018, diametral_inertia_kg_m2=0.0010,
                                   joint="distributing")],
        excitations=[sf.Excitation(name="motor", speed_rpm=1450, orders=[1, 2])])


def same(a: sf.Scene, b: sf.Scene) -> bool:
    """Equal scenes, whatever their file's name."""
    return a._content() == b._content() and a.name == b.name


def test_a_scene_in_code_is_the_scene_of_its_file():
    from shaftfem.workflows.stages import shape_key

    code, file = stepped_in_code(), load_scene(EXAMPLES / "stepped_shaft.toml")
    assert same(code, file)
    assert shape_key(code.shaft, None) == shape_key(file.shaft, None)
    assert code.seat_cuts() == file.seat_cuts() and code.hubs() == file.hubs()


def test_the_table_objects_have_the_schemas_keys():
    tables = {c.TABLE: c for c in (sf.Section, sf.Keyway, sf.Material, sf.Mesh, sf.Grooves,
                                   sf.Support, sf.Attachment, sf.Excitation, sf.Rotor,
                                   sf.Unbalance, sf.Resonance, sf.ModesWanted, sf.Response)}
    for table, kind in tables.items():
        assert [f.name for f in dataclasses.fields(kind)] == list(SCHEMA[table])
    shaft = sf.Shaft(length_mm=1.0).tables()["shaft"]
    assert set(shaft) <= set(SCHEMA["shaft"])


def test_to_toml_gives_the_scene_back(tmp_path):
    code = stepped_in_code()
    text = code.to_toml(tmp_path / "s.toml")
    assert (tmp_path / "s.toml").read_text() == text
    again = load_scene(tmp_path / "s.toml")
    assert same(again, code) and again.to_toml() == text
    paper = load_scene("paper2018")
    assert same(load_scene(tomllib.loads(paper.to_toml())), paper)


def test_vary_replaces_tables_and_a_scene_changed_otherwise_has_no_file():
    from shaftfem.workflows.pipeline import with_mesh

    code = stepped_in_code()
    wheel = sf.Attachment(name="wheel", position_mm=100, width_mm=20, mass_kg=2.0)
    more = sf.vary(code, attachments=[*code.tables["attachment"], wheel],
                   mesh=sf.Mesh(element_size_mm=12))
    assert [a.name for a in more.attachments] == ["sprocket", "wheel"]
    assert more.mesh.size == pytest.approx(12e-3) and code.mesh.size == pytest.approx(8e-3)
    assert same(load_scene(tomllib.loads(more.to_toml())), more)
    with pytest.raises(SceneError, match="changed in code after it was made"):
        with_mesh(code, size_mm=10).to_toml()
    with pytest.raises(SceneError, match=re.escape("attachment 2 (\"wheel\"): mass_kg")):
        sf.vary(code, attachments=[*code.tables["attachment"],
                                   sf.Attachment(name="wheel", position_mm=100, width_mm=20,
                                                 mass_kg=-2.0)])


def _message(exc: pytest.ExceptionInfo, source: str) -> str:
    """The message without the scene's name in front (a file's, or a dict's)."""
    text = str(exc.value)
    assert text.startswith(source), (text, source)
    return text[len(source):]


def _builders_of(data: dict) -> dict:
    """A parsed scene as make_scene's keywords, every table through its object."""
    from shaftfem.scene.builders import REPEATED, SINGLE

    many = {kind.TABLE: (word, kind) for word, kind in REPEATED.items()}
    out: dict = {"shaft": sf.Shaft(**data.get("shaft", {}),
                                   sections=[sf.Section(**s) for s in data.get("section", [])],
                                   keyways=[sf.Keyway(**k) for k in data.get("keyway", [])])}
    for table, value in data.items():
        if table in SINGLE:   # a single table's keyword is its name
            out[table] = SINGLE[table](**value)
        elif table in many:
            out[many[table][0]] = [many[table][1](**v) for v in value]
        elif table in ("name", "description", "sizing"):
            out[table] = value
    return out


@pytest.mark.parametrize("key,value,named", CASES)
def test_code_refuses_what_the_file_refuses_with_the_same_message(tmp_path, key, value, named):
    text = _edit(PAPER, key, value)
    (tmp_path / "bad.toml").write_text(text)
    with pytest.raises(SceneError) as by_file:
        load_scene(tmp_path / "bad.toml")
    data = tomllib.loads(text)
    with pytest.raises(SceneError) as by_dict:
        load_scene(data)
    with pytest.raises(SceneError) as by_objects:
        sf.make_scene(**_builders_of(data))
    expected = _message(by_file, "bad.toml")
    source = f"scene {data['name']!r}"
    assert named in expected
    assert _message(by_dict, source) == expected
    assert _message(by_objects, source) == expected


def test_a_run_saved_and_loaded_is_the_same_run(tmp_path):
    """run.save writes what `shaftfem export` writes with the scene beside it; load_run reads
    the frequencies, bounds, shapes and scene back as they were."""
    import numpy as np

    scene = sf.make_scene(name="bar", shaft=sf.Shaft(length_mm=300.0, diameter_mm=30.0),
                          material=sf.Material(youngs_modulus_mpa=210e3, poisson_ratio=0.3,
                                               density_kg_m3=7850.0),
                          mesh=sf.Mesh(element_size_mm=15.0), modes=sf.ModesWanted(count=4))
    run = sf.solve(scene)
    table = run.table()
    assert list(table["mode"]) == [1, 2, 3, 4]
    assert np.array_equal(table["frequency_hz"], run.frequencies)
    assert np.all(table["low_hz"] <= run.frequencies) and np.all(table["high_hz"] >= run.frequencies)
    assert run.save(tmp_path / "run") == tmp_path / "run"
    back = sf.load_run(tmp_path / "run")
    assert np.array_equal(back.frequencies, run.frequencies) and back.kinds == run.kinds
    assert np.allclose(back.bounds, run.bounds, rtol=1e-15, atol=0)
    assert np.array_equal(back.shapes, run.shapes)
    assert np.array_equal(back.mesh.points, run.mesh.points)
    assert same(back.scene, scene) and back.bounded is None
    picture = back.plot_mode(2, path=tmp_path / "mode2.png")
    from PIL import Image

    assert np.asarray(Image.open(picture)).std() > 10
    with pytest.raises(ValueError, match="modes 1 to 4"):
        back.plot_mode(0)
    with pytest.raises(SceneError, match="not a saved run"):
        sf.load_run(tmp_path)
