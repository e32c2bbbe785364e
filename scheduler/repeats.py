"""Each actor's rows as they play: a repeated row unrolled into one row per repetition.

A motion repeated ``n`` times whose clip does not loop (3回ジャンプする) is one row of
the time table (``repeat = n``) but ``n`` clips on the track, each its own variant
(:attr:`schedule.Schedule.repeats`): equal parts of the row's span, each joined to
the one before; a later row joined to the repeated one is joined to its last repetition.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Generic

from .clips import C
from .schedule import Schedule
from .types import Element
from .variants import Pick


@dataclass(frozen=True)
class Played(Generic[C]):
    """One clip on an actor's track: ``row`` (a table row, or one repetition of one) plays ``clip``."""

    row: Element
    clip: C
    mirrored: bool = False


@dataclass(frozen=True)
class ActorRows(Generic[C]):
    """One actor's played rows in playing order; ``last``: the clip of its last whole-body row
    (the posture the actor ends in), ``None`` when it has none."""

    actor: str | None
    rows: tuple[Played[C], ...]
    last: C | None


def _repetitions(e: Element, picks: Sequence[Pick[C]], first_id: int) -> list[Played[C]]:
    """``e`` as one row per repetition (ids: ``e.id``, then ``first_id``, ``first_id + 1``, ...), of
    equal length, each a connection to the one before; ``repeat`` 1 and no hold each."""
    step = (e.end - e.start) / len(picks)
    out: list[Played[C]] = []
    for k, p in enumerate(picks):
        row = replace(e, id=e.id if k == 0 else first_id + k - 1, start=e.start + k * step,
                      end=e.start + (k + 1) * step, method=e.method if k == 0 else "connection",
                      prev=e.prev if k == 0 else out[-1].row.id, repeat=1, hold=False)
        out.append(Played(row, p.clip, p.mirrored))
    return out


def played_rows(schedule: Schedule[C]) -> list[ActorRows[C]]:
    """Per actor (in the table's order of first appearance), the rows that play and their clips.

    A row in ``schedule.repeats`` (unless a composition is laid on it) is unrolled with
    ids above the table's; every other row plays its own clip, mirrored when in
    ``schedule.mirrored``.
    """
    table = schedule.table
    next_id = max(e.id for e in table.elements) + 1
    bases = {e.prev for e in table.elements if e.method == "composition"}
    out = []
    for actor in table.actors():
        # In playing order (前に puts a later id first); a composition after its base.
        mine = sorted((e for e in table.elements if e.actor == actor),
                      key=lambda e: (e.start, e.method == "composition", e.id))
        last_of: dict[int, int] = {}  # a repeated row's id -> its last repetition's
        rows: list[Played[C]] = []
        for e in mine:
            prev = e.prev if e.method == "composition" or e.prev is None else last_of.get(e.prev, e.prev)
            picks = schedule.repeats.get(e.id) if e.id not in bases else None
            if picks:
                reps = _repetitions(replace(e, prev=prev), picks, next_id)
                next_id += len(reps) - 1
                last_of[e.id] = reps[-1].row.id
                rows.extend(reps)
            else:
                rows.append(Played(replace(e, prev=prev), schedule.clips[e.id], e.id in schedule.mirrored))
        whole = [e for e in mine if e.method != "composition"]  # the body's posture is the whole-body clips'
        out.append(ActorRows(actor, tuple(rows), schedule.clips[whole[-1].id] if whole else None))
    return out


__all__ = ["ActorRows", "Played", "played_rows"]
