"""Files out: every file is written to a temporary name beside it, then renamed.

A failed or interrupted run therefore never leaves a half-written file behind.
"""

from __future__ import annotations

import json
import os
import tempfile
from contextlib import contextmanager
from pathlib import Path

import numpy as np


@contextmanager
def atomic_path(path: str | Path):
    """Yield a temporary path next to `path`; move it into place only on success."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o644)  # mkstemp makes 0600; results are for sharing
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _plain(obj):
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, (np.floating, np.integer, np.bool_)):
        return obj.item()
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def write_json(path: str | Path, data: dict) -> None:
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(data, indent=2, default=_plain) + "\n")


def write_csv(path: str | Path, rows: list[dict]) -> None:
    """Rows of equal keys as CSV, header from the first row (atomic)."""
    import csv

    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def modes_record(result) -> dict:
    """The JSON form of a pipeline.ModalResult (units in the key names)."""
    m, scene = result.modes, result.scene
    return {
        "scene": scene.name,
        "element": f"P{scene.mesh.order}",
        "dofs": int(m.n_dofs),
        "elements": int(result.mesh.n_elements),
        "mesh": {
            "element_size_mm": scene.mesh.size * 1e3,
            "groove_element_size_mm": scene.mesh.groove_size * 1e3,
            "edge_element_size_mm": scene.mesh.edge_size * 1e3,
            "min_jacobian_ratio": result.mesh.min_jacobian_ratio,
        },
        "rigid_body_modes": m.n_rigid,
        "rigid_body_frequencies_hz": m.rigid_frequencies,
        "elastic_modes": [
            {
                "mode": i + 1,
                "frequency_hz": float(f),
                "kind": kind,
                "residual": float(r),
                "energy_fraction": {"axial": float(e[0]), "radial": float(e[1]),
                                    "tangential": float(e[2])},
            }
            for i, (f, kind, r, e) in enumerate(zip(m.frequencies, m.kinds, m.residuals, m.energy))
        ],
        "mass_orthonormality_error": m.orthonormality_error,
        "groove_volume_mm3": {
            "cad": result.shape.groove_volume_cad * 1e9,
            "analytic": result.shape.groove_volume_analytic * 1e9,
        },
        "timings_s": result.seconds,
    }


# --------------------------------------------------------------------------
# Mode shapes and the solid, for ParaView, CAD and other solvers


def nodal_shapes(result) -> np.ndarray:
    """Mode shapes at the mesh's nodes: (n_modes, n_points, 3), m / sqrt(kg).

    The solver's DOFs sit on scikit-fem's P1/P2 nodes, which are the mesh's own
    nodes in another order; they are matched by position.
    """
    from scipy.spatial import cKDTree

    nodes, points = result.system.nodes, result.mesh.points
    dist, idx = cKDTree(nodes).query(points)
    if dist.max() > 1e-12:
        raise RuntimeError("mesh nodes and solver DOF nodes do not coincide")
    X = result.modes.shapes  # (3 n, m), interleaved
    n = nodes.shape[0]
    return np.stack([X[:, k].reshape(n, 3)[idx] for k in range(X.shape[1])])


def field_name(mode: int, frequency: float) -> str:
    return f"mode_{mode:02d}_{frequency:.2f}Hz"


def modes_table(result, errors: np.ndarray | None = None) -> list[dict]:
    """One row per elastic mode: the content of modes.csv and modes.json."""
    rows = []
    for i, (f, kind) in enumerate(zip(result.modes.frequencies, result.modes.kinds)):
        rows.append({
            "mode": i + 1,
            "frequency_hz": float(f),
            "omega_rad_s": float(2 * np.pi * f),
            "period_s": float(1 / f),
            "kind": kind,
            "estimated_error": None if errors is None else float(errors[i]),
        })
    return rows


@contextmanager
def staged_directory(out: str | Path):
    """Write a set of files into a hidden staging folder; move them into `out` at the end.

    On any failure the staging folder is removed and `out` gets none of the files.
    """
    import shutil

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=".staging-", dir=out))
    try:
        yield stage
        for f in sorted(stage.iterdir()):
            os.chmod(f, 0o644)
            os.replace(f, out / f.name)
    finally:
        shutil.rmtree(stage, ignore_errors=True)


def export_modes(result, out: str | Path, errors: np.ndarray | None = None) -> list[Path]:
    """mode_NN.vtu per elastic mode (+ modes.pvd), modes.csv, modes.json, mesh.msh,
    shaft.brep and shaft.step; returns the files written."""
    import meshio

    from .geometry import export_solid

    shapes = nodal_shapes(result)
    mesh = result.mesh
    names = []
    with staged_directory(out) as stage:
        for k, (f, u) in enumerate(zip(result.modes.frequencies, shapes)):
            name = f"mode_{k + 1:02d}.vtu"
            m = meshio.Mesh(mesh.points, [(mesh.cell_type, mesh.cells)],
                            point_data={field_name(k + 1, f): u})
            meshio.write(stage / name, m)
            names.append(name)
        pvd = ['<?xml version="1.0"?>',
               '<VTKFile type="Collection" version="0.1">', "  <Collection>"]
        pvd += [f'    <DataSet timestep="{k + 1}" part="0" file="{n}"/>'
                for k, n in enumerate(names)]
        pvd += ["  </Collection>", "</VTKFile>", ""]
        (stage / "modes.pvd").write_text("\n".join(pvd))
        rows = modes_table(result, errors)
        write_csv(stage / "modes.csv", rows)
        (stage / "modes.json").write_text(json.dumps(
            {**modes_record(result), "modes": rows}, indent=2, default=_plain) + "\n")
        meshio.write(stage / "mesh.msh", meshio.Mesh(mesh.points, [(mesh.cell_type, mesh.cells)]),
                     file_format="gmsh", binary=False)
        export_solid(result.shape.brep, stage / "shaft.step", stage / "shaft.brep")
        written = sorted(p.name for p in stage.iterdir())
    return [Path(out) / n for n in written]


# --------------------------------------------------------------------------
# CalculiX: the same mesh and material as a *FREQUENCY deck, for an independent solve


def calculix_deck(result, n_eigen: int = 16) -> str:
    """A complete CalculiX input deck (SI units) for the free-free modes of `result`'s mesh.

    meshio writes the nodes and the 10-node tetrahedra (its tetra10 node order is
    the Abaqus C3D10 order; gmsh's differs by swapping nodes 8 and 9, which meshio
    undid on reading). Numbers are written with 13 significant digits: CalculiX
    reads at most 20 characters per field.
    """
    import io as _io

    import meshio

    mesh, mat = result.mesh, result.scene.material
    if mesh.order != 2:
        raise ValueError("the CalculiX export writes C3D10 (second-order) meshes only")
    buf = _io.StringIO()
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "mesh.inp"
        meshio.write(path, meshio.Mesh(mesh.points, [("tetra10", mesh.cells)]),
                     file_format="abaqus", float_fmt=".12e")
        text = path.read_text()
    text = text.replace("*ELEMENT, TYPE=C3D10MH", "*ELEMENT, TYPE=C3D10, ELSET=EALL")
    if "TYPE=C3D10, ELSET=EALL" not in text:
        raise RuntimeError("unexpected element card from meshio's Abaqus writer")
    buf.write(text.rstrip() + "\n")
    buf.write(
        f"** free-free modal analysis of {result.scene.name} written by shaftfem (SI units)\n"
        f"*MATERIAL, NAME=M1\n*ELASTIC\n{mat.youngs_modulus:.10e}, {mat.poisson_ratio:.10g}\n"
        f"*DENSITY\n{mat.density:.10e}\n"
        "*SOLID SECTION, ELSET=EALL, MATERIAL=M1\n"
        # STORAGE=YES: the eigenvalues also go, in full double precision, to the binary
        # .eig file (the .dat table prints 7 digits only)
        f"*STEP\n*FREQUENCY, STORAGE=YES\n{n_eigen}\n*END STEP\n"
    )
    return buf.getvalue()


def write_calculix(result, path: str | Path, n_eigen: int = 16) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_text(calculix_deck(result, n_eigen))
    return Path(path)


def read_calculix_frequencies(dat: str | Path) -> np.ndarray:
    """Frequencies (Hz, cycles/time) from the eigenvalue table of a CalculiX .dat file."""
    import re

    lines = Path(dat).read_text().splitlines()
    start = next((i for i, l in enumerate(lines) if "E I G E N V A L U E   O U T P U T" in l),
                 None)
    if start is None:
        raise ValueError(f"{dat}: no eigenvalue output")
    num = r"[-+]?\d+\.\d*E[-+]\d+"
    row = re.compile(rf"^\s*(\d+)\s+({num})\s+({num})\s+({num})\s+({num})\s*$")
    freqs = []
    for line in lines[start + 1:]:
        m = row.match(line)
        if m:
            freqs.append(float(m.group(4)))
        elif freqs and line.strip() and "P A R T I C I P A T I O N" in line:
            break
    return np.array(freqs)


def read_calculix_eig(eig: str | Path) -> np.ndarray:
    """Frequencies (Hz) in full precision from CalculiX's binary .eig file.

    Layout written by ccx 2.20 for *FREQUENCY, STORAGE=YES: four 32-bit integers
    (the last is the number of eigenvalues), then the eigenvalues w^2 as doubles.
    """
    b = Path(eig).read_bytes()
    n = int(np.frombuffer(b[:16], dtype=np.int32)[3])
    lam = np.frombuffer(b[16:16 + 8 * n], dtype=np.float64)
    return np.sqrt(np.abs(lam)) / (2 * np.pi)
