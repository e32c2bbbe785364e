"""A stored clip as the scheduler's rules read it, and the database as they query it.

The scheduler imports no other stage than nlp and core: what it needs of the motion
database is said here as two protocols the API fills (``motiondb.ClipInfo`` is a
:class:`ClipMeta`; the API's adapter over ``motiondb.MotionDB`` is a :class:`ClipSource`).
Only clip metadata is read, never frames.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol, TypeVar

from text2anim.core.bodyparts import BodyPart
from text2anim.core.timebase import resampled_frames
from text2anim.nlp.types import MotionSpec

from .types import ClipTiming


class ClipMeta(Protocol):
    """The metadata of a stored clip that the time-table rules read (``motiondb.ClipInfo`` has it).

    Times are seconds of clip time; ``fps``/``frames`` the clip as stored; postures
    are the words of ``motiondb.types.POSTURES`` (:data:`postures.BRIDGE_VERBS`' keys).
    """

    @property
    def name(self) -> str: ...
    @property
    def character(self) -> str: ...
    @property
    def objects(self) -> tuple[str, ...]: ...
    @property
    def verb(self) -> str: ...
    @property
    def body_part(self) -> BodyPart | None: ...
    @property
    def cyclic(self) -> bool: ...
    @property
    def duration(self) -> float: ...
    @property
    def core(self) -> tuple[float, float]: ...
    @property
    def fps(self) -> float: ...
    @property
    def frames(self) -> int: ...

    def contacts(self, side: str) -> tuple[tuple[int, int], ...]:
        """Contact intervals of the ``left`` or ``right`` foot, ``[start, stop)`` frames."""
        ...

    @property
    def start_posture(self) -> str: ...
    @property
    def end_posture(self) -> str: ...
    @property
    def style(self) -> str | None: ...


#: A clip record of the database the rules hand back as they got it (``motiondb.ClipInfo``).
C = TypeVar("C", bound=ClipMeta)
C_co = TypeVar("C_co", bound=ClipMeta, covariant=True)


class ClipSource(Protocol[C_co]):
    """The motion database as the time-table rules query it, best clips first.

    Neither method raises for a verb the database lacks: it has no clips, ``[]``.
    """

    def candidates(self, spec: MotionSpec, prefer_character: str | None) -> Sequence[C_co]:
        """The clips that can play ``spec`` (its verb, object and body part), ranked."""
        ...

    def by_verb(self, verb: str, *, prefer_character: str | None = None,
                prefer_start_posture: str | None = None) -> Sequence[C_co]:
        """The clips of ``verb``, ranked (``prefer_*``: that character's, that start posture's first)."""
        ...


def foot_moving(info: ClipMeta) -> tuple[tuple[float, float], ...]:
    """Intervals (s) where one foot is off the ground: the gaps between each foot's contacts."""
    out = []
    for side in ("left", "right"):
        cursor = 0
        for a, b in info.contacts(side):
            if a > cursor:
                out.append((cursor / info.fps, a / info.fps))
            cursor = b
        if cursor < info.frames:
            out.append((cursor / info.fps, info.frames / info.fps))
    return tuple(sorted(out))


#: A swing shorter than this (s) is a foot's wobble in the capture, not a step.
MIN_SWING = 0.1


def cycle_steps(info: ClipMeta) -> int:
    """Steps in one cycle of a looping clip: the swings of each foot (the gaps between its contacts,
    the gap across the loop's seam counted once) of at least :data:`MIN_SWING`; 0 for a clip that
    does not loop. The captured walks: 2, the backward walk: 4."""
    if not info.cyclic:
        return 0
    n = 0
    for side in ("left", "right"):
        c = info.contacts(side)
        if not c:
            continue
        gaps = [b0 - a1 for (_, a1), (b0, _) in zip(c, c[1:])] + [info.frames - c[-1][1] + c[0][0]]
        n += sum(g / info.fps >= MIN_SWING for g in gaps)
    return n


def timing(info: ClipMeta) -> ClipTiming:
    """What :func:`plan.plan` needs to know of a clip (durations in seconds)."""
    begin, end = info.core
    return ClipTiming(info.name, info.duration, (begin, end), info.cyclic, info.body_part, foot_moving(info),
                      info.character, cycle_steps(info), info.style)


def played_duration(info: ClipMeta, fps: float) -> float:
    """Seconds a clip lasts once resampled to ``fps`` (as synthesis plays it)."""
    return resampled_frames(info.frames, info.fps, fps) / fps


__all__ = ["C", "ClipMeta", "ClipSource", "MIN_SWING", "cycle_steps", "foot_moving", "played_duration", "timing"]
