"""Motion adaptation of paper 000 §4.1/§4.2.3: the next motion's lower body fitted to the previous feet.

"後の要素動作の下半身の姿勢を前の要素動作の両足の位置に合わせて変形させた動作":
the next motion with its lower body deformed so that its feet stand where the
previous motion left them. The next motion is first placed through its
support foot (:func:`synthesis.join.align.align_through_foot`), so that foot needs
no change; the other foot is ``d`` metres (horizontally) from where the
previous motion has it. :func:`adapt`:

- every foot target is the motion's own foot moved by its offset (0 for the
  support foot, ``d`` for the other), so a foot that is planted in the motion
  stays planted, where the previous motion had it;
- **the hips keep their place relative to both feet** (§4.1, last paragraph
  of the method list): they move by the mean of the two offsets;
- both legs are solved by two-bone IK (:func:`core.ik.leg_ik`) and each
  ankle keeps its world orientation (:func:`core.ik.set_world_rotation`),
  so the sole stays on the ground; the upper body is untouched (its joints are
  local to the hips).

The return to the motion's own lower body over the next step (eq. (8)) fades
the same deformation (``scale`` from 1 to 0), so the motion's own movement
plays through it and the support foot never moves. :func:`pin_feet` puts feet
back exactly on reference positions where they should be planted — used when
§4.4.2 case (c) turns that return into a pose–pose blend of two leg solutions,
which would otherwise let a planted foot drift by a few millimetres per frame.
"""
from __future__ import annotations

import numpy as np

from text2anim.core import rotkernels as rk
from text2anim.core.bodyparts import body_map
from text2anim.core.ik import leg_ik, set_world_rotation
from text2anim.core.motion import Motion


def adapt(motion: Motion, offsets: dict[str, np.ndarray], scale=None) -> Motion:
    """``motion`` with each foot moved by ``offsets[side]`` (metres, ``(3,)``; only x and z are used),
    the hips by their mean, legs re-solved by IK, ankles keeping their world rotation.

    ``scale`` ``(T,)`` in [0, 1] (default 1 everywhere) scales the offsets per frame: 1 is the adapted
    motion, 0 the motion's own; in between the deformation fades (eq. (8)'s return to the own pose, which
    leaves a support foot with no offset exactly where it is).
    """
    feet = body_map(motion.skeleton).feet
    d = {s: np.array([float(v[0]), 0.0, float(v[2])]) for s, v in offsets.items()}
    if max(np.abs(x).max() for x in d.values()) < 1e-9:
        return motion
    k = np.ones(motion.n_frames) if scale is None else np.asarray(scale, dtype=np.float64).reshape(-1)
    mask = k > 1e-9
    shift = np.outer(k, 0.5 * (d["left"] + d["right"]))
    pose = motion.pose
    out = motion.replace(root_positions=motion.root_positions + shift)
    for side in ("left", "right"):
        ankle = feet[side][0]
        out = leg_ik(out, side, pose.positions[:, ankle] + np.outer(k, d[side]), mask=mask)
        out = set_world_rotation(out, ankle, rk.as_quat(rk.from_matrix(pose.rotations[:, ankle])), mask=mask)
    return out


def pin_feet(motion: Motion, reference: Motion, masks: dict[str, np.ndarray]) -> Motion:
    """``motion`` with each foot put on ``reference``'s (ankle position and world rotation) on the frames
    where ``masks[side]`` ``(T,)`` is true; both motions on the same frames."""
    feet = body_map(motion.skeleton).feet
    ref = reference.pose
    out = motion
    for side, mask in masks.items():
        mask = np.asarray(mask, dtype=bool)
        if not mask.any():
            continue
        ankle = feet[side][0]
        out = leg_ik(out, side, ref.positions[:, ankle], mask=mask)
        out = set_world_rotation(out, ankle, rk.as_quat(rk.from_matrix(ref.rotations[:, ankle])), mask=mask)
    return out
