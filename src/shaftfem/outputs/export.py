"""Files out: mode shapes for ParaView, tables, the mesh and the solid.

Every file is written under a temporary name beside it and renamed, and a set
of files into a staging folder moved at the end (shaftfem.store): a failed or
interrupted run never leaves a half-written file behind.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.store import json_text, staged_directory, write_csv

if TYPE_CHECKING:
    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.fem.result import ModalResult, ModelMoves


def modes_record(result: ModalResult, est: ErrorEstimate | None = None,
                 moves: ModelMoves | None = None) -> dict:
    """The JSON form of a modal run (units in the key names): `modes --json` and modes.json;
    with `moves`, how far each frequency moves under each flipped modelling choice."""
    from shaftfem.outputs import tables

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
        "installation": installation_record(result),
        "rigid_body_modes": m.n_rigid,
        "rigid_body_frequencies_hz": m.rigid_frequencies,
        "modes": modes_table(result, est),
        "bound_covers": None if est is None else tables.bound_coverage(scene),
        **({} if moves is None else {"model_sensitivity": [
            {"choice": c, "moves_percent": [None if v != v else float(100 * v) for v in row]}
            for c, row in zip(moves.choices, moves.moves)]}),
        "mass_orthonormality_error": m.orthonormality_error,
        "groove_volume_mm3": {
            "cad": result.shape.groove_volume_cad * 1e9,
            "analytic": result.shape.groove_volume_analytic * 1e9,
        },
        "timings_s": tables.timings(result, est),
    }


def modes_table(result: ModalResult, est: ErrorEstimate | None = None) -> list[dict]:
    """One row per elastic mode: the content of modes.csv and of the record's "modes"."""
    m = result.modes
    low, high = (None, None) if est is None else est.interval(m.frequencies)
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
            # the truth lies in [f (1 - bound), f (1 + upper)]: the discretisation error is
            # one-sided, the geometry allowances (volume, straightening) move either way
            "error_bound_percent": None if est is None else float(100 * est.relative_error[i]),
            "error_bound_upper_percent": None if est is None else float(100 * est.upward[i]),
            "true_frequency_low_hz": None if low is None else float(low[i]),
            "true_frequency_high_hz": None if high is None else float(high[i]),
            # an order-adaptive run computes it only where its rounds' drops leave a mode
            "recovery_estimate_percent": (None if est is None or not np.isfinite(est.recovery[i])
                                          else float(100 * est.recovery[i])),
            "error_bound_confirmed": None if est is None else bool(est.reliable[i]),
            # the bound's share for the straightened elements' faces (fem.estimate.straightening)
            "straightening_allowance_percent": (
                None if est is None else 0.0 if est.straightening is None
                else float(100 * est.straightening[i])),
        })
    if result.scene.held:
        from shaftfem.fem.response import DIRECTIONS, modal_basis, participation

        p = participation(modal_basis(result))
        units = {"x": "kg", "y": "kg", "z": "kg", "rz": "kg_m2"}
        factor_units = {"x": "kg^0.5", "y": "kg^0.5", "z": "kg^0.5", "rz": "kg^0.5_m"}
        for i, row in enumerate(rows):
            for k, d in enumerate(DIRECTIONS):
                row[f"participation_factor_{d}_{factor_units[d]}"] = float(p.factors[i, k])
                row[f"effective_mass_{d}_{units[d]}"] = float(p.effective[i, k])
                row[f"cumulative_fraction_{d}"] = float(p.cumulative[i, k])
    return rows


