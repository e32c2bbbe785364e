"""The pipeline's ``manner`` stage: each row's manner made from its clip where no clip of it was found.

A row whose manner the scheduler gave to the modifiers (``Manner.by == "modifiers"``, :mod:`scheduler.manner`)
gets its clip restyled (:func:`synthesis.manner.restyle`: its contacts held, its quality kept) before the
synthesis joins the clips (whose foot locking plants the feet at the joins); a row played by a clip of the style keeps it. What was done to each row
is a :class:`Styled` record: in the report (``manners``), and, for a manner that is not shown (a word of no
style, or a skeleton the modifiers cannot work on), a warning on stderr, in the report and in the studio.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from text2anim.core.notice import Notice

if TYPE_CHECKING:
    from text2anim.scheduler import TimeTable
    from text2anim.synthesis import tracks as splan


@dataclass(frozen=True)
class Styled:
    """What the animation did with one row's manner: ``by`` ``"clip"``, ``"modifiers"`` or ``None`` (not
    shown, ``note`` says why); ``changes`` the modifiers' parameters at the row's intensity."""

    id: int
    verb: str
    word: str
    style: str | None
    intensity: float
    by: str | None
    changes: dict[str, float] = field(default_factory=dict)
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"id": self.id, "verb": self.verb, "word": self.word, "style": self.style,
                             "intensity": self.intensity, "by": self.by}
        if self.changes:
            d["changes"] = self.changes
        if self.note:
            d["note"] = self.note
        return d

    def warning(self) -> str | None:
        """The sentence for stderr when the manner is not shown, else None."""
        notice = self.notice()
        return notice.text if notice is not None else None

    def notice(self) -> Notice | None:
        """When the manner is not shown, the :class:`core.notice.Notice` ``manner_not_shown`` (``row``, ``verb``,
        ``word``, ``why``: ``no_style`` when the word names no style the modifiers make and no clip of it was
        found, ``refused`` when the modifiers could not keep the clip's quality; :attr:`note` in English);
        else None."""
        if self.by is not None:
            return None
        return Notice.of("manner_not_shown", f"row {self.id} {self.verb}: the manner {self.word} is not shown: {self.note}",
                         row=self.id, verb=self.verb, word=self.word, why="no_style" if self.note == NO_STYLE else "refused")


NO_STYLE = "it names no style the modifiers make (docs/language.md §2.1) and no clip of it was found"


def restyle_tracks(table: TimeTable, tracks: tuple) -> tuple[tuple, tuple[Styled, ...]]:
    """``tracks`` with the clip of each row the modifiers style restyled, and a record per row with a manner."""
    from text2anim.synthesis.manner import restyle

    rows = {e.id: e for e in table.elements if e.manner is not None}
    done: dict[int, Styled] = {}
    out = []
    for track in tracks:
        elements = []
        for el in track.elements:
            row = rows.get(el.id)
            m = row.manner if row is not None else None
            if row is None or m is None:
                elements.append(el)
                continue
            if m.by != "modifiers" or m.style is None:
                done.setdefault(el.id, Styled(el.id, row.verb, m.word, m.style, m.intensity, m.by,
                                              note="" if m.by else NO_STYLE))
                elements.append(el)
                continue
            made = restyle(el.clip.motion, m.style, m.intensity, el.clip.cyclic, el.speed)
            by = None if made.refused else "modifiers"
            note = made.refused or (f"intensity lowered to {made.intensity:g} to keep the quality limits"
                                    if made.intensity != m.intensity else "")
            done.setdefault(el.id, Styled(el.id, row.verb, m.word, m.style, m.intensity, by, made.changes, note))
            elements.append(replace(el, clip=_clip(el.clip, made.motion, m.style, m.intensity)))
        out.append(replace(track, elements=tuple(elements)))
    return tuple(out), tuple(done[i] for i in sorted(done))


def _clip(clip: splan.Clip, motion, style: str, intensity: float) -> splan.Clip:
    """The clip in its style, named for it (``walk~tired``, ``walk~tired1.4``): the report's source figures
    are the styled clip's."""
    suffix = style + (f"{intensity:g}" if intensity != 1.0 else "")
    return replace(clip, name=f"{clip.name}~{suffix}", motion=motion)
