"""Files out: mode shapes for ParaView, tables, the mesh, the solid, a CalculiX deck.

Every file is written under a temporary name beside it and renamed, and a set
of files into a staging folder moved at the end (shaftfem.store): a failed or
interrupted run never leaves a half-written file behind.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.store import json_text, staged_directory, write_csv, write_text

if TYPE_CHECKING:
    from shaftfem.fem.estimate import ErrorEstimate
    from shaftfem.workflows.pipeline import ModalResult


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
        "installation": installation_record(result),
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
                         "diametral_inertia_kg_m2": a.diametral_inertia}
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
    import shutil

    import meshio

    from shaftfem.cad.build import write_solid
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
    if result.installed is not None:
        buf.write(_installation_cards(result))
    buf.write(
        f"** {'installed' if result.installed is not None else 'free-free'} modal analysis "
        f"of {result.scene.name} written by shaftfem (SI units)\n"
        f"*MATERIAL, NAME=M1\n*ELASTIC\n{mat.youngs_modulus:.10e}, {mat.poisson_ratio:.10g}\n"
        f"*DENSITY\n{mat.density:.10e}\n"
        "*SOLID SECTION, ELSET=EALL, MATERIAL=M1\n"
        # STORAGE=YES: the eigenvalues also go, in full double precision, to the binary
        # .eig file (the .dat table prints 7 digits only)
        f"*STEP\n*FREQUENCY, STORAGE=YES\n{n_eigen}\n*END STEP\n"
    )
    return buf.getvalue()


def _terms(nodes: np.ndarray, dofs: np.ndarray, coeffs: np.ndarray) -> list[str]:
    """*EQUATION term lines, four terms (node, DOF, coefficient) a line (13 digits: CalculiX
    reads at most 20 characters a field)."""
    cells = [f"{n}, {d}, {c:.12e}" for n, d, c in zip(nodes, dofs, coeffs)]
    return [", ".join(cells[i:i + 4]) for i in range(0, len(cells), 4)]


def part_point_masses(mass: float, polar: float, diametral: float
                      ) -> list[tuple[float, tuple[float, float, float]]]:
    """Six point masses m / 6 with the part's mass and inertia tensor (for CalculiX,
    which has no rotary inertia on a rigid body): at +-a on x and y and +-b on z
    from the centre, 4 (m/6) a^2 = I_p and 2 (m/6)(a^2 + b^2) = I_d."""
    if mass == 0:
        return []
    a2 = 1.5 * polar / mass
    b2 = max(3 * diametral / mass - a2, 0.0)
    a, b = math.sqrt(a2), math.sqrt(b2)
    spots = [(a, 0, 0), (-a, 0, 0), (0, a, 0), (0, -a, 0), (0, 0, b), (0, 0, -b)]
    return [(mass / 6, p) for p in spots]


def _installation_cards(result: ModalResult) -> str:
    """Seats and parts as CalculiX cards, the same constraints shaftfem eliminates: a
    held mean motion is an *EQUATION over its band; a spring acts on a node of its
    own that the *EQUATION makes the mean, through a SPRING1; a part is a *RIGID BODY
    of its band with six point masses carrying its mass and inertias; a rigid-coupled
    seat is a *RIGID BODY of its band, its springs SPRING1s on the reference and
    rotation nodes, its holds *BOUNDARY cards there."""
    from shaftfem.fem.supports import ring_stiffness

    inst, system, mesh = result.installed, result.system, result.mesh
    assert inst is not None  # called for installed shafts only
    node_of = np.empty(system.nodes.shape[0], dtype=np.int64)
    node_of[system.point_dofs] = np.arange(1, mesh.points.shape[0] + 1)  # Abaqus ids
    next_node, next_el = mesh.points.shape[0] + 1, mesh.cells.shape[0] + 1
    out = ["** seats and parts of the installed shaft (shaftfem.fem.supports)"]
    if inst.clamped.size:
        out.append("*BOUNDARY")
        out += [f"{node_of[d // 3]}, {d % 3 + 1}, {d % 3 + 1}" for d in inst.clamped]
    for r in inst.restraints:
        order = np.argsort(-np.abs(r.coeffs), kind="stable")  # the pivot first, as ours
        nodes, dofs, coeffs = node_of[r.dofs[order] // 3], r.dofs[order] % 3 + 1, r.coeffs[order]
        out.append(f"** {r.name}")
        if r.held:
            out += ["*EQUATION", str(len(nodes))] + _terms(nodes, dofs, coeffs)
            continue
        z = float(np.mean(system.nodes[r.dofs // 3, 2]))
        out += ["*NODE", f"{next_node}, 0.0, 0.0, {z:.12e}",
                "*EQUATION", str(len(nodes) + 1)]
        out += _terms(np.r_[next_node, nodes], np.r_[1, dofs], np.r_[-1.0, coeffs])
        # the spring's node has no element but the spring: its unused DOFs are held
        out += ["*BOUNDARY", f"{next_node}, 2, 3",
                f"*ELEMENT, TYPE=SPRING1, ELSET=ES{next_el}", f"{next_el}, {next_node}",
                f"*SPRING, ELSET=ES{next_el}", "1", f"{r.stiffness:.12e}"]
        next_node, next_el = next_node + 1, next_el + 1
    for k, (idx, part) in enumerate(zip(inst.tied, result.scene.attachments)):
        c = np.array([0.0, 0.0, part.position])
        masses = part_point_masses(part.mass, part.polar_inertia, part.diametral_inertia)
        ref, rot = next_node, next_node + 1
        extra = list(range(next_node + 2, next_node + 2 + len(masses)))
        out += [f"** {part.name}", "*NODE", f"{ref}, 0.0, 0.0, {c[2]:.12e}",
                f"{rot}, 0.0, 0.0, {c[2]:.12e}"]
        out += [f"{n}, {c[0] + p[0]:.12e}, {c[1] + p[1]:.12e}, {c[2] + p[2]:.12e}"
                for n, (_, p) in zip(extra, masses)]
        members = list(node_of[idx]) + extra
        out += [f"*NSET, NSET=PART{k + 1}"]
        out += [", ".join(str(n) for n in members[i:i + 8]) for i in range(0, len(members), 8)]
        out += [f"*RIGID BODY, NSET=PART{k + 1}, REF NODE={ref}, ROT NODE={rot}"]
        for n, (m, _) in zip(extra, masses):
            out += [f"*ELEMENT, TYPE=MASS, ELSET=EM{next_el}", f"{next_el}, {n}",
                    f"*MASS, ELSET=EM{next_el}", f"{m:.12e}"]
            next_el += 1
        next_node += 2 + len(masses)
    rings = [s for s in result.scene.held if s.coupling == "rigid"]  # as install() took them
    for j, (idx, s) in enumerate(zip(inst.rings, rings)):
        ref, rot = next_node, next_node + 1
        out += [f"** {s.name}: a rigid ring", "*NODE", f"{ref}, 0.0, 0.0, {s.position:.12e}",
                f"{rot}, 0.0, 0.0, {s.position:.12e}", f"*NSET, NSET=RING{j + 1}"]
        members = list(node_of[idx])
        out += [", ".join(str(n) for n in members[i:i + 8]) for i in range(0, len(members), 8)]
        out += [f"*RIGID BODY, NSET=RING{j + 1}, REF NODE={ref}, ROT NODE={rot}"]
        for d, stiffness in enumerate(ring_stiffness(s)):
            node, dof = (ref if d < 3 else rot), d % 3 + 1   # ROT NODE's DOFs are rotations
            if math.isinf(stiffness):
                out += ["*BOUNDARY", f"{node}, {dof}, {dof}"]
            elif stiffness > 0:
                out += [f"*ELEMENT, TYPE=SPRING1, ELSET=ES{next_el}", f"{next_el}, {node}",
                        f"*SPRING, ELSET=ES{next_el}", str(dof), f"{stiffness:.12e}"]
                next_el += 1
        next_node += 2
    return "\n".join(out) + "\n"


def write_calculix(result: ModalResult, path: str | Path, n_eigen: int | None = None) -> Path:
    """shaft.inp: `n_eigen` eigenvalues (default: ours plus the six rigid-body modes)."""
    return write_text(path, calculix_deck(result, n_eigen or result.modes.count
                                          + result.modes.n_rigid))


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
