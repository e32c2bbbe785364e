"""Inertialization: an offset between two motions decays to zero with continuous velocity.

A join switches from the outgoing motion ``A`` to the incoming ``B`` at a
frame ``s``; where ``A``'s state at ``s`` (extrapolated from its last two
frames) differs from ``B``'s, the difference ``x0`` and its rate ``v0`` are
added onto ``B`` and made to decay, so position *and* velocity carry over:
``out(s + t) = B(s + t) + x(t)`` with ``x(0) = x0``, ``x'(0) = v0``.

Two decays, both vectorised over any trailing shape (joints, axes):

- :func:`quintic` — Bollo, "Inertialization: High-Performance Animation
  Transitions in Gears of War" (GDC 2018): the quintic with ``x(0) = x0``,
  ``x'(0) = v0``, ``x''(0) = a0`` and ``x = x' = x'' = 0`` at ``t1``; the
  talk's ``a0 = (-8 v0 t1 - 20 x0) / t1²`` (its velocity clamp is left out:
  here the velocity must carry over exactly, eq. numbers are the talk's slide
  order (B1)–(B3)). It reaches zero at a known time, so a join's region is finite.
- :func:`spring` — Holden, "Dead Blending" / "Spring-It-On" (theorangeduck.com):
  the critically damped spring ``x(t) = e^{-yt} (x0 + (v0 + y x0) t)`` with
  ``y = 2 ln 2 / halflife``, the closed form of his ``decay_spring_implicit``.

Rotations are offset as quaternions ``(x, y, z, w)``: the offset rotation
``dq = q_A q_B^-1`` is decayed in its rotation-vector form and applied in front
of ``B``'s (:func:`inertialize_at`). Units: seconds, metres, radians.
"""
from __future__ import annotations

import numpy as np

from text2anim.core import rotkernels as rk
from text2anim.core.motion import Motion, unroll_quaternions


def quintic(x0: np.ndarray, v0: np.ndarray, t: np.ndarray, t1: float) -> np.ndarray:
    """Bollo's decaying offset at times ``t`` (s, ``(N,)``): ``(N,) + x0.shape``; zero from ``t1`` on.

    ``x0`` (offset) and ``v0`` (its rate per second) have the same shape.
    """
    x0 = np.asarray(x0, dtype=np.float64)
    v0 = np.asarray(v0, dtype=np.float64)
    t1 = max(float(t1), 1e-6)
    a0 = (-8.0 * v0 * t1 - 20.0 * x0) / t1 ** 2  # (B1)
    A = -(a0 * t1 ** 2 + 6.0 * v0 * t1 + 12.0 * x0) / (2.0 * t1 ** 5)  # (B2)
    B = (3.0 * a0 * t1 ** 2 + 16.0 * v0 * t1 + 30.0 * x0) / (2.0 * t1 ** 4)
    C = -(3.0 * a0 * t1 ** 2 + 12.0 * v0 * t1 + 20.0 * x0) / (2.0 * t1 ** 3)
    tt = np.clip(np.asarray(t, dtype=np.float64), 0.0, t1).reshape((-1,) + (1,) * x0.ndim)
    return ((((A * tt + B) * tt + C) * tt + 0.5 * a0) * tt + v0) * tt + x0  # (B3)


def spring(x0: np.ndarray, v0: np.ndarray, t: np.ndarray, halflife: float) -> np.ndarray:
    """Holden's critically damped decay of an offset at times ``t`` (s): ``(N,) + x0.shape``."""
    x0 = np.asarray(x0, dtype=np.float64)
    v0 = np.asarray(v0, dtype=np.float64)
    y = 2.0 * np.log(2.0) / max(float(halflife), 1e-6)
    tt = np.maximum(np.asarray(t, dtype=np.float64), 0.0).reshape((-1,) + (1,) * x0.ndim)
    return np.exp(-y * tt) * (x0 + (v0 + y * x0) * tt)


