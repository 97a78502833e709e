"""What a cross-section carries: the axial force, the bending moments and the torque of
a stress field through the solid disc at z, by equilibrium (they hold on any section,
a notch's too), for the nominal stresses a notch factor is measured against.

    N = int sigma_zz dA,  M_x = int sigma_zz y dA,  M_y = -int sigma_zz x dA,
    T = int (x tau_yz - y tau_xz) dA
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from shaftfem.fem.probe import Probe

# Gauss-Legendre points across the radius (never on the surface, where a point may lie
# a hair outside the straight-sided mesh) and even steps round the circle (exact for
# the trigonometric polynomials a turning load gives)
RINGS = 12
SPOKES = 72


def resultants(read: Callable[[np.ndarray], Probe], stress: np.ndarray, z: float,
               radius: float) -> np.ndarray | None:
    """(cases, 4): N (N), M_x, M_y, T (N m) of each case's stress field (cases, N, 3, 3)
    at the mesh's vertices, read at points (k, 3) by `read` (shaftfem.fem.probe), through
    the disc of `radius` (m) at z; None where the disc leaves the solid."""
    t, w = np.polynomial.legendre.leggauss(RINGS)
    r = 0.5 * radius * (t + 1)
    theta = np.linspace(0.0, 2 * np.pi, SPOKES, endpoint=False)
    R, TH = np.meshgrid(r, theta, indexing="ij")
    weight = (0.5 * radius * w)[:, None] * R * (2 * np.pi / SPOKES)     # r dr dtheta
    x, y = (R * np.cos(TH)).ravel(), (R * np.sin(TH)).ravel()
    at = read(np.column_stack([x, y, np.full(x.size, z)]))
    if not at.found.all():
        return None
    s = at.tensors(stress)
    wt = weight.ravel()[:, None]
    szz, txz, tyz = s[..., 2, 2], s[..., 0, 2], s[..., 1, 2]
    return np.column_stack([
        (wt * szz).sum(0), (wt * szz * y[:, None]).sum(0), -(wt * szz * x[:, None]).sum(0),
        (wt * (x[:, None] * tyz - y[:, None] * txz)).sum(0)])
