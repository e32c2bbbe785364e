"""From the analysis of a text and the retrieved clips to the motion time table.

Start times follow paper 003 §3.3 as docs/language.md §3 extends it:

- connection: the next motion starts when the previous one has finished, plus any delay;
- transition: it starts at the previous motion's foot-moving interval after
  its core (for a looping clip: its last whole step), and the previous motion
  ends when that step ends, so the two overlap over one step;
- composition: the partial motion is laid onto the whole-body one (the base
  is chosen by the clips' body-part declarations, not by word order) and
  starts with it; the synthesis stage refines the switch times (eq. (1)).
  たまま: the base plays to its end and is held there while the other plays;
- across actors a link only fixes the start: serial with overlap starts at the
  end of the first motion's core, serial without overlap at its end (plus
  delay), parallel at its start.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

from text2anim.core.methods import Method
from text2anim.nlp.lexicon import STEPPING_VERBS
from text2anim.nlp.types import Analysis, Constraint, MotionSpec

from .errors import ScheduleError
from .lengths import played_length, transition_window
from .manner import manner_of, played_spec
from .together import together
from .types import ClipTiming, Element, TimeTable

#: Finds the clip for a motion: ``(motion, preferred character) -> ClipTiming``.
ClipFinder = Callable[[MotionSpec, "str | None"], ClipTiming]


@dataclass
class _Row:
    """A time-table element while it is being placed."""

    spec: MotionSpec
    clip: ClipTiming
    method: Method
    prev: int | None
    start: float
    end: float
    body_part: str | None = None
    delay: float | None = None
    repeat: int | None = None  # set by a rule (a short base repeated under a composition), else the text's

    @property
    def partial(self) -> bool:
        return self.body_part is not None or self.clip.body_part is not None

    def freeze(self) -> Element:
        s = self.spec
        return Element(s.id, s.actor, s.verb, self.clip.name, self.method, self.prev, self.start, self.end,
                       self.body_part, s.speed, self.repeats, s.hold, self.delay, s.object, s.target, s.target_role,
                       s.target_side, manner_of(s, self.clip))

    @property
    def repeats(self) -> int:
        return self.spec.repeat if self.repeat is None else self.repeat


_UNSIDED = {"arm": ("right_arm", "left_arm", "both_arms"), "leg": ("right_leg", "left_leg")}


def _resolve_part(asked: str | None, declared: str | None) -> str:
    """The part a composition takes: what the text asked for, sided by the clip when the text
    gave no side (手を振る → the clip's right_arm); a whole-body clip gives its upper body."""
    if asked in _UNSIDED:
        return declared if declared in _UNSIDED[asked] else _UNSIDED[asked][0]
    return asked or declared or "upper"


def _order(analysis: Analysis) -> list[tuple[MotionSpec, Constraint | None]]:
    """Motions in an order where every constraint's first comes before its second."""
    incoming: dict[int, Constraint] = {}
    for c in analysis.constraints:
        if c.second in incoming:
            raise ScheduleError(f"motion {c.second} is linked to two earlier motions")
        incoming[c.second] = c
    by_id = {m.id: m for m in analysis.motions}
    # per motion id (None: the roots), its successors: the constraint leading to each, or a root's id
    children: dict[int | None, list[Constraint | int]] = {}
    for m in analysis.motions:
        link = incoming.get(m.id)
        children.setdefault(link.first if link else None, []).append(link if link else m.id)
    out: list[tuple[MotionSpec, Constraint | None]] = []
    # Compositions first among siblings, so a base's length is final before a successor is placed.
    key = lambda x: (0, x.second) if isinstance(x, Constraint) and x.method == "composition" else (1, x if isinstance(x, int) else x.second)  # noqa: E731
    stack = sorted(children.get(None, []), key=key, reverse=True)
    while stack:
        item = stack.pop()
        mid = item if isinstance(item, int) else item.second
        out.append((by_id[mid], None if isinstance(item, int) else item))
        stack.extend(sorted(children.get(mid, []), key=key, reverse=True))
    if len(out) != len(analysis.motions):
        raise ScheduleError("the temporal links of this text form a cycle")
    return out


def _cover(base: _Row, end: float) -> None:
    """A short whole-body base repeats to cover a composition that lasts until ``end`` (s):
    ジャンプしながら手を叩く jumps for as long as the clapping lasts, not once then standing.

    Only a base that neither loops nor is partial, whose text gave no count or duration
    (3回, 5秒); the repetitions are the nearest whole number, at least 2 (the base then
    holds its last pose for any rest).
    """
    s = base.spec
    if base.clip.cyclic or base.partial or s.repeat != 1 or s.duration is not None or base.repeat is not None:
        return
    once = base.clip.duration / s.speed
    n = round((end - base.start) / once) if once > 0 else 1
    if n >= 2:
        base.repeat = n
        base.end = base.start + n * once


class _Planner:
    def __init__(self, find: ClipFinder, together: dict[int, tuple[int, ...]]):
        self.find = find
        self.together = together
        self.rows: dict[int, _Row] = {}
        self.last: dict[str | None, int] = {}  # last whole-body element per actor
        self.lengths: dict[int, float] = {}  # each motion's played length as placed (s)

    def place(self, spec: MotionSpec, link: Constraint | None) -> None:
        prev_id = self.last.get(spec.actor)
        prefer = self.rows[prev_id].clip.character if prev_id is not None else None
        clip = self.find(spec, prefer)
        spec = played_spec(spec, clip)  # a style's tempo (scheduler.manner)
        mate = next((m for m in self.together.get(spec.id, ()) if m in self.lengths), None)
        # co-actors of one motion play it for the same time (together.py): the first placed sets it
        duration = self.lengths[mate] if mate is not None and spec.duration is None else spec.duration
        length = played_length(clip, spec.speed, spec.repeat, duration,
                              steps=spec.repeat > 1 and spec.verb in STEPPING_VERBS)
        self.lengths[spec.id] = length
        first = self.rows.get(link.first) if link else None
        if link is None or first is None:
            self._sequence(spec, clip, length, "connection", start=None, delay=None)
        elif first.spec.actor != spec.actor:
            self._cross_actor(spec, clip, length, link, first)
        elif link.method == "composition":
            self._compose(spec, clip, length, first)
        elif link.method == "transition":
            self._transition(spec, clip, length, first)
        else:
            self._sequence(spec, clip, length, "connection", start=None, delay=link.delay)

    # -- whole-body sequence on one actor's track --------------------------------------------
    def _sequence(self, spec: MotionSpec, clip: ClipTiming, length: float, method: Method, start: float | None,
                  delay: float | None) -> None:
        prev_id = self.last.get(spec.actor)
        if prev_id is None:
            t0 = start if start is not None else (spec.delay or 0.0)  # 3秒後に歩く: held back
            row = _Row(spec, clip, "initial", None, t0, t0 + length)
        else:
            prev = self.rows[prev_id]
            t0 = prev.end + (delay or 0.0)
            if start is not None:
                t0 = max(t0, start)
            row = _Row(spec, clip, method, prev_id, t0, t0 + length, delay=delay)
        self.rows[spec.id] = row
        self.last[spec.actor] = spec.id

    def _transition(self, spec, clip, length, first: _Row):
        if self.last.get(spec.actor) != first.spec.id:
            self._sequence(spec, clip, length, "connection", None, None)
            return
        window = transition_window(first.clip, first.spec.speed, first.repeats, first.end - first.start)
        if window is None:  # no step after the core: join at the end, as a connection at the footstep
            self._sequence(spec, clip, length, "transition", None, None)
            return
        t0 = first.start + window[0]
        first.end = first.start + window[1]
        self.rows[spec.id] = _Row(spec, clip, "transition", first.spec.id, t0, t0 + length)
        self.last[spec.actor] = spec.id

    # -- composition ---------------------------------------------------------------------------
    def _compose(self, spec, clip, length, first: _Row):
        row = _Row(spec, clip, "composition", None, 0.0, length, body_part=spec.body_part)
        swap = (first.partial and not row.partial) or (
            not first.partial and not row.partial and row.clip.cyclic and not first.clip.cyclic)
        if first.spec.hold:  # たまま: the first motion is the base, held at its end pose
            base, top = first, row
            top.start = base.end
        elif swap:  # the whole-body (or looping) motion is the base, whatever the word order
            base, top = self._swap_base(first, row)
        else:
            base, top = first, row
            top.start = base.start
        if top is row:
            top.end = top.start + length
        top.method, top.prev = "composition", base.spec.id
        top.body_part = _resolve_part(top.body_part, top.clip.body_part)
        if not base.spec.hold:
            _cover(base, top.end)
        base.end = max(base.end, top.end)
        self.rows[spec.id] = row

    def _swap_base(self, first: _Row, row: _Row) -> tuple[_Row, _Row]:
        """``row`` (whole-body) takes ``first``'s place in the sequence; ``first`` is laid onto it."""
        length = row.end - row.start
        row.method, row.prev, row.start = first.method, first.prev, first.start
        row.end = row.start + length
        row.delay = first.delay
        if self.last.get(first.spec.actor) == first.spec.id:
            self.last[first.spec.actor] = row.spec.id
        span = first.end - first.start
        first.start, first.end = row.start, row.start + span
        return row, first

    # -- across actors -------------------------------------------------------------------------
    def _cross_actor(self, spec, clip, length, link: Constraint, first: _Row):
        if link.relation == "parallel":
            # a delay (either way: a partner's instant of contact met, scene.timing) moves it off the first's start
            t0 = max(0.0, first.start + (link.delay or 0.0))
        elif link.overlap:
            t0 = first.start + first.clip.core[1] / first.spec.speed
        else:
            t0 = first.end + (link.delay or 0.0)
        self._sequence(spec, clip, length, "connection", start=t0, delay=None)


def plan(analysis: Analysis, find: ClipFinder, fps: float = 30.0) -> TimeTable:
    """The motion time table of ``analysis``, clips found with ``find``."""
    planner = _Planner(find, together(analysis))
    for spec, link in _order(analysis):
        planner.place(spec, link)
    elements = tuple(sorted((r.freeze() for r in planner.rows.values()), key=lambda e: e.id))
    return TimeTable(analysis.text, fps, elements)


def without(analysis: Analysis, drop: set[int]) -> Analysis:
    """``analysis`` with the motions ``drop`` removed and their links bridged.

    A motion whose link came from a dropped one is linked to that one's own
    predecessor instead (with its own method), so the rest still plays in order.
    """
    if not drop:
        return analysis
    incoming = {c.second: c for c in analysis.constraints}
    kept = []
    for c in analysis.constraints:
        if c.second in drop:
            continue
        first = c.first
        while first in drop and first in incoming:
            first = incoming[first].first
        if first in drop:
            continue
        kept.append(replace(c, first=first))
    motions = tuple(m for m in analysis.motions if m.id not in drop)
    return replace(analysis, motions=motions, constraints=tuple(kept))
