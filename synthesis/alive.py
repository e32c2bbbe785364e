"""No held pose: the captured idle and a breathing layer wherever an actor's motion would stand still.

A track holds a pose where nothing plays: before its first element starts, after
its last one ends (a co-actor still acting, a join given more time), where an
element is not executed, and where a clip ends at rest (lying after 転ぶ).
Every joint then moves slower than :data:`core.metrics.FROZEN_SPEED` (0.5 cm/s):
a frozen frame (docs/timetable.md §3), which no living body shows. The layer is laid
wherever every joint is slower than :data:`NEAR_FROZEN` times that: retargeted onto
another rig (its own proportions, the legs solved again) a body lying still at 0.6 cm/s
moved at 0.3 and read frozen.

:func:`keep_alive` finds those frames and settles them into the track's captured
idle (for the built-in character the ``wait`` clip, CMU 10_01 before the kick:
torso sway, looking about, arms hanging loose) when it is on the actor's skeleton: the idle's
turn of each upper-body joint away from its own mean pose, looped, is laid on
the held pose (:data:`IDLE_WEIGHTS`: trunk and head whole, arms at half so a
held gesture stays that gesture). Hips and legs keep the held pose, so planted
feet stay planted; the idle's weight shifts between the feet are not carried
over. On every skeleton it also lays a breathing layer: the
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

from collections.abc import Callable

import numpy as np
from scipy.ndimage import distance_transform_edt
from scipy.spatial.transform import Rotation

from text2anim.core.easing import smoothstep
from text2anim.core.metrics import frozen_pairs
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton

#: (joint, cone half-angle in degrees, frequency Hz) of the breathing layer.
CHEST_DEG, CHEST_HZ = 1.2, 0.25
NECK_DEG, NECK_HZ = 1.5, 0.17
#: Frames whose joints are all slower than this times core.metrics.FROZEN_SPEED get the layer (module docstring).
NEAR_FROZEN = 2.0
#: Seconds over which the layer fades in before a frozen stretch and out after it.
FADE = 0.4
#: The share of the idle's turn laid on each joint.
IDLE_WEIGHTS = {"LowerBack": 1.0, "Spine": 1.0, "Spine1": 1.0, "Neck": 1.0, "Neck1": 1.0, "Head": 1.0,
                "LeftArm": 0.5, "RightArm": 0.5, "LeftForeArm": 0.5, "RightForeArm": 0.5}


def frozen_frames(motion: Motion, factor: float = 1.0) -> np.ndarray:
    """``(T,)`` bool: frames on which every joint moves slower than ``factor`` times FROZEN_SPEED
    (:func:`core.metrics.frozen_pairs`, either neighbouring pair)."""
    T = motion.n_frames
    if T < 2:
        return np.zeros(T, dtype=bool)
    pair = frozen_pairs(motion, factor)  # (T-1,)
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


def idle_turns(idle: Motion, skeleton: Skeleton, fps: float) -> tuple[list[int], np.ndarray] | None:
    """``idle`` as turns away from its own mean pose: joint indices ``(k,)`` and rotation vectors
    ``(N, k, 3)`` (radians, scaled by :data:`IDLE_WEIGHTS`), one loop at ``fps``; ``None`` when ``idle`` is
    not on ``skeleton`` (same joints and bone lengths: another character's idle is not this one's)."""
    ref = idle.skeleton
    if ref.names != skeleton.names or not np.allclose(ref.offsets, skeleton.offsets, atol=1e-4):
        return None
    if abs(idle.fps - fps) > 1e-6:
        idle = idle.resample(fps)
    joints = [ref.names.index(n) for n in IDLE_WEIGHTS if n in ref.names]
    turns = np.empty((idle.n_frames, len(joints), 3))
    for i, j in enumerate(joints):
        r = Rotation.from_quat(idle.rotations[:, j])
        turns[:, i] = (r.mean().inv() * r).as_rotvec() * IDLE_WEIGHTS[ref.names[j]]
    return joints, turns


def keep_alive(motion: Motion, idle: Callable[[], Motion | None] | None = None) -> Motion:
    """``motion`` with the idle ``idle()`` gives (a captured idle of its character, asked for only when a
    pose is held; laid when it fits) and the breathing layer on its frozen frames (unchanged when it has
    none)."""
    names = motion.skeleton.names
    frozen = frozen_frames(motion, NEAR_FROZEN)
    if not frozen.any() or "Spine1" not in names:
        return motion
    w = layer_weight(frozen, int(round(FADE * motion.fps)))
    t = np.arange(motion.n_frames) / motion.fps
    rots = np.array(motion.rotations)
    clip = idle() if idle is not None else None
    turned = idle_turns(clip, motion.skeleton, motion.fps) if clip is not None else None
    if turned is not None:
        joints, turns = turned
        loop = turns[np.arange(motion.n_frames) % len(turns)]  # (T, k, 3); the clip loops seamlessly
        for i, j in enumerate(joints):
            layer = Rotation.from_rotvec(loop[:, i] * w[:, None])
            rots[:, j] = (Rotation.from_quat(rots[:, j]) * layer).as_quat()
    for joint, deg, hz in (("Spine1", CHEST_DEG, CHEST_HZ), ("Neck1", NECK_DEG, NECK_HZ)):
        if joint not in names:
            continue
        j = names.index(joint)
        layer = Rotation.from_rotvec(_cone(t, deg, hz).as_rotvec() * w[:, None])
        rots[:, j] = (Rotation.from_quat(rots[:, j]) * layer).as_quat()
    return motion.replace(rotations=rots)
