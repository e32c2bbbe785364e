"""Paper 000's building blocks on their own: weights (§4.4), the search (§4.3), ranges (§4.2), selection (§4.2.5).

The search is checked against a brute-force evaluation of eqs. (10)–(15) on
real captured poses (CMU walk and run cycles), pair by pair in plain Python.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from text2anim.core import read_bvh
from text2anim.core.ground import Rigid
from text2anim.synthesis.optimal.blend_ranges import Bounds, after, ranges
from text2anim.synthesis.optimal.blend_search import SMOOTH_FIRST, TIME_FIRST, evaluate, evaluate_motions, preset, search
from text2anim.synthesis.join.gait import Step
from text2anim.synthesis.optimal.method_select import Choice, cyclic_core_begin, cyclic_core_end, select
from text2anim.synthesis.optimal.posedist import distance, features, part_joints
from text2anim.synthesis.optimal.weights import (MAX_SLOPE, hermite_weights, linear_weights, monotone_slopes, plan_partial, shape_of,
                               slope)

from shared_data import cmu

FPS = 30


# ------------------------------------------------------------------------------------------ §4.4 weights
@pytest.mark.parametrize("m0, m1", [(0.0, 0.0), (1.0, 1.0), (0.3, 2.0), (2.5, 0.1), (2.9, 2.9), (5.0, 0.0)])
def test_hermite_weights_are_monotone_from_0_to_1(m0, m1):
    w = hermite_weights(30, m0, m1)
    assert w[0] == pytest.approx(0.0) and w[-1] == pytest.approx(1.0)
    assert np.all(np.diff(w) >= -1e-12)
    assert np.all((w >= -1e-12) & (w <= 1 + 1e-12))


def test_end_slopes_follow_eq_16():
    V0, V1, D, T = 0.4, 1.2, 0.3, 0.5  # m/s, m/s, m, s: mean speed 0.6 m/s
    m0, m1 = slope(V0, D, T), slope(V1, D, T)
    assert (m0, m1) == pytest.approx((0.4 / 0.6, 1.2 / 0.6))  # eq. (16): V(t) / (D / (t1 - t0))
    n = 400
    w = hermite_weights(n, m0, m1)
    du = 1.0 / n
    assert (w[1] - w[0]) / du == pytest.approx(m0, abs=0.01)  # dw/du at the ends
    assert (w[-1] - w[-2]) / du == pytest.approx(m1, abs=0.01)


def test_slope_is_zero_where_the_motion_reverses():
    assert slope(-0.5, 0.3, 0.5) == 0.0
    n = 2000
    w = hermite_weights(n, slope(-0.5, 0.3, 0.5), 1.0)
    assert (w[1] - w[0]) * n == pytest.approx(0.0, abs=2e-3)  # (a first difference of a flat start)
    assert (w[-1] - w[-2]) * n == pytest.approx(1.0, abs=2e-3)


def test_equal_poses_give_a_straight_line_and_steep_slopes_are_scaled_onto_the_circle():
    assert slope(0.7, 0.0, 0.5) == 1.0
    assert np.allclose(hermite_weights(10, 1.0, 1.0), linear_weights(10))
    m0, m1 = monotone_slopes(6.0, 8.0)
    assert np.hypot(m0, m1) == pytest.approx(MAX_SLOPE) and m0 / m1 == pytest.approx(0.75)


@pytest.mark.parametrize("kind, d, case, new_kind, span", [
    # pose -> motion: distance from the held pose to the motion's poses
    ("pose-motion", [0.0, 0.05, 0.1, 0.15, 0.2], "a", "pose-motion", (0, 4)),  # increases: Hermite
    ("pose-motion", [0.0, 0.1, 0.3, 0.1, 0.05], "b", "pose-motion", (0, 2)),  # maximum: weight 1 there
    ("pose-motion", [0.3, 0.2, 0.15, 0.1, 0.05], "c", "pose-pose", (0, 4)),  # decreases: pose-pose
    # motion -> pose: the same in reversed time
    ("motion-pose", [0.3, 0.2, 0.15, 0.1, 0.05], "a", "motion-pose", (0, 4)),  # approaches the pose
    ("motion-pose", [0.05, 0.1, 0.3, 0.1, 0.0], "b", "motion-pose", (2, 4)),  # the apex is kept: weight 0 to it
    ("motion-pose", [0.0, 0.05, 0.1, 0.15, 0.2], "c", "pose-pose", (0, 4)),  # moves away: pose-pose
])
def test_motion_pose_blends_follow_the_three_cases_of_4_4_2(kind, d, case, new_kind, span):
    pp = plan_partial(kind, np.array(d), min_frames=2)
    assert (pp.case, pp.kind, (pp.begin, pp.end)) == (case, new_kind, span)


def test_a_small_change_is_flat_and_a_maximum_needs_room():
    assert shape_of(np.array([0.1, 0.105, 0.1]))[0] == "flat"
    assert shape_of(np.array([0.6, 0.9, 0.5, 0.4, 0.3]), min_frames=2)[0] == "decrease"  # peak too early


# ------------------------------------------------------------------------------------------- §4.3 search
@lru_cache(maxsize=None)
def _cmu(name):
    return read_bvh(cmu(name), drop_first=True).resample(FPS)


def brute_force(fa_motion, fb_motion, joints, t0s, t1s, weights, p_len, min_len, motions=False):
    """eq. (10) pair by pair, in plain Python, from per-frame features."""
    fa = lambda t: features(fa_motion, joints, [t])[0]  # noqa: E731
    fb = lambda t: features(fb_motion, joints, [t])[0]  # noqa: E731
    best = (np.inf, None)
    for t0 in t0s:
        for t1 in t1s:
            if t1 - t0 < min_len:
                continue
            T = (t1 - t0) / FPS
            if motions:
                D = 0.5 * (distance(fa(t0), fb(t0)) + distance(fa(t1), fb(t1)))
                Qv = (abs(distance(fa(t0), fa(t0 + 1)) - distance(fb(t0), fb(t0 + 1))) * FPS
                      + abs(distance(fa(t1), fa(t1 + 1)) - distance(fb(t1), fb(t1 + 1))) * FPS)
            else:
                D = distance(fa(t0), fb(t1))  # eq. (13)
                V0 = (D - distance(fa(t0 + 1), fb(t1))) * FPS  # eq. (14) at the start
                V1 = (D - distance(fa(t0), fb(t1 - 1))) * FPS  # ... and at the end
                Qv = abs(V0 - D / T) + abs(V1 - D / T)  # eq. (15)
            Qt = abs(p_len / FPS - T) if p_len is not None else T  # eq. (11) / (12)
            cost = weights.time * Qt + weights.pose * D + weights.velocity * Qv
            if cost < best[0] - 1e-12:
                best = (cost, (t0, t1))
    return best


def _searched(a, b, joints, t0, t1, w, p_len, min_len):
    """The search of eq. (10) over start frames ``t0`` of ``a`` and end frames ``t1`` of ``b`` (both ``[lo, hi]``),
    the features it read, and the brute force's ``(cost, pair)`` over the same ranges."""
    fa = features(a, joints, np.arange(t0[0], t0[1] + 2))
    fb = features(b, joints, np.arange(t1[0] - 1, t1[1] + 1))
    f = search(fa, fb, t0, t1, FPS, w, p_len, min_len)
    return f, (fa, fb), brute_force(a, b, joints, range(t0[0], t0[1] + 1), range(t1[0], t1[1] + 1), w, p_len, min_len)


