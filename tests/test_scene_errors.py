"""Bad scene input: a one-line error naming the key, exit code 2, no traceback."""

import re

import pytest

from shaftfem.cli import main
from shaftfem.errors import SceneError
from shaftfem.scene.load import GEOMETRY_DIR, load_scene

PAPER = (GEOMETRY_DIR / "paper2018.toml").read_text()
EXAMPLES = GEOMETRY_DIR.parent / "examples"


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
    ("order", "6", "mesh.order"),
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


def test_cubic_elements_on_an_installed_shaft_are_refused(tmp_path, capsys):
    """Seats and parts read nodal values that cubic elements do not have: order 3 with
    [[support]] or [[attachment]] tables is refused at load, naming the key, and on the
    command line before any work."""
    f = tmp_path / "installed.toml"
    f.write_text(_edit((GEOMETRY_DIR / "paper2018_installed.toml").read_text(), "order", "3"))
    with pytest.raises(SceneError, match=re.escape("mesh.order") + ".*free shafts only"):
        load_scene(f)
    assert main(["modes", "paper2018_installed", "--order", "3", "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "free shafts only" in err and "Traceback" not in err


def test_orders_adapted_on_a_mesh_too_fine_for_the_budget_are_refused(capsys):
    """Adapting the orders assembles the whole order-4 space once: the default mesh's
    (about 5e5 DOFs, from the element sizes) is refused before any work when it is over
    twice a 100,000-DOF budget, with its size and memory, exit 2."""
    assert main(["modes", "paper2018", "--order", "4", "--accuracy", "0.1",
                 "--max-dofs", "100000", "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert "up to 4" in err and "GB" in err and "--max-dofs" in err


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


HUGE = [("length_mm", "1e300", "shaft.length_mm"), ("diameter_mm", "1e300", "shaft.diameter_mm"),
        ("pitch_mm", "1e300", "grooves.pitch_mm"),
        ("youngs_modulus_mpa", "1e300", "material.youngs_modulus_mpa"),
        ("density_kg_m3", "1e300", "material.density_kg_m3"),
        ("power_kw", "1e300", "sizing.power_kw"),
        ("rounding_step_mm", "1e300", "sizing.rounding_step_mm"),
        ("speed_rpm", "inf", "excitation 1 (\"engine\"): speed_rpm"), ("depth_mm", "nan", "grooves.depth_mm")]


@pytest.mark.parametrize("key,value,named", HUGE)
def test_absurd_values_are_refused_before_any_work(tmp_path, capsys, key, value, named):
    f = tmp_path / "bad.toml"
    text = PAPER
    if named.startswith("excitation"):
        text = text.replace("speed_rpm = 3600.0", f"speed_rpm = {value}")
    else:
        text = _edit(PAPER, key, value)
    f.write_text(text)
    assert main(["modes", str(f), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and named in err and "Traceback" not in err


@pytest.mark.parametrize("args", [
    ["check", "--mesh-size", "inf"], ["check", "--mesh-size", "nan"],
    ["check", "--mesh-size", "1e9"], ["check", "--mesh-size", "600"],
    ["check", "--margin", "inf"], ["check", "--margin", "100"], ["modes", "--modes", "0"],
    ["modes", "--modes", "many"], ["modes", "--max-frequency", "nan"],
    ["study", "--p2", "12,0"], ["sweep", "no_such_sweep.toml"], ["size", "no_such_scene"],
    ["modes", "--order", "6"], ["frobnicate"]])
def test_bad_command_lines_are_one_line_and_exit_2(capsys, args):
    argv = args[:1] + (["plain_cylinder"] if args[0] in ("check", "modes") else []) + args[1:]
    assert main(argv + (["-q"] if args[0] in ("check", "modes") else [])) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "error" in err and "Traceback" not in err


def test_a_binary_scene_file_is_bad_input(tmp_path, capsys):
    f = tmp_path / "shaft.toml"
    f.write_bytes(bytes(range(256)) * 4)
    assert main(["modes", str(f), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "not a text file" in err


@pytest.mark.parametrize("option", ["--out-file", "--json-dir"])
def test_unusable_output_paths_are_refused_before_the_solve(tmp_path, capsys, monkeypatch,
                                                            option):
    from shaftfem.workflows import pipeline

    def never(*_a, **_k):
        raise AssertionError("the solve ran")

    monkeypatch.setattr(pipeline, "run_modes", never)
    a_file = tmp_path / "a_file"
    a_file.write_text("x")
    argv = (["export", "plain_cylinder", "--out", str(a_file)] if option == "--out-file"
            else ["modes", "plain_cylinder", "--json", str(tmp_path)])
    assert main(argv + ["-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and ("is a file" in err or "is a folder" in err)


def test_a_mesh_beyond_the_dof_budget_is_refused_before_meshing(tmp_path, capsys):
    """0.5 mm elements on the cylinder would need billions of DOFs: refused at once, with
    the estimate and the way to raise the budget, exit 2; the scene key works too."""
    import time

    t0 = time.perf_counter()
    assert main(["modes", "plain_cylinder", "--mesh-size", "0.5", "-q"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "Traceback" not in err[0]
    assert re.search(r"about [0-9.e+]+ DOFs and [0-9.e+]+ GB, above the budget of 400000 DOFs",
                     err[0]) and "--max-dofs" in err[0]
    assert time.perf_counter() - t0 < 5
    scene = tmp_path / "small_budget.toml"
    scene.write_text((GEOMETRY_DIR / "plain_cylinder.toml").read_text()
                     .replace("order = 2", "order = 2\nmax_dofs = 5000"))
    assert main(["modes", str(scene), "-q"]) == 2
    assert "above the budget of 5000 DOFs" in capsys.readouterr().err
    assert main(["modes", str(scene), "--mesh-size", "12", "--max-dofs", "2000", "-q"]) == 2


def test_every_modal_command_takes_the_modal_flags_and_an_unknown_one_points_to_its_help(
        capsys):
    """--no-estimate and --margin are accepted by every modal command (those that do not
    use them say so in their help); an unknown flag names the command whose help to read."""
    from shaftfem.cli.parser import build_parser

    parser = build_parser()
    for command in ("modes", "check", "export", "render", "design", "paper"):
        args = parser.parse_args([command, "--no-estimate", "--margin", "20"]
                                 + (["--out", "x"] if command in ("export", "render") else []))
        assert args.no_estimate and args.margin == 20
    assert main(["check", "--no-such-flag"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == ("shaftfem check: error: unrecognized arguments: --no-such-flag "
                   "(see shaftfem check --help)")


THIN = """
name = "{name}"
[[section]]
length_mm = 400.0
diameter_mm = 40.0
bore_mm = {bore}
fillet_mm = {fillet}
[[section]]
length_mm = 100.0
diameter_mm = 50.0
[material]
youngs_modulus_mpa = 210000.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0
[mesh]
element_size_mm = 8.0
{extra}
"""


@pytest.mark.parametrize("name,bore,fillet,extra", [
    ("thin_wall", 39.0, 0.0, ""),                                # a 0.5 mm wall
    ("tiny_fillet", 0.0, 0.05, "groove_element_size_mm = 0.05"),  # a 0.05 mm fillet, sized
], ids=["thin wall", "tiny fillet"])
def test_a_scene_past_the_budget_is_refused_at_once_with_its_dofs_and_memory(
        tmp_path, capsys, name, bore, fillet, extra):
    """The estimate before meshing sees a thin wall (elements of its thickness) and a small
    feature's graded layer: such a scene is refused within seconds, exit 2."""
    import time

    f = tmp_path / f"{name}.toml"
    f.write_text(THIN.format(name=name, bore=bore, fillet=fillet, extra=extra))
    t0 = time.perf_counter()
    assert main(["modes", str(f), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert time.perf_counter() - t0 < 10
    assert re.search(r"would need about [0-9.e+]+ DOFs and [0-9.]+ GB, above the budget of "
                     r"400000 DOFs", err), err


def test_a_mesh_whose_counted_dofs_pass_the_budget_is_refused_before_assembly(capsys):
    """The estimate can miss small elements a STEP solid's curvature asks for: the mesh's
    own DOFs are counted after meshing, and a mesh past the budget never reaches assembly."""
    from shaftfem.cad.mesh import estimate_dofs
    from shaftfem.workflows import stages

    step = EXAMPLES / "step_shaft.toml"
    scene, _ = stages.solid(load_scene(step))
    estimate = estimate_dofs(scene.shaft, None, scene.mesh)
    assert main(["modes", str(step), "-q", "--no-estimate", "--max-dofs",
                 str(int(1.05 * estimate))]) == 2
    err = capsys.readouterr().err
    assert re.search(r"meshed to \d+ elements, which have [0-9.e+]+ DOFs", err), err
    assert "assembl" not in err and "Traceback" not in err


def test_a_run_the_free_memory_cannot_hold_is_refused(monkeypatch, capsys):
    """Memory for the solve's peak is asked of the machine before assembly: with 0.2 GB
    free the cylinder's 28k DOFs (about 0.3 GB) are refused, exit 2."""
    import collections

    import psutil

    free = collections.namedtuple("free", "available")(0.2e9)
    monkeypatch.setattr(psutil, "virtual_memory", lambda: free)
    assert main(["modes", "plain_cylinder", "-q", "--no-estimate"]) == 2
    err = capsys.readouterr().err
    assert "GB at the solve's peak, and this machine has 0.2 GB free" in err, err


@pytest.mark.parametrize("order", [2, 4])
def test_the_counted_dofs_are_the_systems(order):
    """mesh_dofs counts what assembly makes: P2's nodes, and order 4's hierarchical
    functions on vertices, edges, faces and cells."""
    from shaftfem.cad.mesh import mesh_dofs
    from shaftfem.workflows.pipeline import run_modes, with_mesh

    r = run_modes(with_mesh(load_scene("plain_cylinder"), 24.0, order=order))
    assert mesh_dofs(r.mesh) == r.system.n_dofs
