"""The gmsh session: one model per job, gmsh's and OpenCASCADE's failures translated
into shaftfem's errors with the library's own message kept as the cause."""

from __future__ import annotations

import os
from contextlib import contextmanager

from shaftfem.errors import ShaftfemError


def gmsh_version() -> str:
    import gmsh

    return gmsh.__version__


class Session:
    """One gmsh job: its own model; options it changes are put back for a caller's session."""

    def __init__(self, gmsh, owner: bool):
        self.gmsh, self.owner = gmsh, owner
        self._saved: dict[str, float] = {}

    def option(self, name: str, value: float) -> None:
        if name not in self._saved:
            self._saved[name] = self.gmsh.option.getNumber(name)
        self.gmsh.option.setNumber(name, value)

    def restore(self) -> None:
        for name, value in self._saved.items():
            self.gmsh.option.setNumber(name, value)


@contextmanager
def session(model: str, verbose: bool = False):
    """A gmsh model for one job. gmsh's state is global: a session we open we also
    close; inside a caller's open session we work in a model of our own and leave
    the caller's models, current model and options as they were."""
    import gmsh

    owner = not gmsh.isInitialized()
    if owner:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
    previous = None if owner else gmsh.model.getCurrent()
    s = Session(gmsh, owner)
    s.option("General.Terminal", 1 if verbose else 0)
    gmsh.model.add(model)
    try:
        yield s
    finally:
        if owner:
            gmsh.finalize()
        else:
            gmsh.model.remove()
            gmsh.model.setCurrent(previous)
            s.restore()


@contextmanager
def translated(kind: type[ShaftfemError], what: str):
    """gmsh and OpenCASCADE raise bare Exceptions carrying their log line, and meshio
    may call sys.exit: either becomes one `kind` error saying which step failed."""
    try:
        yield
    except ShaftfemError:
        raise
    except (Exception, SystemExit) as exc:
        raise kind(f"{what}: {type(exc).__name__}: {exc}") from exc


@contextmanager
def stdout_to_devnull():
    """Silence C-level prints on stdout (OpenCASCADE's STEP writer talks there)."""
    import sys

    sys.stdout.flush()
    saved = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)
