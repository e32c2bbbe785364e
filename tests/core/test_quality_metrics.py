"""The literature's quality figures (docs/timetable.md §3, issue 11) on motions whose answer is known by
construction, and on real captures.

Constructed motions hold one real CMU pose (``16_01_jump`` frame 0, standing) and move it rigidly or
lift one leg, so toe heights, speeds and accelerations are known exactly.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from shared_data import cmu, requires_cmu
from text2anim.core import Motion, read_bvh
from text2anim.core.metrics import (against_limits, against_sources, quality, root_acceleration, skating_by_frame,
                                    skating_pairs, skating_ratio, toe_joints)

pytestmark = requires_cmu
FPS = 30.0


def _pose() -> Motion:
    return read_bvh(cmu("16_01_jump"), drop_first=True)[:1]


def _held(n: int, root_xz, height: float = 0.02, fps: float = FPS, lift_left: bool = False) -> Motion:
    """The standing pose for ``n`` frames, its toes ``height`` m above y = 0, the root at ``root_xz(t)`` ``(n, 2)``."""
    m = _pose()
    rot = m.rotations.copy()
    if lift_left:  # bend the left hip 70 degrees forward: that foot leaves the floor
        j = m.skeleton.index("LeftUpLeg")
        rot[0, j] = (Rotation.from_quat(rot[0, j]) * Rotation.from_euler("x", -70, degrees=True)).as_quat()
    still = Motion(m.skeleton, fps, m.root_positions, rot)
    toes_y = still.positions[0, toe_joints(still), 1].min()
    root = np.repeat(m.root_positions[:1], n, axis=0)
    root[:, 1] += height - toes_y
    root[:, [0, 2]] += root_xz(np.arange(n) / fps)
    return Motion(m.skeleton, fps, root, np.repeat(rot, n, axis=0))


def _slide(speed):
    return lambda t: np.stack([speed * t, np.zeros_like(t)], axis=1)


def test_a_foot_sliding_at_1_m_s_at_2_cm_skates_on_every_frame():
    m = _held(60, _slide(1.0))
    assert skating_ratio(m) == 1.0
    assert quality(m).skating_ratio == 1.0


def test_a_foot_sliding_at_0_3_m_s_does_not_skate():
    assert skating_ratio(_held(60, _slide(0.3))) == 0.0


def test_a_foot_sliding_6_cm_above_the_floor_does_not_skate():
    assert skating_ratio(_held(60, _slide(1.0), height=0.06)) == 0.0


def test_one_skating_foot_is_enough():
    m = _held(60, _slide(1.0), lift_left=True)
    left, right = m.positions[0, toe_joints(m), 1]
    assert left > 0.10 and right == pytest.approx(0.02)  # the construction: one foot up, one down
    assert skating_pairs(m).all()  # GMD's np.logical_or over the feet, not "both feet"


def test_the_speed_must_also_hold_over_five_frames():
    # one fast frame pair in a still hold: above 0.5 m/s, but its 5-frame average is 1/5 of it
    step = np.zeros((30, 2))
    step[15:, 0] = 2.0 / FPS  # 2 m/s for one frame pair -> average 0.4 m/s
    m = _held(30, lambda t: step)
    assert skating_ratio(m) == 0.0
    step[15:, 0] = 3.0 / FPS  # 3 m/s -> average 0.6 m/s: skates, on that pair only
    m = _held(30, lambda t: step)
    assert skating_pairs(m).nonzero()[0].tolist() == [14]
    assert skating_by_frame(m).nonzero()[0].tolist() == [14] and len(skating_by_frame(m)) == 30


def test_a_velocity_step_of_the_hips_gives_its_acceleration_spread_over_the_average():
    # 1 m/s, then 3 m/s from frame 30: a velocity step of 2 m/s. After the 3-frame average of position,
    # the second difference spreads it over three frames: 2 m/s * 30 fps / 3 = 20 m/s^2.
    def path(t):
        x = np.where(t < 1.0, t, 1.0 + 3.0 * (t - 1.0))
        return np.stack([x, np.zeros_like(t)], axis=1)

    m = _held(60, path)
    assert quality(m).root_pop == pytest.approx(20.0, rel=1e-6)
    acc = root_acceleration(m)
    assert np.count_nonzero(acc > 1e-6) == 3
    assert quality(_held(60, _slide(1.5))).root_pop == pytest.approx(0.0, abs=1e-6)  # constant speed: no pop


def test_a_hips_jump_of_3_cm_in_one_frame_pops():
    jump = np.zeros((60, 2))
    jump[30:, 1] = 0.03  # the hips move 3 cm sideways between two frames: 0.03 m * 30^2 / 3 = 9 m/s^2
    assert quality(_held(60, lambda t: jump)).root_pop == pytest.approx(9.0, rel=1e-6)


def test_figures_compare_at_30_fps_whatever_the_file_rate():
    def path(t):
        x = np.where(t < 1.0, t, 1.0 + 3.0 * (t - 1.0))
        return np.stack([x, np.zeros_like(t)], axis=1)

    fast = _held(240, path, fps=120.0)
    q = quality(fast)
    assert q.fps == 30.0 and q.frames == 60
    assert q.root_pop == pytest.approx(20.0, rel=1e-3)
    assert quality(fast, fps=None).root_pop == pytest.approx(2.0 * 120 / 3, rel=1e-3)  # at its own rate: 4x


def test_floor_penetration_is_the_lowest_joint_or_end_site_below_y0_in_cm():
    sunk = _held(30, _slide(0.0), height=-0.03)
    tip = float(sunk.end_site_positions()[..., 1].min())
    assert tip < -0.035  # the toe's tip lies under its joint: joints alone would say 3 cm
    assert quality(sunk).floor_penetration_cm == pytest.approx(-tip * 100, abs=1e-6)
    assert quality(_held(30, _slide(0.0), height=0.01 + (-0.03 - tip))).floor_penetration_cm == 0.0


def test_gmd_skating_reads_heights_above_the_motions_own_lowest_foot_point():
    # toes 6 cm up: above the floor-true 5 cm, but on GMD's floor (the lowest foot point) they are at 0
    sliding = _held(30, _slide(1.0), height=0.06)
    q = quality(sliding)
    assert q.skating_ratio == 0.0
    assert q.skating_gmd == pytest.approx(1.0)
    assert quality(_held(30, _slide(0.2), height=0.06)).skating_gmd == 0.0  # slow: no skating either way


def test_frozen_frames_are_those_where_every_joint_is_still():
    assert quality(_held(30, _slide(0.0))).frozen_fraction == 1.0
    assert quality(_held(30, _slide(0.004))).frozen_fraction == 1.0  # 0.4 cm/s: below 0.5 cm/s
    assert quality(_held(30, _slide(0.01))).frozen_fraction == 0.0

    def half(t):
        return np.stack([np.maximum(t - 0.5, 0.0), np.zeros_like(t)], axis=1)

    q = quality(_held(31, half))  # still for 15 of the 30 frame pairs, then 1 m/s
    assert q.frozen_fraction == pytest.approx(15 / 30)


def test_jerk_p99_of_a_cubic_path_is_its_constant_jerk():
    m = _held(60, lambda t: np.stack([t ** 3, np.zeros_like(t)], axis=1))
    assert quality(m).jerk_p99 == pytest.approx(6.0, rel=1e-6)


def test_a_window_measures_only_its_frames():
    def path(t):
        x = np.where(t < 1.0, t, 1.0 + 3.0 * (t - 1.0))
        return np.stack([x, np.zeros_like(t)], axis=1)

    m = _held(90, path)
    assert quality(m, window=(0.5, 1.5)).root_pop == pytest.approx(20.0)
    assert quality(m, window=(1.5, 3.0)).root_pop == pytest.approx(0.0, abs=1e-6)


def test_criteria_against_sources_and_limits():
    src = [quality(_held(60, _slide(1.0 if k else 0.2))) for k in (0, 1)]
    still = quality(_held(60, _slide(0.0)))
    assert against_sources(src[0], src) == {"skating": True, "root_pop": True, "jerk": True,
                                            "penetration": True, "frozen": True, "floating": True}
    bad = against_sources(still, src)
    assert bad["frozen"] is False and bad["skating"] is True
    assert against_limits(src[1])["skating"] is False  # a 1 m/s slide skates on every frame


@pytest.mark.parametrize("name", ["02_01_walk", "07_02_walk", "07_04_slowwalk", "16_15_walk"])
def test_a_real_walk_skates_within_the_published_range(name):
    # CMU capture at 30 fps: 0-0.075 (docs/timetable.md §3). Files as captured (their toe joints planted 0.6-2.2 cm
    # above y = 0).
    q = quality(read_bvh(cmu(name), drop_first=True))
    assert 0.0 <= q.skating_ratio <= 0.075
    assert 2.0 < q.root_pop < 7.0  # walking at 30 fps: 4-6 m/s^2 (docs/timetable.md §3), within a margin
    assert q.frozen_fraction == 0.0
