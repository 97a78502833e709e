"""The CAD and mesh stages with the cache around them: each stage is a pure function of
its inputs (cad.solid.make_shape, cad.mesh.generate_mesh); this layer keys its result by
everything it depends on, keeps it, and checks a kept entry before it is used.

A damaged entry (truncated, altered) is discarded, said in one line, and made again. A
STEP file is imported once: what its import found (axis, length, outer radii) is kept
with its solid, so a warm run places the scene without reading the file.
"""

from __future__ import annotations

import json
from dataclasses import asdict, replace
from typing import TYPE_CHECKING

from shaftfem.scene.model import Grooves, MeshSettings, Scene, Shaft
from shaftfem.scene.toml_reading import where
from shaftfem.store import (
    atomic_path,
    cache_dir,
    checksum,
    content_key,
    discard,
    load_arrays,
    save_arrays,
    scratch_dir,
    write_json,
)

if TYPE_CHECKING:
    from pathlib import Path

    from shaftfem.cad.mesh import ShaftMesh
    from shaftfem.cad.solid import ShaftShape


def shape_key(shaft: Shaft, grooves: Grooves | None) -> str:
    """A hash of everything the solid depends on (a STEP shaft's as its scene gives it:
    known without reading the file, whose checksum is in it)."""
    from shaftfem.cad.build import SECTIONS_PER_CELL
    from shaftfem.cad.solid import CONSTRUCTION_VERSION

    return content_key({"version": CONSTRUCTION_VERSION, "sections": SECTIONS_PER_CELL,
                        "shaft": asdict(shaft.unplaced()), "grooves": grooves_key(grooves)})


def grooves_key(grooves: Grooves | None) -> dict | None:
    """The grooves as a key holds them: without runouts as before runouts were modelled
    (their solids and meshes stay valid), with them with how they are built."""
    if grooves is None:
        return None
    if not grooves.runout:
        return {k: v for k, v in asdict(grooves).items() if k != "runout"}
    from shaftfem.cad.build import RUNOUT_SECTIONS
    from shaftfem.cad.profile import RUNOUT_CLEARANCE, RUNOUT_FORM

    return {**asdict(grooves), "runout": [RUNOUT_FORM, RUNOUT_SECTIONS, RUNOUT_CLEARANCE]}


def solid(scene: Scene, use_cache: bool = True) -> tuple[Scene, ShaftShape]:
    """The scene placed (a STEP shaft's length and diameter as its import found them) and
    its checked solid, from the cache where it holds them; without `use_cache` the cache
    is neither read nor written (the BREP lives in a scratch folder for this process)."""
    from shaftfem.cad.solid import make_shape, needs_cad
    from shaftfem.cad.step import placed

    shaft, grooves = scene.shaft, scene.grooves
    if not needs_cad(shaft, grooves):
        return scene, make_shape(shaft, grooves, None)
    key = shape_key(shaft, grooves)
    folder = (cache_dir() if use_cache else scratch_dir()) / "shapes"
    brep, meta_file = folder / f"{key}.brep", folder / f"{key}.json"
    shape: ShaftShape | None = None
    if use_cache and (brep.exists() or meta_file.exists()):
        kept, why = _verified(brep, meta_file)
        if kept is not None:
            shape = _shape_of(brep, kept)
        else:
            discard(f"solid {key}", why, brep, meta_file)
    if shape is None:
        with atomic_path(brep) as tmp:
            shape = make_shape(shaft, grooves, tmp, where(scene.source, "shaft", "step_file"))
        shape = replace(shape, brep=brep)
        meta = _meta(shape)
        write_json(meta_file, {**meta, "brep_sha256": checksum(brep.read_bytes()),
                               "sha256": _meta_checksum(meta)})
    if shape.found is not None:
        scene = placed(scene, shape.found)
    return scene, shape


def _meta(shape: ShaftShape) -> dict:
    from shaftfem.cad.solid import META_KEYS

    return {**{k: getattr(shape, k) for k in META_KEYS},
            "found": shape.found.as_dict() if shape.found is not None else None}


