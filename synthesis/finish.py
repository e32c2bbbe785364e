"""The last step of every engine, per actor: swinging feet clear the floor, held poses breathe.

A join can carry a swinging foot lower than either of its clips does: the
post-pass's root offset decays over the seam into the next clip (walk → sit
down: the body 1.7-2.7 cm low through the sit's first step) while the foot's
lock has just been released, or the first clip's end pose is carried into
the second's lower body (dance → laugh: toes 1.2-2.5 cm up, sliding at
0.7-1.5 m/s). The built-in library keeps swinging feet 1.5 cm clear of the
floor (:func:`core.clearance.clear_swings`, the minimum toe clearance of
human gait); :func:`finish` applies the same rule to the joined motion, keeps every joint and
end site (toe and finger tips) above the floor (:func:`core.clearance.clear_floor`: a pointed toe,
a fall landing on the hands), then
:func:`synthesis.alive.keep_alive` (held poses play the track's captured idle and breathe). Planted feet, the hips and everything
above the knees' IK are left as they are; a motion with no low swing and no
frozen stretch is returned unchanged. The joins' own figures in the report are
measured before this step: they judge the join as the engine made it.
"""
from __future__ import annotations

from collections.abc import Callable

from text2anim.core.clearance import clear_floor, clear_swings
from text2anim.core.motion import Motion

from .alive import keep_alive


def finish(motion: Motion, feet: bool = True, idle: Callable[[], Motion | None] | None = None) -> Motion:
    """``motion`` with its swinging feet clear of the floor and its limbs' ends above it (``feet``: the engines that clean feet; the
    baselines do not, that is what they stand for) and no frozen frame: held poses play ``idle`` (the
    track's captured idle) where it fits the skeleton, and breathe (see the module docstring)."""
    return keep_alive(clear_floor(clear_swings(motion)) if feet else motion, idle)
