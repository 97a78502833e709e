"""Failures inside gmsh/OpenCASCADE, meshio, the factorisation and ARPACK come back as
one-line shaftfem errors of the step that failed (exit 3), never as the library's own
exception or a process exit."""

import numpy as np
import pytest
import scipy.sparse as sp

from shaftfem.cli import main
from shaftfem.errors import EXIT_COMPUTATION, GeometryError, MeshError, SolverError


def _pencil(n=60):
    """A free-free spring chain: K singular (one rigid mode), M = I."""
    d = np.full(n, 2.0)
    d[[0, -1]] = 1.0
    K = sp.diags([d, -np.ones(n - 1), -np.ones(n - 1)], [0, -1, 1], format="csr")
    return K, sp.identity(n, format="csr")


def test_a_failed_factorisation_is_a_solver_error(monkeypatch):
    from shaftfem.fem import eigen, factor
    from shaftfem.scene.model import ModeRequest

    def broken(A, backend="auto"):
        raise RuntimeError("Factor is exactly singular")

    monkeypatch.setattr(factor, "factorise", broken)
    with pytest.raises(SolverError, match="factorising K - sigma M .* RuntimeError: Factor"):
        eigen.solve_modes(*_pencil(), ModeRequest(3))


def test_an_arpack_failure_is_a_solver_error(monkeypatch):
    from shaftfem.fem import eigen
    from shaftfem.scene.model import ModeRequest

    def broken(*a, **k):
        raise sp.linalg.ArpackError(-9999)

    monkeypatch.setattr(eigen, "eigsh", broken)
    with pytest.raises(SolverError, match="ARPACK"):
        eigen.solve_modes(*_pencil(), ModeRequest(3))


def test_a_meshio_exit_is_a_mesh_error(monkeypatch):
    import meshio

    from shaftfem.cad.mesher import mesh_solid
    from shaftfem.scene.load import load_scene

    def exits(*a, **k):
        raise SystemExit("Couldn't read file as either of ansys, gmsh")

    monkeypatch.setattr(meshio, "read", exits)
    s = load_scene("plain_cylinder")
    with pytest.raises(MeshError, match="gmsh could not mesh the solid: SystemExit"):
        mesh_solid(None, s.shaft, None, s.mesh)


def test_an_opencascade_failure_is_a_geometry_error_and_exit_3(monkeypatch, tmp_path, capsys):
    from shaftfem.cad import build

    def broken(*a, **k):
        raise Exception("BRepAlgoAPI_Cut failed")  # as gmsh raises OCC's errors

    monkeypatch.setattr(build, "_build", broken)
    with pytest.raises(GeometryError, match="OpenCASCADE could not build .* BRepAlgoAPI_Cut"):
        build.build_solid(*_paper_parts(), tmp_path / "x.brep")
    argv = ["modes", "paper2018", "--no-cache", "--no-estimate", "-q"]
    assert main(argv) == EXIT_COMPUTATION
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "BRepAlgoAPI_Cut" in err[0] and "Traceback" not in err[0]
    # for debugging: the traceback, with OpenCASCADE's error kept as the cause
    monkeypatch.setenv("SHAFTFEM_DEBUG", "1")
    assert main(argv) == EXIT_COMPUTATION
    err = capsys.readouterr().err
    assert "Exception: BRepAlgoAPI_Cut failed" in err
    assert "The above exception was the direct cause of the following exception" in err
    assert err.strip().splitlines()[-1].startswith("shaftfem: error: OpenCASCADE could not build")


def _paper_parts():
    from shaftfem.scene.load import load_scene

    s = load_scene("paper2018")
    return s.shaft, s.grooves
