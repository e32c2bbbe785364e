"""Building blocks of the synthesis engine: slerp blending, rigid placement, timing, switching, sway."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

from text2anim.synthesis.join.align import align_through_foot
from text2anim.synthesis.join.blend import blend, ramp, sample, slerp
from text2anim.synthesis.join.composition import hermite_sway
from text2anim.core.contacts import FootContacts
from text2anim.core.ground import Rigid, headings, match, wrap_angle
from text2anim.synthesis.join.footlock import plan_locks, planted_targets
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton
from text2anim.synthesis.constraint.switching import find_switch, planted_for
from text2anim.synthesis.join.gait import steps
from text2anim.synthesis.join.cycles import cycle_move, loop, make_cyclic
from text2anim.synthesis.join.timing import at_speed, ease_hold, hold, soft_clip, trim


def _skeleton() -> Skeleton:
    """A small CMU-named skeleton (hips, two legs with toes, spine, head, two arms)."""
    names = ["Hips", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "RightUpLeg", "RightLeg", "RightFoot",
             "RightToeBase", "Spine", "Neck", "Head", "LeftArm", "LeftForeArm", "LeftHand", "RightArm",
             "RightForeArm", "RightHand"]
    parents = [-1, 0, 1, 2, 3, 0, 5, 6, 7, 0, 9, 10, 9, 12, 13, 9, 15, 16]
    offsets = [[0, 0, 0], [0.1, -0.05, 0], [0, -0.42, 0], [0, -0.42, 0], [0, -0.06, 0.12],
               [-0.1, -0.05, 0], [0, -0.42, 0], [0, -0.42, 0], [0, -0.06, 0.12],
               [0, 0.25, 0], [0, 0.25, 0], [0, 0.1, 0], [0.18, 0.2, 0], [0.28, 0, 0], [0.25, 0, 0],
               [-0.18, 0.2, 0], [-0.28, 0, 0], [-0.25, 0, 0]]
    return Skeleton(names, parents, offsets)


def _motion(T=40, seed=0, fps=30.0, scale=0.3) -> Motion:
    rng = np.random.default_rng(seed)
    sk = _skeleton()
    t = np.linspace(0, 1, T)[:, None, None]
    axes = rng.normal(size=(1, sk.n_joints, 3)) * scale
    rots = Rotation.from_rotvec((axes * np.sin(2 * np.pi * t)).reshape(-1, 3)).as_quat().reshape(T, -1, 4)
    root = np.stack([np.zeros(T), np.full(T, 0.95), np.linspace(0, 1.2, T)], axis=1)
    return Motion(sk, fps, root, rots)


# ------------------------------------------------------------------------------------------- blend
def test_slerp_is_scipy_slerp_per_joint_and_frame():
    rng = np.random.default_rng(1)
    qa = Rotation.random(60, random_state=2).as_quat().reshape(20, 3, 4)
    qb = Rotation.random(60, random_state=3).as_quat().reshape(20, 3, 4)
    w = rng.uniform(size=(20, 3))
    out = Rotation.from_quat(slerp(qa, qb, w).reshape(-1, 4))
    for i in range(20):
        for j in range(3):
            ref = Slerp([0, 1], Rotation.from_quat([qa[i, j], qb[i, j]]))([w[i, j]])
            assert (ref.inv() * out[i * 3 + j]).magnitude()[0] < 1e-9


def test_slerp_ends_and_sign_independence():
    qa = Rotation.random(10, random_state=4).as_quat()
    qb = Rotation.random(10, random_state=5).as_quat()
    for w, ref in ((0.0, qa), (1.0, qb)):
        got = Rotation.from_quat(slerp(qa, qb, w))
        assert np.all((got.inv() * Rotation.from_quat(ref)).magnitude() < 1e-9)
    # -q is the same rotation: the blend must not take the long way round
    half = Rotation.from_quat(slerp(qa, -qb, 0.5))
    assert np.allclose((half.inv() * Rotation.from_quat(slerp(qa, qb, 0.5))).magnitude(), 0, atol=1e-9)


def test_slerp_is_the_formula_bit_for_bit():
    # A * exp(w log(A^-1 B)) by scipy's Rotation, the same bits: also on rows of weight 0 (+0 and -0) and
    # where A has components that are zero (+0 and -0), whose signs the logarithm decides
    rng = np.random.default_rng(7)
    qa = Rotation.random(400, random_state=8).as_quat()
    qb = Rotation.random(400, random_state=9).as_quat()
    qa[:60] = [0.0, 0.0, 0.0, 1.0]
    qa[60:90] = [-0.0, 0.0, -0.0, 1.0]
    qa[90:120, 1] = 0.0
    qb[120:140] = qa[120:140]
    w = rng.uniform(size=400)
    w[rng.uniform(size=400) < 0.6] = 0.0
    w[:120:7] = -0.0
    ra, rb = Rotation.from_quat(qa), Rotation.from_quat(qb)
    ref = (ra * Rotation.from_rotvec((ra.inv() * rb).as_rotvec() * w[:, None])).as_quat()
    assert slerp(qa, qb, w).tobytes() == ref.tobytes()
    held = w == 0.0
    assert slerp(qa[held], qb[held], 0.0).tobytes() == ref[held].tobytes()


def test_ramp_profiles():
    for profile in ("linear", "smooth"):
        w = ramp(20, profile)
        assert np.all(np.diff(w) > 0) and 0 < w[0] < 0.1 and 0.9 < w[-1] < 1
    s = ramp(40, "smooth")
    assert s[0] < ramp(40, "linear")[0] / 10  # eases in with zero slope


def test_blend_and_sample():
    a, b = _motion(seed=1), _motion(seed=2)
    assert np.allclose(blend(a, b, np.zeros(a.n_frames)).positions, a.positions)
    assert np.allclose(blend(a, b, np.ones(a.n_frames)).positions, b.positions)
    s = sample(a, np.array([0.0, 3.0, 3.5, 100.0]))
    assert np.allclose(s.positions[1], a.positions[3])
    assert np.allclose(s.positions[3], a.positions[-1])
    assert np.allclose(s.root_positions[2], 0.5 * (a.root_positions[3] + a.root_positions[4]))


# ------------------------------------------------------------------------------------------- align
def test_rigid_compose_inverse_and_motion():
    m = _motion()
    r1, r2 = Rigid(0.7, (1.0, -2.0)), Rigid(-0.2, (0.5, 0.3))
    p = np.random.default_rng(0).normal(size=(5, 3))
    assert np.allclose(r1.then(r2).apply_points(p), r2.apply_points(r1.apply_points(p)))
    assert np.allclose(r1.inverse().apply_points(r1.apply_points(p)), p)
    moved = r1.apply(m)
    assert np.allclose(moved.positions, r1.apply_points(m.positions))
    assert np.allclose(wrap_angle(headings(moved) - headings(m)), 0.7)


def test_match_and_align_through_foot():
    a = Rigid(0.4, (2.0, 1.0)).apply(_motion(seed=3))
    b = _motion(seed=4)
    mv = match(np.array([1.0, 0.0, 2.0]), 0.3, np.array([-1.0, 5.0, 0.5]), -1.0)
    assert np.allclose(mv.apply_points(np.array([1.0, 0.0, 2.0]))[[0, 2]], [-1.0, 0.5])
    rg = align_through_foot(a, 10, b, 5, "left")
    placed = rg.apply(b)
    foot = [3, 4]
    assert np.allclose(placed.positions[5, foot].mean(0)[[0, 2]], a.positions[10, foot].mean(0)[[0, 2]])
    assert abs(wrap_angle(headings(placed, 0.5)[5] - headings(a, 0.5)[10])) < 1e-9


# ------------------------------------------------------------------------------------------ timing
def test_speed_hold_trim():
    m = _motion(T=61)
    assert at_speed(m, 2.0, 30).n_frames == 31
    assert at_speed(m, 0.5, 30).n_frames == 121
    h = hold(m, 80)
    assert h.n_frames == 80 and np.allclose(h.rotations[-1], m.rotations[-1])
    cut, over = trim(m, 20, (5, 30))
    assert cut.n_frames == 30 and over == 10  # never inside the core
    cut, over = trim(m, 40, (5, 30))
    assert cut.n_frames == 40 and over == 0


def test_soft_clip_and_ease_hold():
    x = np.linspace(-10, 60, 701)
    y = soft_clip(x, 0, 50, 4)
    assert np.all(np.diff(y) >= -1e-12) and y.min() == 0 and y.max() == 50
    mid = (x > 4) & (x < 46)
    assert np.allclose(y[mid], x[mid])
    assert np.max(np.abs(np.diff(np.diff(y)))) < 0.02  # no corner: C1
    m = _motion(T=30)
    e = ease_hold(m, 45)
    assert e.n_frames == 45 and np.allclose(e.positions[-1], m.positions[-1])
    step = np.linalg.norm(np.diff(e.root_positions, axis=0), axis=1)
    assert step[-16] < step[10]  # slowed down before stopping


def test_loop_accumulates_travel_and_has_no_seam():
    m = _motion(T=30)
    c = make_cyclic(m)
    move = cycle_move(c)
    out = loop(c, 95)
    assert out.n_frames == 95
    travel = out.root_positions[90, 2] - out.root_positions[0, 2]
    assert travel == pytest.approx(3 * move.offset[1], rel=1e-6)
    steps = np.linalg.norm(np.diff(out.positions, axis=0), axis=-1).max(axis=1)
    assert steps[29] < 2.5 * np.median(steps)  # the seam between cycles is an ordinary frame
    back = loop(c, 60, first=-30)
    assert np.allclose(back.root_positions[30:], c.root_positions)


# --------------------------------------------------------------------------------------- switching
def _contacts(left, right, fps=30.0):
    return FootContacts(fps, np.array(left, dtype=bool), np.array(right, dtype=bool))


def test_switch_needs_a_common_planted_foot():
    a, b = _motion(seed=5), _motion(seed=6)
    T = a.n_frames
    ca = _contacts([True] * T, [False] * T)
    lb = [False] * 10 + [True] * (T - 10)
    cb = _contacts(lb, [True] * T)
    sw = find_switch(a, ca, (30, 40), b, cb, (0, 20), lambda i, j: (j + 0 * i) / 30.0)
    assert sw.support == "left" and sw.b >= 10
    assert sw.exact is False


def test_planted_for_and_swings():
    c = _contacts([1, 1, 0, 0, 0, 1, 1, 1, 0, 1], [1] * 10)
    assert list(planted_for(c, "left")) == [2, 1, 0, 0, 0, 3, 2, 1, 0, 1]
    sw = steps(c, side="left")
    assert [(s.begin, s.end) for s in sw] == [(2, 5), (8, 9)]


# ---------------------------------------------------------------------------------------- footlock
def test_planted_targets_follow_only_planted_sources():
    T = 10
    still = np.zeros((T, 3))
    moving = np.stack([np.linspace(0, 1, T), np.zeros(T), np.zeros(T)], axis=1)
    ident = Rotation.identity(T).as_quat()  # quaternions (T, 4)
    # the source that moves is not planted: the target stays
    p, _ = planted_targets(np.zeros(3), Rotation.identity().as_quat(), [still, moving], [ident, ident],
                           [np.ones(T), np.zeros(T)])
    assert np.allclose(p, 0)
    # only the moving one is planted: the target moves with it
    p, _ = planted_targets(np.zeros(3), Rotation.identity().as_quat(), [still, moving], [ident, ident],
                           [np.zeros(T), np.ones(T)])
    assert np.allclose(p, moving)


def test_plan_locks_lock_through_the_window_and_release_in_the_air():
    n = 40
    left = np.zeros(n, dtype=bool)
    left[5:25] = True
    left[32:] = True
    locks = plan_locks({"left": left, "right": np.zeros(n, dtype=bool)}, (10, 20), n)
    assert len(locks) == 1
    lk = locks[0]
    assert (lk.begin, lk.end, lk.release_end) == (10, 25, 32)


# ------------------------------------------------------------------------------------------- sway
def test_hermite_sway_vanishes_at_the_ends_and_on_hermite_motion():
    T = 50
    t = np.linspace(0, 1, T)
    wobble = np.sin(6 * np.pi * t) * 0.2
    rv = np.stack([0.5 * t, 0.3 * t ** 2 + wobble, np.zeros(T)], axis=1)
    q = Rotation.from_rotvec(rv).as_quat()[:, None, :]
    base, sway = hermite_sway(q, 30.0)
    mag = Rotation.from_quat(sway[:, 0]).magnitude()
    assert mag[0] < 1e-9 and mag[-1] < 1e-9 and mag.max() > 0.1
    # the base trajectory is one cubic (in rotation-vector coordinates relative to the start) ...
    rb = (Rotation.from_quat(q[:1, 0]).inv() * Rotation.from_quat(base[:, 0])).as_rotvec()
    assert np.abs(np.diff(rb, n=4, axis=0)).max() < 1e-9
    # ... and base * sway is the real trajectory
    back = Rotation.from_quat(base[:, 0]) * Rotation.from_quat(sway[:, 0])
    assert np.all((back.inv() * Rotation.from_quat(q[:, 0])).magnitude() < 1e-9)
    # a trajectory that is itself a cubic (in rotation-vector space, about one axis) has no sway
    smooth = Rotation.from_rotvec(np.stack([np.zeros(T), 0.4 * t ** 3 - 0.2 * t, np.zeros(T)], axis=1)).as_quat()
    _, sway = hermite_sway(smooth[:, None, :], 30.0)
    assert Rotation.from_quat(sway[:, 0]).magnitude().max() < 0.02
