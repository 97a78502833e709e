"""Sweep files: a base scene and the values of its keys to sweep, expanded into
variants and checked before any runs.

A sweep file (TOML) names a base scene and the values of any numeric scene keys:

    base = "paper2018"              # scene name in geometry/ or a path
    mesh_size_mm = 12               # optional: element size for every variant
    [axes]                          # full grid over these ("table.key" = values)
    "grooves.depth_mm" = [2.0, 3.0, 4.0]
    "shaft.length_mm" = {start = 500, stop = 600, num = 3}
    # or, instead of [axes], an explicit list:
    # points = [{"grooves.depth_mm" = 2.0, "shaft.length_mm" = 520}, ...]

Every variant's scene is checked when the file is loaded, and grids beyond
MAX_VARIANTS are refused there.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from pathlib import Path

from shaftfem.errors import SceneError
from shaftfem.scene.load import SceneText, check_entries, load_scene, read_scene_text, scene_beside
from shaftfem.scene.toml_reading import known_keys, number, parameter, read_toml
from shaftfem.store import content_key

# The largest sweep or calibration grid accepted: at 5-40 s a variant, 10,000 variants
# keep two workers busy for one to five days; a larger grid is a typo more often than
# a plan (three axes of 1000 values, or 20^5 calibration points).
MAX_VARIANTS = 10_000

@dataclass(frozen=True)
class Sweep:
    base: SceneText             # the base scene's content, read by the client
    mesh_size_mm: float | None
    variants: list[dict]        # each: {"table.key": value in file units}
    parameters: list[str]
    n_modes: int                # the lowest n_modes of every variant are recorded

    def key(self, estimate: bool) -> dict:
        """What defines every variant's result besides its own values."""
        from shaftfem import __version__

        return {"base": self.base.source, "base_content": content_key({"text": self.base.text}),
                "mesh_size_mm": self.mesh_size_mm, "n_modes": self.n_modes,
                "parameters": list(self.parameters), "estimate": estimate,
                "shaftfem": __version__}


def check_count(source: str, n: int, what: str) -> None:
    """Refuse a sweep or grid of more than MAX_VARIANTS variants, before it is built."""
    if n > MAX_VARIANTS:
        raise SceneError(f"{source}: {what} make {n:,} variants; at most {MAX_VARIANTS:,} "
                         "are run (split the sweep, or use fewer values)")


def check_variants(source: str, base: SceneText, variants: list[dict]) -> None:
    """Every variant's scene is valid (a seat past the shaft end, a negative depth): the
    first bad one is named with its values, before any variant runs."""
    for i, v in enumerate(variants):
        try:
            load_scene(base, overrides=v)
        except SceneError as exc:
            values = ", ".join(f"{k} = {x:g}" for k, x in v.items())
            raise SceneError(f"{source}: variant {i + 1} ({values}): {exc}") from exc


def _axis_values(source: str, name: str, spec) -> list[float]:
    where = f"axes.{name}"
    if isinstance(spec, list):
        if not spec:
            raise SceneError(f"{source}: {where} = []: give at least one value")
        return [number(source, where, v, -1e300, 1e300) for v in spec]
    if isinstance(spec, dict):
        known_keys(source, spec, {"start", "stop", "num"}, where)
        n = spec.get("num")
        if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 1000:
            raise SceneError(f"{source}: {where}.num = {n!r}: must be an integer in [1, 1000]")
        a = number(source, f"{where}.start", spec.get("start"), -1e300, 1e300)
        b = number(source, f"{where}.stop", spec.get("stop"), -1e300, 1e300)
        return [a + (b - a) * i / max(n - 1, 1) for i in range(n)]
    raise SceneError(f"{source}: {where} = {spec!r}: expected a list of numbers or "
                     "{start = ..., stop = ..., num = ...}")


def load_sweep(path: str | Path) -> Sweep:
    """Read a sweep file and expand it into variants (every entry checked for form; the
    values themselves are checked per variant, where a bad one is recorded as failed)."""
    path = Path(path)
    src = path.name
    data = known_keys(src, read_toml(path, "sweep file"), {"base", "mesh_size_mm", "axes", "points"})
    if not isinstance(data.get("base"), str):
        raise SceneError(f"{src}: base = {data.get('base')!r}: missing or not a scene name "
                         "or file (the scene the variants start from)")
    if ("axes" in data) == ("points" in data):
        raise SceneError(f"{src}: give either [axes] (a grid) or points (a list)")
    if "axes" in data:
        axes = data["axes"]
        if not isinstance(axes, dict) or not axes:
            raise SceneError(f"{src}: axes = {axes!r}: must be a table of at least one "
                             "parameter, e.g. \"shaft.length_mm\" = [500, 550]")
        names = [parameter(src, n) for n in axes]
        values = [_axis_values(src, n, axes[n]) for n in names]
        check_count(src, math.prod(len(v) for v in values), "the axes")
        variants = [dict(zip(names, combo)) for combo in itertools.product(*values)]
    else:
        points = data["points"]
        if not isinstance(points, list) or not points or not all(isinstance(p, dict) and p
                                                                 for p in points):
            raise SceneError(f"{src}: points = {points!r}: must be a list of at least one "
                             "table of parameters")
        check_count(src, len(points), "the points")
        variants = [{parameter(src, k): number(src, f"points[{i}].{k}", v, -1e300, 1e300)
                     for k, v in p.items()} for i, p in enumerate(points)]
        names = sorted({k for v in variants for k in v})
    base = read_scene_text(scene_beside(data["base"], path))
    check_entries(src, base, names)
    check_variants(src, base, variants)
    size = mesh_size(src, data.get("mesh_size_mm"), base)
    return Sweep(base=base, mesh_size_mm=size, variants=variants, parameters=names,
                 n_modes=load_scene(base).modes.count)


def mesh_size(src: str, size: object, base: SceneText) -> float | None:
    """A sweep or calibration file's mesh_size_mm, checked against its base scene (at most
    the shaft length, within the DOF budget) before any variant runs."""
    if size is None:
        return None
    size = number(src, "mesh_size_mm", size, 0, 20_000)
    from shaftfem.cad.mesh import check_budget
    from shaftfem.workflows.pipeline import with_mesh

    try:
        scene = with_mesh(load_scene(base), size)
        check_budget(scene.shaft, scene.grooves, scene.mesh, scene.max_dofs, scene.hubs())
    except SceneError as exc:
        raise SceneError(f"{src}: mesh_size_mm = {size:g} for the base scene: {exc}") from exc
    return size
