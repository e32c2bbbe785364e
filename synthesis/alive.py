"""No held pose: a breathing layer wherever an actor's motion would stand still.

A track holds a pose where nothing plays: before its first element starts, after
its last one ends (a co-actor still acting, a join given more time), where an
element is not executed, and where a clip ends at rest (lying after 転ぶ).
Every joint then moves slower than :data:`core.metrics.FROZEN_SPEED` (0.5 cm/s):
a frozen frame (timetable.md §3), which no living body shows.

:func:`keep_alive` finds those frames and lays a breathing layer on them: the
chest (``Spine1``) and the neck (``Neck1``) each turn on a small cone, a
rotation of :data:`CHEST_DEG` / :data:`NECK_DEG` about the joint's x axis times
``sin`` and about its z axis times ``cos`` of one frequency, so the joints
above them circle at a constant speed that never stops (hands and head move
1-2 cm/s, the shoulders about 0.6 cm/s; a standing person's sway is of that
order). Hips and legs are untouched, so planted feet stay planted. The layer
fades in over :data:`FADE` seconds before each frozen stretch and out after it
(smoothstep), where the motion moves by itself. Deterministic: the phase is
the frame's time.

Shapes: rotations ``(T, J, 4)`` ``(x, y, z, w)``.
"""
from __future__ import annotations

import numpy as np
from scipy.ndimage import distance_transform_edt
from scipy.spatial.transform import Rotation

from text2anim.core.easing import smoothstep
from text2anim.core.metrics import frozen_pairs
from text2anim.core.motion import Motion

#: (joint, cone half-angle in degrees, frequency Hz) of the breathing layer.
CHEST_DEG, CHEST_HZ = 1.2, 0.25
NECK_DEG, NECK_HZ = 1.5, 0.17
#: Seconds over which the layer fades in before a frozen stretch and out after it.
FADE = 0.4


def frozen_frames(motion: Motion) -> np.ndarray:
    """``(T,)`` bool: frames on which every joint moves slower than FROZEN_SPEED (:func:`core.metrics.frozen_pairs`, either neighbouring pair)."""
    T = motion.n_frames
    if T < 2:
        return np.zeros(T, dtype=bool)
    pair = frozen_pairs(motion)  # (T-1,)
    out = np.zeros(T, dtype=bool)
    out[:-1] |= pair
    out[1:] |= pair
    return out


def layer_weight(frozen: np.ndarray, fade_frames: int) -> np.ndarray:
    """``(T,)`` weight: 1 on frozen frames, easing to 0 over ``fade_frames`` either side (smoothstep)."""
    if not frozen.any():
        return np.zeros(len(frozen))
    d = distance_transform_edt(~frozen)  # frames to the nearest frozen frame
    return smoothstep(1.0 - d / (fade_frames + 1))


def _cone(t: np.ndarray, deg: float, hz: float) -> Rotation:
    a = np.radians(deg)
    ph = 2 * np.pi * hz * t
    return Rotation.from_rotvec(np.stack([a * np.sin(ph), np.zeros_like(t), a * np.cos(ph)], axis=1))


def keep_alive(motion: Motion) -> Motion:
    """``motion`` with the breathing layer on its frozen frames (unchanged when it has none)."""
    names = motion.skeleton.names
    frozen = frozen_frames(motion)
    if not frozen.any() or "Spine1" not in names:
        return motion
    w = layer_weight(frozen, int(round(FADE * motion.fps)))
    t = np.arange(motion.n_frames) / motion.fps
    rots = np.array(motion.rotations)
    for joint, deg, hz in (("Spine1", CHEST_DEG, CHEST_HZ), ("Neck1", NECK_DEG, NECK_HZ)):
        if joint not in names:
            continue
        j = names.index(joint)
        layer = Rotation.from_rotvec(_cone(t, deg, hz).as_rotvec() * w[:, None])
        rots[:, j] = (Rotation.from_quat(rots[:, j]) * layer).as_quat()
    return motion.replace(rotations=rots)
