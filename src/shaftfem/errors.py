"""The errors shaftfem raises on purpose: each one is a sentence a designer can act on.

Each class carries the command line's exit status, so that a CI gate can tell a
resonance (1) from bad input (2), from a failure inside the computation (3) and from
a check that passed only on a free-free shaft (4).
"""

EXIT_CHECK_FAILED = 1   # a check failed: a mode too close to an excitation harmonic
EXIT_BAD_INPUT = 2      # a scene, sweep or calibration file or an argument is wrong
EXIT_COMPUTATION = 3    # the mesher, the solver, a cache, the disk or the cluster failed
EXIT_FREE_FREE = 4      # a resonance check passed, but on a shaft that nothing holds


class ShaftfemError(Exception):
    """Base class: the CLI prints the message on one line and exits with `exit_code`."""

    exit_code = EXIT_COMPUTATION


class SceneError(ShaftfemError, ValueError):
    """A scene file is missing, malformed, or has a value outside what is allowed."""

    exit_code = EXIT_BAD_INPUT


class BudgetError(SceneError):
    """The mesh asked for would need more DOFs (and memory) than the budget allows."""


class GeometryError(ShaftfemError):
    """The CAD construction failed or produced a solid that fails its checks."""


class MeshError(ShaftfemError):
    """The mesh is unusable (inverted elements, disconnected parts, ...)."""


class SolverError(ShaftfemError):
    """The eigen solve did not give what a free elastic body must give."""


class UnsettledError(SolverError):
    """Hill's method did not settle at the spin `omega` (rad/s): the Floquet forms spread
    over more harmonics than it takes (a slow spin in bearings that differ along x and y)."""

    def __init__(self, message: str, omega: float, harmonics: int = 0):
        super().__init__(message)
        self.omega = omega
        self.harmonics = harmonics   # the most it took


class ClusterError(ShaftfemError):
    """A Dask cluster that cannot run the work: no workers, or workers without this shaftfem."""


class AssemblyError(ShaftfemError):
    """K or M failed a physical check (a rigid translation must cost no energy)."""