@pytest.mark.parametrize("part, p_len", [("lower", None), ("upper", 12), ("lower", 9)])
def test_search_returns_the_global_minimum_of_eq_10(part, p_len):
    walk, run = _cmu("16_15_walk"), _cmu("16_35_run")  # start poses from the walk, end poses from the run
    joints = part_joints(walk, part)
    t0, t1 = (10, 26), (28, 49)
    w = preset(0.5)
    f, (fa, fb), (cost, pair) = _searched(walk, run, joints, t0, t1, w, p_len, 3)
    assert (f.t0, f.t1) == pair
    assert f.cost == pytest.approx(cost, rel=1e-9)
    g = evaluate(fa, fb, t0, t1, FPS, w, p_len, 3)
    # every pair at least 3 frames apart was evaluated, no other
    assert np.isfinite(g.cost).sum() == sum(1 for a in g.t0 for b in g.t1 if b - a >= 3)


def test_search_on_one_clock_respects_the_shortest_blend():
    walk = _cmu("16_15_walk")
    joints = part_joints(walk, "upper")
    t0, t1 = (20, 40), (22, 60)
    w = preset(0.3)
    f, _, (cost, pair) = _searched(walk, walk, joints, t0, t1, w, None, 4)
    assert (f.t0, f.t1) == pair and f.cost == pytest.approx(cost) and f.t1 - f.t0 >= 4
    assert f.terms()["time"] == pytest.approx(w.time * f.Qt)


