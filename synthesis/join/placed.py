"""An element (or one repetition of it) as laid on its track, and the steps every engine takes to get there.

:func:`expand_repeats` turns a repeated non-cyclic element into its repetitions,
:func:`on_skeleton` plays a prepared clip on the actor's skeleton,
:func:`mirrored_if_needed` mirrors a partial clip for the other side.
Frames are the track's (0 = the start of the animation).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from text2anim.core.contacts import FootContacts
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton

from .align import Rigid
from ..tracks import Element
from .timing import Prepared
from ..constraint.connection import Side


@dataclass
class Placed:
    """An element (or one repetition of it) as laid on its track.

    ``motion`` is its prepared clip moved by ``rigid``; its frame 0 is at
    track frame ``offset``; ``core`` is ``[c0, c1)`` in its own frames; it plays from its own
    frame ``lead`` to ``stop`` (one past); ``repetition`` counts from 0.
    """

    element: Element
    motion: Motion
    offset: int
    core: tuple[int, int]
    contacts: FootContacts
    cyclic: bool
    rigid: Rigid
    repetition: int
    lead: int
    stop: int

    def side(self) -> Side:
        return Side(self.motion, self.offset, self.core, self.contacts, self.cyclic, self.lead, self.stop)


def expand_repeats(elements: Sequence[Element]) -> list[tuple[Element, int]]:
    """Whole-body elements in time order, a repeated non-cyclic one as its repetitions."""
    out = []
    for e in sorted(elements, key=lambda e: (e.start, e.id)):
        n = max(1, int(e.repeat))
        if e.clip.cyclic or n == 1:
            out.append((e, 0))
            continue
        step = (e.end - e.start) / n
        for k in range(n):
            sub = replace(e, start=e.start + k * step, end=e.start + (k + 1) * step, repeat=1,
                          method=e.method if k == 0 else "connection", prev=e.prev if k == 0 else e.id)
            out.append((sub, k))
    return out


def mirrored_if_needed(clip_part: str | None, want: str | None, motion: Motion) -> Motion:
    if not clip_part or not want:
        return motion
    sides = {"left": "right", "right": "left"}
    for s, o in sides.items():
        if clip_part.startswith(s + "_") and want == o + "_" + clip_part.split("_", 1)[1]:
            from text2anim.core.mirror import mirror

            return mirror(motion)
    return motion


def on_skeleton(prep: Prepared, skeleton: Skeleton | None, e: Element) -> tuple[Prepared, Skeleton, str | None]:
    """The prepared clip played on the track's skeleton (the first element's); a note when bone lengths differ."""
    sk = prep.motion.skeleton
    if skeleton is None:
        return prep, sk, None
    if not sk.same_hierarchy(skeleton):
        raise ValueError(f"element {e.id} ({e.clip.name}) uses another joint hierarchy than the actor's first clip")
    if sk is skeleton:
        return prep, skeleton, None
    diff = float(np.abs(sk.offsets - skeleton.offsets).max())
    note = None
    if diff > 0.005:
        note = (f"element {e.id} ({e.clip.name}) was recorded on other bone lengths (up to {100 * diff:.1f} cm "
                f"different); it is played on the actor's skeleton")
    return replace(prep, motion=prep.motion.replace(skeleton=skeleton)), skeleton, note