def _shape_of(brep: Path, meta: dict) -> ShaftShape:
    from shaftfem.cad.solid import META_KEYS, ShaftShape
    from shaftfem.cad.step import StepImport

    found = StepImport.from_dict(meta["found"]) if meta["found"] is not None else None
    return ShaftShape(brep=brep, from_cache=True, found=found,
                      **{k: meta[k] for k in META_KEYS})


def _meta_checksum(meta: dict) -> str:
    return checksum(json.dumps(meta, sort_keys=True).encode())


def _verified(brep: Path, meta_file: Path) -> tuple[dict | None, str]:
    """The kept solid's metadata if the entry is whole and unaltered, else (None, why).

    The BREP's checksum is checked before anything reads it: OpenCASCADE can crash the
    whole process on a damaged BREP."""
    from shaftfem.cad.solid import META_KEYS

    try:
        stored = json.loads(meta_file.read_text())
        meta = {k: stored[k] for k in (*META_KEYS, "found")}
        if stored["sha256"] != _meta_checksum(meta):
            return None, "its metadata do not match their checksum"
        if stored["brep_sha256"] != checksum(brep.read_bytes()):
            return None, "the BREP file does not match its checksum"
    except (OSError, ValueError, KeyError, TypeError) as exc:
        return None, f"{type(exc).__name__}: {exc}"
    return meta, ""


def mesh_key(shape: ShaftShape, shaft: Shaft, grooves: Grooves | None,
             settings: MeshSettings, cuts: tuple[float, ...] = (),
             hubs: tuple[tuple[float, float], ...] = ()) -> str:
    """A hash of everything the mesh depends on: its sizes and the degree of its map,
    not the element order on it (orders 2 to 5 share a quadratic mesh, 3 to 5 a cubic
    one)."""
    from shaftfem.cad.mesh import MESH_VERSION
    from shaftfem.cad.mesher import (
        BORE_ELEMENTS,
        EDGE_GRADING,
        FACE_GRADING,
        HUB_SIZE,
        STEP_CURVATURE,
        WALL_ELEMENTS,
    )
    from shaftfem.cad.session import gmsh_version
    from shaftfem.cad.tetrahedra import KEPT_CURVING, KEPT_RATIO, MIN_JACOBIAN_RATIO

    geometry = {k: v for k, v in asdict(settings).items() if k != "geometry_order"}
    geometry["order"] = 1 if settings.order == 1 else settings.geometry_order
    payload = {
        "version": MESH_VERSION, "gmsh": gmsh_version(),
        "constants": [MIN_JACOBIAN_RATIO, EDGE_GRADING, FACE_GRADING, WALL_ELEMENTS,
                      BORE_ELEMENTS, STEP_CURVATURE],
        "folds": ["partly straightened, each on its own", list(KEPT_CURVING), KEPT_RATIO],
        **({"nodes": "parametric", "inside": "harmonic"} if geometry["order"] == 3 else {}),
        "shaft": asdict(shaft), "grooves": grooves_key(grooves),
        "settings": geometry, **({"cuts": list(cuts)} if cuts else {}),
        **({"hubs": [list(h) for h in hubs], "hub_size": HUB_SIZE} if hubs else {}),
    }
    return content_key(payload, files=() if shape.brep is None else (shape.brep,))


def mesh(shape: ShaftShape, shaft: Shaft, grooves: Grooves | None, settings: MeshSettings,
         use_cache: bool = True, cuts: tuple[float, ...] = (),
         hubs: tuple[tuple[float, float], ...] = ()) -> ShaftMesh:
    """The solid's checked mesh (cad.mesh.generate_mesh), from the cache where it holds
    it; without `use_cache` the cache is neither read nor written."""
    from shaftfem.cad.mesh import MESH_ARRAYS, generate_mesh, mesh_arrays, mesh_from_arrays

    key = mesh_key(shape, shaft, grooves, settings, cuts, hubs)
    path = cache_dir() / "meshes" / f"{key}.npz"
    if use_cache and path.exists():
        fields, why = load_arrays(path, MESH_ARRAYS)
        if fields is not None:  # the entry may be another element order's
            return replace(mesh_from_arrays(fields), order=settings.order)
        discard(f"mesh {key}", why, path)
    made = generate_mesh(shape, shaft, grooves, settings, cuts=cuts, hubs=hubs)
    if use_cache:
        save_arrays(path, mesh_arrays(made))
    return made