def test_motion_motion_search_is_the_global_minimum_too():
    walk, run = _cmu("16_15_walk"), _cmu("16_35_run")
    joints = part_joints(walk, "lower")
    t0, t1 = (5, 20), (12, 35)
    w = preset(0.7)
    fr0, fr1 = np.arange(t0[0], t0[1] + 2), np.arange(t1[0], t1[1] + 2)
    g = evaluate_motions(features(walk, joints, fr0), features(run, joints, fr0), features(walk, joints, fr1),
                         features(run, joints, fr1), t0, t1, FPS, w, 12, 3)
    i, j = np.unravel_index(np.argmin(g.cost), g.cost.shape)
    cost, pair = brute_force(walk, run, joints, range(t0[0], t0[1] + 1), range(t1[0], t1[1] + 1), w, 12, 3,
                             motions=True)
    assert pair == (int(g.t0[i]), int(g.t1[j])) and g.cost[i, j] == pytest.approx(cost)


def test_the_pose_distance_ignores_where_the_clip_stands():

    walk = _cmu("16_15_walk")
    moved = Rigid(1.1, (3.0, -2.0)).apply(walk)
    j = part_joints(walk, "whole")
    assert np.allclose(features(walk, j, [5, 17]), features(moved, j, [5, 17]), atol=1e-9)


def test_the_distance_grid_is_eq_13_for_every_pair_of_a_real_walk_and_run():
    from text2anim.synthesis.optimal.posedist import distance_matrix

    walk, run = _cmu("16_15_walk"), _cmu("16_35_run")
    j = part_joints(walk, "lower")
    fa, fb = features(walk, j, np.arange(3, 40)), features(run, j, np.arange(10, 31))
    D = distance_matrix(fa, fb)
    assert D.shape == (37, 21)
    # eq. (13) written out: the mean over joints of each pair's distance (the grid sums in the same order)
    want = np.sqrt((fa[:, None] - fb[None]) ** 2 @ np.ones(3)).mean(axis=-1)
    np.testing.assert_allclose(D, want, rtol=1e-14, atol=1e-15)
    assert D[4, 7] == pytest.approx(distance(fa[4], fb[7]), rel=1e-14)
    # the features of some frames are those frames' rows of all the frames' (clamped at the ends)
    every = features(run, j)
    assert np.array_equal(features(run, j, [-5, 0, 17, 10 ** 6]), every[[0, 0, 17, run.n_frames - 1]])


def test_the_user_weight_blends_the_two_presets():
    assert preset(0.0) == TIME_FIRST and preset(1.0) == SMOOTH_FIRST
    mid = preset(0.5)
    assert mid.time == pytest.approx(0.5 * (TIME_FIRST.time + SMOOTH_FIRST.time))
    assert mid.velocity == pytest.approx(0.5 * (TIME_FIRST.velocity + SMOOTH_FIRST.velocity))
    with pytest.raises(ValueError):
        preset(1.5)


# ----------------------------------------------------------------------------------------- §4.2 ranges
B = Bounds(c0_end=30, c1=(70, 100), a_end=60, b_first=40, m1_end=120, floor=0, min_len=3)


