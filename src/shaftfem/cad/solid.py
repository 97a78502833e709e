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
# reused (4: entries carry checksums; 5: profiles, keyways, STEP files and a reference
# volume).
CONSTRUCTION_VERSION = 5
VOLUME_TOLERANCE = 0.01         # removed volume vs analytic groove volume
PROFILE_TOLERANCE = 1e-6        # a revolved profile's volume vs its half-section's


@dataclass(frozen=True)
class ShaftShape:
    """A built solid: its BREP file (None for a plain cylinder) and the volumes that
    checked it (m^3): the CAD solid's, the grooves' and keyways' analytic and as cut,
    and the reference the mesh's volume is measured against (the analytic volume of a
    plain bar less its grooves; else the CAD solid's, itself checked against the
    analytic profile)."""

    brep: Path | None
    volume: float
    groove_volume_analytic: float
    groove_volume_cad: float
    n_volumes: int
    from_cache: bool
    reference_volume: float = 0.0

    @property
    def groove_volume_error(self) -> float:
        """Relative difference of the removed volume against the analytic one."""
        if self.groove_volume_analytic == 0:
            return 0.0
        return self.groove_volume_cad / self.groove_volume_analytic - 1.0


def plain_volume(shaft: Shaft, grooves_volume: float) -> float:
    """A plain bar's volume less its grooves', m^3."""
    return math.pi * shaft.radius**2 * shaft.length - grooves_volume


def shape_key(shaft: Shaft, grooves: Grooves | None) -> str:
    from shaftfem.cad.build import SECTIONS_PER_CELL

    return content_key({"version": CONSTRUCTION_VERSION, "sections": SECTIONS_PER_CELL,
                        "shaft": asdict(shaft), "grooves": asdict(grooves) if grooves else None})


def build_shape(shaft: Shaft, grooves: Grooves | None, use_cache: bool = True) -> ShaftShape:
    """Build (or fetch from the cache) the shaft's solid and check its volume; without
    `use_cache` the cache is neither read nor written (the BREP lives in a scratch
    folder for this process)."""
    if grooves is None and shaft.plain:
        v = plain_volume(shaft, 0.0)
        return ShaftShape(brep=None, volume=v, groove_volume_analytic=0.0,
                          groove_volume_cad=0.0, n_volumes=1, from_cache=False,
                          reference_volume=v)
    key = shape_key(shaft, grooves)
    folder = (cache_dir() if use_cache else scratch_dir()) / "shapes"
    brep, meta_file = folder / f"{key}.brep", folder / f"{key}.json"
    if use_cache and (brep.exists() or meta_file.exists()):
        meta, why = _verified(brep, meta_file)
        if meta is not None:
            return ShaftShape(brep=brep, from_cache=True, **meta)
        discard(f"solid {key}", why, brep, meta_file)

    with atomic_path(brep) as tmp:
        meta = _built(shaft, grooves, tmp)
    write_json(meta_file, {**meta, "brep_sha256": checksum(brep.read_bytes()),
                           "sha256": _meta_checksum(meta)})
    return ShaftShape(brep=brep, from_cache=False, **meta)


def _built(shaft: Shaft, grooves: Grooves | None, brep: Path) -> dict:
    """Build the solid into `brep` and check it: the volume its grooves and keyways
    removed against theirs, analytic, to VOLUME_TOLERANCE; a profile's body, before them,
    against its revolved half-section to PROFILE_TOLERANCE. A STEP solid is imported and
    placed (cad.step), its volume its own reference."""
    if shaft.step is not None:
        from shaftfem.cad.step import import_step

        info = import_step(shaft.step, "[shaft] step_file", brep)
        return dict(volume=info.volume, groove_volume_analytic=0.0, groove_volume_cad=0.0,
                    n_volumes=1, reference_volume=info.volume)
    from shaftfem.cad.build import build_solid
    from shaftfem.cad.outline import keyway_volume, outline, revolved_volume

    v_grooves = 0.0
    if grooves is not None:
        section = shaft.profile[shaft.section_at(grooves.start + grooves.length / 2) or 0]
        v_grooves = groove_volume(grooves, section.diameter_start / 2)
    v_keys = sum(keyway_volume(k, shaft.radius_at(k.start + k.length / 2) or 0.0)
                 for k in shaft.keyways)
    body = plain_volume(shaft, 0.0) if shaft.plain else revolved_volume(outline(shaft))
    volume, n_volumes = build_solid(shaft, grooves, brep)
    removed = body - volume
    if v_grooves + v_keys > 0:
        err = removed / (v_grooves + v_keys) - 1.0
        # the keyways' analytic volumes take their floor corners as sharp
        allowed = VOLUME_TOLERANCE * (v_grooves + v_keys) + sum(
            (1 - math.pi / 4) * k.corner_radius**2 * 2 * k.length for k in shaft.keyways)
        if abs(removed - v_grooves - v_keys) > allowed:
            what = " and ".join(w for w, v in (("grooves", v_grooves), ("keyways", v_keys)) if v)
            raise GeometryError(
                f"the {what} removed {removed * 1e9:.1f} mm^3 but their analytic volume is "
                f"{(v_grooves + v_keys) * 1e9:.1f} mm^3 ({100 * err:+.2f} %, allowed "
                f"{100 * VOLUME_TOLERANCE:.0f} %): the CAD booleans went wrong")
    elif abs(removed) > PROFILE_TOLERANCE * body:
        raise GeometryError(
            f"the solid's volume is {volume * 1e9:.1f} mm^3 but its profile's is "
            f"{body * 1e9:.1f} mm^3: the CAD construction went wrong")
    reference = plain_volume(shaft, v_grooves) if shaft.plain else volume
    return dict(volume=volume, groove_volume_analytic=v_grooves, groove_volume_cad=removed,
                n_volumes=n_volumes, reference_volume=reference)


META_KEYS = ("volume", "groove_volume_analytic", "groove_volume_cad", "n_volumes",
             "reference_volume")


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
