"""The feet of a gait: foot-moving intervals (:class:`Step`, :func:`steps`) and where each foot is.

A step is a foot's lift and landing: paper 003 §4.3.2 blends two gaits swing to swing between these key
frames ("foot lift", "foot land"); paper 000 §4.1–4.2 calls them foot-moving intervals ``P`` and chooses its
method and blend ranges from them. Both engines use this one definition. Frames are the clip's own, or the
track's when moved by an ``offset``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import FootContacts, runs
from text2anim.core.motion import Motion

SIDES = ("left", "right")


@dataclass(frozen=True)
class Step:
    """A foot-moving interval: the foot ``side`` lifts at frame ``begin`` and lands at ``end`` (first frame down)."""

    side: str
    begin: int
    end: int

    @property
    def frames(self) -> int:
        return self.end - self.begin

    def overlap(self, other: "Step") -> int:
        return max(0, min(self.end, other.end) - max(self.begin, other.begin))


def steps(contacts: FootContacts, offset: int = 0, side: str | None = None, start: int = 0) -> list[Step]:
    """The complete steps of a clip (the foot lifts after its first frame and lands before its end), of both
    feet or of ``side``, lifting at or after frame ``start`` (the clip's), moved by ``offset`` frames, in
    time order. Only the frames from ``start - 1`` on are read (a join on a long track asks for its last steps)."""
    n = len(contacts.left)
    w = max(0, start - 1)  # the frame before ``start``: a step lifting at ``start`` is seen to lift there
    out = []
    for s in (SIDES if side is None else (side,)):
        for lo, hi in runs(~contacts.of(s)[w:]):
            lo, hi = int(lo) + w, int(hi) + w
            if lo > 0 and hi < n and lo >= start:
                out.append(Step(s, lo + offset, hi + offset))
    return sorted(out, key=lambda s: (s.begin, s.side))


def foot_points(motion: Motion) -> dict[str, np.ndarray]:
    """Centre of each foot (mean of ankle and toe) per frame, ``(T, 3)`` metres."""
    bm = body_map(motion.skeleton)
    pos = motion.positions
    return {s: pos[:, list(bm.feet[s])].mean(axis=1) for s in SIDES}


def foot_points_at(motion: Motion, frame: int) -> dict[str, np.ndarray]:
    """:func:`foot_points` at one frame, ``(3,)`` metres per side, the same bits (a join reads one frame of a
    long track)."""
    bm = body_map(motion.skeleton)
    pos = motion[frame:frame + 1].positions[0]  # (that frame's kinematics: a long track's pose is not joined)
    return {s: pos[list(bm.feet[s])].mean(axis=0) for s in SIDES}
