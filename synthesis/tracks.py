"""What the synthesis stage is asked to do: clips placed on actor tracks.

These frozen records are the input half of the engines' contract with the
pipeline (which turns the scheduler's time table and the database's clips into
them); :mod:`synthesis.result` is the output half. Times are seconds; ``start``/``end`` are on the actor's own
track (0 = the start of the animation).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from text2anim.core.methods import ELEMENT_METHODS, Method
from text2anim.core.motion import Motion

__all__ = ["Clip", "Element", "Track"]


@dataclass(frozen=True, eq=False)
class Clip:
    """A source clip with the metadata synthesis uses.

    Attributes:
        name: the clip's name in the database.
        motion: its frames (metres, Y up).
        core: ``(begin, end)`` seconds of clip time that must be kept (コア区間).
        cyclic: the clip loops (its last frame flows into its first).
        body_part: the group a partial clip is declared for (``right_arm``), ``None`` for whole-body.
    """

    name: str
    motion: Motion
    core: tuple[float, float]
    cyclic: bool = False
    body_part: str | None = None


@dataclass(frozen=True, eq=False)
class Element:
    """One motion on an actor's track: which clip, when, joined how to which element, played how."""

    id: int
    """The time table's element id."""
    clip: Clip
    """The source clip."""
    start: float
    """When the element begins on the track (s)."""
    end: float
    """When it ends (s); ``end - start`` is the played length after speed, repeats, looping (cyclic clips) or
    holding/trimming."""
    method: Method
    """One of :data:`~text2anim.core.methods.ELEMENT_METHODS`; how it joins ``prev``."""
    prev: int | None = None
    """Id of the element it is joined to (the base motion for a composition); ``None`` for ``initial``."""
    speed: float = 1.0
    """Time scale (2.0 plays twice as fast)."""
    repeat: int = 1
    """How many times the clip is performed (:func:`synthesis.join.timing.repetitions`)."""
    hold: bool = False
    """たまま — this element's end pose stays as the base while the element composed onto it plays (the
    time table starts the composition at this element's end and lengthens this one to cover it; synthesis
    holds its end pose as for any clip played past its length, and reads nothing more from the flag)."""
    body_part: str | None = None
    """For a composition, the part taken from this clip (may be the mirror of the clip's declared part:
    ``left_arm`` from a ``right_arm`` clip)."""

    def __post_init__(self):
        if self.method not in ELEMENT_METHODS:
            raise ValueError(f"unknown method {self.method!r}")
        if self.end < self.start:
            raise ValueError(f"element {self.id} ends before it starts")


@dataclass(frozen=True, eq=False)
class Track:
    """All elements of one actor, and where the actor stands at time 0.

    ``origin`` is the (x, z) ground position in metres and ``heading`` the
    facing angle in radians about +Y (0 faces +Z). ``idle`` gives a captured
    idle of the actor's character when first asked (a database read only a
    track that holds a pose pays for): where the actor would hold a pose, it
    plays that, looped (:mod:`synthesis.alive`); ``None``, no clip, or a
    skeleton other than the actor's leaves the breathing layer alone.
    """

    actor: str | None
    elements: tuple[Element, ...]
    origin: tuple[float, float] = (0.0, 0.0)
    heading: float = 0.0
    idle: Callable[[], Motion | None] | None = None
