"""The shaft's solid: built once per set of parameters (occ.py), checked, cached.

The check: the volume the grooves removed must match the analytic groove
volume (profile.py) to 1 %; a boolean that went wrong fails here, loudly,
before anything is meshed. A shaft without grooves is a plain cylinder: it
needs no CAD solid at all (its mesh is built from the parameters).
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path

from shaftfem.cad.profile import groove_volume
from shaftfem.errors import GeometryError
from shaftfem.scene.model import Grooves, Shaft
from shaftfem.store import atomic_path, cache_dir, checksum, content_key, discard, scratch_dir, write_json

# Bump when the construction or the cache entry changes, so old cached shapes are not
# reused (4: entries carry checksums).
CONSTRUCTION_VERSION = 4
VOLUME_TOLERANCE = 0.01         # removed volume vs analytic groove volume


@dataclass(frozen=True)
class ShaftShape:
    """A built solid: its BREP file (None for a plain cylinder) and the volumes that
    checked it (m^3)."""

    brep: Path | None
    volume: float
    groove_volume_analytic: float
    groove_volume_cad: float
    n_volumes: int
    from_cache: bool

    @property
    def groove_volume_error(self) -> float:
        """Relative difference of the removed volume against the analytic one."""
        if self.groove_volume_analytic == 0:
            return 0.0
        return self.groove_volume_cad / self.groove_volume_analytic - 1.0


def shape_key(shaft: Shaft, grooves: Grooves | None) -> str:
    from shaftfem.cad.build import SECTIONS_PER_CELL

    return content_key({"version": CONSTRUCTION_VERSION, "sections": SECTIONS_PER_CELL,
                        "shaft": asdict(shaft), "grooves": asdict(grooves) if grooves else None})


def build_shape(shaft: Shaft, grooves: Grooves | None, use_cache: bool = True) -> ShaftShape:
    """Build (or fetch from the cache) the shaft's solid and check its volume; without
    `use_cache` the cache is neither read nor written (the BREP lives in a scratch
    folder for this process)."""
    if grooves is None:
        return ShaftShape(brep=None, volume=math.pi * shaft.radius**2 * shaft.length,
                          groove_volume_analytic=0.0, groove_volume_cad=0.0, n_volumes=1,
                          from_cache=False)
    key = shape_key(shaft, grooves)
    folder = (cache_dir() if use_cache else scratch_dir()) / "shapes"
    brep, meta_file = folder / f"{key}.brep", folder / f"{key}.json"
    if use_cache and (brep.exists() or meta_file.exists()):
        meta, why = _verified(brep, meta_file)
        if meta is not None:
            return ShaftShape(brep=brep, from_cache=True, **meta)
        discard(f"solid {key}", why, brep, meta_file)

    from shaftfem.cad.build import build_solid

    v_grooves = groove_volume(grooves, shaft.radius)
    with atomic_path(brep) as tmp:
        volume, n_volumes = build_solid(shaft, grooves, tmp)
        removed = math.pi * shaft.radius**2 * shaft.length - volume
        err = removed / v_grooves - 1.0
        if abs(err) > VOLUME_TOLERANCE:
            raise GeometryError(
                f"the grooves removed {removed * 1e9:.1f} mm^3 but the analytic groove "
                f"volume is {v_grooves * 1e9:.1f} mm^3 ({100 * err:+.2f} %, allowed "
                f"{100 * VOLUME_TOLERANCE:.0f} %): the CAD booleans went wrong")
    meta = dict(volume=volume, groove_volume_analytic=v_grooves, groove_volume_cad=removed,
                n_volumes=n_volumes)
    write_json(meta_file, {**meta, "brep_sha256": checksum(brep.read_bytes()),
                           "sha256": _meta_checksum(meta)})
    return ShaftShape(brep=brep, from_cache=False, **meta)


META_KEYS = ("volume", "groove_volume_analytic", "groove_volume_cad", "n_volumes")


def _meta_checksum(meta: dict) -> str:
    return checksum(json.dumps({k: meta[k] for k in META_KEYS}, sort_keys=True).encode())


def _verified(brep: Path, meta_file: Path) -> tuple[dict | None, str]:
    """The cached solid's metadata if the entry is whole and unaltered, else (None, why).

    The BREP's checksum is checked before anything reads it: OpenCASCADE can crash the
    whole process on a damaged BREP."""
    try:
        stored = json.loads(meta_file.read_text())
        meta = {k: stored[k] for k in META_KEYS}
        if stored["sha256"] != _meta_checksum(meta):
            return None, "its metadata do not match their checksum"
        if stored["brep_sha256"] != checksum(brep.read_bytes()):
            return None, "the BREP file does not match its checksum"
    except (OSError, ValueError, KeyError, TypeError) as exc:
        return None, f"{type(exc).__name__}: {exc}"
    return meta, ""