def installation_record(result: ModalResult) -> dict | None:
    """The supports and parts in the file's units (None for a bare free shaft)."""
    scene = result.scene
    if not scene.supports and not scene.attachments:
        return None
    return {
        "hanging_free": scene.hanging_free,
        "supports": [{"name": s.name, "seat_mm": [z * 1e3 for z in s.seat], "kind": s.kind,
                      "radial_stiffness_n_per_mm": s.radial / 1e3,
                      "axial_stiffness_n_per_mm": s.axial / 1e3,
                      "tilting_stiffness_nmm_per_rad": s.tilting * 1e3} for s in scene.held],
        "attachments": [{"name": a.name, "seat_mm": [z * 1e3 for z in a.seat],
                         "mass_kg": a.mass, "polar_inertia_kg_m2": a.polar_inertia,
                         "diametral_inertia_kg_m2": a.diametral_inertia, "joint": a.joint}
                        for a in scene.attachments],
        "free_rigid_motions": list(result.installed.free) if result.installed else
        ["all six"],
        "damping_ratio": scene.damping_ratio,
    }


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
    shapes = write_shape_files(result, folder)
    return listed(shapes, write_mode_tables(result, folder, est),
                  write_solid_files(result, folder))


def listed(shapes: list[Path], tables: list[Path], solid: list[Path]) -> list[Path]:
    """The export's files in the order they are listed: the mode shapes, the tables,
    the mesh (the shapes' last file), the solid."""
    return shapes[:-1] + tables + shapes[-1:] + solid


def write_shape_files(result: ModalResult, folder: Path) -> list[Path]:
    """The mode shapes for ParaView (mode_NN.vtu, modes.pvd, modes_all.vtu,
    open_in_paraview.py) and the mesh (mesh.msh), in `folder`: what needs no bound."""
    import shutil

    import meshio

    from shaftfem.outputs.vtk import write_vtu

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
    shutil.copyfile(Path(__file__).with_name("paraview_script.py"),
                    folder / "open_in_paraview.py")
    meshio.write(folder / "mesh.msh", meshio.Mesh(mesh.points, [(mesh.cell_type, msh_cells(mesh))]),
                 file_format="gmsh", binary=False)
    return [folder / n for n in names + ["modes.pvd", "modes_all.vtu", "open_in_paraview.py",
                                          "mesh.msh"]]


def write_mode_tables(result: ModalResult, folder: Path,
                      est: ErrorEstimate | None = None) -> list[Path]:
    """modes.csv and modes.json: each mode's frequency, kind and bound, in `folder`."""
    write_csv(folder / "modes.csv", modes_table(result, est))
    (folder / "modes.json").write_text(json_text(modes_record(result, est)))
    return [folder / "modes.csv", folder / "modes.json"]


def write_solid_files(result: ModalResult, folder: Path) -> list[Path]:
    """The solid the mesh was made from, as shaft.step and shaft.brep, in `folder`."""
    from shaftfem.cad.build import write_solid

    paths = [folder / "shaft.step", folder / "shaft.brep"]
    write_solid(result.shape.brep, result.scene.shaft, paths)
    return paths


def msh_cells(mesh) -> np.ndarray:
    """The mesh's cells in gmsh's node order (meshio writes them as given): meshio's
    10-node order is put right by meshio itself; cubic cells take gmsh's 20-node order."""
    if mesh.geometry_order == 3:
        from shaftfem.cad.cubic import GMSH_NODES, in_node_order

        return in_node_order(mesh.points, mesh.cells, GMSH_NODES)
    return mesh.cells


def write_strength_files(result, folder: Path) -> list[Path]:
    """strength.vtp (the shaft's surface under its duty: the equivalent stress amplitude,
    signed mean and peak in MPa, the relative stress gradient in 1/mm, FKM's degrees of
    utilisation a_BK and a_SK, NaN where a load or reaction enters) and strength.json,
    for a workflows.strength.StrengthResult."""
    from shaftfem.outputs.vtk import write_vtp
    from shaftfem.store import write_text

    s = result.surface
    files = [write_vtp(folder / "strength.vtp", s.points, s.facets, {
        "amplitude_MPa": s.amplitude / 1e6, "mean_MPa": s.mean / 1e6, "peak_MPa": s.peak / 1e6,
        "stress_gradient_per_mm": s.gradient * 1e-3,
        "fatigue_utilisation_a_BK": s.fatigue_utilisation,
        "yield_utilisation_a_SK": s.yield_utilisation})]
    files.append(write_text(folder / "strength.json", json_text(result.as_dict())))
    return files
