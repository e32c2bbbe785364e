"""Posture: the torso and head bent forward or back, the shoulders dropped and rounded or drawn back.

The style's ``spine_pitch`` is spread evenly over the torso's joints, ``head_pitch`` over the neck and head
(on top of the torso's bend), ``shoulders`` turns each collarbone down and forward by that angle (back for a
negative one), all about the body's own axes frame by frame (:mod:`.body`), so the bend follows the body
wherever it faces. Degrees at intensity 1, scaled by the intensity.
"""
from __future__ import annotations

import numpy as np

from text2anim.core import quat
from text2anim.core.motion import Motion

from .body import UP, Body, about, turned


def pose(motion: Motion, body: Body, spine: float, head: float, shoulders: float) -> Motion:
    """``motion`` with its torso bent ``spine`` degrees forward, its head ``head`` more and its shoulders
    dropped and rounded by ``shoulders`` degrees."""
    if not (spine or head or shoulders):
        return motion
    rot = np.array(motion.rotations)
    for joints, angle in ((body.map.joints("torso"), spine), (body.map.joints("head"), head)):
        for j in joints if angle else ():
            turned(motion, rot, j, about(body.lateral, angle / len(joints)))
    up = np.broadcast_to(UP, body.lateral.shape)
    for side, sign in (("left", 1.0), ("right", -1.0)) if shoulders else ():
        # the left collarbone drops turning about the forward axis by a negative angle, the right by a positive
        drop_and_round = quat.multiply(about(up, -sign * shoulders / 2), about(body.forward, -sign * shoulders))
        turned(motion, rot, body.map.joints(f"{side}_arm")[0], drop_and_round)
    return motion.replace(rotations=rot)
