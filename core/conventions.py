"""Engine conventions for exported motion: root motion, in place, units, loops.

- :func:`root_motion`: the travel moves onto a root bone at the floor (the
  skeleton's own when its root is not the hips, as on the Unreal mannequin;
  else a new joint ``root`` above the hips). The root carries the smoothed
  horizontal path of the hips and their heading (yaw); the hips keep, relative
  to it, their height, their sway and the rest of their turn.
- :func:`in_place`: the same smoothed path is removed instead: the hips sway
  about the origin but do not travel (they keep their heading).
- :func:`scaled`: every length times ``k`` (``--units cm``: ``k = 100``).
- :func:`looped`: a cyclic motion cut where its pose comes back to the
  first frame's and the remaining difference spread over the clip, so that
  the last frame flows into the first.

The path is the hips' horizontal position averaged over :data:`PATH_WINDOW`
seconds (a step's sway is gone, the travel stays); the heading is the
direction the body faces (left hip to right hip, turned a quarter), averaged
the same way. Shapes: ``T`` frames; metres, Y up; quaternions ``(x, y, z, w)``.
"""
from __future__ import annotations

import numpy as np
from scipy.signal import savgol_filter
from scipy.spatial.transform import Rotation

from .motion import Motion, unroll_quaternions
from .rigs import rig_roles
from .skeleton import POSITION_CHANNELS, Skeleton

#: Seconds over which the hips' path and heading are averaged (about one walking cycle).
PATH_WINDOW = 1.0
#: Name of the joint :func:`root_motion` adds above the hips when the skeleton has none.
ROOT_NAME = "root"


def _smooth(x: np.ndarray, fps: float) -> np.ndarray:
    """A moving average over :data:`PATH_WINDOW` s, a straight-line fit over the first and last half window."""
    n = min(int(round(PATH_WINDOW * fps)) | 1, len(x) - (1 - len(x) % 2))
    if n < 3:
        return np.repeat(x.mean(axis=0, keepdims=True), len(x), axis=0) if len(x) else x.copy()
    return savgol_filter(x, n, 1, axis=0, mode="interp")


def hips_index(skel: Skeleton, joint_map: dict[str, str] | None = None) -> int:
    """The hips joint (by role, :mod:`core.rigs`)."""
    return rig_roles(skel, joint_map)[1]["hips"]


