"""What cubic elements buy on the paper's shaft: P3 everywhere, or only where the error is.

    .venv/bin/python benchmarks/cubic_functions.py [GROOVE_SIZES_MM, e.g. 4,3,4/2]
                                                [SHARES, e.g. 0.5,0.8,0.95,1]
                                                [ROOT_RADIUS_MM]

On each mesh (8 mm away from the grooves, the given size on the groove faces and,
after a slash, at the floor edges) the
P2 modes are solved as `shaftfem modes` solves them; then the same mesh gets a
hierarchical cubic basis: the P2 functions plus, per edge, the cubic
lambda_a lambda_b (lambda_a - lambda_b) and, per face, lambda_a lambda_b lambda_c.
All of them together span P3 (the Lagrange P3 space); a subset of them is the P2
space enriched on the edges and faces of the elements that hold the given share
of the P2 recovery estimate (the worst mode's, element by element). Every such
space contains the P2 one, so its frequencies lie between the P2 ones and the
truth (conforming: both bound from above).

True errors against the NGSolve reference of docs/verification.md (order 4 on netgen's
curved mesh, 541k DOFs); with ROOT_RADIUS_MM the reference does not apply and
only the P2 -> P3 change is meaningful. Each mesh runs in a fresh process: the
peak memory is that process' (assembling the full cubic space once, then the
subsets).

scikit-fem has no cubic tetrahedron; this benchmark's basis is not part of
shaftfem.
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import numpy as np  # noqa: E402

from _common import PAPER_REFERENCE_HZ, in_fresh_process, machine, peak_mb  # noqa: E402

REFERENCE_HZ = np.array(PAPER_REFERENCE_HZ)
EDGES = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]   # scikit-fem's RefTet order
FACES = [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)]
GRAD_LAMBDA = np.array([[-1., -1., -1.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])
EDGE_BUBBLE = 10.0   # scales lambda_a lambda_b (lambda_a - lambda_b) to about 1 at its peak


def cubic_element():
    """P2 (Lagrange) plus cubic edge and face bubbles on the tetrahedron: spans P3.

    The edge bubble is odd along its edge, so neighbouring elements must see each
    edge in the same direction: cells with ascending vertex numbers (sorted_cells)."""
    from skfem.element.element_h1 import ElementH1
    from skfem.refdom import RefTet

    V = RefTet.p.T
    locs = [V[i] for i in range(4)]
    for a, b in EDGES:
        locs += [(V[a] + V[b]) / 2] * 2
    locs += [(V[a] + V[b] + V[c]) / 3 for a, b, c in FACES]

    class ElementTetP2Cubic(ElementH1):
        nodal_dofs, edge_dofs, facet_dofs, maxdeg = 1, 2, 1, 3
        dofnames = ["u", "u", "u", "u"]
        doflocs = np.array(locs)
        refdom = RefTet

        def lbasis(self, X, i):
            lam = [1 - X[0] - X[1] - X[2], X[0], X[1], X[2]]
            g = [GRAD_LAMBDA[k].reshape(3, *([1] * X[0].ndim)) for k in range(4)]
            if i < 4:
                la = lam[i]
                return la * (2 * la - 1), (4 * la - 1) * g[i] + 0 * X[0]
            if i < 16:
                e, cubic = divmod(i - 4, 2)
                a, b = EDGES[e]
                la, lb = lam[a], lam[b]
                if not cubic:
                    return 4 * la * lb, 4 * (lb * g[a] + la * g[b])
                c = EDGE_BUBBLE
                return (c * la * lb * (la - lb),
                        c * (2 * la * lb - lb**2) * g[a] + c * (la**2 - 2 * la * lb) * g[b])
            a, b, c = FACES[i - 16]
            la, lb, lc = lam[a], lam[b], lam[c]
            return 27 * la * lb * lc, 27 * (lb * lc * g[a] + la * lc * g[b] + la * lb * g[c])

    return ElementTetP2Cubic()


def sorted_cells(cells: np.ndarray) -> np.ndarray:
    """10-node cells (meshio order) with their vertices in ascending order, edge nodes
    permuted along."""
    order = np.argsort(cells[:, :4], axis=1)
    out = np.empty_like(cells)
    out[:, :4] = np.take_along_axis(cells[:, :4], order, 1)
    column = {}
    for k, (a, b) in enumerate(EDGES):
        column[(a, b)] = column[(b, a)] = 4 + k
    for k, (i, j) in enumerate(EDGES):
        for a in range(4):
            for b in range(4):
                if a != b:
                    sel = (order[:, i] == a) & (order[:, j] == b)
                    out[sel, 4 + k] = cells[sel, column[(a, b)]]
    return out


def one(sizes_mm: str, shares: list[float], root_radius_mm: float | None) -> dict:
    from dataclasses import replace

    import scipy.sparse as sp
    from skfem import Basis

    from shaftfem.cad.mesh import skfem_mesh
    from shaftfem.fem.assembly import Pattern, stiffness_and_mass
    from shaftfem.fem.eigen import solve_modes
    from shaftfem.fem.estimate import recovery_estimate
    from shaftfem.fem.supports import rigid_body_modes
    from shaftfem.scene.load import load_scene
    from shaftfem.scene.model import ModeRequest
    from shaftfem.workflows.pipeline import run_modes

    scene = replace(load_scene("paper2018"), max_dofs=20_000_000)
    if root_radius_mm is not None:
        scene = replace(scene, grooves=replace(scene.grooves, root_radius=root_radius_mm * 1e-3))
    groove, _, edge = sizes_mm.partition("/")
    h = float(groove) * 1e-3
    scene = replace(scene, mesh=replace(scene.mesh, groove_size=h,
                                        edge_size=float(edge or groove) * 1e-3))
    r = run_modes(scene)
    rows = [{"space": "P2", "elements": 0, "dofs": r.modes.n_dofs,
             "seconds": r.timings.solve,
             "f": r.modes.frequencies.tolist()}]
    rec = recovery_estimate(r.mesh, scene.material, r.modes)
    share = (rec.elements / rec.relative[:, None]).max(axis=0)

    skmesh = skfem_mesh(r.mesh.points, sorted_cells(r.mesh.cells))
    basis = Basis(skmesh, cubic_element(), intorder=4)
    K, Ms = stiffness_and_mass(basis, Pattern.of(basis.element_dofs, basis.N), scene.material,
                               6, 2)
    n_el = basis.nelems
    M = sp.kron(Ms, sp.identity(3, format="csr"), format="csr")

    dofs = basis.dofs
    p2 = np.concatenate([dofs.nodal_dofs.ravel(), dofs.edge_dofs[0]])
    edge_cubic, face_cubic = dofs.edge_dofs[1], dofs.facet_dofs[0]
    ranked = np.argsort(-share)
    cumulative = np.cumsum(share[ranked]) / share.sum()
    for s in shares:
        chosen = ranked if s >= 1 else ranked[:np.searchsorted(cumulative, s) + 1]
        scalar = np.concatenate([p2, edge_cubic[np.unique(skmesh.t2e[:, chosen])],
                                 face_cubic[np.unique(skmesh.t2f[:, chosen])]])
        idx = (3 * scalar[:, None] + np.arange(3)).ravel()
        rigid = rigid_body_modes(basis.doflocs.T[scalar])
        rigid[3 * len(p2):] = 0.0   # rigid motions are P1: no cubic part
        t = time.perf_counter()
        sol = solve_modes(K[idx][:, idx].tocsr(), M[idx][:, idx].tocsr(), ModeRequest(10), rigid=rigid)
        lam_e = sol.eigenvalues[6:16]
        rows.append({"space": f"P2 + cubic on {100 * s:g} % of the estimate",
                     "elements": len(chosen), "dofs": len(idx),
                     "seconds": time.perf_counter() - t,
                     "f": (np.sqrt(lam_e) / (2 * np.pi)).tolist()})
    return {"groove": sizes_mm, "elements": n_el, "rows": rows, "peak_mb": peak_mb()}


def main() -> None:
    sizes = (sys.argv[1] if len(sys.argv) > 1 else "4").split(",")
    shares = [float(x) for x in (sys.argv[2] if len(sys.argv) > 2 else "0.5,0.8,0.95,1").split(",")]
    rr = float(sys.argv[3]) if len(sys.argv) > 3 else None
    print(f"machine: {machine()}; paper2018, 8 mm away from the grooves"
          + (f", root radius {rr:g} mm" if rr is not None else "") + "\n")
    errors = ("largest true error | smallest true error" if rr is None
              else "largest change from P2 | -")
    print("| grooves / floor edges (mm) | space | enriched elements | DOFs | factorisation + eigensolve (s) "
          f"| {errors} | peak memory (MB) |")
    print("|---|---|---|---|---|---|---|---|")
    for h in sizes:
        run = in_fresh_process(one, h, shares, rr)
        for row in run["rows"]:
            f = np.array(row["f"])
            if rr is None:
                err = 100 * (f / REFERENCE_HZ - 1)
                cols = f"{err.max():.3f} % | {err.min():.3f} %"
            else:
                p2 = np.array(run["rows"][0]["f"])
                cols = f"{100 * (p2 / f - 1).max():.3f} % | -"
            print(f"| {h} | {row['space']} | {row['elements']} / {run['elements']} | "
                  f"{row['dofs']} | {row['seconds']:.1f} | {cols} | {run['peak_mb']:.0f} |",
                  flush=True)


if __name__ == "__main__":
    main()
