"""Foot contacts on real captures, and the quality metrics on motions with a known answer."""
from __future__ import annotations

import numpy as np
import pytest

from shared_data import cmu
from text2anim.core import Motion, read_bvh
from text2anim.core.contacts import detect_contacts, hysteresis, runs
from text2anim.core.metrics import BUILTIN_LIMITS, compute_metrics, foot_skate, jerk, quality, skating_ratio, speed_curves


def _steps(c):
    """Contact intervals of both feet in time order, as (start, side)."""
    return sorted((a, side) for side in ("left", "right") for a, _ in c.intervals(side))


@pytest.mark.parametrize("name, seconds_per_step", [("02_01_walk", (0.45, 0.7)), ("16_15_walk", (0.45, 0.7))])
def test_walk_contacts_alternate_with_plausible_cadence(name, seconds_per_step):
    m = read_bvh(cmu(name), drop_first=True)
    c = detect_contacts(m)
    steps = _steps(c)
    sides = [s for _, s in steps]
    assert all(a != b for a, b in zip(sides, sides[1:])), sides
    lo, hi = seconds_per_step
    assert m.duration / hi - 1 <= len(steps) <= m.duration / lo + 1
    # Walking has double support and never a flight phase.
    names = {st for a, b, st in c.phases() if b - a > 2}
    assert "both" in names and "none" not in names


@pytest.mark.parametrize("name", ["02_03_run", "16_35_run", "127_07_run"])
def test_run_contacts_alternate_with_flight(name):
    m = read_bvh(cmu(name), drop_first=True)
    c = detect_contacts(m)
    sides = [s for _, s in _steps(c)]
    assert len(sides) >= 3 and all(a != b for a, b in zip(sides, sides[1:]))
    assert any(st == "none" and (b - a) / m.fps > 0.08 for a, b, st in c.phases())


def test_jump_has_one_flight_with_both_feet_down_around_it():
    m = read_bvh(cmu("16_01_jump"), drop_first=True)
    phases = [(st, (b - a) / m.fps) for a, b, st in detect_contacts(m).phases()]
    flights = [d for st, d in phases if st == "none" and d > 0.1]
    assert len(flights) == 1 and 0.25 < flights[0] < 0.6
    assert phases[0][0] == "both" and phases[-1][0] == "both"


def test_hysteresis_removes_flicker():
    mask = np.array([1, 1, 1, 1, 0, 1, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 1, 1], dtype=bool)
    clean = hysteresis(mask, 3)
    assert runs(clean).tolist() == [[0, 8], [17, 21]]
    # a short gap at either end is kept (the clip may start or stop mid-step); a short run there is not
    edges = np.array([0, 0, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 0], dtype=bool)
    assert runs(hysteresis(edges, 3)).tolist() == [[2, 15]]
    assert not hysteresis(np.array([1, 1, 0, 0, 0, 0, 0, 0, 1], dtype=bool), 3).any()


def _standing(m: Motion, n: int, velocity=(0.0, 0.0, 0.0)) -> Motion:
    """Frame 0 of ``m`` held for ``n`` frames, the root moving at ``velocity`` m/s."""
    root = m.root_positions[0] + np.outer(np.arange(n) / m.fps, velocity)
    return Motion(m.skeleton, m.fps, root, np.repeat(m.rotations[:1], n, axis=0))


def test_still_pose_has_no_skate_and_no_jerk():
    m = _standing(read_bvh(cmu("16_01_jump"), drop_first=True), 120)
    met = compute_metrics(m)
    assert met.skating_ratio == 0
    assert all(fs.contact_frames == 120 and fs.slide_cm == pytest.approx(0, abs=1e-9) for fs in met.foot_skate.values())
    assert met.jerk.max == pytest.approx(0, abs=1e-6)


def test_slow_slide_is_skate_in_contact():
    m = _standing(read_bvh(cmu("16_01_jump"), drop_first=True), 120, velocity=(0.2, 0, 0))
    for fs in foot_skate(m).values():
        assert fs.mean_speed_cm_s == pytest.approx(20, rel=1e-3)
        assert fs.slide_cm == pytest.approx(20 * m.duration, rel=0.02)
    assert skating_ratio(m) == 0  # 0.2 m/s is below the GMD skating speed


def test_fast_slide_is_skating():
    m = _standing(read_bvh(cmu("16_01_jump"), drop_first=True), 120, velocity=(0, 0, 1.0))
    assert skating_ratio(m) == 1.0


def test_real_walk_does_not_skate_and_speed_curves_match_travel():
    m = read_bvh(cmu("16_15_walk"), drop_first=True)
    assert quality(m).skating_ratio <= BUILTIN_LIMITS["skating_ratio"]  # GMD ratio at 30 fps
    curves = speed_curves(m)
    hips = m.positions[:, 0]
    travel = np.linalg.norm(hips[-1, [0, 2]] - hips[0, [0, 2]]) / m.duration
    assert 1.0 < travel < 1.8
    assert curves.lower.mean() == pytest.approx(travel, rel=0.35)
    assert curves.upper.shape == curves.lower.shape == (m.n_frames,)


def test_jerk_of_constant_acceleration_is_zero_and_of_a_cubic_is_constant():
    base = read_bvh(cmu("16_01_jump"), drop_first=True)
    t = np.arange(60) / base.fps
    for power, expected in ((2, 0.0), (3, 6.0)):
        root = base.root_positions[0] + np.outer(t ** power, [1.0, 0, 0])
        m = Motion(base.skeleton, base.fps, root, np.repeat(base.rotations[:1], 60, axis=0))
        j = jerk(m)
        assert j.max == pytest.approx(expected, abs=1e-3 * max(expected, 1) + 1e-4)
