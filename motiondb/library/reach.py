"""Hand reach targets: put a wrist exactly somewhere (clapping hands meet, a hand on the floor).

A clip may carry ``"reach": {"left": [KEY, ...], "right": [...]}`` with keys
``{"t": seconds, "at": [x, y, z], "w": weight, "frame": "root"|"world"}``:

- ``at``: the wrist target. In the ``root`` frame (default) ``x``/``z`` are
  metres from the root along the character's left and forward (its hips'
  heading at that time) and ``y`` is the height above the ground; in the
  ``world`` frame they are the clip's world coordinates (the clip starts at
  the origin facing +Z), for things that must not move with the body (an
  object on the floor). Keys with ``w`` 0 may omit ``at``.
- ``w`` (default 1): how much the IK result replaces the keyed arm,
  interpolated between keys (a track normally starts and ends at 0).
- ``pole`` (optional, same frame as ``at``): a point the elbow bends
  towards; without it the keyed elbow's bend plane is kept.

Targets and weights are interpolated like the joint curves (PCHIP slopes,
at rest on the first and last key: no overshoot), the arm solved with :func:`core.ik.arm_ik` keeping the keyed
elbow plane, and the shoulder and elbow rotations slerped from the keyed to
the solved ones by the weight.
"""
from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import body_map
from text2anim.core.ik import arm_ik
from text2anim.core.motion import Motion

from .keyframe_curves import interpolator
from .keyframes import ClipDataError


def _curve(t: np.ndarray, v: np.ndarray, times: np.ndarray) -> np.ndarray:
    """PCHIP through the keys, at rest on the first and last one (as the joint curves)."""
    return interpolator(t, v, "pchip", None)(times)


def _heading(motion: Motion) -> np.ndarray:
    """Yaw (radians) of the root's forward axis per frame."""
    fwd = Rotation.from_quat(motion.rotations[:, 0]).apply([0.0, 0.0, 1.0])
    return np.arctan2(fwd[:, 0], fwd[:, 2])


def apply_reach(motion: Motion, reach: dict, times: np.ndarray, where: str) -> Motion:
    """Apply a clip's ``reach`` tracks to ``motion`` sampled at ``times`` (seconds)."""
    if not reach:
        return motion
    bm = body_map(motion.skeleton)
    skel = motion.skeleton
    yaw = _heading(motion)
    cos, sin = np.cos(yaw), np.sin(yaw)
    out = motion
    for side, keys in reach.items():
        if side not in ("left", "right"):
            raise ClipDataError(f"{where}: reach side must be left or right, got {side!r}")
        if not keys:
            continue
        kt = np.array([float(k["t"]) for k in keys])
        if np.any(np.diff(kt) <= 0):
            raise ClipDataError(f"{where}: reach {side} key times must increase")
        kw = np.array([float(k.get("w", 1.0)) for k in keys])
        have = [i for i, k in enumerate(keys) if "at" in k]
        if not have:
            raise ClipDataError(f"{where}: reach {side} has no target")
        frames = {keys[i].get("frame", "root") for i in have}
        if len(frames) != 1 or not frames <= {"root", "world"}:
            raise ClipDataError(f"{where}: reach {side} must use one frame, root or world")
        frame = frames.pop()
        at = np.array([keys[i]["at"] for i in have], dtype=np.float64)
        target = _curve(kt[have], at, times)
        w = np.clip(_curve(kt, kw[:, None], times)[:, 0], 0.0, 1.0)
        with_pole = [i for i, k in enumerate(keys) if "pole" in k]
        pole = None
        if with_pole:
            pole = _curve(kt[with_pole], np.array([keys[i]["pole"] for i in with_pole], dtype=np.float64), times)
        if frame == "root":
            root = out.root_positions

            def to_world(local):
                world = np.empty_like(local)
                world[:, 0] = root[:, 0] + cos * local[:, 0] + sin * local[:, 2]
                world[:, 2] = root[:, 2] - sin * local[:, 0] + cos * local[:, 2]
                world[:, 1] = local[:, 1]
                return world

            target = to_world(target)
            pole = None if pole is None else to_world(pole)
        mask = w > 1e-6
        if not mask.any():
            continue
        solved = arm_ik(out, side, target, mask=mask, pole=pole)
        hand = bm.hands[side]
        elbow = int(skel.parents[hand])
        shoulder = int(skel.parents[elbow])
        rots = out.rotations.copy()
        for j in (shoulder, elbow):
            r0 = Rotation.from_quat(out.rotations[:, j])
            r1 = Rotation.from_quat(solved.rotations[:, j])
            rots[:, j] = (r0 * Rotation.from_rotvec((r0.inv() * r1).as_rotvec() * w[:, None])).as_quat()
        out = out.replace(rotations=rots)
    return out
