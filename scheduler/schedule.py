"""The scheduling stage in one call: every rule that writes the motion time table, in order.

1. :func:`plan.plan` times the text's motions with the clips a :class:`picker.Picker`
   takes (the best candidates' next variant; one variant per repetition);
2. :func:`arrangement.arrange` makes the postures meet (other clips, actions kept
   seated as compositions onto a seated idle (:mod:`seated`), bridging motions) and, when it changed anything, the motions are planned again;
3. ``check`` (the caller's limits) sees that table;
4. :func:`fillers.fill_waits` adds the stops and idles of the waits as rows.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Generic

from text2anim.nlp.types import Analysis

from .arrangement import arrange
from .clips import C, ClipSource
from .fillers import fill_waits
from .picker import Picker
from .plan import plan
from .together import together
from .types import TimeTable
from .variants import Pick


@dataclass(frozen=True)
class Schedule(Generic[C]):
    """A text's time table and the clip of every row.

    Attributes:
        analysis: the analysis the table was planned from, bridging motions included.
        table: every row that will play: the text's motions, the bridges, the fillers.
        clips: row id -> its clip.
        fillers: ids of the rows added in the waits (:mod:`fillers`).
        mirrored: ids of the rows whose clip plays mirrored.
        repeats: for a repeated row, the clip of each repetition (:mod:`repeats`).
    """

    analysis: Analysis
    table: TimeTable
    clips: dict[int, C]
    fillers: tuple[int, ...] = ()
    mirrored: frozenset[int] = frozenset()
    repeats: dict[int, tuple[Pick[C], ...]] = field(default_factory=dict)


def schedule(analysis: Analysis, source: ClipSource[C], fps: float,
             check: Callable[[TimeTable], None] | None = None) -> Schedule[C]:
    """The time table of ``analysis`` with clips from ``source`` (see the module docstring).

    ``check`` is called with the table before its waits are filled (the API's output
    budget: it raises to refuse the text).
    """
    picker = Picker(source, together(analysis))
    table = plan(analysis, picker, fps)
    arranged = arrange(analysis, table, picker.chosen, source)
    if arranged.changed:
        analysis, picker = arranged.analysis, Picker(source, together(arranged.analysis))
        table = plan(analysis, arranged.finder(picker), fps)
    if check is not None:
        check(table)
    filled = fill_waits(table, dict(picker.chosen), source, fps)
    return Schedule(analysis, filled.table, filled.clips, filled.fillers,
                    frozenset(picker.mirrored) | filled.mirrored, dict(picker.repeats))


__all__ = ["Schedule", "schedule"]
