"""A modal run as code holds it (a notebook, a script): the frequencies and their bounds,
a table, a mode and the frequencies drawn, and the run saved as the files
`shaftfem export` writes and read back from them.

    run = shaftfem.solve(scene)
    run.frequencies, run.bounds          # Hz; fractions (the truth >= f (1 - bound))
    run.table()                          # one row per mode (pandas.DataFrame(run.table()))
    run.plot_mode(1)                     # pyvista: a picture, or interactive (trame)
    run.plot_frequencies()               # matplotlib: the modes against the excitations
    run.save("out/run"); shaftfem.load_run("out/run")
    shaftfem.campbell(scene).plot()      # a turning shaft's Campbell diagram
"""

from __future__ import annotations

import json
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.runtime import RunOptions
from shaftfem.scene.model import Scene

if TYPE_CHECKING:
    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.fem.whirl import Campbell
    from shaftfem.workflows.bounded import Bounded

SCENE_FILE = "scene.toml"   # beside the exported modes: the scene that made them
TABLE_FIELDS = [("mode", "i4"), ("frequency_hz", "f8"), ("kind", "U8"),
                ("bound_percent", "f8"), ("low_hz", "f8"), ("high_hz", "f8")]


@dataclass(frozen=True)
class Run:
    """One modal run: the scene, each mode's frequency (Hz) and kind, its bound (fraction
    of the frequency; None when not bounded) and interval [low, high] (Hz), the mesh, the
    mode shapes at its points ((n_modes, n_points, 3), m / sqrt(kg)), the record that
    `modes --json` prints, the scene as it was given (what `save` writes: `scene` is it as
    solved, a STEP shaft placed), and the live run behind it (None for a run loaded from
    its files)."""

    scene: Scene
    frequencies: np.ndarray
    kinds: tuple[str, ...]
    bounds: np.ndarray | None
    low: np.ndarray | None
    high: np.ndarray | None
    mesh: ShaftMesh
    shapes: np.ndarray
    record: dict
    given: Scene
    bounded: Bounded | None = None

    @classmethod
    def of(cls, bounded: Bounded, given: Scene) -> Run:
        """The run of run_bounded's answer for the scene `given`."""
        from shaftfem.outputs.export import modes_record

        result, est = bounded.result, bounded.estimate
        m = result.modes
        low, high = (None, None) if est is None else est.interval(m.frequencies)
        return cls(scene=result.scene, frequencies=m.frequencies, kinds=tuple(m.kinds),
                   bounds=None if est is None else est.relative_error, low=low, high=high,
                   mesh=result.mesh, shapes=result.shapes_at_points(),
                   record=modes_record(result, est), given=given, bounded=bounded)

    def table(self) -> np.ndarray:
        """One row per mode: mode (from 1), frequency_hz, kind, bound_percent, low_hz and
        high_hz (NaN where not bounded), as a NumPy structured array (pandas.DataFrame
        takes it as it is)."""
        n = len(self.frequencies)
        rows = np.zeros(n, dtype=TABLE_FIELDS)
        rows["mode"] = np.arange(1, n + 1)
        rows["frequency_hz"] = self.frequencies
        rows["kind"] = self.kinds
        nan = np.full(n, np.nan)
        rows["bound_percent"] = nan if self.bounds is None else 100 * self.bounds
        rows["low_hz"] = nan if self.low is None else self.low
        rows["high_hz"] = nan if self.high is None else self.high
        return rows

    def plot_mode(self, mode: int = 1, path: str | Path | None = None,
                  interactive: bool = False, size: tuple[int, int] = (900, 400)) -> Any:
        """Mode `mode` (from 1) drawn as the pictures draw it: written to `path` (PNG) and
        the path returned; else shown, as a picture (in Jupyter, inline), or interactive
        (`interactive=True`: pyvista's trame backend in Jupyter, a window elsewhere)."""
        from shaftfem.outputs.render import drawing_of, load_pyvista, mode_view

        k = self._index(mode)
        d = drawing_of(load_pyvista(), self.scene, self.mesh, self.frequencies[k:k + 1],
                       self.kinds[k:k + 1], self.shapes[k:k + 1])
        d = replace(d, titles=[self._title(k)])
        p = mode_view(d, 0, self.scene, size, off_screen=path is not None or not interactive)
        if path is not None:
            from shaftfem.store import atomic_path

            with atomic_path(path) as tmp:
                p.screenshot(str(tmp))
            p.close()
            return Path(path)
        return p.show(jupyter_backend="trame" if interactive else "static")

    def plot_frequencies(self, path: str | Path | None = None):
        """The modes (markers, with their intervals) against each excitation harmonic and
        its required margin: a matplotlib Figure (Jupyter shows it), or written to `path`
        (PNG) and the path returned."""
        from shaftfem.outputs.plots import modes_figure

        harmonics = [(f"{e.name} {k}x", k * e.frequency) for e in self.scene.excitations
                     for k in e.orders]
        fig = modes_figure(self.frequencies, self.low, self.high, list(self.kinds),
                           harmonics, self.scene.required_margin)
        fig.suptitle(f"{self.scene.name}: natural frequencies"
                     + (" with their intervals" if self.bounds is not None else ""),
                     fontsize=9)
        return _shown(fig, path)

    def save(self, folder: str | Path) -> Path:
        """The files `shaftfem export` writes (modes_all.vtu, modes.json, modes.csv, one VTU
        per mode, mesh.msh, shaft.step ...) and the scene as scene.toml, published together
        in `folder`; load_run reads them back."""
        from shaftfem.outputs.export import MANIFEST, write_mode_files
        from shaftfem.store import staged_directory

        if self.bounded is None:
            raise SceneError(f"{self.scene.source}: a run loaded from its files is saved "
                             "already; copy its folder")
        text = self.given.to_toml()
        with staged_directory(folder, MANIFEST) as stage:
            write_mode_files(self.bounded.result, stage, self.bounded.estimate)
            (stage / SCENE_FILE).write_text(text)
        return Path(folder)

    def _index(self, mode: int) -> int:
        if not (isinstance(mode, (int, np.integer)) and 1 <= mode <= len(self.frequencies)):
            raise ValueError(f"mode {mode!r}: the run has modes 1 to {len(self.frequencies)}")
        return int(mode) - 1

    def _title(self, k: int) -> str:
        f = self.frequencies[k]
        bound = "" if self.bounds is None else f", bound {100 * self.bounds[k]:.2g} %"
        return f"mode {k + 1}: {f:.2f} Hz{bound}, {self.kinds[k]}"


