"""The scene's parts asked for their coefficients: each journal, ball or roller bearing,
seal and stage as its physics gives them (shaftfem.parts), at the loads the static
solution puts on the journals that wait for theirs.

The scene holds the parts as declared; the rotor model is built on what they answer.
A part that answered once keeps its answer (`with_parts` is idempotent), and a case that
changes a part's declaration clears it to be asked again (workflows.cases). The journals
that wait for their load get it from the static solution (workflows.static.equipped).
"""

from __future__ import annotations

import functools
from dataclasses import replace
from typing import TYPE_CHECKING

from shaftfem.errors import SceneError
from shaftfem.scene.model import (
    Attachment,
    BearingCoefficients,
    JournalBearing,
    Rotor,
    Scene,
    Support,
)
from shaftfem.scene.toml_reading import entry, where

if TYPE_CHECKING:
    from shaftfem.aside import Aside


def _film_path(bearing: JournalBearing):
    """The film's L / D (rounded), cavitation and bore, and where its table is kept."""
    from dataclasses import asdict

    from shaftfem.parts import journal
    from shaftfem.store import cache_dir, content_key

    ratio, cavitation, bore = round(bearing.ratio, 9), bearing.cavitation, bearing.bore
    settings = journal.SETTINGS
    if bore is not None:
        from shaftfem.parts import pads

        settings = {**pads.SETTINGS, "bore": asdict(bore)}
    key = content_key({"ratio": ratio, "cavitation": cavitation, **settings})
    return ratio, cavitation, bore, cache_dir() / "films" / f"{key}.npz"


# film tables being solved beside the run (films_ahead), by their cache path
_AHEAD: dict[str, Aside] = {}


def films_ahead(bearings: list[JournalBearing]) -> list[str]:
    """Start solving beside the run (aside.Aside) the film tables of these journals that
    the cache lacks: a table hangs on the journal's L / D alone, not on the load the
    static solution is about to give it, and takes seconds. The paths started, for
    `film_table` to take them from and `films_dropped` to stop."""
    from shaftfem.aside import Aside

    started = []
    for b in bearings:
        ratio, cavitation, bore, path = _film_path(b)
        if not path.exists() and str(path) not in _AHEAD:
            _AHEAD[str(path)] = Aside(_solved_table, ratio, cavitation, bore)
            started.append(str(path))
    return started


def films_dropped(paths: list[str]) -> None:
    """Stop the film tables started by films_ahead that no journal took."""
    for p in paths:
        job = _AHEAD.pop(p, None)
        if job is not None:
            job.close()


def _solved_table(ratio: float, cavitation: str, bore=None):
    """A film's table solved: the plain bore's (parts.journal), or a bore of pads'
    (parts.pads)."""
    from shaftfem.parts import journal, pads

    if bore is not None:
        return pads.film_table(bore, ratio)
    return journal.table(ratio, cavitation)


def film_table(bearing: JournalBearing) -> None:
    """A journal film's table from the cache (keyed by its L / D, cavitation and the
    film's settings), else solved (or taken from beside the run, films_ahead) and kept
    there: every run of a scene needs it, and it takes seconds to solve."""
    import numpy as np

    from shaftfem.parts import journal
    from shaftfem.store import discard, load_arrays, save_arrays

    ratio, cavitation, bore, path = _film_path(bearing)
    names = journal.TABLE_FIELDS + journal.HEAT_FIELDS + (() if bore is None else ("thinnest",))
    if bore is not None and bore.kind == "tilting_pad":
        names += journal.PAD_FIELDS
    ahead = _AHEAD.pop(str(path), None)
    if ahead is None and path.exists():
        fields, why = load_arrays(path, names)
        if fields is not None:
            journal.remember(journal.FilmTable(ratio, cavitation, bore=bore, **fields))
            return
        discard("journal film table", why, path)
    t = _solved_table(ratio, cavitation, bore) if ahead is None else ahead.result()
    journal.remember(t)
    try:
        save_arrays(path, {n: np.asarray(getattr(t, n)) for n in names})
    except OSError:   # a cache that cannot be written costs time, not the result
        pass


