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
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _plain(obj):
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, (np.floating, np.integer)):
        return obj.item()
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def write_json(path: str | Path, data: dict) -> None:
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(data, indent=2, default=_plain) + "\n")


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
