"""Files out: mode shapes for ParaView, tables, the mesh, the solid, a CalculiX deck.

Every file is written under a temporary name beside it and renamed, and a set
of files into a staging folder moved at the end (shaftfem.store): a failed or
interrupted run never leaves a half-written file behind.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .store import json_text, staged_directory, write_csv, write_text

if TYPE_CHECKING:
    from .pipeline import ModalResult
    from .estimate import ErrorEstimate


def modes_record(result: ModalResult, est: ErrorEstimate | None = None) -> dict:
    """The JSON form of a modal run (units in the key names): `modes --json` and modes.json."""
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
        "modes": modes_table(result, est),
        "mass_orthonormality_error": m.orthonormality_error,
        "groove_volume_mm3": {
            "cad": result.shape.groove_volume_cad * 1e9,
            "analytic": result.shape.groove_volume_analytic * 1e9,
        },
        "timings_s": dict(result.timings.items()),
    }


def modes_table(result: ModalResult, est: ErrorEstimate | None = None) -> list[dict]:
    """One row per elastic mode: the content of modes.csv and of the record's "modes"."""
    m = result.modes
    rows = []
    for i, (f, kind) in enumerate(zip(m.frequencies, m.kinds)):
        e = m.energy[i]
        rows.append({
            "mode": i + 1,
            "frequency_hz": float(f),
            "omega_rad_s": float(2 * np.pi * f),
            "period_s": float(1 / f),
            "kind": kind,
            "residual": float(m.residuals[i]),
            "backward_error": float(m.backward_errors[i]),
            "energy_axial": float(e[0]),
            "energy_radial": float(e[1]),
            "energy_tangential": float(e[2]),
            # FE frequencies converge from above: the truth lies in [f (1 - bound), f]
            "error_bound_percent": None if est is None else float(100 * est.relative_error[i]),
            "recovery_estimate_percent": None if est is None else float(100 * est.recovery[i]),
            "error_bound_confirmed": None if est is None else bool(est.reliable[i]),
        })
    return rows


KINDS = ("bending", "torsion", "axial", "mixed")
# Field data must be numeric for meshio to read the files back; the name says the code.
KIND_FIELD = "kind: " + ", ".join(f"{i} {k}" for i, k in enumerate(KINDS))


MANIFEST = "export.manifest.json"


def export_modes(result: ModalResult, out: str | Path,
                 est: ErrorEstimate | None = None) -> list[Path]:
    """Mode shapes for ParaView (mode_NN.vtu, modes.pvd, modes_all.vtu, open_in_paraview.py),
    modes.csv, modes.json, mesh.msh, shaft.brep and shaft.step, published together in `out`
    under export.manifest.json; returns the files written."""
    with staged_directory(out, MANIFEST) as stage:
        written = write_mode_files(result, stage, est)
    return [Path(out) / p.name for p in written]


def write_mode_files(result: ModalResult, folder: Path,
                     est: ErrorEstimate | None = None) -> list[Path]:
    """The files of export_modes, written straight into `folder`."""
    import shutil

    import meshio

    from .occ import write_solid
    from .vtkio import write_vtu

    shapes = result.shapes_at_points()
    mesh, m = result.mesh, result.modes
    names = []
    # one array name in every step, so that a filter set up on one mode shows them all
    for k, (f, kind, u) in enumerate(zip(m.frequencies, m.kinds, shapes)):
        names.append(f"mode_{k + 1:02d}.vtu")
        write_vtu(folder / names[-1], mesh,
                  {"displacement": u, "displacement_magnitude": np.linalg.norm(u, axis=1)},
                  {"mode": k + 1, "frequency_hz": float(f), KIND_FIELD: KINDS.index(kind)})
    pvd = ['<?xml version="1.0"?>',
           '<VTKFile type="Collection" version="0.1">', "  <Collection>"]
    pvd += [f'    <DataSet timestep="{k + 1}" part="0" file="{n}"/>'
            for k, n in enumerate(names)]
    pvd += ["  </Collection>", "</VTKFile>", ""]
    (folder / "modes.pvd").write_text("\n".join(pvd))
    # every mode in one file, as named arrays (for tools that read one file)
    write_vtu(folder / "modes_all.vtu", mesh,
              {f"mode_{k + 1:02d}": u for k, u in enumerate(shapes)},
              {"frequency_hz": m.frequencies, KIND_FIELD: [KINDS.index(k) for k in m.kinds]})
    shutil.copyfile(Path(__file__).with_name("paraview_view.py"),
                    folder / "open_in_paraview.py")
    write_csv(folder / "modes.csv", modes_table(result, est))
    (folder / "modes.json").write_text(json_text(modes_record(result, est)))
    meshio.write(folder / "mesh.msh", meshio.Mesh(mesh.points, [(mesh.cell_type, mesh.cells)]),
                 file_format="gmsh", binary=False)
    write_solid(result.shape.brep, result.scene.shaft,
                [folder / "shaft.step", folder / "shaft.brep"])
    return [folder / n for n in names + ["modes.pvd", "modes_all.vtu", "open_in_paraview.py",
                                          "modes.csv", "modes.json", "mesh.msh", "shaft.step",
                                          "shaft.brep"]]


# --------------------------------------------------------------------------
# CalculiX: the same mesh and material as a *FREQUENCY deck, for an independent solve


def calculix_deck(result: ModalResult, n_eigen: int = 16) -> str:
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


def write_calculix(result: ModalResult, path: str | Path, n_eigen: int | None = None) -> Path:
    """shaft.inp: `n_eigen` eigenvalues (default: ours plus the six rigid-body modes)."""
    return write_text(path, calculix_deck(result, n_eigen or result.modes.count + 6))


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
