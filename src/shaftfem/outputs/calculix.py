"""CalculiX: the same mesh, material, seats and parts as a *FREQUENCY deck, for an
independent solve, and its results read back."""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from shaftfem.errors import SceneError
from shaftfem.fem.supports import Carried, Restraint, ring_stiffness
from shaftfem.scene.model import Attachment, Support
from shaftfem.store import write_text

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult


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
        raise SceneError(f"the CalculiX deck is of C3D10 (order 2) elements; this run is of "
                         f"order {mesh.order}: export it with --order 2")
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
    own that the *EQUATION makes the mean, through a SPRING1; a part on a rigid joint
    is a *RIGID BODY of the shaft's slice under its hub with six point masses carrying
    its mass and inertias, one on a distributing joint two mass nodes that six
    *EQUATIONs tie to the section at its centre; a rigid-coupled seat is a *RIGID
    BODY of its band, its springs SPRING1s on the reference and rotation nodes, its
    holds *BOUNDARY cards there."""
    inst, system, mesh = result.installed, result.system, result.mesh
    assert inst is not None  # called for installed shafts only
    node_of = np.empty(system.nodes.shape[0], dtype=np.int64)
    node_of[system.point_dofs] = np.arange(1, mesh.points.shape[0] + 1)  # Abaqus ids
    ids = _Ids(mesh.points.shape[0] + 1, mesh.cells.shape[0] + 1)
    out = ["** seats and parts of the installed shaft (shaftfem.fem.installation)"]
    if inst.clamped.size:
        out.append("*BOUNDARY")
        out += [f"{node_of[d // 3]}, {d % 3 + 1}, {d % 3 + 1}" for d in inst.clamped]
    for r in inst.restraints:
        out += _restraint_cards(r, node_of, system.nodes, ids)
    for k, (idx, part) in enumerate(zip(inst.tied, inst.parts)):
        out += _part_cards(k, part, node_of[idx], ids)
    for c in inst.carried:
        out += _carried_cards(c, node_of, ids)
    rings = [s for s in result.scene.held if s.coupling == "rigid"]  # as install() took them
    for j, (idx, s) in enumerate(zip(inst.rings, rings)):
        out += _ring_cards(j, s, node_of[idx], ids)
    return "\n".join(out) + "\n"


@dataclass
class _Ids:
    """The next free node and element numbers of the deck."""

    node: int
    element: int


def _nset(name: str, members: list) -> list[str]:
    return [f"*NSET, NSET={name}"] + [", ".join(str(n) for n in members[i:i + 8])
                                      for i in range(0, len(members), 8)]


def _restraint_cards(r: Restraint, node_of: np.ndarray, nodes: np.ndarray, ids: _Ids
                     ) -> list[str]:
    """A held mean: an *EQUATION; a spring on a mean: a node of its own that an
    *EQUATION makes the mean, and a SPRING1 on it."""
    order = np.argsort(-np.abs(r.coeffs), kind="stable")  # the pivot first, as ours
    band, dofs, coeffs = node_of[r.dofs[order] // 3], r.dofs[order] % 3 + 1, r.coeffs[order]
    out = [f"** {r.name}"]
    if r.held:
        return out + ["*EQUATION", str(len(band))] + _terms(band, dofs, coeffs)
    n, e = ids.node, ids.element
    z = float(np.mean(nodes[r.dofs // 3, 2]))
    out += ["*NODE", f"{n}, 0.0, 0.0, {z:.12e}", "*EQUATION", str(len(band) + 1)]
    out += _terms(np.r_[n, band], np.r_[1, dofs], np.r_[-1.0, coeffs])
    # the spring's node has no element but the spring: its unused DOFs are held
    out += ["*BOUNDARY", f"{n}, 2, 3", f"*ELEMENT, TYPE=SPRING1, ELSET=ES{e}", f"{e}, {n}",
            f"*SPRING, ELSET=ES{e}", "1", f"{r.stiffness:.12e}"]
    ids.node, ids.element = n + 1, e + 1
    return out


def _part_cards(k: int, part: Attachment, band: np.ndarray, ids: _Ids) -> list[str]:
    """A part: a *RIGID BODY of its band and six point masses with its inertias."""
    c = np.array([0.0, 0.0, part.position])
    masses = part_point_masses(part.mass, part.polar_inertia, part.diametral_inertia)
    ref, rot = ids.node, ids.node + 1
    extra = list(range(ids.node + 2, ids.node + 2 + len(masses)))
    out = [f"** {part.name}", "*NODE", f"{ref}, 0.0, 0.0, {c[2]:.12e}",
           f"{rot}, 0.0, 0.0, {c[2]:.12e}"]
    out += [f"{n}, {c[0] + p[0]:.12e}, {c[1] + p[1]:.12e}, {c[2] + p[2]:.12e}"
            for n, (_, p) in zip(extra, masses)]
    out += _nset(f"PART{k + 1}", list(band) + extra)
    out += [f"*RIGID BODY, NSET=PART{k + 1}, REF NODE={ref}, ROT NODE={rot}"]
    for n, (m, _) in zip(extra, masses):
        out += [f"*ELEMENT, TYPE=MASS, ELSET=EM{ids.element}", f"{ids.element}, {n}",
                f"*MASS, ELSET=EM{ids.element}", f"{m:.12e}"]
        ids.element += 1
    ids.node += 2 + len(masses)
    return out


def _carried_cards(c: Carried, node_of: np.ndarray, ids: _Ids) -> list[str]:
    """A part on a distributing joint: its (U, Theta) = C u as the DOFs of two nodes of
    its own, tied to the section by six *EQUATIONs; each is solved for one section DOF
    (pivots by QR with column pivoting), so that the part's mass and inertia sit on
    independent DOFs (CalculiX holds no DOF of a mass node): the same kinetic energy
    C^T M_p C. Node 1 carries U and the mass m; node 2 carries (Theta_x, Theta_y,
    a Theta_z) and the diametral inertia I_d, with a^2 I_d = I_p."""
    from scipy.linalg import qr

    part = c.part
    _, _, piv = qr(c.C, pivoting=True, mode="economic")
    pivots, rest = piv[:6], np.sort(piv[6:])
    A_inv = np.linalg.inv(c.C[:, pivots])
    coupled = A_inv @ c.C[:, rest]                 # u_P = A^-1 q - A^-1 C_R u_R
    a = math.sqrt(part.polar_inertia / part.diametral_inertia) if part.diametral_inertia else 1.0
    per_dof = np.array([1, 1, 1, 1, 1, 1 / a])     # q in the two nodes' DOFs
    nodes, dofs = node_of[c.dofs // 3], c.dofs % 3 + 1
    n = ids.node
    out = [f"** {part.name}: a distributing joint", "*NODE",
           f"{n}, 0.0, 0.0, {part.position:.12e}", f"{n + 1}, 0.0, 0.0, {part.position:.12e}"]
    q_nodes, q_dofs = np.array([n, n, n, n + 1, n + 1, n + 1]), np.array([1, 2, 3, 1, 2, 3])
    for k in range(6):
        out += ["*EQUATION", str(7 + rest.size)] + _terms(
            np.r_[nodes[pivots[k]], q_nodes, nodes[rest]],
            np.r_[dofs[pivots[k]], q_dofs, dofs[rest]],
            np.r_[1.0, -A_inv[k] * per_dof, coupled[k]])
    for node, mass in ((n, part.mass), (n + 1, part.diametral_inertia)):
        if mass > 0:
            out += [f"*ELEMENT, TYPE=MASS, ELSET=EM{ids.element}", f"{ids.element}, {node}",
                    f"*MASS, ELSET=EM{ids.element}", f"{mass:.12e}"]
            ids.element += 1
    ids.node += 2
    return out


def _ring_cards(j: int, s: Support, band: np.ndarray, ids: _Ids) -> list[str]:
    """A rigid-coupled seat: a *RIGID BODY of its band, SPRING1s and *BOUNDARY cards on
    its reference (translations) and rotation nodes."""
    ref, rot = ids.node, ids.node + 1
    out = [f"** {s.name}: a rigid ring", "*NODE", f"{ref}, 0.0, 0.0, {s.position:.12e}",
           f"{rot}, 0.0, 0.0, {s.position:.12e}"]
    out += _nset(f"RING{j + 1}", list(band))
    out += [f"*RIGID BODY, NSET=RING{j + 1}, REF NODE={ref}, ROT NODE={rot}"]
    for d, stiffness in enumerate(ring_stiffness(s)):
        node, dof = (ref if d < 3 else rot), d % 3 + 1   # ROT NODE's DOFs are rotations
        if math.isinf(stiffness):
            out += ["*BOUNDARY", f"{node}, {dof}, {dof}"]
        elif stiffness > 0:
            e = ids.element
            out += [f"*ELEMENT, TYPE=SPRING1, ELSET=ES{e}", f"{e}, {node}",
                    f"*SPRING, ELSET=ES{e}", str(dof), f"{stiffness:.12e}"]
            ids.element += 1
    ids.node += 2
    return out


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
