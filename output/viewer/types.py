"""What the outputs a person looks at (viewer page, GLB, plots) are given.

- :class:`Track`: one actor's animation, a named :class:`~core.motion.Motion`;
- :class:`Span`: an interval on an actor's timeline, either a time-table
  element (``kind="element"``, label like ``"2 蹴る (transition)"``) or a blend
  interval (``kind="blend"``, ``part`` ``"upper"``, ``"lower"`` or ``None`` for
  the whole body).

Times are seconds from the start of the animation, the same clock for every actor.
"""
from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from text2anim.core.motion import Motion

SPAN_KINDS = ("element", "blend")

#: Body-part names (``core.bodyparts.GROUPS``) drawn in the lower-body lane of a blend;
#: every other named part (arms, head, torso, "upper") in the upper lane; ``None``: both.
LOWER_PARTS = frozenset({"lower", "right_leg", "left_leg", "legs", "hips"})


@dataclass(frozen=True)
class Track:
    """One actor: its name (shown in the viewer, the GLB's node names) and its motion."""

    name: str
    motion: Motion

    def __post_init__(self):
        if not isinstance(self.name, str):
            raise TypeError(f"track name must be a string, got {type(self.name).__name__}")
        if not isinstance(self.motion, Motion):
            raise TypeError(f"track {self.name!r}: expected a Motion, got {type(self.motion).__name__}")
        if self.motion.n_frames == 0:
            raise ValueError(f"track {self.name!r}: the motion has no frames")


@dataclass(frozen=True)
class Span:
    """An interval of an actor's timeline.

    Attributes:
        actor: the :attr:`Track.name` it belongs to.
        label: text shown on the bar (Japanese is fine in the viewer).
        start, end: seconds, ``start <= end``.
        kind: ``"element"`` (a time-table element) or ``"blend"`` (a blend interval).
        part: for blends, the body part blended: ``"upper"``, ``"lower"`` (or a
            body-part group name) or ``None`` for the whole body.
        alt: optional ASCII label (e.g. the clip name ``"kick_ball"``) used where
            Japanese cannot be drawn (plots on a machine without a CJK font).
    """

    actor: str
    label: str
    start: float
    end: float
    kind: str = "element"
    part: str | None = None
    alt: str | None = None

    def __post_init__(self):
        if self.kind not in SPAN_KINDS:
            raise ValueError(f"span kind must be one of {SPAN_KINDS}, got {self.kind!r}")
        start, end = float(self.start), float(self.end)
        if not (math.isfinite(start) and math.isfinite(end)):
            raise ValueError(f"span {self.label!r}: times must be finite, got {start}..{end}")
        if end < start:
            raise ValueError(f"span {self.label!r}: end {end} is before start {start}")
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "end", end)

    @property
    def lane(self) -> str:
        """``"upper"``, ``"lower"`` or ``"both"``: where a blend is drawn."""
        if self.part is None or self.part in ("whole", "full", "all"):
            return "both"
        return "lower" if self.part in LOWER_PARTS else "upper"


def as_tracks(tracks) -> list[Track]:
    """Accept a list of :class:`Track`, one :class:`Motion`, or a ``{name: Motion}`` mapping."""
    if isinstance(tracks, Motion):
        tracks = [Track("", tracks)]
    elif isinstance(tracks, Track):
        tracks = [tracks]
    elif isinstance(tracks, dict):
        tracks = [Track(str(k), v) for k, v in tracks.items()]
    out = list(tracks)
    if not out:
        raise ValueError("no tracks to show")
    for t in out:
        if not isinstance(t, Track):
            raise TypeError(f"expected Track objects, got {type(t).__name__}")
    names = [t.name for t in out]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"two tracks share the name {dup[0]!r}")
    return out


def as_spans(spans: Iterable[Span]) -> list[Span]:
    out = list(spans or ())
    for s in out:
        if not isinstance(s, Span):
            raise TypeError(f"expected Span objects, got {type(s).__name__}")
    return out
