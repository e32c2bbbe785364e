"""The adapted lower body of §4.2.3 (:func:`synthesis.optimal.adaptation.adapt`) on the built-in library's clips:
both legs solved as rows of one two-bone solve give, bit for bit, what solving each leg in turn with the IK
kernels gives (:func:`core.ik.leg_ik`, then :func:`core.ik.set_world_rotation` for its ankle) — the outputs
the goldens hold were made that way."""
from __future__ import annotations

import numpy as np

from text2anim.core import rotkernels as rk
from text2anim.core.bodyparts import body_map
from text2anim.core.ground import Rigid
from text2anim.core.ik import leg_ik, set_world_rotation
from text2anim.motiondb import MotionDB
from text2anim.synthesis.optimal.adaptation import adapt


def _leg_by_leg(motion, out, k, d, mask):
    """The legs of ``out`` (``motion`` with its hips moved) solved one after the other with the kernels."""
    feet = body_map(motion.skeleton).feet
    pose = motion.pose
    for side in ("left", "right"):
        ankle = feet[side][0]
        out = leg_ik(out, side, pose.positions[:, ankle] + np.outer(k, d[side]), mask=mask)
        out = set_world_rotation(out, ankle, rk.as_quat(rk.from_matrix(pose.rotations[:, ankle])), mask=mask)
    return out


def _bits(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a).view(np.int64)


def test_both_legs_in_one_solve_are_each_leg_solved_in_turn(library_db):
    db = MotionDB.open(library_db)
    try:
        names = ("walk", "run", "kick")
        clips = {c.name: db.load(c) for c in db.clips() if c.name in names}
    finally:
        db.close()
    assert set(clips) == set(names)
    rng = np.random.default_rng(7)
    for name, clip in clips.items():
        placed = Rigid(0.7, (1.5, -0.4)).apply(clip)
        T = placed.n_frames
        # a wide stance (the hips sink), a support foot with no offset, a fade that leaves frames untouched
        for offsets, scale in (({"left": np.array([0.45, 0.0, 0.1]), "right": np.array([-0.3, 0.0, 0.2])}, None),
                               ({"left": np.zeros(3), "right": rng.normal(0, 0.2, 3)}, np.clip(np.linspace(1.3, -0.3, T), 0, 1))):
            got = adapt(placed, offsets, scale)
            k = np.ones(T) if scale is None else scale
            d = {s: np.array([v[0], 0.0, v[2]]) for s, v in offsets.items()}
            moved = placed.replace(root_positions=got.root_positions)
            mask = (k > 1e-9) | (placed.root_positions[:, 1] - got.root_positions[:, 1] > 1e-9)  # where the hips sank
            want = _leg_by_leg(placed, moved, k, d, mask)
            assert (_bits(got.rotations) == _bits(want.rotations)).all(), name
            assert (_bits(got.positions) == _bits(want.positions)).all(), name
