"""Damaged cache entries are detected before use, said in one line, and rebuilt.

A short grooved shaft (one half-pitch cell) keeps each rebuild to seconds. Every
kind of entry (the solid's BREP, its metadata, the mesh, the eigensolver's shift, the last
solve's shift and shapes) is truncated, emptied,
garbled and altered in value; the next run must warn and give the clean run's
frequencies.
"""

import json

import numpy as np
import pytest

from shaftfem.scene.load import load_scene
from shaftfem.store import CacheWarning
from shaftfem.workflows.pipeline import run_modes, with_mesh, with_modes


def _scene():
    s = load_scene("paper2018", overrides={"shaft.length_mm": 120.0,
                                           "grooves.grooved_length_mm": 40.0})
    return with_modes(with_mesh(s, 16.0), count=3)


def _truncate(p):
    p.write_bytes(p.read_bytes()[: len(p.read_bytes()) * 3 // 4])


def _empty(p):
    p.write_bytes(b"")


def _garble(p):
    b = bytearray(p.read_bytes())
    mid = len(b) // 2
    b[mid:mid + 64] = bytes(255 - x for x in b[mid:mid + 64])
    p.write_bytes(bytes(b))


def _alter(p):
    """A plausible, well-formed entry with one value changed (the checksum left as it was)."""
    if p.suffix == ".json":
        meta = json.loads(p.read_text())
        meta["volume"] *= 1.01
        p.write_text(json.dumps(meta))
    elif p.suffix == ".npz":
        with np.load(p) as z:
            fields = {k: z[k] for k in z.files}
        name = "points" if "points" in fields else "shift"
        fields[name] = fields[name] * 1.01
        with open(p, "wb") as fh:
            np.savez(fh, **fields)
    else:  # BREP text: one coordinate digit changed
        text = p.read_text()
        i = text.index("0.016")
        p.write_text(text[:i] + "0.017" + text[i + 5:])


@pytest.fixture(scope="module")
def clean(own_cache):
    """The module's own cache, which its tests damage, filled by a clean run."""
    return run_modes(_scene()).modes.frequencies


# every kind of entry and every kind of damage in the default run, each once; all twenty
# pairs in the slow one
QUICK = {("brep", _truncate), ("meta", _alter), ("mesh", _garble), ("shift", _empty),
         ("solve", _alter)}
DAMAGED = [pytest.param(entry, damage, id=f"{entry}-{damage.__name__}",
                        marks=() if (entry, damage) in QUICK else pytest.mark.slow)
           for entry in ("brep", "meta", "mesh", "shift", "solve")
           for damage in (_truncate, _empty, _garble, _alter)]


@pytest.mark.parametrize("entry,damage", DAMAGED)
def test_a_damaged_entry_is_rebuilt(clean, entry, damage):
    from shaftfem.store import cache_dir

    pattern = {"brep": "shapes/*.brep", "meta": "shapes/*.json", "mesh": "meshes/*.npz",
               "shift": "shifts/*.npz", "solve": "solves/*.npz"}[entry]
    (path,) = cache_dir().glob(pattern)  # the clean run's, or the last case's rebuild
    damage(path)
    if entry == "shift":  # read only where no solve on this mesh was kept
        for kept in cache_dir().glob("solves/*.npz"):
            kept.unlink()
    with pytest.warns(CacheWarning, match="damaged"):
        f = run_modes(_scene()).modes.frequencies
    assert np.max(np.abs(f / clean - 1)) < 1e-9
    # and the rebuilt entry is good: no warning the next time
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", CacheWarning)
        again = run_modes(_scene())
    assert again.mesh.from_cache and again.shape.from_cache


def test_a_bound_comes_back_from_the_cache_as_made_and_a_damaged_one_is_made_again(clean):
    """A warm run reads its mesh's bound back (keyed by the scene and the mesh's nodes):
    the same numbers as a bound made afresh; a damaged entry is said and made again."""
    from dataclasses import replace

    from shaftfem.runtime import RunOptions
    from shaftfem.store import cache_dir
    from shaftfem.workflows.bounded import estimate_errors

    result = run_modes(_scene())
    made = estimate_errors(result)
    (path,) = cache_dir().glob("bounds/*.npz")
    kept = estimate_errors(result)
    fresh = estimate_errors(result, replace(RunOptions(), use_cache=False))
    for name in ("relative_error", "recovery", "two_mesh", "reliable"):
        np.testing.assert_array_equal(getattr(kept, name), getattr(made, name))
        np.testing.assert_allclose(getattr(kept, name), getattr(fresh, name), rtol=1e-9)
    assert (kept.coarse_dofs, kept.method, kept.notes) == (fresh.coarse_dofs, fresh.method,
                                                           fresh.notes)
    _garble(path)
    with pytest.warns(CacheWarning, match="damaged"):
        again = estimate_errors(result)
    np.testing.assert_array_equal(again.relative_error, made.relative_error)
