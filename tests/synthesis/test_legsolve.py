"""synthesis.join.legsolve: many leg goals solved as rows of one IK solve give, bit for bit, what one
solve per goal gives (solve_leg, then set_world_rotation), on a walk the built-in library animates."""
from __future__ import annotations

import numpy as np

from text2anim.core import rotkernels as rk
from text2anim.core.ik import set_world_rotation
from text2anim.synthesis.join.legsolve import LegGoal, leg_chain, solve_leg, solve_legs


def _goal(motion, side: str, b: int, e: int, lift: float, turn: float) -> LegGoal:
    """The ankle over [b, e) raised by ``lift`` m and turned by ``turn`` rad about the vertical."""
    ankle = leg_chain(motion, side)[2]
    pose = motion.pose
    target = pose.positions[b:e, ankle] + np.array([0.02, lift, -0.01])
    own = rk.from_matrix(pose.rotations[b:e, ankle])
    rot = rk.as_quat(rk.compose(rk.from_rotvec(np.array([[0.0, turn, 0.0]])), own))
    return LegGoal(side, b, e, target, rot)


def _one_by_one(motion, goals):
    out = motion
    for g in goals:
        sub = out[g.begin:g.end]
        solved = set_world_rotation(solve_leg(sub, g.side, g.targets), leg_chain(out, g.side)[2], g.ankle)
        rots = out.rotations.copy()
        rots[g.begin:g.end] = solved.rotations
        out = out.replace(rotations=rots)
    return out


def test_goals_of_both_legs_in_one_solve_are_the_solves_one_by_one(walk_motion):
    m = walk_motion
    goals = [_goal(m, "left", 10, 25, 0.04, 0.2), _goal(m, "right", 12, 20, 0.03, -0.1),
             _goal(m, "left", 25, 31, 0.0, 0.05), _goal(m, "right", 40, 44, 0.06, 0.0)]
    batched = solve_legs(m, goals)
    assert batched.rotations.tobytes() == _one_by_one(m, goals).rotations.tobytes()
    # and the goals are met: each ankle on its target (within reach) and turned as asked
    pose = batched.pose
    for g in goals:
        ankle = leg_chain(m, g.side)[2]
        assert np.abs(pose.positions[g.begin:g.end, ankle] - g.targets).max() < 1e-6
        got = rk.from_matrix(pose.rotations[g.begin:g.end, ankle])
        assert np.abs(np.abs(np.sum(got * g.ankle, axis=1)) - 1.0).max() < 1e-9


def test_solve_leg_with_an_ankle_rotation_is_the_two_steps(walk_motion):
    m = walk_motion[5:35]
    g = _goal(m, "right", 0, m.n_frames, 0.05, 0.3)
    ankle = leg_chain(m, "right")[2]
    two_steps = set_world_rotation(solve_leg(m, "right", g.targets), ankle, g.ankle)
    assert solve_leg(m, "right", g.targets, ankle=g.ankle).rotations.tobytes() == two_steps.rotations.tobytes()
