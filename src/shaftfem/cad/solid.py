"""The shaft's solid: built from its parameters (cad.build) or imported (cad.step), checked.

The check: the volume the grooves removed must match the analytic groove
volume (profile.py) to 1 %; a boolean that went wrong fails here, loudly,
before anything is meshed. A shaft without grooves is a plain cylinder: it
needs no CAD solid at all (its mesh is built from the parameters).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from shaftfem.cad.profile import groove_volume
from shaftfem.cad.step import StepImport
from shaftfem.errors import GeometryError
from shaftfem.scene.model import Grooves, Shaft

# Bump when the construction or what is kept of it changes, so that solids built before
# are not reused (workflows.stages keys them with it; 5: profiles, keyways, STEP files
# and a reference volume; 6: a STEP import's findings kept with its solid; 7: with its
# outer surface sampled; 8: the grooves' root fillet meeting the floor at 4.4 degrees,
# not 14; 9: the keyways' analytic volume kept with the grooves', as the volume cut is,
# and a keyway's cutter reaching above a fillet it runs into).
CONSTRUCTION_VERSION = 9
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
    found: StepImport | None = None   # what a STEP import found (a STEP shaft's only)

    @property
    def groove_volume_error(self) -> float:
        """Relative difference of the removed volume against the analytic one."""
        if self.groove_volume_analytic == 0:
            return 0.0
        return self.groove_volume_cad / self.groove_volume_analytic - 1.0


def plain_volume(shaft: Shaft, grooves_volume: float) -> float:
    """A plain bar's volume less its grooves', m^3."""
    return math.pi * shaft.radius**2 * shaft.length - grooves_volume


def needs_cad(shaft: Shaft, grooves: Grooves | None) -> bool:
    """Whether the shaft needs a CAD solid: a plain bar is meshed from its parameters."""
    return not (grooves is None and shaft.plain)


def make_shape(shaft: Shaft, grooves: Grooves | None, brep: Path | None,
               step_key: str = "[shaft] step_file") -> ShaftShape:
    """Build the shaft's solid into `brep` and check its volume (a plain bar: no file, its
    volume analytic). A STEP solid is imported and placed once, and what the import found
    comes with the shape (`step_key` names the scene key in its errors)."""
    if not needs_cad(shaft, grooves):
        v = plain_volume(shaft, 0.0)
        return ShaftShape(brep=None, volume=v, groove_volume_analytic=0.0,
                          groove_volume_cad=0.0, n_volumes=1, from_cache=False,
                          reference_volume=v)
    if brep is None:
        raise ValueError("a shaft with grooves, a profile or a STEP file needs a BREP path")
    meta, found = _built(shaft, grooves, brep, step_key)
    return ShaftShape(brep=brep, from_cache=False, found=found, **meta)


def _built(shaft: Shaft, grooves: Grooves | None, brep: Path, step_key: str
           ) -> tuple[dict, StepImport | None]:
    """Build the solid into `brep` and check it: the volume its grooves and keyways
    removed against theirs, analytic, to VOLUME_TOLERANCE; a profile's body, before them,
    against its revolved half-section to PROFILE_TOLERANCE. A STEP solid is imported and
    placed (cad.step), its volume its own reference."""
    if shaft.step is not None:
        from shaftfem.cad.step import import_step

        info = import_step(shaft.step, step_key, brep)
        return dict(volume=info.volume, groove_volume_analytic=0.0, groove_volume_cad=0.0,
                    n_volumes=1, reference_volume=info.volume), info
    from shaftfem.cad.build import build_solid
    from shaftfem.cad.outline import keyway_volume, outline, revolved_volume, surface_radius

    v_grooves = 0.0
    if grooves is not None:
        section = shaft.profile[shaft.section_at(grooves.start + grooves.length / 2) or 0]
        v_grooves = groove_volume(grooves, section.diameter_start / 2)
    v_keys = sum(keyway_volume(k, shaft.radius_at(k.start + k.length / 2) or 0.0,
                               surface=lambda z: surface_radius(shaft, z))
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
    return dict(volume=volume, groove_volume_analytic=v_grooves + v_keys,
                groove_volume_cad=removed,
                n_volumes=n_volumes, reference_volume=reference), None


META_KEYS = ("volume", "groove_volume_analytic", "groove_volume_cad", "n_volumes",
             "reference_volume")
