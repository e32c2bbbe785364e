"""One actor's track as an engine has laid it: the frames, the elements placed, the joins made.

Every engine (paper 003's, optimal blending, the baselines, the online timeline) fills a
:class:`Laid`; :mod:`synthesis.assemble` composes the partial elements onto it
(:class:`LaidPart`), runs the join post-pass and measures every :class:`LaidJoin`.
Frames are the track's (0 = the start of the animation), windows ``[begin, end)``.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from text2anim.core.motion import Motion

from ..result import JoinReport
from ..tracks import Element
from .composition import Composed
from .placed import Placed

#: A span of track frames ``(begin, end)``, end excluded.
Frames = tuple[int, int]


@dataclass(frozen=True)
class LaidJoin:
    """One join as laid, before it is measured.

    ``window``: the blend's frames (its figures are the join's); ``region``: the blend and the feet
    released after it. Both ``None`` for a join not carried out (nothing to measure). ``first`` and
    ``second``: the two elements, as indices into the track's placed elements (:attr:`Laid.placed`; a
    later join or the post-pass may replace an element there), ``None`` for a composition, whose sources
    are its base track and its :class:`LaidPart`. ``extra``: further windows measured with the blend (a
    composition's blend out).
    """

    report: JoinReport
    window: Frames | None = None
    region: Frames | None = None
    first: int | None = None
    second: int | None = None
    extra: tuple[Frames, ...] = ()


@dataclass(frozen=True)
class LaidPart:
    """A partial element composed onto the track: the composition, the clip that gave the part (mirrored
    if needed) and its core ``[c0, c1)`` in that clip's frames."""

    element: Element
    composed: Composed
    donor: Motion
    core: Frames


@dataclass
class Laid:
    """One track after its whole-body elements are laid.

    ``skipped``: element ids not executed, with the reason. ``delays``: ``(element id, s)`` of elements
    the joiner moved in time (the partial elements laid on them move too).
    """

    motion: Motion
    placed: list[Placed]
    joins: list[LaidJoin] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    skipped: dict[int, str] = field(default_factory=dict)
    delays: list[tuple[int, float]] = field(default_factory=list)
