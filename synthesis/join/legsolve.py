"""Leg IK for the foot locks and lifts (:mod:`synthesis.join.footlock`): :func:`solve_leg` (an ankle onto targets,
the knee bending forward, within reach) and :func:`solve_goals`, which solves many :class:`LegGoal` s — both
legs, several frame ranges — as rows of one two-bone solve (:func:`core.ik.solve_rows`) and turns each ankle
to its world rotation, with the arithmetic of :func:`solve_leg` then :func:`core.ik.set_world_rotation`
per goal (each row alone: the same bits), in one call instead of one per goal.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from text2anim.core import rotkernels as rk
from text2anim.core.bodyparts import body_map
from text2anim.core.fk import quat_to_matrix
from text2anim.core.ground import rest_forward
from text2anim.core.ik import leg_ik, solve_rows, world_to_local
from text2anim.core.motion import Motion


def leg_chain(motion: Motion, side: str) -> tuple[int, int, int]:
    """``(hip, knee, ankle)`` joint indices of the ``side`` leg."""
    ankle = body_map(motion.skeleton).feet[side][0]
    knee = int(motion.skeleton.parents[ankle])
    return int(motion.skeleton.parents[knee]), knee, ankle


def chain_length(motion: Motion, chain: tuple[int, int, int]) -> float:
    """Thigh plus shin (m) of a leg ``(hip, knee, ankle)`` (:func:`leg_chain`), from the skeleton's offsets."""
    offs = motion.skeleton.offsets
    return float(np.linalg.norm(offs[chain[1]]) + np.linalg.norm(offs[chain[2]]))


#: IK targets are kept within this fraction of the leg's length from the hip: a leg pulled fully
#: straight has no bend plane, and the knee would flip from frame to frame. Captured legs reach 0.99
#: of their length, the built-in ones 0.999.
REACH = 0.998


def solve_leg(motion: Motion, side: str, targets: np.ndarray, ankle: np.ndarray | None = None) -> Motion:
    """:func:`core.ik.leg_ik` with targets ``(T, 3)`` pulled within :data:`REACH` of the leg's length and the
    knee bending towards the thigh's forward direction; with ``ankle`` (world rotations, quaternions
    ``(T, 4)``) the ankle turned to them too: ``set_world_rotation(solve_leg(m, side, targets), ankle_joint,
    ankle)``, bit for bit, without the second pass of kinematics (:func:`solve_goals`)."""
    if ankle is not None:
        return solve_legs(motion, [LegGoal(side, 0, motion.n_frames, np.asarray(targets, dtype=np.float64),
                                           np.asarray(ankle, dtype=np.float64).reshape(-1, 4))])
    hip, knee, foot = leg_chain(motion, side)
    reach = REACH * chain_length(motion, (hip, knee, foot))
    pos = motion.positions
    h = pos[:, hip]
    v = targets - h
    dist = np.linalg.norm(v, axis=-1)
    scale = np.minimum(1.0, reach / np.maximum(dist, 1e-9))
    # the knee bends towards the thigh's own forward: with the leg's own knee as the pole, a nearly
    # straight leg has no bend plane to keep and the knee could swing sideways (a hinge knee bends in
    # the thigh's forward plane, so for a bent leg this is the plane it already has)
    fwd = np.einsum("tij,j->ti", motion.pose.rotations[:, hip], rest_forward(motion.skeleton))
    pole = pos[:, knee] + 0.5 * fwd
    return leg_ik(motion, side, h + v * scale[:, None], pole=pole)


@dataclass(frozen=True)
class LegGoal:
    """A leg driven over frames ``[begin, end)``: its ankle onto ``targets`` ``(n, 3)`` (world, metres;
    :func:`solve_leg` 's reach and knee direction) and turned to the world rotations ``ankle`` ``(n, 4)``."""

    side: str
    begin: int
    end: int
    targets: np.ndarray
    ankle: np.ndarray


