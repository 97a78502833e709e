"""The errors shaftfem raises on purpose: each one is a sentence a designer can act on."""


class ShaftfemError(Exception):
    """Base class: the CLI prints the message on one line and exits nonzero."""


class SceneError(ShaftfemError, ValueError):
    """A scene file is missing, malformed, or has a value outside what is allowed."""


class GeometryError(ShaftfemError):
    """The CAD construction failed or produced a solid that fails its checks."""


class MeshError(ShaftfemError):
    """The mesh is unusable (inverted elements, disconnected parts, ...)."""


class SolverError(ShaftfemError):
    """The eigen solve did not give what a free elastic body must give."""


class ClusterError(ShaftfemError):
    """A Dask cluster that cannot run the work: no workers, or workers without this shaftfem."""


class AssemblyError(ShaftfemError):
    """K or M failed a physical check (a rigid translation must cost no energy)."""
