"""Analytic two-bone inverse kinematics (legs and arms), vectorised over frames.

A two-bone chain is ``(upper, middle, end)``: hip, knee, ankle or shoulder,
elbow, wrist, each joint the parent of the next. :func:`two_bone_ik` changes
the local rotations of ``upper`` and ``middle`` so that ``end`` lands on a
world target, in three steps per frame:

1. **Bend.** The middle joint turns about its *hinge* axis (the axis fixed
   in the upper bone about which a positive rotation flexes it: ``+X`` for a
   knee of the canonical skeleton) until the distance upper→end equals the
   distance upper→target. Of the two solutions the one on the flexion side
   is taken, so a knee never bends backwards. Its other rotation components
   (twist, side tilt) are kept.
2. **Aim.** The upper joint turns by the shortest arc that points the
   upper→end line at the target.
3. **Twist.** The upper joint turns about the upper→target line so that the
   middle joint lies in the plane through upper, target and the *pole*
   (default: where the middle joint was, i.e. the bend plane is kept).

A target farther than the chain's length gives a straight chain pointing at
it; a target nearer than ``|l1 - l2|`` gives a fully folded one: never NaN.

Shapes: ``T`` frames; targets ``(T, 3)`` world metres; masks ``(T,)`` bool;
quaternions ``(x, y, z, w)`` (scipy order). The end joint's *local*
rotation is left as it was (so its world orientation follows the chain);
:func:`set_world_rotation` then orients it, e.g. a foot flat on the ground.
"""
from __future__ import annotations

import numpy as np

from . import rotkernels as rk
from .bodyparts import body_map
from .motion import Motion

_EPS = 1e-12


def _norm(v: np.ndarray, keepdims: bool = False) -> np.ndarray:
    """``np.linalg.norm(v, axis=-1)``: its arithmetic (the sum of squares along the last axis, square
    root) without its checks, which cost more than the sum on a join's few frames."""
    squares = np.add.reduce(v * v, axis=-1, keepdims=True) if keepdims else np.add.reduce(v * v, axis=-1)
    return np.sqrt(squares)


