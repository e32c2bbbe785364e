"""Turning a motion on its way, about the foot on the floor: :func:`steer`.

A person who walks towards someone who is not straight ahead turns over a few steps: each step lands a
little further round while the foot on the floor stays where it is. :func:`steer` does that to a motion:
between two frames it turns the rest of the motion by an angle about +Y in small shares, each frame's
share about the point the body stands on then (the planted foot; both feet's middle, which share the
turn; the hips while in the air), so a planted foot stays where it is and the hips' path bends. Only the root moves (its position and
its world rotation); every joint keeps its local rotation. Frames before ``start`` are unchanged, frames
from ``end`` on are turned by the whole angle.
"""
from __future__ import annotations

import numpy as np

from . import rotkernels as rk
from .bodyparts import body_map
from .contacts import detect_contacts
from .motion import Motion

_UP = np.array([0.0, 1.0, 0.0])


def steer(motion: Motion, start: int, end: int, angle: float) -> Motion:
    """``motion`` turned by ``angle`` rad about +Y over frames ``[start, end)`` (smoothstep shares, each about
    the foot on the floor at its frame) and by the whole angle after; the frames before ``start`` unchanged."""
    n = motion.n_frames
    start = int(np.clip(start, 0, n))
    end = int(np.clip(end, start + 1, n + 1))
    if angle == 0.0 or start >= n:
        return motion
    u = np.clip((np.arange(n) - start + 1) / (end - start), 0.0, 1.0)
    yaw = angle * u * u * (3.0 - 2.0 * u)  # the whole turn at each frame, (T,)
    delta = np.diff(yaw, prepend=0.0)
    # Frame k is turned by yaw[k] about the origin, then moved by shift[k]. Its share delta[k] turns about
    # its pivot p_k where the turn so far put it, P = R(yaw[k-1]) p_k + shift[k-1]; so
    # shift[k] = R(delta[k]) (shift[k-1] - P) + P = shift[k-1] + (I - R(delta[k])) R(yaw[k-1]) p_k: a running sum.
    so_far = _turn_all(_standing_points(motion), yaw - delta)
    step = so_far - _turn_all(so_far, delta)
    step[delta == 0.0] = 0.0
    shift = np.cumsum(step, axis=0)
    root = _turn_all(np.asarray(motion.root_positions, dtype=float), yaw) + shift
    rots = np.array(motion.rotations, dtype=float)
    turned = yaw != 0.0  # the frames before the turn keep their bits
    rots[turned, 0] = rk.as_quat(rk.compose(rk.from_rotvec(np.multiply.outer(yaw[turned], _UP)),
                                            rk.from_quat(rots[turned, 0])))
    return motion.replace(root_positions=root, rotations=rots)


def _turn_all(points: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Points ``(T, 3)`` each turned by its angle ``(T,)`` about the +Y axis through the origin (+Z towards +X)."""
    c, s = np.cos(angles), np.sin(angles)
    return np.stack([c * points[:, 0] + s * points[:, 2], points[:, 1], -s * points[:, 0] + c * points[:, 2]], axis=1)


def _standing_points(motion: Motion) -> np.ndarray:
    """Per frame, the point the body turns about ``(T, 3)``: the planted foot (ankle and toe's middle), both
    feet's middle when both are down, the hips when none is."""
    bm = body_map(motion.skeleton)
    contacts = detect_contacts(motion)
    pos = motion.positions
    feet = {side: pos[:, list(bm.feet[side])].mean(axis=1) for side in ("left", "right")}
    left, right = contacts.left[:, None], contacts.right[:, None]
    both = 0.5 * (feet["left"] + feet["right"])
    return np.where(left & right, both, np.where(left, feet["left"], np.where(right, feet["right"],
                                                                                motion.root_positions)))