def path_and_heading(motion: Motion, joint_map: dict[str, str] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The hips' smoothed floor path ``(T, 3)`` (``y = 0``) and heading angle about +Y ``(T,)`` radians.

    Heading 0 faces +Z; the angle is unwrapped before smoothing, so a turn is followed.
    """
    _, roles = rig_roles(motion.skeleton, joint_map)
    P = motion.positions
    hips = P[:, roles["hips"]]
    left = P[:, roles["leftUpperLeg"]] - P[:, roles["rightUpperLeg"]]
    yaw = np.unwrap(np.arctan2(-left[:, 2], left[:, 0]))  # forward = left x up: (−l_z, 0, l_x) after a quarter turn
    path = _smooth(hips, motion.fps)
    path[:, 1] = 0.0
    return path, _smooth(yaw, motion.fps)


def _yaw(angles: np.ndarray) -> Rotation:
    return Rotation.from_euler("y", np.asarray(angles)[:, None])


def _hips_relative(motion: Motion, hips: int, path: np.ndarray, heading: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The hips' world position and rotation expressed in the path frame: ``(T, 3)``, ``(T, 4)``."""
    pose = motion.pose
    inv = _yaw(heading).inv()
    pos = inv.apply(pose.positions[:, hips] - path)
    rot = (inv * Rotation.from_matrix(pose.rotations[:, hips])).as_quat()
    return pos, unroll_quaternions(rot)


def root_motion(motion: Motion, joint_map: dict[str, str] | None = None) -> Motion:
    """``motion`` with its travel and heading on a root bone at the floor (see the module docstring)."""
    skel = motion.skeleton
    hips = hips_index(skel, joint_map)
    path, heading = path_and_heading(motion, joint_map)
    hip_pos, hip_rot = _hips_relative(motion, hips, path, heading)
    T = motion.n_frames
    root_rot = _yaw(heading).as_quat()
    if hips != 0:  # the rig's own root bone: it must sit directly above the hips
        if skel.parents[hips] != 0:
            raise ValueError(f"the hips {skel.names[hips]!r} do not hang from the root {skel.names[0]!r}")
        channels = list(skel.channels)
        if not skel.has_position_channels(0):
            channels[0] = POSITION_CHANNELS + tuple(c for c in channels[0] if c not in POSITION_CHANNELS)
        if not skel.has_position_channels(hips):
            channels[hips] = POSITION_CHANNELS + tuple(channels[hips])
        out_skel = Skeleton(skel.names, skel.parents, skel.offsets, skel.end_sites, tuple(channels))
        rots = motion.rotations.copy()
        rots[:, 0], rots[:, hips] = root_rot, hip_rot
        trans = motion.local_translations()
        trans[:, hips] = hip_pos
        return Motion(out_skel, motion.fps, path + skel.offsets[0], rots, trans)
    names = (ROOT_NAME,) + skel.names
    if ROOT_NAME in skel.names:
        raise ValueError(f"the skeleton already has a joint named {ROOT_NAME!r} that is not above its hips")
    parents = np.concatenate([[-1], skel.parents + 1])
    parents[1] = 0
    offsets = np.vstack([np.zeros(3), skel.offsets])
    offsets[1] = 0.0
    new_channels: tuple[tuple[str, ...], ...] = ((*POSITION_CHANNELS, "Zrotation", "Yrotation", "Xrotation"),)
    ends = tuple((j + 1, o) for j, o in skel.end_sites)
    out_skel = Skeleton(names, parents, offsets, ends, new_channels + skel.channels)
    rots = np.concatenate([root_rot[:, None], motion.rotations], axis=1)
    rots[:, 1] = hip_rot
    trans = np.concatenate([np.zeros((T, 1, 3)), motion.local_translations()], axis=1)
    trans[:, 1] = hip_pos
    return Motion(out_skel, motion.fps, path, rots, trans)


def in_place(motion: Motion, joint_map: dict[str, str] | None = None) -> Motion:
    """``motion`` with the hips' travel removed: they sway about the origin (their heading is kept)."""
    skel = motion.skeleton
    hips = hips_index(skel, joint_map)
    path, _ = path_and_heading(motion, joint_map)
    if hips == 0:
        root = motion.root_positions.copy()
        root[:, [0, 2]] -= path[:, [0, 2]]
        return motion.replace(root_positions=root)
    # a root bone above the hips: the hips' translation from it loses the path, in the root's frame
    parent = Rotation.from_matrix(motion.pose.rotations[:, skel.parents[hips]])
    trans = motion.local_translations()
    trans[:, hips] -= parent.inv().apply(path)
    return motion.replace(translations=trans)


def scaled(motion: Motion, k: float) -> Motion:
    """Every length of ``motion`` (offsets, root path, translations) times ``k``."""
    trans = None if motion.translations is None else motion.translations * k
    return Motion(motion.skeleton.scaled(k), motion.fps, motion.root_positions * k, motion.rotations, trans)


def _pose_features(motion: Motion) -> np.ndarray:
    """Joint positions relative to the root, in the root's heading frame, and their velocities, ``(T, F)``."""
    P = motion.positions
    rel = P - P[:, :1]
    vel = np.gradient(P, axis=0) * motion.fps if motion.n_frames > 1 else np.zeros_like(P)
    return np.concatenate([rel.reshape(len(P), -1), 0.1 * vel.reshape(len(P), -1)], axis=1)


def looped(motion: Motion, min_fraction: float = 0.5) -> Motion:
    """A loop of ``motion``: frames ``0 .. t*-1`` where frame ``t*`` (in the last ``1 - min_fraction`` of the clip)
    is the closest to frame 0 in pose and joint velocities; the difference between frame ``t*`` and frame 0
    (local rotations, root height) is removed progressively, ``k / t*`` of it at frame ``k``.

    Travel is kept: played in a loop, the hips carry on from where the last frame left them only with
    root motion or in place; the pose and its velocity flow from the last frame into the first.
    """
    T = motion.n_frames
    if T < 4:
        return motion
    feats = _pose_features(motion)
    first = int(np.ceil(min_fraction * T))
    cand = np.arange(max(first, 2), T)
    dist = np.linalg.norm(feats[cand] - feats[0], axis=1)
    t_star = int(cand[np.argmin(dist)])
    q0, qt = motion.rotations[0], motion.rotations[t_star]
    delta = Rotation.from_quat(qt.reshape(-1, 4)) * Rotation.from_quat(q0.reshape(-1, 4)).inv()  # (J) world-less delta
    w = np.arange(t_star) / t_star  # (t*)
    J = motion.skeleton.n_joints
    rotvec = delta.as_rotvec()  # (J, 3)
    corr = Rotation.from_rotvec((w[:, None, None] * rotvec[None]).reshape(-1, 3)).inv()
    rots = (corr * Rotation.from_quat(motion.rotations[:t_star].reshape(-1, 4))).as_quat().reshape(t_star, J, 4)
    root = motion.root_positions[:t_star].copy()
    root[:, 1] -= w * (motion.root_positions[t_star, 1] - motion.root_positions[0, 1])
    trans = None if motion.translations is None else motion.translations[:t_star]
    return Motion(motion.skeleton, motion.fps, root, unroll_quaternions(rots), trans)


__all__ = ["PATH_WINDOW", "ROOT_NAME", "in_place", "looped", "path_and_heading", "root_motion", "scaled"]