def _sum(v: np.ndarray, axis: int = -1) -> np.ndarray:
    """``np.sum(v, axis)``: the reduction it calls (``np.add.reduce``), without its wrapper's dispatch."""
    return np.add.reduce(v, axis=axis)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.cross`` of 3-vectors ``(..., 3)``, each component as it computes it (``a1 b2 - a2 b1``, ...)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def _unit(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    n = _norm(v, keepdims=True)
    return v / np.maximum(n, _EPS), n[..., 0]


def _joint(motion: Motion, j) -> int:
    return motion.skeleton.index(j) if isinstance(j, str) else int(j)


def _rows(a, T: int, what: str) -> np.ndarray:
    arr = np.asarray(a, dtype=np.float64)
    if arr.shape == (3,):
        return np.broadcast_to(arr, (T, 3)).copy()
    if arr.shape != (T, 3):
        raise ValueError(f"{what} must be (3,) or ({T}, 3), got {arr.shape}")
    return arr


def _shortest_arc(src: np.ndarray, dst: np.ndarray) -> np.ndarray:
    """Rotations ``(T, 4)`` (:mod:`core.rotkernels` stacks) turning unit vectors ``src`` onto unit vectors ``dst``
    by the shortest arc."""
    axis = _cross(src, dst)
    s = _norm(axis)
    c = _sum(src * dst, axis=-1)
    angle = np.arctan2(s, c)
    # Antiparallel vectors: any axis perpendicular to src will do.
    anti = s < 1e-9
    if anti.any():
        alt = _cross(src[anti], np.array([1.0, 0.0, 0.0]))
        bad = _norm(alt) < 1e-6
        alt[bad] = _cross(src[anti][bad], np.array([0.0, 1.0, 0.0]))
        axis[anti] = alt
    axis, _ = _unit(axis)
    return rk.from_rotvec(axis * angle[:, None])


def solve_rows(a: np.ndarray, b: np.ndarray, c: np.ndarray, Ra: np.ndarray, Rb: np.ndarray, Rp: np.ndarray,
               targets: np.ndarray, poles: np.ndarray, hinge=(1.0, 0.0, 0.0)) -> tuple[np.ndarray, np.ndarray]:
    """:func:`two_bone_ik` 's arithmetic on rows: each row a chain on one frame, rows independent (so the
    chains of both legs, or of several frame ranges, are solved in one call with the same bits).

    Args:
        a, b, c: ``(N, 3)`` world positions of the upper, middle and end joints.
        Ra, Rb, Rp: ``(N, 3, 3)`` world rotations of the upper and middle joints and of the upper's parent.
        targets, poles: ``(N, 3)`` world positions for the end joint and for the middle joint to bend towards.
        hinge: the middle joint's flexion axis in the upper bone's frame, ``(3,)``.

    Returns:
        The new local rotations of the upper and middle joints, quaternions ``(N, 4)`` each.
    """
    # 1. Bend about the hinge (fixed in the upper bone) to get the right reach.
    n, _ = _unit(np.einsum("tij,j->ti", Ra, np.asarray(hinge, dtype=np.float64)))
    w = b - a
    v = c - b
    l1 = _norm(w)
    l2 = _norm(v)
    d = _norm(targets - a)
    n_dot_v = _sum(n * v, axis=-1)
    v_par = n * n_dot_v[:, None]
    v_perp = v - v_par
    n_x_v = _cross(n, v)
    p_ = _sum(w * v_par, axis=-1)
    q_ = _sum(w * v_perp, axis=-1)
    s_ = _sum(w * n_x_v, axis=-1)
    k_ = (d ** 2 - l1 ** 2 - l2 ** 2) / 2.0
    r_ = np.hypot(q_, s_)
    psi = np.arctan2(s_, q_)  # the rotation that straightens the chain as far as the hinge allows
    cos_arg = np.minimum(np.maximum((k_ - p_) / np.maximum(r_, _EPS), -1.0), 1.0)  # np.clip's values
    phi = psi + np.arccos(cos_arg)  # flexion side of the straight configuration
    phi = (phi + np.pi) % (2 * np.pi) - np.pi
    bend = rk.from_rotvec(n * phi[:, None])
    Rb_bent = rk.as_matrix(bend) @ Rb
    c_bent = b + rk.apply(bend, v)

    # 2. Aim: upper->end onto upper->target.
    aim_dir, aim_len = _unit(targets - a)
    degenerate = aim_len < 1e-9
    if degenerate.any():  # target on the upper joint: keep the current direction
        aim_dir[degenerate] = _unit(c_bent - a)[0][degenerate]
    q1 = _shortest_arc(_unit(c_bent - a)[0], aim_dir)

    # 3. Twist about the aim line so the middle joint faces the pole.
    b1 = a + rk.apply(q1, w)
    p1 = b1 - a
    p2 = poles - a
    p1 = p1 - aim_dir * _sum(p1 * aim_dir, axis=-1)[:, None]
    p2 = p2 - aim_dir * _sum(p2 * aim_dir, axis=-1)[:, None]
    ok = (_norm(p1) > 1e-6) & (_norm(p2) > 1e-6)
    twist = np.arctan2(_sum(aim_dir * _cross(p1, p2), axis=-1), _sum(p1 * p2, axis=-1))
    twist = np.where(ok, twist, 0.0)
    q2 = rk.from_rotvec(aim_dir * twist[:, None])
    G = rk.as_matrix(rk.compose(q2, q1))

    Ra_new = G @ Ra
    local_a = np.swapaxes(Rp, -1, -2) @ Ra_new
    local_b = np.swapaxes(Ra, -1, -2) @ Rb_bent  # G cancels: R_a'^T (G R_b') = R_a^T R_b'
    q = rk.as_quat(rk.from_matrix(np.concatenate([local_a, local_b])))  # one conversion: rows are independent
    return q[:len(local_a)], q[len(local_a):]


def two_bone_ik(motion: Motion, chain, targets, mask=None, pole=None, hinge=(1.0, 0.0, 0.0)) -> Motion:
    """Rotate ``chain``'s upper and middle joints so its end joint reaches ``targets``.

    Args:
        motion: the motion to edit (not modified).
        chain: ``(upper, middle, end)`` joint names or indices, each the parent
            of the next (``("LeftUpLeg", "LeftLeg", "LeftFoot")``).
        targets: ``(T, 3)`` (or ``(3,)``) world positions for the end joint, metres.
        mask: ``(T,)`` bool, the frames to solve; others are returned unchanged.
            ``None`` solves every frame.
        pole: ``None``, ``(3,)`` or ``(T, 3)`` world points the middle joint
            should bend towards (a point in front of the knee). ``None`` keeps
            the current bend plane (the current middle joint is the pole).
        hinge: the middle joint's flexion axis in the upper bone's frame
            (positive rotation about it flexes). Knee of the canonical (CMU-like)
            skeleton: ``(1, 0, 0)``; left elbow ``(0, -1, 0)``, right ``(0, 1, 0)``.

    Returns:
        A new :class:`Motion`; only the local rotations of upper and middle change.
    """
    skel = motion.skeleton
    T = motion.n_frames
    a_j, b_j, c_j = (_joint(motion, j) for j in chain)
    if skel.parents[b_j] != a_j or skel.parents[c_j] != b_j:
        raise ValueError(f"{[skel.names[j] for j in (a_j, b_j, c_j)]} is not a parent-child chain")
    mask = np.ones(T, dtype=bool) if mask is None else np.asarray(mask, dtype=bool).reshape(T)
    if T == 0 or not mask.any():
        return motion
    targets = _rows(targets, T, "targets")[mask]
    idx = np.flatnonzero(mask)

    pose = motion.pose
    P, R = pose.positions[idx], pose.rotations[idx]
    parent = skel.parents[a_j]
    Rp = R[:, parent] if parent >= 0 else np.broadcast_to(np.eye(3), R[:, a_j].shape)
    poles = P[:, b_j].copy() if pole is None else _rows(pole, T, "pole")[mask]
    qa, qb = solve_rows(P[:, a_j], P[:, b_j], P[:, c_j], R[:, a_j], R[:, b_j], Rp, targets, poles, hinge)

    rots = motion.rotations.copy()
    rots[idx, a_j] = qa
    rots[idx, b_j] = qb
    return motion.replace(rotations=rots)


def set_world_rotation(motion: Motion, joint, rotations, mask=None) -> Motion:
    """Set ``joint``'s local rotation so its *world* rotation is ``rotations`` (``(T, 4)`` quats)."""
    j = _joint(motion, joint)
    T = motion.n_frames
    mask = np.ones(T, dtype=bool) if mask is None else np.asarray(mask, dtype=bool).reshape(T)
    if T == 0 or not mask.any():
        return motion
    q = np.asarray(rotations, dtype=np.float64).reshape(T, 4)[mask]
    p = motion.skeleton.parents[j]
    rots = motion.rotations.copy()
    rots[mask, j] = world_to_local(motion.pose.rotations[mask, p] if p >= 0 else None, q)
    return motion.replace(rotations=rots)


def world_to_local(parent: np.ndarray | None, world: np.ndarray) -> np.ndarray:
    """Local rotations ``(N, 4)`` that give a joint the world rotations ``world`` (quaternions ``(N, 4)``)
    under its parent's world rotations ``parent`` (matrices ``(N, 3, 3)``; ``None`` for the root): rows
    independent, :func:`set_world_rotation` 's arithmetic."""
    q = rk.from_quat(world)
    return rk.as_quat(q if parent is None else rk.compose(rk.inverse(rk.from_matrix(parent)), q))


def _limb(motion: Motion, side: str, kind: str) -> tuple[tuple[int, int, int], tuple[float, float, float]]:
    if side not in ("left", "right"):
        raise ValueError(f"side must be 'left' or 'right', got {side!r}")
    bm = body_map(motion.skeleton)
    parents = motion.skeleton.parents
    if kind == "leg":
        end = bm.feet[side][0]
        hinge = (1.0, 0.0, 0.0)
    else:
        end = bm.hands[side]
        hinge = (0.0, -1.0, 0.0) if side == "left" else (0.0, 1.0, 0.0)
    mid = int(parents[end])
    up = int(parents[mid])
    return (up, mid, end), hinge


def leg_ik(motion: Motion, side: str, targets, mask=None, pole=None) -> Motion:
    """:func:`two_bone_ik` on the ``side`` leg (hip, knee, ankle from the body map); ankle targets ``(T, 3)``."""
    chain, hinge = _limb(motion, side, "leg")
    return two_bone_ik(motion, chain, targets, mask, pole, hinge)


def arm_ik(motion: Motion, side: str, targets, mask=None, pole=None) -> Motion:
    """:func:`two_bone_ik` on the ``side`` arm (shoulder, elbow, wrist); wrist targets ``(T, 3)``."""
    chain, hinge = _limb(motion, side, "arm")
    return two_bone_ik(motion, chain, targets, mask, pole, hinge)


def chain_angle(motion: Motion, chain) -> np.ndarray:
    """Flexion of a chain's middle joint in degrees per frame, ``(T,)``: 0 straight, 180 folded."""
    a_j, b_j, c_j = (_joint(motion, j) for j in chain)
    P = motion.positions
    u1 = _unit(P[:, b_j] - P[:, a_j])[0]
    u2 = _unit(P[:, c_j] - P[:, b_j])[0]
    return np.degrees(np.arccos(np.clip(np.sum(u1 * u2, axis=-1), -1.0, 1.0)))
