"""The notebook in examples/ runs as a user runs it: it builds a keyed stepped shaft in
code, solves it (the same frequencies to the last bit as the shaft's scene file, asserted
in the notebook), draws a mode and the frequencies, sweeps the middle diameter, and
writes a scene file that `shaftfem modes` runs."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
# the pictures stay where a person can look at them after the run
OUTPUTS = ROOT / "out" / "test-outputs" / "shaft_in_code"


def _picture(path: Path) -> np.ndarray:
    from PIL import Image

    assert path.is_file(), path
    return np.asarray(Image.open(path).convert("RGB"), float)


def test_every_cell_of_the_notebook_compiles_and_names_what_shaftfem_has():
    """The fast twin of the run below: each code cell is Python (its IPython magics
    aside), and every `sf.NAME` it calls is in shaftfem's public namespace, so a renamed
    or dropped function breaks this test before a user's notebook."""
    import ast

    import nbformat

    import shaftfem

    nb = nbformat.read(EXAMPLES / "shaft_in_code.ipynb", as_version=4)
    nbformat.validate(nb)
    cells = [c.source for c in nb.cells if c.cell_type == "code"]
    assert len(cells) >= 8
    used = set()
    for source in cells:
        code = "\n".join(line for line in source.splitlines() if not line.startswith("%"))
        for node in ast.walk(ast.parse(code)):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id == "sf"):
                used.add(node.attr)
    assert {"make_scene", "solve", "vary", "load_scene", "RunOptions"} <= used
    assert [n for n in sorted(used) if not hasattr(shaftfem, n)] == []


@pytest.mark.slow
def test_the_notebook_builds_solves_draws_sweeps_and_writes_its_scene(monkeypatch):
    import nbformat
    from nbclient import NotebookClient

    monkeypatch.setenv("SHAFTFEM_EXAMPLE_OUT", str(OUTPUTS))
    for old in OUTPUTS.glob("*"):
        old.unlink()
    nb = nbformat.read(EXAMPLES / "shaft_in_code.ipynb", as_version=4)
    NotebookClient(nb, timeout=900, kernel_name="python3",
                   resources={"metadata": {"path": str(EXAMPLES)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    # the refused value, named as the file route names it
    text = "".join(o.get("text", "") for o in outputs if o.output_type == "stream")
    assert "mesh.element_size_mm = 0.0: must be" in text
    # the mode drawn (a picture, not a blank) and shown inline, the frequencies too
    mode = _picture(OUTPUTS / "mode_1.png")
    assert mode.shape[0] > 300 and mode.std() > 20
    assert _picture(OUTPUTS / "frequencies.png").std() > 10
    assert sum("image/png" in o.get("data", {}) for o in outputs) >= 2
    # the sweep: a thicker middle, a stiffer first bending pair
    pairs = [[float(v) for v in line.split(" pair ")[1].replace(" Hz", "").split(" and ")]
             for line in text.splitlines() if line.startswith("middle ")]
    assert len(pairs) == 3 and pairs[0][0] < pairs[1][0] < pairs[2][0]
    # its scene file runs on the command line, and gives the sweep's 40 mm frequencies
    toml = OUTPUTS / "stepped_shaft_40.toml"
    out = subprocess.run([sys.executable, "-m", "shaftfem", "modes", str(toml), "-q",
                          "--no-estimate", "--json", str(OUTPUTS / "modes_40.json")],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    rows = json.loads((OUTPUTS / "modes_40.json").read_text())["modes"]
    assert [r["frequency_hz"] for r in rows[:2]] == pytest.approx(pairs[2], abs=0.051)
