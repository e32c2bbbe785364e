"""Posture continuity: clips chosen so that each starts where the previous one ended.

Every clip declares the posture of its first and last frame
(:data:`motiondb.types.POSTURES`: ``standing``, ``seated``, ``crouched``,
``kneeling``, ``lying``). Along one actor's sequence of whole-body motions a
clip should start in the posture the previous clip ends in: しゃがんで、立ち上がる
rises from the crouch (``crouch_down`` + ``stand_from_crouch``), not from a
chair that is not there; 転んで、起き上がる gets up from the floor (``fall`` +
``get_up``).

- :func:`choose` picks one clip per motion from the ranked candidates
  (the database's order) with the fewest posture mismatches along the
  sequence, a dynamic programme over the sequence; ties keep the database's
  ranking, earlier motions first.
- :func:`bridges` gives the clips to insert where no candidate can match
  (座って、歩く: ``stand_up`` between ``sit_down`` and ``walk``), found in the
  database by the verbs of :data:`BRIDGE_VERBS`.
- :func:`matching` finds a clip that keeps a posture (a seated idle for a
  wait after 座る), for fillers.

:func:`arrangement.arrange` applies them to a planned time table.

Nothing here reads frame data: postures are clip metadata
(:class:`clips.ClipMeta` ``start_posture``/``end_posture``), and the clips come
from the database through a :class:`clips.ClipSource`.
"""
from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import Any, overload

from .clips import C, ClipMeta, ClipSource
from .seated import KEPT, plays_in

#: Verbs whose clips take the actor *into* each posture, tried in this order to build bridges.
#: Only clips that change posture (start elsewhere, end there), whole-body and not looping, are used.
#: Its keys are the postures a clip starts and ends in (``motiondb.types.POSTURES``, in that order).
BRIDGE_VERBS: dict[str, tuple[str, ...]] = {
    "standing": ("立ち上がる", "起き上がる", "立つ"),
    "seated": ("座る", "腰掛ける"),
    "crouched": ("しゃがみ込む", "しゃがむ"),
    "kneeling": ("ひざまずく", "膝をつく"),
    "lying": ("横になる", "寝転ぶ", "寝る"),
}
POSTURES = tuple(BRIDGE_VERBS)
LYING = "lying"
#: At most this many clips are inserted between two motions (seated -> crouched takes two:
#: stand up, crouch down).
MAX_BRIDGE = 2


# ------------------------------------------------------------------- choose
def _mismatch(prev_end: str | None, start: str) -> int:
    return 0 if prev_end is None or prev_end == start else 1


def _step(before: str | None, clip: ClipMeta) -> tuple[int, str | None]:
    """``(mismatch, posture after)`` of playing ``clip`` in the posture ``before``: a standing action
    that can be played seated or kneeling (:func:`seated.plays_in`) keeps that posture and meets it. An
    action done lying (``read_lying``) needs the actor lying already: in an unknown posture it is a
    mismatch (本を読んで、立ち上がった reads seated and stands up, not on the floor and gets up)."""
    if before in KEPT and clip.start_posture != before and plays_in(clip, before):
        return 0, before
    if before is None and clip.start_posture == clip.end_posture == LYING:
        return 1, LYING
    return _mismatch(before, clip.start_posture), clip.end_posture


@overload
def choose(candidates_by_motion: Mapping[Any, Sequence[C]], *,
           initial: str | None = None) -> dict[Any, C | None]: ...


@overload
def choose(candidates_by_motion: Sequence[Sequence[C]], *,
           initial: str | None = None) -> list[C | None]: ...


def choose(candidates_by_motion: Sequence[Sequence[C]] | Mapping[Any, Sequence[C]], *,
           initial: str | None = None) -> list[C | None] | dict[Any, C | None]:
    """One clip per motion of a sequence, so that postures meet where the candidates allow it.

    Args:
        candidates_by_motion: for each motion of one actor's sequence, in
            playing order, its candidate clips best first (``db.search``'s
            ranking); a list of lists, or a mapping (motion id -> list) in
            playing order.
        initial: the posture the actor is in before the first motion;
            ``None`` (default) lets the first clip start in any posture.

    Returns:
        The chosen clip per motion, in the same shape (a list, or a dict with
        the same keys); ``None`` for a motion without candidates, which the
        posture chain passes through (the next clip is matched to the one before).

    The choice minimises, in this order: the number of joins where a clip
    starts in another posture than the actor is in (the previous clip's end, or
    ``initial`` for the first; a standing action played seated or kneeling keeps
    the actor there, as :mod:`seated` plays it: 膝をついて、祈って、立ち上がる rises
    from the knee), then the candidates' ranks, the first motion's rank first (so
    with no mismatch to avoid, every motion gets its best candidate). A dynamic
    programme over the sequence and the posture the actor is in: O(n k p) for n
    motions of k candidates and p postures.
    """
    keys = list(candidates_by_motion) if isinstance(candidates_by_motion, Mapping) else None
    lists = [list(candidates_by_motion[k]) for k in keys] if keys is not None else \
        [list(c) for c in candidates_by_motion]
    if initial is not None and initial not in POSTURES:
        raise ValueError(f"unknown posture {initial!r}; known: {', '.join(POSTURES)}")
    present = [i for i, c in enumerate(lists) if c]
    picks: list[C | None] = [None] * len(lists)
    if present:
        # best[posture] = (mismatches, ranks so far) of the best path that leaves the actor in that
        # posture after the current motion; tuples compare as the docstring says (fewer mismatches,
        # then earlier ranks)
        best: dict[str | None, tuple[int, tuple[int, ...]]] = {initial: (0, ())}
        for i in present:
            nxt: dict[str | None, tuple[int, tuple[int, ...]]] = {}
            for before, (m, ranks) in best.items():
                for k, c in enumerate(lists[i]):
                    cost, after = _step(before, c)
                    cand = (m + cost, ranks + (k,))
                    if after not in nxt or cand < nxt[after]:
                        nxt[after] = cand
            best = nxt
        _, path = min(best.values())
        for i, k in zip(present, path):
            picks[i] = lists[i][k]
    if keys is not None:
        return dict(zip(keys, picks))
    return picks


