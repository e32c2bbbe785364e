"""Motion core: forward kinematics, slicing, resampling, concatenation."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from shared_data import cmu
from text2anim.core import Motion, Skeleton, concatenate, read_bvh
from text2anim.core.motion import unroll_quaternions


def _chain():
    return Skeleton(["root", "a", "b"], [-1, 0, 1], [[0, 0, 0], [0, 1, 0], [0, 1, 0]])


def test_fk_matches_rotations_composed_by_hand():
    rng = np.random.default_rng(0)
    rots = Rotation.random(3 * 5, random_state=1).as_quat().reshape(5, 3, 4)
    root = rng.normal(size=(5, 3))
    m = Motion(_chain(), 30, root, rots)
    for t in range(5):
        r0, r1 = Rotation.from_quat(rots[t, 0]), Rotation.from_quat(rots[t, 1])
        a = root[t] + r0.apply([0, 1, 0])
        b = a + (r0 * r1).apply([0, 1, 0])
        np.testing.assert_allclose(m.positions[t], [root[t], a, b], atol=1e-12)
        np.testing.assert_allclose(m.pose.rotations[t, 2], (r0 * r1 * Rotation.from_quat(rots[t, 2])).as_matrix(), atol=1e-12)


def test_slicing_by_frames_and_time():
    m = read_bvh(cmu("16_35_run"), drop_first=True)
    part = m[10:40]
    assert part.n_frames == 30
    np.testing.assert_allclose(part.positions, m.positions[10:40])
    t = m.between(0.25, 0.5)
    assert t.n_frames == pytest.approx(0.25 * m.fps, abs=1)
    np.testing.assert_allclose(t.positions[0], m.positions[int(np.ceil(0.25 * m.fps - 1e-9))])
    with pytest.raises(TypeError):
        m[::2]


def test_resample_keeps_poses_at_shared_times():
    m = read_bvh(cmu("16_35_run"), drop_first=True)
    r = m.resample(30)
    assert r.fps == 30
    assert r.duration == pytest.approx(m.duration, abs=2 / 30)
    # Every 4th frame at 120 fps is a frame at 30 fps (to the file's 1e-6 rounding of the frame time).
    k = np.arange(r.n_frames)
    np.testing.assert_allclose(r.positions, m.positions[np.round(k * m.fps / 30).astype(int)], atol=2e-3)


def test_resample_slerps_between_frames():
    q = Rotation.from_euler("z", [[0], [90]], degrees=True).as_quat()
    rots = np.stack([np.tile([0, 0, 0, 1.0], (2, 1)), q, np.tile([0, 0, 0, 1.0], (2, 1))], axis=1)
    m = Motion(_chain(), 1, np.zeros((2, 3)), rots)
    mid = m.resample(2).rotations[1, 1]
    assert Rotation.from_quat(mid).magnitude() == pytest.approx(np.radians(45))


def test_concatenate_appends_frames():
    m = read_bvh(cmu("16_35_run"), drop_first=True)
    both = concatenate([m[:10], m[10:25]])
    np.testing.assert_allclose(both.positions, m.positions[:25])
    with pytest.raises(ValueError, match="resample"):
        concatenate([m, m.resample(30)])


def test_a_concatenation_whose_parts_are_partly_solved_has_the_whole_frames_kinematics():
    m = read_bvh(cmu("16_35_run"), drop_first=True)
    known = m[:40]
    known.pose  # solved: its kinematics is reused, the other parts' is computed when asked
    fresh = m[40:70].replace(fps=m.fps)  # no pose of its own yet
    both = concatenate([known, fresh, m[70:75]])
    whole = Motion(m.skeleton, m.fps, both.root_positions.copy(), both.rotations.copy())
    assert np.array_equal(both.positions, whole.positions)
    assert np.array_equal(both.pose.rotations, whole.pose.rotations)


def test_a_motion_whose_hips_moved_has_the_kinematics_of_its_own_frames():
    m = read_bvh(cmu("16_35_run"), drop_first=True)[:60]
    m.pose  # solved: the moved copy keeps its world rotations and sums the positions again
    moved = m.replace(root_positions=m.root_positions + np.array([0.3, 0.01, -1.2]))
    fresh = Motion(m.skeleton, m.fps, moved.root_positions.copy(), m.rotations.copy())
    assert np.array_equal(moved.positions, fresh.positions)
    assert np.array_equal(moved.pose.rotations, fresh.pose.rotations)
    assert not np.array_equal(moved.positions, m.positions)


def test_unroll_keeps_neighbours_in_one_hemisphere():
    q = Rotation.from_euler("z", np.linspace(0, 720, 50)[:, None], degrees=True).as_quat()
    q[1::2] *= -1
    u = unroll_quaternions(q)
    assert np.all(np.sum(u[1:] * u[:-1], axis=-1) > 0)
    np.testing.assert_allclose(Rotation.from_quat(u).as_matrix(), Rotation.from_quat(q).as_matrix(), atol=1e-12)


def test_motion_rejects_mismatched_shapes():
    with pytest.raises(ValueError):
        Motion(_chain(), 30, np.zeros((4, 3)), np.zeros((5, 3, 4)))
    with pytest.raises(ValueError):
        Motion(_chain(), 0, np.zeros((1, 3)), np.tile([0, 0, 0, 1.0], (1, 3, 1)))


def test_a_limb_edit_redoes_only_its_subtree_and_gives_the_full_kinematics_bit_for_bit():
    """``Motion.replace(rotations=...)`` that changes some joints (what IK does) redoes the kinematics of
    their subtree only, from the known pose: the same bits as the full computation, edits on edits too."""
    from conftest import make_motion

    m = make_motion(40, 30.0, 3, translations=True)
    m.pose  # known: the edited motions start from it
    rng = np.random.default_rng(5)

    def edit(motion, joints):
        rots = motion.rotations.copy()
        r = rots[:, joints] + 0.2 * rng.standard_normal(rots[:, joints].shape)
        rots[:, joints] = r / np.linalg.norm(r, axis=-1, keepdims=True)
        return rots

    def full(rots):
        return Motion(m.skeleton, m.fps, m.root_positions, rots, m.translations).pose

    J = m.skeleton.n_joints
    for top in range(1, J):
        sub = m.skeleton.subtree(top)
        assert sub[0] == top and all(m.skeleton.parents[j] in sub for j in sub[1:])
        rots = edit(m, [top, sub[-1]])
        once = m.replace(rotations=rots)
        twice = once.replace(rotations=edit(once, [int(rng.integers(1, J))]))  # its pose not asked before
        cases = ((once, once, slice(None)), (twice[5:30], twice, slice(5, 30)), (twice, twice, slice(None)))
        for motion, whole, sl in cases:  # the slice first: it solves the edit on its frames only
            expect = full(whole.rotations)
            assert np.array_equal(motion.pose.rotations, expect.rotations[sl])
            assert np.array_equal(motion.pose.positions, expect.positions[sl])
    assert m.replace(rotations=m.rotations.copy()).pose is not None


def test_world_quaternions_of_some_joints_are_those_of_all_joints():
    from conftest import make_motion

    pose = make_motion(30, 30.0, 4).pose
    every = pose.quaternions()
    assert np.array_equal(pose.quaternions(3), every[:, 3])
    assert np.array_equal(pose.quaternions([5, 1]), every[:, [5, 1]])


def test_a_motion_sharing_anothers_pose_runs_kinematics_for_its_changed_frames_only_bit_for_bit():
    """``Motion.share_pose``: a join's region edited (and the frames after it shifted by the frames it
    gained) takes the kinematics of its unchanged frames from the original's pose; its own is the full
    computation's, slices too, and a frame claimed the same but edited is recomputed."""
    from conftest import make_motion

    m = make_motion(50, 30.0, 3, translations=True)
    m.pose
    rots, root = m.rotations.copy(), m.root_positions.copy()
    region = np.concatenate([rots[:20], np.roll(rots[20:30], 1, axis=1), rots[25:]])  # 5 frames more
    moved = np.concatenate([root[:20], root[20:30] + 0.1, root[25:]])
    moved[40] += 1e-12  # a frame after the region edited too
    trans = np.concatenate([m.translations[:20], m.translations[20:30], m.translations[25:]])
    edited = Motion(m.skeleton, m.fps, moved, region, trans)
    rows = np.concatenate([np.arange(20), np.full(10, -1), np.arange(25, 50)])
    full = Motion(m.skeleton, m.fps, moved, region, trans).pose
    shared = Motion(m.skeleton, m.fps, moved, region, trans).share_pose(m, rows)
    part = shared[15:45]
    assert np.array_equal(part.pose.positions, full.positions[15:45])
    assert np.array_equal(shared.pose.positions, full.positions)
    assert np.array_equal(shared.pose.rotations, full.rotations)
    assert not np.array_equal(full.positions[40], m.pose.positions[35])  # the edit after the region counted
    assert edited.share_pose(Motion(m.skeleton, m.fps, root, rots, m.translations), rows) is edited  # pose unknown
