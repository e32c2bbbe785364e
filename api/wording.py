"""What the synthesizer says about its elements and joins, said in the user's terms.

The synthesizer numbers what it joins by element id (``join 1→3``, ``element 4 (jump)``); the ids of
a repeated motion's repetitions (``3回跳ぶ``) lie beyond the time table the user sees. :class:`Terms`
names an element as the printed table does: its row and verb (``row 1 跳ぶ``), which repetition it is
(``row 1 跳ぶ (2 of 3)``), and a join by its two motions and the second's start in seconds.
"""
from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from text2anim.core.notice import Notice

#: ``element 4`` or ``element 4 (jump)`` (the clip's name) in a synthesizer's message.
_ELEMENT = re.compile(r"\belement (\d+)(?: \(([^()]*)\))?")
#: ``1→3`` (a join: first element → second) in a synthesizer's message.
_JOIN = re.compile(r"\b(\d+)→(\d+)\b")


@dataclass(frozen=True)
class Named:
    """One synthesis element in the table's terms: ``row`` and ``verb``, the ``nth`` of ``of`` repetitions
    (1 of 1 when not repeated), and its start (s): ``row 1 跳ぶ (2 of 3)``."""

    row: int
    verb: str
    nth: int
    of: int
    start: float

    def __str__(self) -> str:
        repetition = f" ({self.nth} of {self.of})" if self.of > 1 else ""
        return f"row {self.row} {self.verb}{repetition}"


@dataclass(frozen=True)
class Terms:
    """The user's name of every synthesis element id, and :meth:`reword` for the synthesizer's messages."""

    names: Mapping[int, Named]

    @classmethod
    def of(cls, table, tracks: Iterable) -> Terms:
        """From the time table (rows, verbs) and the synthesis tracks (``track.elements`` in playing order:
        a repeated row's repetitions follow it, under ids the table does not have)."""
        rows = {e.id: e for e in table.elements}
        runs: dict[int, list] = {}
        for track in tracks:
            row = None
            for e in track.elements:
                row = e.id if e.id in rows else row
                if row is not None:
                    runs.setdefault(row, []).append(e)
        names = {e.id: Named(e.id, e.verb, 1, 1, e.start) for e in table.elements}
        for row, played in runs.items():
            for k, e in enumerate(played):
                names[e.id] = Named(row, rows[row].verb, k + 1, len(played), e.start)
        return cls(names)

    def element(self, eid: int, clip: str | None = None) -> str:
        """``row 2 蹴る``; an id the table does not know stays ``element N (clip)``."""
        named = self.names.get(eid)
        if named is None:
            return f"element {eid}" + (f" ({clip})" if clip else "")
        return str(named)

    def join(self, first: int, second: int) -> str:
        """``row 1 走る → row 2 蹴る at 2.10 s`` (the second motion's start)."""
        a, b = self.names.get(first), self.names.get(second)
        if a is None or b is None:
            return f"{first}→{second}"
        return f"{a} → {b} at {b.start:.2f} s"

    def reword(self, message: str) -> str:
        """A synthesizer's message with its element ids and joins named as the printed table names them."""
        message = _JOIN.sub(lambda m: self.join(int(m[1]), int(m[2])), message)
        return _ELEMENT.sub(lambda m: self.element(int(m[1]), m[2]), message)

    def notice(self, message: str) -> Notice:
        """A synthesizer's message as a :class:`core.notice.Notice` of kind ``synthesis``: :meth:`reword`'s
        sentence, with the ``row`` and ``verb`` of the motion it is about: a join's second one, else the first
        element it names (the synthesizer says its warnings as sentences only)."""
        join, element = _JOIN.search(message), _ELEMENT.search(message)
        eid = int(join[2]) if join else int(element[1]) if element else None
        named = self.names.get(eid) if eid is not None else None
        params = {"row": named.row, "verb": named.verb} if named is not None else {}
        return Notice.of("synthesis", self.reword(message), **params)

    def label(self, first: int, second: int) -> str:
        """A short join label for the viewer and plots: ``1→2``, ``1 (1/3)→1 (2/3)`` within a repeat."""
        def short(eid: int) -> str:
            named = self.names.get(eid)
            if named is None:
                return str(eid)
            return f"{named.row} ({named.nth}/{named.of})" if named.of > 1 else str(named.row)

        return f"{short(first)}→{short(second)}"
