"""The rows the time table gets in its waits: stops, idles and held poses.

A wait longer than :data:`IDLE_GAP` seconds is filled rather than frozen:

- an actor who comes in later idles (in the posture its first clip starts in) from 0 s;
- before a connection that waits, a looping motion (walk, run) first comes to a stop
  (:data:`STOP_VERB`, joined by ``transition``), then the idle clip (:data:`IDLE_VERB`)
  plays until the next motion; so after 走る。3秒後に歩く the runner stops and stands,
  breathing, before walking; a wait (待つ, or the scene's waiting person) plays on instead;
- an actor who finishes before the last one stops and idles to the end, or, when no idle
  keeps its posture (seated, lying), holds its last pose: that element's ``end`` moves
  to the end.

The idle of a posture other than standing is a clip of :data:`IDLE_VERB` that starts
and ends in it (:func:`postures.matching`); none: the actor holds still.
Actors idling side by side are not clones: the ``k``-th actor takes the ``k``-th
variant of the standing idle (:func:`variants.nth`: another clip of 待つ,
else the mirror image), listed in ``Filled.mirrored`` when mirrored.
The added elements are rows of the time table like the text's own (ids above
them), so ``text2anim plan`` shows what will play. Only clip metadata is read.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Generic

from text2anim.core.methods import Method

from .clips import C, ClipSource, played_duration
from .postures import matching
from .types import Element, TimeTable
from .variants import nth

#: Seconds of waiting above which a wait is filled.
IDLE_GAP = 0.5
IDLE_VERB = "待つ"
STOP_VERB = "止まる"


@dataclass(frozen=True)
class Filled(Generic[C]):
    """A time table with its waits filled: ``clips`` covers every element, ``fillers`` are the added ids."""

    table: TimeTable
    clips: dict[int, C]
    fillers: tuple[int, ...]
    mirrored: frozenset[int] = frozenset()


class _Finder(Generic[C]):
    """The stop and idle clips of the database, by posture and character."""

    def __init__(self, source: ClipSource[C]):
        self.source = source
        self.variant = 0  # the actor's index: which variant of the standing idle it plays

    def by_verb(self, verb: str, character: str | None) -> C | None:
        hits = self.source.by_verb(verb, prefer_character=character)
        return hits[0] if hits else None

    def idle(self, posture: str, character: str | None) -> tuple[C | None, bool]:
        """The idle clip for ``posture`` (a seated one after 座る), or None: the actor holds still;
        and whether it plays mirrored (the current actor's variant of the standing idle)."""
        if posture == "standing":
            hits = self.source.by_verb(IDLE_VERB, prefer_character=character)
            if not hits:
                return None, False
            pick = nth(hits, self.variant)
            return pick.clip, pick.mirrored
        return matching(self.source, IDLE_VERB, posture, character=character), False


class _Adder(Generic[C]):
    """Collects the added elements and their clips, numbering them from ``next_id``."""

    def __init__(self, next_id: int):
        self.next_id = next_id
        self.clips: dict[int, C] = {}
        self.mirrored: set[int] = set()

    def add(self, actor: str | None, verb: str, info: C, method: Method, prev: int | None,
            start: float, end: float, mirrored: bool = False) -> Element:
        e = Element(self.next_id, actor, verb, info.name, method, prev, start, end)
        self.clips[e.id] = info
        if mirrored:
            self.mirrored.add(e.id)
        self.next_id += 1
        return e


def _fill_gap(find: _Finder[C], add: _Adder[C], prev: Element, prev_info: C, start: float, end: float,
              character: str | None, fps: float) -> list[Element]:
    """Elements that fill ``[start, end)`` s after ``prev``: a stop for a looping motion, then idling."""
    out: list[Element] = []
    stop = find.by_verb(STOP_VERB, character) if prev_info.cyclic else None
    if stop is not None:
        t1 = min(end, start + played_duration(stop, fps))
        if end - t1 <= IDLE_GAP:
            t1 = end
        out.append(add.add(prev.actor, STOP_VERB, stop, "transition", prev.id, start, t1))
        start = t1
    idle, mirrored = find.idle(prev_info.end_posture, character) if end - start > IDLE_GAP else (None, False)
    if idle is not None:
        out.append(add.add(prev.actor, IDLE_VERB, idle, "connection", out[-1].id if out else prev.id, start, end,
                           mirrored))
    return out


def _idles(e: Element, info: C) -> bool:
    """Is ``e`` a wait playing a looping idle (a person waiting, the scene's own): it plays on into a wait
    after it, with nothing to stop (a walk comes to a stop first) and no second idle joined to it."""
    return e.verb == IDLE_VERB and info.cyclic


def _walks_to_stop(find: _Finder[C], before: C, info: C) -> bool:
    """Does a looping motion (walk, run) go on until the stop that comes next (兄が止まると、彼も止まった:
    he walks until then, rather than stopping, standing and stopping again)?"""
    if not before.cyclic:
        return False
    stop = find.by_verb(STOP_VERB, info.character)
    return stop is not None and stop.name == info.name


def _actor_track(find: _Finder[C], add: _Adder[C], mine: list[Element], clips: dict[int, C],
                 fps: float) -> list[Element]:
    """One actor's elements in playing order with a late start's idle and the connections' waits filled."""
    track: list[Element] = []
    for e in mine:
        info = clips[e.id]
        prev, method = e.prev, e.method
        idle, mirrored = find.idle(info.start_posture, info.character) \
            if method == "initial" and e.start > IDLE_GAP else (None, False)
        if idle is not None:  # an actor who comes in later stands idle until then
            first = add.add(e.actor, IDLE_VERB, idle, "initial", None, 0.0, e.start, mirrored)
            track.append(first)
            prev, method = first.id, "connection"
        before = next((x for x in track if x.id == e.prev), None) if e.method == "connection" else None
        if before is not None and e.start - before.end > IDLE_GAP:
            before_info = clips.get(before.id) or add.clips[before.id]
            if _idles(before, before_info) or _walks_to_stop(find, before_info, info):
                track[track.index(before)] = replace(before, end=e.start)  # its loop plays longer
            else:
                fill = _fill_gap(find, add, before, before_info, before.end, e.start, info.character, fps)
                track.extend(fill)
                if fill:
                    prev = fill[-1].id
        track.append(replace(e, method=method, prev=prev))
    return track


def fill_waits(table: TimeTable, clips: dict[int, C], source: ClipSource[C], fps: float) -> Filled[C]:
    """The time table with its waits filled (see the module docstring); ``clips``: element id -> clip."""
    find: _Finder[C] = _Finder(source)
    add: _Adder[C] = _Adder(max(e.id for e in table.elements) + 1)
    tracks = []
    for k, actor in enumerate(table.actors()):
        # In playing order (前に puts a later id first); a composition after its base.
        mine = sorted((e for e in table.elements if e.actor == actor),
                      key=lambda e: (e.start, e.method == "composition", e.id))
        find.variant = k
        tracks.append(_actor_track(find, add, mine, clips, fps))
    # Actors who finish early stop and stand idle until the last one is done.
    end = max(e.end for e in table.elements)
    elements: list[Element] = []
    for k, track in enumerate(tracks):
        find.variant = k
        last = max((x for x in track if x.method != "composition"), key=lambda x: x.end)
        if end - last.end > IDLE_GAP:
            character = clips[last.id].character if last.id in clips else None
            last_info = clips.get(last.id) or add.clips[last.id]
            fill = [] if _idles(last, last_info) else _fill_gap(find, add, last, last_info, last.end, end,
                                                                 character, fps)
            if not fill and (not last_info.cyclic or _idles(last, last_info)):
                track[track.index(last)] = replace(last, end=end)  # hold the last pose (no idle keeps a seated
                # or lying posture), or wait on
            track.extend(fill)
        elements.extend(track)
    filled = TimeTable(table.text, table.fps, tuple(sorted(elements, key=lambda e: e.id)))
    return Filled(filled, {**clips, **add.clips}, tuple(sorted(add.clips)), frozenset(add.mirrored))
