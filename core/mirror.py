"""Left/right mirroring of a motion across the character's sagittal plane.

Used to serve a left-side request (左手を振る) with a clip declared for the
right side (``body_part="right_arm"``), and the other way round.

How: the reflection is ``M = diag(-1, 1, 1)`` (world X -> -X; the character
faces +Z with Y up, so X is its left-right axis).

- Root positions: ``(x, y, z) -> (-x, y, z)``.
- Rotations: a rotation ``R`` reflects to ``M R M``. For a unit quaternion
  ``(x, y, z, w)`` that is ``(x, -y, -z, w)``: the axis component along X
  is kept, the components along the mirrored plane flip. This holds for
  every *local* rotation as long as the rest pose's joint axes are aligned
  with the world (true of CMU-style BVH skeletons and the built-in one).
- Then each left joint takes the (reflected) rotation of its right
  counterpart and vice versa (:func:`core.bodyparts.mirror_index`);
  centre joints keep their own.

Forward kinematics of the result is then exactly the reflection of the
original's, joint for joint swapped, provided the skeleton itself is
mirror-symmetric (each left offset the reflection of its right one, as the
built-in skeleton is). A captured skeleton with slightly unequal sides gets
the mirrored *rotations* on its own bone lengths: the motion is mirrored,
the bones are not. Mirroring twice gives back the input exactly.
"""
from __future__ import annotations

import numpy as np

from .bodyparts import mirror_index
from .motion import Motion

_REFLECT_Q = np.array([1.0, -1.0, -1.0, 1.0])
_REFLECT_P = np.array([-1.0, 1.0, 1.0])


def mirror(motion: Motion) -> Motion:
    """``motion`` reflected across its sagittal plane (X -> -X), left and right joints swapped."""
    idx = mirror_index(motion.skeleton)
    rots = motion.rotations[:, idx] * _REFLECT_Q
    root = motion.root_positions * _REFLECT_P
    trans = None
    if motion.translations is not None:
        trans = motion.translations[:, idx] * _REFLECT_P
    return Motion(motion.skeleton, motion.fps, root, rots, trans)


def is_symmetric(skeleton, tol: float = 1e-6) -> bool:
    """Whether every joint's rest offset is the reflection of its counterpart's."""
    idx = mirror_index(skeleton)
    return bool(np.allclose(skeleton.offsets[idx] * _REFLECT_P, skeleton.offsets, atol=tol))
