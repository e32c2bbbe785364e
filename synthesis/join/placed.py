"""A clip placed on a track (:class:`Placed`), and the steps every engine takes to put it there.

One record serves every stage of an element (or one repetition of it) on its track: prepared and
scheduled but not yet moved in space (``rigid`` ``None``: the track's next element, the side ``B`` of a
join), then placed (the clip moved by its ``rigid``, the side ``A`` of the next join). It is frozen: a join
that changes where an element's core ends or when it plays replaces it on the track
(:mod:`synthesis.join.commit`).
:func:`on_skeleton` plays a prepared clip on the actor's skeleton,
:func:`mirrored_if_needed` mirrors a partial clip for the other side.
Frames are the track's (0 = the start of the animation).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from text2anim.core.contacts import FootContacts
from text2anim.core.ground import Rigid
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton

from ..tracks import Element
from .timing import Prepared


@dataclass(frozen=True, eq=False)
class Placed:
    """An element (or one repetition of it) on its track.

    Attributes:
        element: the time table's element (a repetition: its share of the element's time).
        motion: its prepared clip, ``(T, J)`` frames; moved by ``rigid`` once placed.
        offset: the track frame of the clip's frame 0.
        core: ``[c0, c1)`` in its own frames (a looped clip is all core but the steps its joins use).
        contacts: the clip's foot contacts, own frames.
        cyclic: the clip loops.
        lead: the own frame it starts playing (a looped clip carries a margin cycle before it).
        stop: one past the own frame it stops playing.
        repetition: which repetition of a repeated element, from 0.
        rigid: the ground-plane move that placed ``motion``; ``None`` while not yet placed.
    """

    element: Element
    motion: Motion
    offset: int
    core: tuple[int, int]
    contacts: FootContacts
    cyclic: bool
    lead: int
    stop: int
    repetition: int = 0
    rigid: Rigid | None = None

    @property
    def first(self) -> int:
        """Track frame the element starts."""
        return self.offset + self.lead

    @property
    def end(self) -> int:
        """One past its last track frame."""
        return self.offset + self.stop

    @property
    def joined_by(self) -> str:
        """The method of the join into it: the element's own, a connection for a later repetition."""
        return "connection" if self.repetition > 0 else self.element.method

    def unlabelled(self) -> "Placed":
        """The element without its time table labels (its ``id`` and ``prev`` as 0 and ``None``): what a join
        reads of it but the names its reports and warnings give (a sentence added to a text renumbers the
        elements the scheduler inserted, not their joins)."""
        return replace(self, element=replace(self.element, id=0, prev=None))

    def moved(self, frames: int) -> "Placed":
        """The element delayed by ``frames`` (all of it, start, core and end)."""
        return replace(self, offset=self.offset + frames)

    def at_phase(self, offset: int) -> "Placed":
        """A looped element entered at another phase: same start and end on the track, other offset."""
        return replace(self, offset=offset, lead=self.first - offset, stop=self.end - offset)


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

