"""Posture classification: which of :data:`motiondb.types.POSTURES` a frame of motion is in.

Stored clips get a ``start_posture`` and an ``end_posture`` from their first and
last frames (:func:`clip_postures`) unless their record declares them.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import BodyMapError, body_map
from text2anim.core.motion import Motion
from text2anim.core.size import leg_length
from text2anim.core.skeleton import Skeleton

from .types import DEFAULT_POSTURE, Posture

#: Hip joints at least this fraction of the leg length above the floor: standing.
STAND_HIP = 0.75
#: Head below this fraction of the leg length above the floor: lying.
LIE_HEAD = 0.45
#: A knee this close to the floor (fraction of the leg length) rests on it ...
KNEE_DOWN = 0.15
#: ... and with the hips this much higher than it (fraction of the leg length): kneeling.
KNEEL_HIP = 0.15
#: Hips this low (fraction of the leg length) sit on the floor.
FLOOR_SIT_HIP = 0.25
#: Hips this far (fraction of the leg length, horizontally) from the middle of the ankles
#: are not over the feet: seated (on a seat), else crouched.
SEAT_OFFSET = 0.3


def _leg_joints(skel: Skeleton, side: str) -> tuple[int, int, int, int]:
    """``(hip, knee, ankle, toe)`` joint indices of one leg (the hip is the knee's parent)."""
    ankle, toe = body_map(skel).feet[side]
    knee = int(skel.parents[ankle])
    hip = int(skel.parents[knee])
    if knee < 0 or hip < 0:
        raise BodyMapError(f"the {side} leg has no knee and hip above its ankle")
    return hip, knee, ankle, toe


def classify_posture(motion: Motion, frame: int = 0) -> Posture:
    """The posture (one of :data:`motiondb.types.POSTURES`) of one frame of ``motion``.

    Heights are measured from the floor, taken as the lowest foot joint's 5th
    percentile over the clip (clamped to 0..0.10 m, as the contact detector
    does), in units of the leg length ``L`` (rest-pose height of the hip joints
    above the lowest foot joint: 0.86 m on the built-in 1.70 m skeleton). In
    this order:

    1. hip joints at least :data:`STAND_HIP` ``L`` up: ``standing`` (bending
       over or reaching does not change it);
    2. the head below :data:`LIE_HEAD` ``L``: ``lying`` (face down or up);
    3. a knee within :data:`KNEE_DOWN` ``L`` of the floor and the hips
       :data:`KNEEL_HIP` ``L`` above it: ``kneeling`` (also on all fours);
    4. hips below :data:`FLOOR_SIT_HIP` ``L``: ``seated`` (on the floor);
    5. hips more than :data:`SEAT_OFFSET` ``L`` horizontally from the middle of
       the ankles (the weight is not over the feet): ``seated``; else ``crouched``.

    Falls back to :data:`motiondb.types.DEFAULT_POSTURE` for a skeleton whose
    legs cannot be found.
    """
    skel = motion.skeleton
    try:
        legs = [_leg_joints(skel, side) for side in ("left", "right")]
        length = leg_length(skel)
    except BodyMapError:
        return DEFAULT_POSTURE
    foot_joints = [j for leg in legs for j in leg[2:]]
    pos = motion.positions
    floor = float(np.clip(np.percentile(pos[:, foot_joints, 1].min(axis=1), 5.0), 0.0, 0.10))
    p = pos[frame]
    hips = np.mean([p[leg[0]] for leg in legs], axis=0)
    hip_h = (hips[1] - floor) / length
    if hip_h >= STAND_HIP:
        return "standing"
    head_h = (p[body_map(skel).head, 1] - floor) / length
    if head_h < LIE_HEAD:
        return "lying"
    knees = [(p[leg[1], 1] - floor) / length for leg in legs]
    if min(knees) < KNEE_DOWN and hip_h - min(knees) > KNEEL_HIP:
        return "kneeling"
    if hip_h < FLOOR_SIT_HIP:
        return "seated"
    ankles = np.mean([p[leg[2]] for leg in legs], axis=0)
    offset = float(np.hypot(*(hips - ankles)[[0, 2]])) / length
    return "seated" if offset > SEAT_OFFSET else "crouched"


def clip_postures(motion: Motion) -> tuple[Posture, Posture]:
    """``(start, end)`` postures of a clip: :func:`classify_posture` of its first and last frames."""
    return classify_posture(motion, 0), classify_posture(motion, motion.n_frames - 1)