@functools.lru_cache(maxsize=64)
def journal_coefficients(bearing: JournalBearing, rotor: Rotor) -> BearingCoefficients:
    """A loaded journal's coefficients against speed (parts.journal.coefficients), its
    film's table from the cache, tilting pads fed at a supply on their heated film
    (parts.pad_heat.heated_table); kept for the process: every study of a scene and each
    of its cases asks for the same journals."""
    from functools import partial

    from shaftfem.parts import heat, journal

    film_table(bearing)
    amend = None
    if bearing.bore is not None and bearing.bore.kind == "tilting_pad" \
            and bearing.oil_supply_temperature is not None:
        # fed tilting pads: their heated film on grown parts, exact at the operating
        # speeds
        amend = partial(_heated_table, at=tuple(rotor.speeds))
    return journal.coefficients(bearing, rotor, film=heat.at_speed, amend=amend)


def _heated_table(b: JournalBearing, t, at: tuple[float, ...]):
    """Fed tilting pads' speed table on their heated film (parts.pad_heat.heated_table)
    from the cache, keyed by the bearing, the table's speeds, its film table's and the
    heated film's settings; else solved and kept there: it solves the heated film some
    ten times, seconds each."""
    from dataclasses import asdict

    import numpy as np

    from shaftfem.parts import pad_heat
    from shaftfem.store import cache_dir, content_key, discard, load_arrays, save_arrays

    film = _film_path(b)[3]
    key = content_key({"bearing": asdict(b), "speeds": t.speeds.tolist(), "at": list(at),
                       "film": film.stem, **pad_heat.settings()})
    path = cache_dir() / "heated" / f"{key}.npz"
    names = ("K", "C", "pad_K", "pad_C")
    if path.exists():
        fields, why = load_arrays(path, names)
        if fields is not None:
            return replace(t, **fields)
        discard("heated film table", why, path)
    out = pad_heat.heated_table(b, t, at=at)
    try:
        save_arrays(path, {n: np.asarray(getattr(out, n)) for n in names})
    except OSError:   # a cache that cannot be written costs time, not the result
        pass
    return out


def _journal(scene: Scene, i: int, s: Support) -> Support:
    """A journal's support with its oil's viscosity (and its tolerance range's, from the
    oil temperatures), and its film's coefficients if its load is known."""
    from shaftfem.parts import journal, oil

    assert s.journal is not None and scene.rotor is not None   # scene.load checks both
    b = journal.with_oil(s.journal)
    t = s.tolerance
    if t is not None and t.temperature is not None and t.viscosity is None:
        assert b.oil_iso_vg is not None
        # cold oil is the most viscous: the viscosities run (min, nominal, max) as the
        # temperatures run (max, nominal, min)
        lo, nominal, hi = (oil.dynamic(b.oil_iso_vg, c) for c in t.temperature[::-1])
        t = replace(t, viscosity=(lo, nominal, hi))
    s = replace(s, journal=b, tolerance=t)
    if s.bearing is not None or b.load <= 0:   # its load: its reaction, once solved
        return s
    try:
        return replace(s, bearing=journal_coefficients(b, scene.rotor))
    except ValueError as e:
        raise SceneError(f"{where(scene.source, entry('support', i, s), 'load_n')} = "
                         f"{b.load:g}: {e}") from None


def support_coefficients(scene: Scene, i: int, s: Support) -> Support:
    """Support i of the scene with its part's coefficients (a support without a part, or
    whose part answered already, as it is)."""
    from shaftfem.parts import rolling, seal

    if s.journal is not None:
        return _journal(scene, i, s)
    if s.bearing is not None:
        return s
    if s.seal is not None:
        assert scene.rotor is not None   # scene.load checks it
        return replace(s, bearing=seal.coefficients(s.seal, scene.rotor.max_speed))
    if s.rolling is not None:
        return replace(s, bearing=rolling.coefficients(s.rolling))
    return s


def stage_coefficients(scene: Scene, a: Attachment) -> Attachment:
    """A part with its stage's cross-coupling (Wachel)."""
    from shaftfem.parts import wachel

    if a.stage is None or a.cross_coupling is not None:
        return a
    assert scene.rotor is not None   # scene.load checks it
    return replace(a, cross_coupling=wachel.coefficients(a.stage, scene.rotor))


def with_parts(scene: Scene) -> Scene:
    """The scene with every part's coefficients that need no static solution: bearings,
    seals and stages, and the journals given their load."""
    supports = tuple(support_coefficients(scene, i, s) for i, s in enumerate(scene.supports))
    attachments = tuple(stage_coefficients(scene, a) for a in scene.attachments)
    if supports == scene.supports and attachments == scene.attachments:
        return scene
    return replace(scene, supports=supports, attachments=attachments)
