"""Stride: a gait's steps longer or shorter, the hips travelling as far more or less per step.

A gait is a looping clip whose hips travel (:func:`is_gait`). Its thighs' swing about their mean takes the
style's ``stride`` factor (:mod:`.excursion`) and so does the hips' horizontal travel, frame by frame, so a
longer step covers more ground in the same time; the feet are planted again where they land by the foot
locking that runs after (:mod:`synthesis.join.footlock`). The cadence is the scheduler's (the style's
``tempo``: ``scheduler.manner``). Factors at intensity 1, raised to the intensity.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.motion import Motion

from .body import Body
from .excursion import scaled

#: Hips' mean horizontal speed (m/s) above which a looping clip is a gait (a walk in place is not).
GAIT_SPEED = 0.3


def is_gait(motion: Motion, cyclic: bool) -> bool:
    """Is ``motion`` a looping clip whose hips travel at least :data:`GAIT_SPEED`?"""
    if not cyclic or motion.n_frames < 2:
        return False
    travel = motion.root_positions[-1, [0, 2]] - motion.root_positions[0, [0, 2]]
    return float(np.linalg.norm(travel)) / motion.duration >= GAIT_SPEED


def stride(motion: Motion, body: Body, factor: float) -> Motion:
    """The gait ``motion`` with steps ``factor`` times as long."""
    if factor == 1.0:
        return motion
    rot = np.array(motion.rotations)
    for side in ("left", "right"):
        thigh = body.map.joints(f"{side}_leg")[1]
        rot[:, thigh] = scaled(rot[:, thigh], factor, cyclic=True)
    root = np.array(motion.root_positions)
    step = np.diff(root[:, [0, 2]], axis=0) * factor
    root[1:, [0, 2]] = root[0, [0, 2]] + np.cumsum(step, axis=0)
    return motion.replace(rotations=rot, root_positions=root)
