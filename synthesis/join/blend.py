"""Blending joint rotations by slerp, with per-frame (and per-joint) weights.

Every blend of the project goes through :func:`slerp`: for rotations ``A``
and ``B`` and a weight ``w`` it is ``A * exp(w * log(A^-1 B))`` computed
with :class:`scipy.spatial.transform.Rotation` (``as_rotvec`` returns the
shortest arc, so the blend never takes the long way round). That is the
spherical linear interpolation of paper 003 eq. (3) — the paper writes a
linear blend of angles, the project never blends Euler angles. It is
vectorised over any leading shape (frames, joints).

Weight profiles over a blend of ``n`` frames (:func:`ramp`):

- ``linear``: eq. (4), ``ratio = time / blend_duration``;
- ``smooth``: the quintic ``6u^5 - 15u^4 + 10u^3`` of the same ratio: zero
  first and second derivative at both ends, so a blend adds no velocity or
  acceleration step (no jerk spike) where it starts and stops.
"""
from __future__ import annotations

import numpy as np

from text2anim.core import rotkernels as rk
from text2anim.core.easing import smootherstep
from text2anim.core.motion import Motion

PROFILES = ("linear", "smooth")


def ratio(n: int) -> np.ndarray:
    """eq. (4): ``ratio = time / blend_duration`` for the ``n`` frames of a blend, ``(n,)``.

    The frames of the blend sit strictly between its two ends (frame ``k``
    at ``(k + 1) / (n + 1)``): the frame before the blend is all first
    motion (ratio 0), the one after all second motion (ratio 1).
    """
    return (np.arange(n, dtype=np.float64) + 1.0) / (n + 1.0)


def ease(u: np.ndarray, profile: str = "smooth") -> np.ndarray:
    """A weight profile applied to a ratio in ``[0, 1]``."""
    if profile == "linear":
        return np.clip(np.asarray(u, dtype=np.float64), 0.0, 1.0)
    if profile == "smooth":
        return smootherstep(u)
    raise ValueError(f"unknown blend profile {profile!r}; known: {', '.join(PROFILES)}")


def ramp(n: int, profile: str = "smooth") -> np.ndarray:
    """Weights of the second motion over an ``n``-frame blend, rising from 0 to 1, ``(n,)``."""
    return ease(ratio(n), profile)


def slerp(qa: np.ndarray, qb: np.ndarray, w) -> np.ndarray:
    """Spherical interpolation of quaternions ``(..., 4)`` (x, y, z, w); ``w`` broadcasts to ``qa.shape[:-1]``.

    ``w = 0`` gives ``qa``, ``w = 1`` gives ``qb`` (as rotations; the sign of
    the quaternion may differ).
    """
    qa = np.asarray(qa, dtype=np.float64)
    qb = np.asarray(qb, dtype=np.float64)
    shape = np.broadcast_shapes(qa.shape, qb.shape)
    w = np.broadcast_to(np.asarray(w, dtype=np.float64), shape[:-1])
    if int(np.prod(shape[:-1])) == 0:
        return np.zeros(shape)
    # A * exp(w log(A^-1 B)) by scipy's own kernels, without Rotation objects (the same bits, less overhead)
    ra = rk.from_quat(np.broadcast_to(qa, shape))
    rb = rk.from_quat(np.broadcast_to(qb, shape))
    rel = rk.as_rotvec(rk.compose(rk.inverse(ra), rb))
    return rk.as_quat(rk.compose(ra, rk.from_rotvec(rel * w.reshape(-1, 1)))).reshape(shape)


def lerp(a: np.ndarray, b: np.ndarray, w) -> np.ndarray:
    """Linear interpolation of ``(..., k)`` arrays with weights broadcasting to ``a.shape[:-1]``."""
    w = np.asarray(w, dtype=np.float64)[..., None]
    return (1.0 - w) * a + w * b


def blend(a: Motion, b: Motion, w) -> Motion:
    """Frame-by-frame blend of two equally long motions of one skeleton.

    ``w`` is ``(T,)`` (the same weight for every joint) or ``(T, J)`` (per
    joint; the root position follows joint 0's weight). Root positions are
    interpolated linearly, rotations by :func:`slerp`.
    """
    if a.n_frames != b.n_frames:
        raise ValueError(f"cannot blend {a.n_frames} frames with {b.n_frames}")
    T, J = a.n_frames, a.skeleton.n_joints
    w = np.asarray(w, dtype=np.float64)
    wj = np.broadcast_to(w[:, None] if w.ndim == 1 else w, (T, J))
    root = lerp(a.root_positions, b.root_positions, wj[:, 0])
    rots = slerp(a.rotations, b.rotations, wj)
    return Motion(a.skeleton, a.fps, root, rots)


def sample(motion: Motion, frames, origin: int = 0) -> Motion:
    """The motion at fractional frame positions ``(K,)`` (clamped to its range): lerp/slerp between neighbours.

    This is the time warp of a blend: a clip played faster, slower or
    unevenly, e.g. the cycle of a walk stretched onto the cycle of a run.

    ``origin``: ``motion`` is the window of a longer track starting at that frame, and ``frames`` are the
    track's positions: the fractions are those of the track's positions, bit for bit (``47.3 - 47`` is not
    ``52.3 - 52``).
    """
    i0, i1, u = neighbours(frames, motion.n_frames, origin)
    root = lerp(motion.root_positions[i0], motion.root_positions[i1], u)
    rots = slerp(motion.rotations[i0], motion.rotations[i1], np.broadcast_to(u[:, None], (len(u), motion.skeleton.n_joints)))
    trans = None
    if motion.translations is not None:
        trans = lerp(motion.translations[i0], motion.translations[i1], np.broadcast_to(u[:, None], (len(u), motion.skeleton.n_joints)))
    return Motion(motion.skeleton, motion.fps, root, rots, trans)


def sample_path(path: np.ndarray, frames, origin: int = 0) -> np.ndarray:
    """The root positions of :func:`sample` (bit for bit) from a motion's root positions ``path`` ``(T, 3)`` alone:
    ``(K, 3)`` at the fractional frame positions ``frames`` ``(K,)``."""
    i0, i1, u = neighbours(frames, len(path), origin)
    return lerp(path[i0], path[i1], u)


def neighbours(frames, n: int, origin: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(i0, i1, u)`` ``(K,)`` each: the frames (of ``n``, the window's from ``origin``) either side of each of the
    track's positions ``frames`` (clamped to the window), and the fraction between them (:func:`sample`)."""
    f = np.clip(np.asarray(frames, dtype=np.float64), origin, origin + n - 1)
    i0 = np.floor(f).astype(int)
    u = f - i0
    i0 -= origin
    return i0, np.minimum(i0 + 1, n - 1), u


def blend_parts(base: Motion, other: Motion, joints, w) -> Motion:
    """``base`` with the rotations of ``joints`` blended towards ``other``'s by weights ``(T,)``.

    The body-part switch of a composition (paper 003 eq. (3) with slerp);
    the root position is left to ``base`` unless joint 0 is among ``joints``.
    """
    T, J = base.n_frames, base.skeleton.n_joints
    wj = np.zeros((T, J))
    wj[:, list(joints)] = np.asarray(w, dtype=np.float64)[:, None]
    if 0 not in set(joints):
        other = other.replace(root_positions=base.root_positions)
    return blend(base, other, wj)