def test_transition_ranges_eqs_1_and_2():
    p0, p1 = Step("left", 32, 48), Step("left", 35, 50)
    s0, s1 = ranges(Choice("motion_transition", p0, p1, "right"), B)
    assert (s0.part, s0.kind, s0.eq, s1.part, s1.kind, s1.eq) == ("lower", "motion-motion", "(1)", "upper", "pose-pose", "(2)")
    assert s0.t0 == (40, 49)  # c0_end <= t0 < p1_end, and the next motion must be playing
    assert s0.t1 == (40, 70)  # p0_begin < t1 <= c1_begin
    assert s0.p_len == 16  # eq. (11) against the steps' mean length (16 and 15 frames)


def test_connection_ranges_eq_3_and_4():
    p0 = Step("right", 36, 50)
    s0, s1 = ranges(Choice("motion_connection", p0, None, "left"), B)
    assert s0.kind == "motion-pose" and s0.t0 == (36, 36)  # eq. (3): t_s0,begin = t_p0,begin
    assert s0.t1 == (40, 70) and s0.p_len == 14
    assert s1.t0[0] == 37 and s1.t1[1] == 70  # eq. (4): p0_begin < t_s1 < c1_begin


def test_adaptation_ranges_eqs_5_to_9():
    p1 = Step("left", 80, 95)
    s0, s1, s3 = ranges(Choice("motion_adaptation_step", None, p1, "right"), B)
    assert (s0.kind, s1.kind, s3.kind) == ("pose-pose", "pose-pose", "pose-motion")
    assert s0.src == ("A", "Bad") and s3.src == ("Bad", "B")
    assert s0.t0 == (30, 59) and s0.t1[1] == 80  # S0 ends before the step (eq. (7): S2 between)
    assert s3.t1 == (95, 95) and s3.t0[0] == 80  # eq. (8): t_s3,end = t_p1,end; the foot is in the air
    assert after(s3, 86, 3).t0[0] == 86
    (s0n, _) = ranges(Choice("motion_adaptation"), B)
    assert s0n.t1[1] == 119  # eq. (5)/(9): up to the end of the next motion


def test_a_range_without_room_is_widened_into_the_core():
    tight = Bounds(c0_end=30, c1=(31, 60), a_end=40, b_first=20, m1_end=80)
    s0, _ = ranges(Choice("motion_connection", Step("right", 30, 40), None, "left"), tight)
    assert not s0.feasible(3)
    r = s0.relax(3)
    assert r.feasible(3) and r.relaxed and r.t1[1] == 33


# ------------------------------------------------------------------------------------ §4.2.5 selection
def test_selection_follows_the_papers_priority():
    a = [Step("left", 40, 52), Step("right", 52, 64)]
    same_time = [Step("left", 42, 53)]
    other_foot = [Step("right", 42, 53)]
    assert select(a, same_time, 35, (70, 90)).method == "motion_transition"
    assert select(a, other_foot, 35, (70, 90)).method == "motion_connection"
    c = select(a, other_foot, 35, (70, 90))
    assert c.p0 == Step("left", 40, 52) and c.support == "right"  # the step nearest the core
    assert select([], [Step("left", 80, 92)], 35, (70, 90), b_first=40).method == "motion_adaptation_step"
    assert select([], [], 35, (70, 90)).method == "motion_adaptation"
    # a step that *is* the next core (the kick itself) cannot be blended: no transition
    assert select(a, [Step("left", 70, 90)], 35, (70, 100)).method == "motion_connection"
    # a step of the first motion inside its core does not count
    assert select(a, same_time, 45, (70, 90)).p0 == Step("right", 52, 64)


def test_a_looped_clip_is_all_core_but_the_step_a_join_uses():
    st = [Step("left", 10, 20), Step("right", 22, 32), Step("left", 34, 44)]
    assert cyclic_core_end(st, 0, 40, (0, 60)) == 34
    assert cyclic_core_begin(st, 12, (0, 60)) == 32
