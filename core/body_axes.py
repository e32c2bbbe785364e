"""Where a body faces, frame by frame: its lateral and forward axes on the floor.

Shapes: ``T`` frames; axes ``(T, 3)`` unit world vectors with no vertical part, Y up. The lateral axis points
to the body's left (from the right leg to the left, turned with the hips), the forward axis is
``lateral × up``; a rotation by a positive angle about the lateral axis bends the body forward.
"""
from __future__ import annotations

import numpy as np

from . import quat
from .bodyparts import BodyMap
from .motion import Motion

UP = np.array([0.0, 1.0, 0.0])


def body_axes(motion: Motion, bm: BodyMap) -> tuple[np.ndarray, np.ndarray]:
    """``(lateral, forward)`` of ``motion`` (body map ``bm``), each ``(T, 3)``."""
    rest = motion.skeleton.rest_positions()
    side = rest[bm.joints("left_leg")[-1]] - rest[bm.joints("right_leg")[-1]]
    side[1] = 0.0
    lateral = quat.rotate(motion.pose.quaternions(bm.hips), side / max(float(np.linalg.norm(side)), 1e-9))
    lateral[:, 1] = 0.0
    lateral /= np.maximum(np.linalg.norm(lateral, axis=1, keepdims=True), 1e-9)
    return lateral, np.cross(lateral, UP)
