"""Edits of a time table kept as constraints on the text's analysis (the studio's timeline).

An edit names a motion by its verb and which occurrence of that verb it is (``歩く`` #0 is the first
walk of the text), not by id: after the text is edited, an edit applies to the motion that is still
there, and one whose motion is gone is dropped. What an edit can say (docs/language.md §2-§3):

- ``shift`` (s): added to the delay of the constraint that starts the motion (a bar dragged later or
  earlier; never below no delay, except on a parallel link to another actor's motion, which may start it
  before that one), or to the opening delay of an actor's first motion; a transition moved later no
  longer flows out of the motion before it: it becomes a connection after that delay;
- ``duration`` (s): how long it plays (a bar's end dragged), as 3秒間 says;
- ``method``: how it joins the motion before it: ``connection`` (after it ends), ``transition``
  (flowing out of its last step) or ``composition`` (at the same time).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from text2anim.core.notice import Notice
from text2anim.nlp.types import Analysis, Constraint, MotionSpec

METHODS = {"connection": ("serial", False), "transition": ("serial", True), "composition": ("parallel", None)}
#: Longest duration or shift an edit may ask for (s): the output's own budget bounds the rest.
MAX_SECONDS = 60.0


class EditError(ValueError):
    """An edit that cannot be applied (a bad value); the message says which and why, ``notice`` the same for a
    front end to word (:class:`core.notice.Notice`, kinds ``edit_method``, ``edit_shift``, ``edit_duration``,
    ``edit_nth`` and ``edit_bad``)."""

    user_facing = True

    def __init__(self, notice: Notice):
        self.notice = notice
        super().__init__(notice)


@dataclass(frozen=True)
class Edit:
    """``verb``'s ``nth`` occurrence in the text (0-based): shifted, given a duration or another join method."""

    verb: str
    nth: int = 0
    shift: float = 0.0
    duration: float | None = None
    method: str | None = None

    def __post_init__(self):
        if self.method is not None and self.method not in METHODS:
            raise EditError(Notice.of("edit_method", f"unknown join method {self.method!r}; known: {', '.join(METHODS)}",
                                      verb=self.verb, method=str(self.method)))
        if not abs(self.shift) <= MAX_SECONDS:
            raise EditError(Notice.of("edit_shift", f"a shift of {self.shift} s is out of range (at most "
                                      f"{MAX_SECONDS:g} s either way)", verb=self.verb, s=self.shift, max=MAX_SECONDS))
        if self.duration is not None and not 0.1 <= self.duration <= MAX_SECONDS:
            raise EditError(Notice.of("edit_duration", f"a duration of {self.duration} s is out of range (0.1 to "
                                      f"{MAX_SECONDS:g} s)", verb=self.verb, s=self.duration, min=0.1, max=MAX_SECONDS))
        if self.nth < 0:
            raise EditError(Notice.of("edit_nth", "nth counts occurrences from 0", verb=self.verb, nth=self.nth))

    @classmethod
    def from_dict(cls, d: dict) -> "Edit":
        try:
            return cls(str(d["verb"]), int(d.get("nth", 0)), float(d.get("shift", 0.0)),
                       None if d.get("duration") is None else float(d["duration"]), d.get("method"))
        except (KeyError, TypeError, ValueError) as exc:
            if isinstance(exc, EditError):
                raise
            raise EditError(Notice.of("edit_bad", f"an edit needs a verb and numbers: {d!r}")) from None


def occurrences(analysis: Analysis) -> dict[tuple[str, int], int]:
    """``(verb, nth) -> motion id`` of every motion of ``analysis``, in text order."""
    seen: dict[str, int] = {}
    out = {}
    for m in analysis.motions:
        k = seen.get(m.verb, 0)
        out[(m.verb, k)] = m.id
        seen[m.verb] = k + 1
    return out


def _actor(analysis: Analysis, motion_id: int) -> str | None:
    return next((m.actor for m in analysis.motions if m.id == motion_id), None)


def apply_edits(analysis: Analysis, edits) -> Analysis:
    """``analysis`` with ``edits`` (:class:`Edit`) applied; an edit whose motion is gone is dropped."""
    if not edits:
        return analysis
    ids = occurrences(analysis)
    by_id = {ids[(e.verb, e.nth)]: e for e in edits if (e.verb, e.nth) in ids}
    motions: list[MotionSpec] = []
    for m in analysis.motions:
        e = by_id.get(m.id)
        if e is not None and e.duration is not None:
            m = replace(m, duration=e.duration)
        motions.append(m)
    starts = {c.second for c in analysis.constraints}
    constraints: list[Constraint] = []
    for c in analysis.constraints:
        e = by_id.get(c.second)
        if e is not None:
            if e.method is not None:
                relation, overlap = METHODS[e.method]
                c = replace(c, relation=relation, overlap=overlap, method=e.method)
            if e.shift and c.relation == "parallel" and _actor(analysis, c.first) != _actor(analysis, c.second):
                c = replace(c, delay=round((c.delay or 0.0) + e.shift, 6) or None)  # either way off the other's start
            elif e.shift:
                if e.shift > 0 and c.method == "transition":
                    c = replace(c, relation="serial", overlap=False, method="connection")
                c = replace(c, delay=max(0.0, (c.delay or 0.0) + e.shift) or None)
        constraints.append(c)
    for i, m in enumerate(motions):  # an actor's first motion: its opening delay
        e = by_id.get(m.id)
        if e is not None and e.shift and m.id not in starts:
            motions[i] = replace(m, delay=max(0.0, (m.delay or 0.0) + e.shift) or None)
    return replace(analysis, motions=tuple(motions), constraints=tuple(constraints))