def _shown(fig, path: str | Path | None):
    """A chart as the plot methods give it: the Figure (Jupyter shows it), or written to
    `path` (PNG) and the path returned."""
    if path is None:
        return fig
    from shaftfem.outputs.plots import save_png

    return save_png(fig, path)


def solve(scene: Scene, options: RunOptions = RunOptions(), estimate: bool = True) -> Run:
    """The scene's modes with their bounds (workflows.bounded.run_bounded), as a Run."""
    from shaftfem.workflows.bounded import run_bounded

    return Run.of(run_bounded(scene, estimate=estimate, options=options), scene)


def load_run(folder: str | Path) -> Run:
    """A run saved by Run.save (or `shaftfem export` with its scene.toml beside), read
    back: the scene, the record and the shapes from modes_all.vtu."""
    import meshio

    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.outputs.export import MANIFEST
    from shaftfem.scene.load import load_scene
    from shaftfem.store import manifest_complete

    folder = Path(folder)
    if not manifest_complete(folder, MANIFEST):
        raise SceneError(f"{folder}: not a saved run (no {MANIFEST} vouching for its files); "
                         "save one with run.save(folder) or `shaftfem export`")
    if not (folder / SCENE_FILE).is_file():
        raise SceneError(f"{folder}: has no {SCENE_FILE}: the exported modes come without "
                         "their scene; save the run with run.save(folder)")
    record = json.loads((folder / "modes.json").read_text())
    grid = meshio.read(folder / "modes_all.vtu")
    cells = [c for c in grid.cells if c.type in ("tetra", "tetra10")]
    if len(cells) != 1:
        raise SceneError(f"{folder / 'modes_all.vtu'}: holds {[c.type for c in grid.cells]}; "
                         "a saved run holds one block of 4- or 10-node tetrahedra")
    rows = record["modes"]
    n = len(rows)
    shapes = np.stack([grid.point_data[f"mode_{k + 1:02d}"] for k in range(n)])
    mesh = ShaftMesh(points=np.asarray(grid.points, float), cells=cells[0].data,
                     order=int(record["element"].lstrip("P")),
                     min_jacobian_ratio=record["mesh"]["min_jacobian_ratio"], straightened=0,
                     from_cache=True)

    def column(name: str, per: float = 1.0) -> np.ndarray | None:
        values = [r[name] for r in rows]
        return None if any(v is None for v in values) else np.array(values, float) / per

    given = load_scene(folder / SCENE_FILE)
    scene = given
    if given.shaft.step is not None:  # placed as it was solved (its import kept, or made)
        from shaftfem.workflows.stages import solid

        scene, _ = solid(given)
    return Run(scene=scene, given=given,
               frequencies=np.array([r["frequency_hz"] for r in rows]),
               kinds=tuple(r["kind"] for r in rows), bounds=column("error_bound_percent", 100.0),
               low=column("true_frequency_low_hz"), high=column("true_frequency_high_hz"),
               mesh=mesh, shapes=shapes, record=record)


@dataclass(frozen=True)
class Turning:
    """A turning shaft's run as code holds it: the Campbell record (`campbell`: whirl at
    every speed, critical speeds, onsets of instability, the unbalance response) and its
    pictures."""

    campbell: Campbell

    @property
    def critical_speeds(self) -> tuple:
        """Each critical speed: order, whirl, speed_rpm, frequency_hz, mode."""
        return self.campbell.critical_speeds

    def plot(self, path: str | Path | None = None):
        """The Campbell diagram (with the log decrements when the bearings damp): a
        matplotlib Figure, or written to `path` (PNG) and the path returned."""
        from shaftfem.outputs.campbell_plot import campbell_figure

        fig = campbell_figure(self.campbell)
        return _shown(fig, path)

    def plot_bode(self, path: str | Path | None = None):
        """The unbalance response against speed at each probe (the scene needs an
        [[unbalance]]): a Figure, or written to `path` (PNG) and the path returned."""
        from shaftfem.outputs.campbell_plot import bode_figure

        if self.campbell.unbalance is None:
            raise SceneError(f"{self.campbell.result.scene.source}: no [[unbalance]]: there "
                             "is no unbalance response to draw")
        fig = bode_figure(self.campbell)
        return _shown(fig, path)


def campbell(scene: Scene, speeds_rpm: np.ndarray | None = None,
             options: RunOptions = RunOptions()) -> Turning:
    """The scene's shaft turning (workflows.campbell.run_campbell; it needs [rotor]), as a
    Turning: `campbell(scene).plot()` draws its Campbell diagram."""
    from shaftfem.workflows.campbell import run_campbell

    return Turning(run_campbell(scene, options, speeds_rpm))
