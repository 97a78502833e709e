"""shaftfem: finite-element modal analysis of machine shafts.

Importing the package is cheap: gmsh, scikit-fem and pyvista are imported only
by the steps that need them (geometry/mesh, assembly, render).
"""

__version__ = "0.1.0"

from shaftfem.errors import GeometryError, MeshError, SceneError, ShaftfemError, SolverError  # noqa: F401
from shaftfem.scene.model import Scene, load_scene  # noqa: F401
