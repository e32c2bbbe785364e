"""Two-bone IK (core.ik): reach, bend direction, unreachable targets, masks, poles."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from text2anim.motiondb.library import canonical_skeleton
from shared_data import cmu
from text2anim.core import Motion, read_bvh
from text2anim.core.ik import arm_ik, chain_angle, leg_ik, set_world_rotation, two_bone_ik

LEG = ("LeftUpLeg", "LeftLeg", "LeftFoot")


def _standing(T: int = 1, knee: float = 5.0) -> Motion:
    """The canonical skeleton standing, arms down, knees slightly bent, ``T`` frames."""
    skel = canonical_skeleton()
    rots = np.zeros((T, skel.n_joints, 4))
    rots[..., 3] = 1.0
    for side, sign in (("Left", 1), ("Right", -1)):
        rots[:, skel.index(f"{side}Leg")] = Rotation.from_euler("x", knee, degrees=True).as_quat()
        rots[:, skel.index(f"{side}Arm")] = Rotation.from_euler("z", -80 * sign, degrees=True).as_quat()
        rots[:, skel.index(f"{side}ForeArm")] = Rotation.from_euler("y", -15 * sign, degrees=True).as_quat()
    root = np.tile([0.0, 0.93, 0.0], (T, 1))
    return Motion(skel, 30.0, root, rots)


def _signed_flexion(m: Motion, chain, hinge) -> np.ndarray:
    """Flexion of the middle joint in degrees, negative when it bends against its hinge (hyperextension)."""
    skel = m.skeleton
    a, b, c = (skel.index(j) for j in chain)
    p = m.positions
    u1, u2 = p[:, b] - p[:, a], p[:, c] - p[:, b]
    ang = np.degrees(np.arccos(np.clip(np.sum(u1 * u2, 1) / np.linalg.norm(u1, axis=1) / np.linalg.norm(u2, axis=1), -1, 1)))
    axis = np.einsum("tij,j->ti", m.pose.rotations[:, a], hinge)
    return ang * np.sign(np.sum(np.cross(u1, u2) * axis, 1) + 1e-12)


@settings(max_examples=60, deadline=None)
@given(dx=st.floats(-0.25, 0.25), dy=st.floats(0.25, 0.78), dz=st.floats(-0.35, 0.35))
def test_reachable_targets_are_reached_and_the_knee_bends_forward(dx, dy, dz):
    m = _standing()
    hip = m.positions[0, m.skeleton.index("LeftUpLeg")]
    target = hip + np.array([dx, -dy, dz])
    if np.linalg.norm(target - hip) > 0.80:  # keep it strictly reachable (leg 0.805 m)
        target = hip + (target - hip) * 0.80 / np.linalg.norm(target - hip)
    out = leg_ik(m, "left", target[None])
    ankle = out.positions[0, m.skeleton.index("LeftFoot")]
    assert np.linalg.norm(ankle - target) < 1e-3
    flex = _signed_flexion(out, LEG, (1.0, 0.0, 0.0))
    assert flex[0] > -0.5, "the knee bent backwards"


def test_knee_goes_forward_of_the_hip_ankle_line():
    m = _standing()
    hip = m.positions[0, m.skeleton.index("LeftUpLeg")]
    target = hip + np.array([0.0, -0.6, 0.0])  # straight below, needs a deep bend
    out = leg_ik(m, "left", target[None])
    knee = out.positions[0, m.skeleton.index("LeftLeg")]
    assert knee[2] > hip[2] + 0.1  # the knee is in front (+Z)
    assert 60 < chain_angle(out, LEG)[0] < 90


def test_unreachable_target_gives_a_straight_leg_pointing_at_it_without_nan():
    m = _standing(T=3)
    hip = m.positions[0, m.skeleton.index("LeftUpLeg")]
    targets = hip + np.array([[0.0, -2.0, 0.0], [1.5, -1.0, 0.8], [0.0, 0.0, 0.0]])  # far, far, on the hip
    out = leg_ik(m, "left", targets)
    assert np.all(np.isfinite(out.rotations))
    p = out.positions
    ankle = p[:2, m.skeleton.index("LeftFoot")]
    angle = chain_angle(out, LEG)
    assert np.all(angle[:2] < 0.5)
    for k in range(2):
        d_ankle = (ankle[k] - hip) / np.linalg.norm(ankle[k] - hip)
        d_target = (targets[k] - hip) / np.linalg.norm(targets[k] - hip)
        assert np.dot(d_ankle, d_target) > 0.9999


def test_target_nearer_than_the_folded_chain_folds_it():
    m = _standing()
    hip = m.positions[0, m.skeleton.index("LeftUpLeg")]
    out = leg_ik(m, "left", (hip + [0.0, -0.003, 0.0])[None])
    assert np.all(np.isfinite(out.rotations))
    assert chain_angle(out, LEG)[0] > 170


def test_mask_leaves_other_frames_alone_and_only_the_chain_changes():
    m = _standing(T=4)
    hip = m.positions[:, m.skeleton.index("LeftUpLeg")]
    targets = hip + np.array([0.05, -0.7, 0.1])
    mask = np.array([True, False, True, False])
    out = leg_ik(m, "left", targets, mask=mask)
    assert np.array_equal(out.rotations[~mask], m.rotations[~mask])
    changed = np.flatnonzero(np.any(out.rotations[mask] != m.rotations[mask], axis=(0, 2)))
    names = {m.skeleton.names[j] for j in changed}
    assert names <= {"LeftUpLeg", "LeftLeg"}
    assert np.allclose(out.positions[mask, m.skeleton.index("LeftFoot")], targets[mask], atol=1e-6)


def test_pole_sets_the_bend_plane():
    m = _standing()
    skel = m.skeleton
    hip = m.positions[0, skel.index("LeftUpLeg")]
    target = hip + np.array([0.0, -0.65, 0.0])
    pole = hip + np.array([0.5, -0.3, 0.5])  # knee out and forward
    out = two_bone_ik(m, LEG, target[None], pole=pole)
    p = out.positions[0]
    knee = p[skel.index("LeftLeg")]
    normal = np.cross(target - hip, pole - hip)
    assert abs(np.dot(knee - hip, normal / np.linalg.norm(normal))) < 1e-6
    assert np.dot(knee - hip, pole - hip) > 0
    assert np.linalg.norm(p[skel.index("LeftFoot")] - target) < 1e-6


def test_arm_ik_reaches_and_the_elbow_bends_the_natural_way():
    m = _standing()
    skel = m.skeleton
    for side, sign in (("left", 1), ("right", -1)):
        target = np.array([0.05 * sign, 1.2, 0.3])
        out = arm_ik(m, side, target[None])
        wrist = out.positions[0, skel.index(f"{side.capitalize()}Hand")]
        assert np.linalg.norm(wrist - target) < 1e-3
        chain = tuple(f"{side.capitalize()}{j}" for j in ("Arm", "ForeArm", "Hand"))
        flex = _signed_flexion(out, chain, (0.0, -1.0 * sign, 0.0))
        assert 20 < flex[0] < 150


def test_set_world_rotation_orients_a_joint_exactly():
    m = _standing(T=2)
    skel = m.skeleton
    want = Rotation.from_euler("YX", [[30, 10], [-20, 45]], degrees=True)
    out = set_world_rotation(m, "LeftFoot", want.as_quat())
    got = Rotation.from_matrix(out.pose.rotations[:, skel.index("LeftFoot")])
    assert np.allclose((got.inv() * want).magnitude(), 0.0, atol=1e-9)


def test_chain_must_be_parent_child():
    with pytest.raises(ValueError):
        two_bone_ik(_standing(), ("LeftUpLeg", "LeftFoot", "LeftLeg"), np.zeros((1, 3)))


def test_foot_locking_on_a_real_capture():
    m = read_bvh(cmu("02_01_walk"), drop_first=True).resample(30)
    skel = m.skeleton
    ankle = skel.index("RightFoot")
    targets = m.positions[:, ankle] + np.array([0.02, 0.03, -0.04])  # nudged, still reachable
    out = leg_ik(m, "right", targets)
    err = np.linalg.norm(out.positions[:, ankle] - targets, axis=1)
    assert err.max() < 1e-3
    flex = _signed_flexion(out, ("RightUpLeg", "RightLeg", "RightFoot"), (1.0, 0.0, 0.0))
    assert flex.min() > -1.0
