"""Where a character faces, and the rigid ground-plane moves that place motions.

A :class:`Rigid` is a yaw about the world +Y axis followed by a horizontal translation: the one kind of
move that places a motion on the ground without changing it (synthesis joins clips through the support
foot with it, paper 003 §4.3; the scene puts a whole actor where the text wants them). Heights are never
changed (every motion stands on the same floor, y = 0).

Heading convention (the project's): radians about +Y, 0 faces +Z, so a
heading ``h`` faces ``(sin h, 0, cos h)``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import uniform_filter1d
from scipy.spatial.transform import Rotation

from . import rotkernels as rk
from .bodyparts import body_map
from .motion import Motion
from .skeleton import Skeleton

_UP = np.array([0.0, 1.0, 0.0])


def wrap_angle(a):
    """Angles mapped to ``(-pi, pi]``."""
    return np.pi - np.mod(np.pi - np.asarray(a, dtype=np.float64), 2 * np.pi)


def rest_forward(skeleton: Skeleton) -> np.ndarray:
    """The direction the rest pose faces, in the root's frame (unit, horizontal), ``(3,)``.

    From the legs: ``left - right`` is the character's left, and forward is
    ``left x up`` (right-handed, Y up). A CMU-like skeleton gives ``+Z``.
    Computed once per skeleton (kept in :attr:`Skeleton.derived`); a copy of it is returned.
    """
    return skeleton.derived.get("rest_forward", lambda: _rest_forward(skeleton)).copy()


def _rest_forward(skeleton: Skeleton) -> np.ndarray:
    bm = body_map(skeleton)
    rest = skeleton.rest_positions()
    across = rest[list(bm.joints("left_leg"))].mean(axis=0) - rest[list(bm.joints("right_leg"))].mean(axis=0)
    fwd = np.cross(across, _UP)
    fwd[1] = 0.0
    n = np.linalg.norm(fwd)
    return fwd / n if n > 1e-9 else np.array([0.0, 0.0, 1.0])


def root_headings(motion: Motion) -> np.ndarray:
    """The root's own facing angle per frame (radians about +Y, 0 faces +Z), ``(T,)`` read-only, not
    smoothed: Kovar aligns each pose by its root's yaw. Computed once per motion, kept in its cache (a
    join's search asks for the same clip's features many times)."""
    return motion.cache.get("root_headings", lambda: _root_headings(motion))


def _root_headings(motion: Motion) -> np.ndarray:
    fwd = rk.apply(rk.from_quat(motion.rotations[:, 0]), rest_forward(motion.skeleton))  # Rotation's bits
    h = np.arctan2(fwd[:, 0], fwd[:, 2])
    h.setflags(write=False)
    return h


def headings(motion: Motion, smooth: float = 0.0) -> np.ndarray:
    """Facing angle per frame, ``(T,)`` radians, unwrapped (continuous across ±pi), read-only.

    The rest pose's forward direction carried by the root's world rotation,
    projected on the ground. ``smooth`` (seconds) averages it over a window,
    which removes the pelvis' own swing in gait (±5-10 degrees per step).
    Computed once per motion and ``smooth``, kept in the motion's cache (a join asks for the track's and
    the next clip's headings several times).
    """
    return motion.cache.get(("headings", smooth), lambda: _headings(motion, smooth))


def _headings(motion: Motion, smooth: float) -> np.ndarray:
    if motion.n_frames == 0:
        h = np.zeros(0)
    else:
        h = np.unwrap(root_headings(motion))
        n = int(round(smooth * motion.fps))
        if n > 1:
            h = uniform_filter1d(h, size=n, mode="nearest")
    h.setflags(write=False)
    return h


def yaw_rotation(yaw) -> Rotation:
    """Rotation(s) by ``yaw`` radians about +Y."""
    yaw = np.asarray(yaw, dtype=np.float64)
    return Rotation.from_rotvec(np.multiply.outer(yaw, _UP))


def _yaw_quat(yaw: float) -> np.ndarray:
    """:func:`yaw_rotation` of one angle as a quaternion stack ``(1, 4)`` (:mod:`core.rotkernels`)."""
    return rk.from_rotvec(float(yaw) * _UP)


def to_heading_frame(vectors: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """World vectors ``(T, ..., 3)`` expressed in the frame turned by ``-heading`` ``(T,)``: +Z is forward."""
    c, s = np.cos(heading), np.sin(heading)
    shape = (len(heading),) + (1,) * (vectors.ndim - 2)
    c, s = c.reshape(shape), s.reshape(shape)
    x, y, z = vectors[..., 0], vectors[..., 1], vectors[..., 2]
    return np.stack([c * x - s * z, y, s * x + c * z], axis=-1)


@dataclass(frozen=True)
class Rigid:
    """A yaw about +Y (radians) then a horizontal translation ``offset`` (x, z metres)."""

    yaw: float = 0.0
    offset: tuple[float, float] = (0.0, 0.0)

    @property
    def translation(self) -> np.ndarray:
        return np.array([self.offset[0], 0.0, self.offset[1]])

    def rotation(self) -> Rotation:
        return yaw_rotation(self.yaw)

    def apply_points(self, points: np.ndarray) -> np.ndarray:
        """Move world points ``(..., 3)``."""
        p = np.array(points, dtype=np.float64)  # a copy: scipy wants a writable buffer
        return rk.apply(_yaw_quat(self.yaw), p.reshape(-1, 3)).reshape(p.shape) + self.translation

    def apply(self, motion: Motion) -> Motion:
        """The motion moved rigidly: root positions and the root's world rotation change."""
        if self.yaw == 0.0 and self.offset == (0.0, 0.0):
            return motion
        rots = motion.rotations.copy()
        if len(rots):  # yaw * root rotation, as Rotation composes them
            rots[:, 0] = rk.as_quat(rk.compose(_yaw_quat(self.yaw), rk.from_quat(rots[:, 0])))
        return motion.replace(root_positions=self.apply_points(motion.root_positions), rotations=rots)

    def then(self, other: "Rigid") -> "Rigid":
        """``other`` after ``self``."""
        t = other.apply_points(self.translation)
        return Rigid(float(self.yaw + other.yaw), (float(t[0]), float(t[2])))

    def inverse(self) -> "Rigid":
        t = yaw_rotation(-self.yaw).apply(self.translation)
        return Rigid(-self.yaw, (float(-t[0]), float(-t[2])))


def match(point: np.ndarray, heading: float, to_point: np.ndarray, to_heading: float) -> Rigid:
    """The :class:`Rigid` that turns ``heading`` into ``to_heading`` and puts ``point`` over ``to_point``.

    Only the ground-plane (x, z) coordinates of the points matter.
    """
    yaw = float(wrap_angle(to_heading - heading))
    p = rk.apply(_yaw_quat(yaw), np.asarray(point, dtype=np.float64))[0]  # yaw_rotation(yaw).apply's bits
    return Rigid(yaw, (float(to_point[0] - p[0]), float(to_point[2] - p[2])))