def offsets_at(motion: Motion, s: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The jump at frame ``s`` (``2 <= s < T - 1``): root ``(x0, v0)`` ``(3,)`` and rotation ``(x0, v0)``
    ``(J, 3)`` as rotation vectors, between frames ``< s`` continued by their last velocity and frames ``>= s``.

    ``x0``: where the continued motion would be at ``s`` minus where it is; ``v0``: the continued
    velocity minus the velocity leaving ``s`` (per second).
    """
    fps = motion.fps
    p = motion.root_positions
    q = unroll_quaternions(motion.rotations[s - 2:s + 2])
    r = rk.from_quat(q.reshape(-1, 4))  # Rotation's arithmetic without its objects (the same bits)
    J = motion.skeleton.n_joints
    rots = [r[k * J:(k + 1) * J] for k in range(4)]  # frames s-2, s-1, s, s+1
    w_in = rk.compose(rk.inverse(rots[0]), rots[1])  # local step s-2 -> s-1 (body frame)
    w_out = rk.compose(rk.inverse(rots[2]), rots[3])
    pred = rk.compose(rots[1], w_in)  # s continued
    back = rk.inverse(rots[2])
    rx0 = rk.as_rotvec(rk.compose(pred, back))  # offset in front of B's rotation
    turn = rk.from_rotvec(rk.as_rotvec(w_in) - rk.as_rotvec(w_out))
    rv0 = rk.as_rotvec(rk.compose(rk.compose(rots[2], turn), back)) * fps
    px0 = 2.0 * p[s - 1] - p[s - 2] - p[s]
    pv0 = ((p[s - 1] - p[s - 2]) - (p[s + 1] - p[s])) * fps
    return px0, pv0, rx0, rv0


def inertialize_at(motion: Motion, s: int, duration: float, joints=None) -> Motion:
    """``motion`` with the velocity (and position) jump at frame ``s`` carried over and decayed by
    :func:`quintic` over ``duration`` seconds (root position and the local rotations of ``joints``,
    default all). Frames before ``s`` are unchanged; nothing happens where ``s`` is too near an end."""
    T = motion.n_frames
    if not 2 <= s < T - 1:
        return motion
    px0, pv0, rx0, rv0 = offsets_at(motion, s)
    n = min(T - s, int(np.ceil(duration * motion.fps)) + 1)
    t = np.arange(n) / motion.fps
    dp = quintic(px0, pv0, t, duration)  # (n, 3)
    dr = quintic(rx0, rv0, t, duration)  # (n, J, 3)
    J = motion.skeleton.n_joints
    sel = np.arange(J) if joints is None else np.asarray(list(joints), dtype=int)
    mask = np.zeros(J, dtype=bool)
    mask[sel] = True
    dr[:, ~mask] = 0.0
    rots = motion.rotations.copy()
    cur = rk.from_quat(rots[s:s + n].reshape(-1, 4))
    rots[s:s + n] = rk.as_quat(rk.compose(rk.from_rotvec(dr.reshape(-1, 3)), cur)).reshape(n, J, 4)
    root = motion.root_positions.copy()
    root[s:s + n] += dp
    return motion.replace(root_positions=root, rotations=rots)


def _reversed(motion: Motion) -> Motion:
    return motion.replace(root_positions=motion.root_positions[::-1].copy(), rotations=motion.rotations[::-1].copy())


def inertialize_before(motion: Motion, s: int, duration: float, joints=None) -> Motion:
    """:func:`inertialize_at` backwards in time: the frames *before* ``s`` take the offset, decaying over
    ``duration`` s into the past, so that they arrive at frame ``s`` with its own velocity; frames from ``s``
    on are unchanged (a blend that must hand over to a core it may not touch)."""
    T = motion.n_frames
    if not 2 <= T - s < T - 1:
        return motion
    return _reversed(inertialize_at(_reversed(motion), T - s, duration, joints))
