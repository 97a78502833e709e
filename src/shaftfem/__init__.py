"""shaftfem: finite-element modal analysis of machine shafts.

    import shaftfem
    scene = shaftfem.load_scene("paper2018")          # a shipped scene, or a file
    run = shaftfem.solve(scene)                       # modes and their error bounds
    run.frequencies, run.bounds, run.table()          # Hz, fractions, one row per mode
    run.plot_mode(1); run.plot_frequencies(); run.save("out/run")
    shaftfem.run_design(scene, "out/paper2018")       # sizing, check, files, report
    shaftfem.run_campbell(shaftfem.load_scene("examples/overhung_spindle.toml"))  # turning

Importing the package is cheap: the names below load their modules on first use,
and gmsh, scikit-fem, SciPy and pyvista only come with the steps that need them.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

from shaftfem.errors import GeometryError, MeshError, SceneError, ShaftfemError, SolverError

__version__ = "0.1.0"

# name -> the module that defines it, imported when the name is first used
_LAZY = {
    "Scene": "shaftfem.scene.model",
    "load_scene": "shaftfem.scene.load",
    **{name: "shaftfem.scene.builders" for name in (
        "make_scene", "vary", "Shaft", "Section", "Keyway", "Material", "Mesh", "Grooves",
        "Support", "Attachment", "Excitation", "Rotor", "Unbalance", "Resonance",
        "ModesWanted", "Response", "Static", "Force")},
    "RunOptions": "shaftfem.runtime",
    "ModalResult": "shaftfem.fem.result",
    "run_modes": "shaftfem.workflows.pipeline",
    "with_mesh": "shaftfem.workflows.pipeline",
    "with_modes": "shaftfem.workflows.pipeline",
    "Bounded": "shaftfem.workflows.bounded",
    "run_bounded": "shaftfem.workflows.bounded",
    "with_accuracy": "shaftfem.workflows.bounded",
    "DesignResult": "shaftfem.workflows.design",
    "run_design": "shaftfem.workflows.design",
    "Modes": "shaftfem.fem.modes",
    "run_campbell": "shaftfem.workflows.campbell",
    "run_ucs": "shaftfem.workflows.ucs",
    "run_level1": "shaftfem.workflows.level1",
    "run_static": "shaftfem.workflows.static",
    "Run": "shaftfem.workflows.results",
    "solve": "shaftfem.workflows.results",
    "load_run": "shaftfem.workflows.results",
    "campbell": "shaftfem.workflows.results",
    "Turning": "shaftfem.workflows.results",
    "Campbell": "shaftfem.fem.whirl",
    "ErrorEstimate": "shaftfem.fem.estimate",
}

__all__ = ["GeometryError", "MeshError", "SceneError", "ShaftfemError", "SolverError",
           "__version__", *_LAZY]


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'shaftfem' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # once loaded, an ordinary attribute
    return value


def __dir__() -> list[str]:
    return sorted(__all__)


if TYPE_CHECKING:
    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.fem.modes import Modes
    from shaftfem.fem.result import ModalResult
    from shaftfem.fem.whirl import Campbell
    from shaftfem.runtime import RunOptions
    from shaftfem.scene.builders import (
        Attachment,
        Excitation,
        Force,
        Grooves,
        Keyway,
        Material,
        Mesh,
        ModesWanted,
        Resonance,
        Response,
        Rotor,
        Section,
        Shaft,
        Static,
        Support,
        Unbalance,
        make_scene,
        vary,
    )
    from shaftfem.scene.load import load_scene
    from shaftfem.scene.model import Scene
    from shaftfem.workflows.bounded import Bounded, run_bounded, with_accuracy
    from shaftfem.workflows.campbell import run_campbell
    from shaftfem.workflows.design import DesignResult, run_design
    from shaftfem.workflows.level1 import run_level1
    from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes
    from shaftfem.workflows.results import Run, Turning, campbell, load_run, solve
    from shaftfem.workflows.static import run_static
    from shaftfem.workflows.ucs import run_ucs
