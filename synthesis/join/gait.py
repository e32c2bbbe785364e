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
from text2anim.core.contacts import FootContacts
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


def steps(contacts: FootContacts, offset: int = 0, side: str | None = None) -> list[Step]:
    """The complete steps of a clip (the foot lifts after its first frame and lands before its end), of both
    feet or of ``side``, moved by ``offset`` frames, in time order."""
    n = len(contacts.left)
    out = []
    for s in (SIDES if side is None else (side,)):
        for lo, hi in contacts.moving(s):
            if lo > 0 and hi < n:
                out.append(Step(s, int(lo) + offset, int(hi) + offset))
    return sorted(out, key=lambda s: (s.begin, s.side))


def foot_points(motion: Motion) -> dict[str, np.ndarray]:
    """Centre of each foot (mean of ankle and toe) per frame, ``(T, 3)`` metres."""
    bm = body_map(motion.skeleton)
    pos = motion.positions
    return {s: pos[:, list(bm.feet[s])].mean(axis=1) for s in SIDES}
