"""What the body does in a clip, measured from its frames: locomotion, moving parts, energy.

Stored with each clip (``clips.description``, :class:`motiondb.types.ClipDescription`) beside
its postures; the clip's ``actions`` (WordNet senses) come from its record, not from here.
All figures are over the clip's core, at the clip's frame rate, in units of the skeleton's
leg length ``L`` per second (0.86 m on the built-in 1.70 m body), so a character's size
does not change its description.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import BodyMapError, body_map
from text2anim.core.motion import Motion
from text2anim.core.size import leg_length

from .types import ClipDescription

#: Hips travelling faster than this (leg lengths per second, horizontally, start to end of
#: the core): locomotion. A slow walk covers about 1.2 L/s; weight shifts and a step
#: on the spot stay under 0.15.
LOCOMOTION = 0.35
#: The parts a description names, each with the body-map groups it reads and the speed
#: relative to the hips (leg lengths per second; its fastest joint's 95th percentile over
#: the frames, so an arm raised once and held moves) above which it moves: breathing and sway of a captured idle stay below it; a
#: nod turns the head joint itself slowly, so the head's bar is lower.
PARTS = (("head", ("head",), 0.10), ("arms", ("left_arm", "right_arm"), 0.25),
         ("legs", ("left_leg", "right_leg"), 0.25), ("trunk", ("torso",), 0.25))


def describe(motion: Motion, core: tuple[float, float], actions: tuple[str, ...] = ()) -> ClipDescription:
    """The description of ``motion`` over ``core`` (seconds): travel, moving parts and energy.

    ``energy`` is the mean speed of hands, feet and head relative to the hips (leg lengths per
    second). A skeleton whose legs or parts cannot be found gets only its ``actions``.
    """
    a = int(np.clip(round(core[0] * motion.fps), 0, motion.n_frames - 1))
    b = int(np.clip(round(core[1] * motion.fps), a + 1, motion.n_frames))
    seconds = max((b - a) / motion.fps, 1e-6)
    try:
        L, bm = leg_length(motion.skeleton), body_map(motion.skeleton)
    except BodyMapError:
        return ClipDescription(actions=actions)
    root = motion.root_positions[a:b]
    travel = float(np.linalg.norm((root[-1] - root[0])[[0, 2]])) / seconds / L
    if b - a < 2:
        return ClipDescription(actions=actions, locomotion=travel > LOCOMOTION)
    pos = motion.positions[a:b]  # (T, J, 3) metres
    rel = pos - pos[:, bm.hips:bm.hips + 1]
    speed = np.linalg.norm(np.diff(rel, axis=0), axis=-1) * motion.fps / L  # (T-1, J) L/s
    fast = np.percentile(speed, 95, axis=0)  # (J,) each joint's speed on its fastest twentieth of frames
    moving = tuple(part for part, groups, bar in PARTS
                   if any(bm.groups[g] for g in groups) and float(fast[[j for g in groups for j in bm.groups[g]]].max()) > bar)
    ends = [bm.head, *bm.hands.values(), *(ankle for ankle, _ in bm.feet.values())]
    return ClipDescription(actions=actions, locomotion=travel > LOCOMOTION, moving=moving,
                           energy=round(float(speed[:, ends].mean()), 3))