def solve_goals(span: Motion, lo: int, goals: list[LegGoal]) -> np.ndarray:
    """The local rotations ``(T, J, 4)`` of ``span`` (the motion's frames from ``lo`` on) with every goal
    solved: :func:`solve_leg` then :func:`core.ik.set_world_rotation` per goal, all goals' frames as rows of
    one solve (per row the same arithmetic: the same bits). The goals of one leg must not overlap."""
    skel = span.skeleton
    chains = [leg_chain(span, g.side) for g in goals]
    frames = np.concatenate([np.arange(g.begin - lo, g.end - lo) for g in goals])
    hip, knee, ankle = (np.concatenate([np.full(g.end - g.begin, c[k]) for g, c in zip(goals, chains)])
                        for k in range(3))
    reach = np.concatenate([np.full(g.end - g.begin, REACH * chain_length(span, c)) for g, c in zip(goals, chains)])
    pose = span.pose
    P, R = pose.positions, pose.rotations
    h = P[frames, hip]
    v = np.concatenate([g.targets for g in goals]) - h
    dist = np.linalg.norm(v, axis=-1)
    scale = np.minimum(1.0, reach / np.maximum(dist, 1e-9))
    Rh = R[frames, hip]
    pole = P[frames, knee] + 0.5 * np.einsum("tij,j->ti", Rh, rest_forward(skel))  # as solve_leg
    above = skel.parents[hip]
    Rp = R[frames, above] if (above >= 0).all() else np.where((above >= 0)[:, None, None], R[frames, above], np.eye(3))
    qa, qb = solve_rows(h, P[frames, knee], P[frames, ankle], Rh, R[frames, knee], Rp, h + v * scale[:, None], pole)
    return put_legs(span.rotations, frames, (hip, knee, ankle), qa, qb, Rp, np.concatenate([g.ankle for g in goals]))


def put_legs(rotations: np.ndarray, frames: np.ndarray, chain: tuple[np.ndarray, np.ndarray, np.ndarray],
             qa: np.ndarray, qb: np.ndarray, Rp: np.ndarray, ankle_world: np.ndarray) -> np.ndarray:
    """A copy of the local rotations ``rotations`` ``(T, J, 4)`` with, on rows ``frames`` ``(n,)`` of the legs'
    ``chain`` (hip, knee, ankle joints, ``(n,)`` each), the hips' and knees' solved rotations ``qa``, ``qb``
    ``(n, 4)`` (:func:`core.ik.solve_rows`, the hips' parents' world rotations ``Rp`` ``(n, 3, 3)``) and the
    ankles turned to the world rotations ``ankle_world`` ``(n, 4)``."""
    hip, knee, ankle = chain
    rots = rotations.copy()
    rots[frames, hip] = qa
    rots[frames, knee] = qb
    # the knees' new world rotations, as forward kinematics has them (Motion.pose: parent @ local, the
    # local matrices from the stored quaternions), on these rows only
    local = quat_to_matrix(np.concatenate([qa, qb]))
    knee_world = (Rp @ local[:len(qa)]) @ local[len(qa):]
    rots[frames, ankle] = world_to_local(knee_world, ankle_world)
    return rots


def solve_legs(motion: Motion, goals: list[LegGoal]) -> Motion:
    """``motion`` with every goal solved (:func:`solve_goals`; the goals of one leg must not overlap)."""
    goals = [g for g in goals if g.end > g.begin]
    if not goals:
        return motion
    lo, hi = min(g.begin for g in goals), max(g.end for g in goals)
    return motion.with_rotations(lo, solve_goals(motion[lo:hi], lo, goals))


def quaternions(blocks: list[np.ndarray]) -> list[np.ndarray]:
    """:func:`core.rotkernels.from_matrix` of each block of matrices ``(n_i, 3, 3)``, in one call (rows are
    independent: the same bits): a list of ``(n_i, 4)``."""
    q = rk.from_matrix(np.concatenate(blocks))
    return np.split(q, np.cumsum([len(b) for b in blocks])[:-1])


def feet_kept(before: Motion, after: Motion, a: int, b: int) -> Motion:
    """``after`` (``before`` with its hips moved) with both legs solved back, over frames ``[a, b)``, onto
    where ``before`` has its feet: each ankle's world position and rotation (:func:`solve_legs`), so no foot
    moves and the upper body rides on the hips."""
    pose = before[a:b].pose
    goals = [LegGoal(side, a, b, pose.positions[:, ankle], rk.as_quat(rk.from_matrix(pose.rotations[:, ankle])))
             for side, (ankle, _toe) in body_map(before.skeleton).feet.items()]
    # outside [a, b) the frames are ``before``'s (where bit for bit so): their kinematics is known
    return solve_legs(after, goals).share_pose(before, np.arange(before.n_frames))
