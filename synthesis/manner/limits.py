"""The quality a style must keep: a restyled clip meets the limits of motion made from the built-in library
(:data:`core.metrics.BUILTIN_LIMITS`, README *Quality figures*) wherever the clip as captured meets them.

Both are measured as the track plays them (:mod:`synthesis.join.timing`), at the row's speed (the style's
tempo is the time table's, as a speed word's is: what the modifiers change is judged here), a looping clip
looped over two cycles (its cycle lengthened where a quicker tempo would jerk past the limit, as the
synthesis does), any other clip as it is.
"""
from __future__ import annotations

from text2anim.core.metrics import COMPARE_FPS, against_limits, quality
from text2anim.core.motion import Motion

from ..join.timing import at_speed, cycle_at_speed, loop, make_cyclic


def played(motion: Motion, cyclic: bool, speed: float) -> Motion:
    """``motion`` as a track plays it at ``speed``, at the rate the figures are compared at."""
    if cyclic and motion.n_frames >= 3:
        cycle = make_cyclic(cycle_at_speed(motion, speed, COMPARE_FPS))
        return loop(cycle, 2 * cycle.n_frames, 0)
    return at_speed(motion, speed, COMPARE_FPS)


def broken(styled: Motion, captured: Motion, cyclic: bool, speed: float) -> list[str]:
    """The criteria ``styled`` misses that ``captured`` meets, both played at ``speed``."""
    mine = against_limits(quality(played(styled, cyclic, speed)))
    theirs = against_limits(quality(played(captured, cyclic, speed)))
    return [name for name, ok in mine.items() if not ok and theirs[name]]
