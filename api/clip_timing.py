"""A stored clip as the scheduler sees it: ``motiondb.ClipInfo`` -> ``scheduler.ClipTiming``."""
from __future__ import annotations

from text2anim.motiondb import ClipInfo
from text2anim.scheduler import ClipTiming


def foot_moving(info: ClipInfo) -> tuple[tuple[float, float], ...]:
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


def timing(info: ClipInfo) -> ClipTiming:
    """What the scheduler needs to know of a clip (durations in seconds)."""
    return ClipTiming(info.name, info.duration, tuple(info.core), info.cyclic, info.body_part,
                      foot_moving(info), info.character)