def mismatches(clips: Sequence[ClipMeta | None], *, initial: str | None = None) -> list[int]:
    """Indices ``i`` where ``clips[i]`` starts in another posture than the actor is in: the clip before
    ends in, or keeps (a standing action played seated or kneeling); ``None`` entries are passed
    through; ``initial`` is the posture before the first."""
    out = []
    before: str | None = initial
    for i, c in enumerate(clips):
        if c is None:
            continue
        cost, before = _step(before, c)
        if cost:
            out.append(i)
    return out


# ------------------------------------------------------------------ bridges
def _changers(source: ClipSource[C], character: str | None) -> list[C]:
    """Every posture-changing clip found by :data:`BRIDGE_VERBS`, in preference order."""
    out: list[C] = []
    seen: set[str] = set()
    for target, verbs in BRIDGE_VERBS.items():
        for verb in verbs:
            for c in source.by_verb(verb, prefer_character=character):
                if (c.name not in seen and c.body_part is None and not c.cyclic
                        and c.end_posture == target and c.start_posture != target):
                    seen.add(c.name)
                    out.append(c)
    return out


def bridges(prev_end_posture: str, next_start_posture: str, source: ClipSource[C], *,
            character: str | None = None, max_clips: int = MAX_BRIDGE) -> list[C]:
    """The clips to play between a clip ending in ``prev_end_posture`` and one starting in ``next_start_posture``.

    The clips come from ``source`` (the motion database): those found by
    the verbs of :data:`BRIDGE_VERBS` that change posture (whole-body, not
    looping, ``start_posture != end_posture``), ``character``'s first. The
    shortest chain (at most ``max_clips``) from one posture to the other wins;
    among equally short ones, the verbs' order in :data:`BRIDGE_VERBS` and then
    the database's ranking. With the built-in library: seated -> standing
    ``[stand_up]``, crouched -> standing ``[stand_from_crouch]``, lying ->
    standing ``[get_up]``, standing -> seated ``[sit_down]``, standing ->
    crouched ``[crouch_down]``, seated -> crouched ``[stand_up, crouch_down]``.

    Returns ``[]`` when the postures are the same, and when the database has
    no chain between them (standing -> lying: no clip lies down on purpose);
    the caller then joins the clips as before.
    """
    for p in (prev_end_posture, next_start_posture):
        if p not in POSTURES:
            raise ValueError(f"unknown posture {p!r}; known: {', '.join(POSTURES)}")
    if prev_end_posture == next_start_posture:
        return []
    edges = _changers(source, character)
    for n in range(1, max_clips + 1):
        # chains of n clips, in the order of the edges (itertools.product is lexicographic)
        for path in itertools.product(edges, repeat=n):
            if path[0].start_posture != prev_end_posture or path[-1].end_posture != next_start_posture:
                continue
            if all(a.end_posture == b.start_posture for a, b in zip(path, path[1:])):
                return list(path)
    return []


def matching(source: ClipSource[C], verb: str, posture: str, *, character: str | None = None) -> C | None:
    """The best clip of ``verb`` that starts and ends in ``posture``, or ``None`` (also for an unknown verb).

    For fillers that must not change the posture: the idle clip (待つ) after a
    clip that ends seated is a seated idle if the database has one, else
    nothing (the actor holds its last pose).
    """
    if posture not in POSTURES:
        raise ValueError(f"unknown posture {posture!r}; known: {', '.join(POSTURES)}")
    hits = source.by_verb(verb, prefer_character=character, prefer_start_posture=posture)
    return next((c for c in hits if c.start_posture == posture and c.end_posture == posture), None)


__all__ = ["BRIDGE_VERBS", "MAX_BRIDGE", "POSTURES", "bridges", "choose", "matching", "mismatches"]
