"""How long an element plays, and where a transition may overlap it (seconds)."""
from __future__ import annotations

import math

from .types import ClipTiming


#: A looping clip given no duration plays whole cycles for at least this many seconds: a captured
#: walk or run is a single gait cycle (0.8-1.1 s), which alone would be over in one or two steps.
MIN_LOOP = 2.0


def played_length(clip: ClipTiming, speed: float, repeat: int, duration: float | None,
                  steps: bool = False) -> float:
    """Seconds an element plays after speed, repeats and an explicit duration.

    A cyclic clip loops to fill ``duration`` (without one: whole cycles for at
    least :data:`MIN_LOOP` seconds); any other clip plays whole and then holds
    its last pose, or is trimmed, but never inside its core. With ``steps``
    (a stepping verb: its repeat counts steps, docs/language.md §7.6) a looping
    gait plays ``repeat`` steps: 3歩歩く is 1.5 cycles of a two-step walk.
    """
    if duration is not None:
        return duration if clip.cyclic else max(duration, clip.core[1] / speed)
    if steps and clip.cyclic and clip.cycle_steps > 0:
        return repeat / clip.cycle_steps * clip.duration / speed
    cycles = 1
    if clip.cyclic and clip.duration > 0:
        cycles = max(1, math.ceil(MIN_LOOP * speed / clip.duration - 1e-9))
    return repeat * cycles * clip.duration / speed


def moving_intervals(clip: ClipTiming, speed: float, length: float) -> list[tuple[float, float]]:
    """Foot-moving intervals in element time over ``[0, length]``, a looping clip's repeated each cycle."""
    period = clip.duration / speed
    cycles = max(1, math.ceil(length / period)) if period > 0 else 1
    out = []
    for k in range(cycles):
        for a, b in clip.foot_moving:
            a2, b2 = k * period + a / speed, k * period + b / speed
            if a2 < length:
                out.append((a2, min(b2, length)))
    return sorted(out)


def transition_window(clip: ClipTiming, speed: float, repeat: int, length: float) -> tuple[float, float] | None:
    """The foot-moving interval (element time) over which the next motion overlaps this one.

    Cyclic clips: the last step that fits in the played length. Others: the
    first foot-moving interval after the core (of the last repetition).
    ``None`` when the clip has none: the next motion then starts at the end.
    """
    steps = moving_intervals(clip, speed, length)
    if clip.cyclic:
        whole = [s for s in steps if s[1] <= length + 1e-9 and s[1] - s[0] > 1e-3]
        return whole[-1] if whole else None
    core_end = (repeat - 1) * clip.duration / speed + clip.core[1] / speed
    after = [s for s in steps if s[0] >= core_end - 1e-9 and s[1] - s[0] > 1e-3]
    return after[0] if after else None
