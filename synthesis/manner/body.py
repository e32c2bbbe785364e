"""The body a manner modifier works on: its joints by part, its axes frame by frame, and turns about them.

Shapes: ``T`` frames; axes ``(T, 3)`` unit world vectors (:mod:`core.body_axes`); quaternions ``(T, 4)``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from text2anim.core import quat
from text2anim.core.body_axes import UP, body_axes
from text2anim.core.bodyparts import BodyMap, body_map
from text2anim.core.motion import Motion

__all__ = ["UP", "Body", "about", "turned"]


@dataclass(frozen=True)
class Body:
    """A motion's body map and its axes per frame (:func:`core.body_axes.body_axes`)."""

    map: BodyMap
    lateral: np.ndarray
    forward: np.ndarray

    @staticmethod
    def of(motion: Motion) -> "Body":
        bm = body_map(motion.skeleton)
        return Body(bm, *body_axes(motion, bm))


def about(axis: np.ndarray, degrees: float | np.ndarray) -> np.ndarray:
    """Quaternions ``(T, 4)`` rotating by ``degrees`` (a number or ``(T,)``) about the unit world ``axis`` ``(T, 3)``."""
    half = np.radians(np.broadcast_to(np.asarray(degrees, dtype=np.float64), axis.shape[:1])) / 2.0
    return np.concatenate([axis * np.sin(half)[:, None], np.cos(half)[:, None]], axis=1)


def turned(motion: Motion, rotations: np.ndarray, joint: int, world: np.ndarray) -> None:
    """Turn ``joint`` (and what hangs from it) by the world rotations ``world`` ``(T, 4)``, writing its local
    rotation into ``rotations`` ``(T, J, 4)``: ``local' = parent⁻¹ · world · parent · local``, the parent's world
    rotation taken from ``motion`` as it was (so turns of a chain add up)."""
    parent = motion.skeleton.parents[joint]
    p = motion.pose.quaternions(int(parent)) if parent >= 0 else np.tile([0.0, 0.0, 0.0, 1.0], (motion.n_frames, 1))
    rotations[:, joint] = quat.multiply(quat.conjugate(p), quat.multiply(world, quat.multiply(p, rotations[:, joint])))
