"""Floating feet (docs/timetable.md §3, core.floating): a still foot on a leg hanging straight down, off
the floor. Measured on the built-in library's clips, on real CMU captures and on motions lifted off the floor."""
from __future__ import annotations

import numpy as np
import pytest

from shared_data import CMU_FILES, cmu, requires_cmu
from text2anim.core import read_bvh
from text2anim.core.floating import floating_cm, floating_heights
from text2anim.core.bodyparts import body_map
from text2anim.core.floor import FOOT_CLEARANCE, place_on_floor
from text2anim.core.metrics import BUILTIN_LIMITS, quality
from text2anim.core.size import at_human_size
from text2anim.motiondb import MotionDB


@pytest.fixture(scope="module")
def clips(library_db):
    with MotionDB.open(library_db) as db:
        return {c.name: db.load(c.name) for c in db.clips()}


def _lifted(motion, metres: float):
    root = motion.root_positions.copy()
    root[:, 1] += metres
    return motion.replace(root_positions=root)


def test_no_built_in_clip_stands_on_air(clips):
    worst = max(clips, key=lambda n: floating_cm(clips[n]))
    assert floating_cm(clips[worst]) <= BUILTIN_LIMITS["floating_cm"], worst


@pytest.mark.parametrize("name", ["walk", "wait", "wave_hand"])
def test_a_body_lifted_off_the_floor_floats_by_the_lift(clips, name):
    base = floating_cm(clips[name])
    lifted = floating_cm(_lifted(clips[name], 0.30))
    assert lifted == pytest.approx(base + 30.0, abs=3.0) and lifted > BUILTIN_LIMITS["floating_cm"]
    assert quality(_lifted(clips[name], 0.30)).floating_cm == pytest.approx(lifted, abs=3.0)  # at 30 fps too


def test_a_raised_bent_leg_is_no_floating_foot(clips):
    """A kick's chamber and a knee raise hold a foot up, but on a bent leg: not standing on air."""
    for name in ("kick", "exercise", "squat"):
        heights = floating_heights(clips[name])
        assert heights.max() * 100 <= BUILTIN_LIMITS["floating_cm"], name


@requires_cmu
def test_real_capture_on_the_floor_stays_within_the_calibration():
    """Capture of people on the floor (walks, runs, kicks, sitting, ...) floats at most 14 cm (docs/timetable.md §3)."""
    worst = []
    for path in CMU_FILES:
        m, _ = place_on_floor(read_bvh(path, drop_first=True))
        m, _ = at_human_size(m)
        worst.append((floating_cm(m.resample(30)), path.name))
    assert max(worst)[0] <= 15.0, max(worst)
    assert np.median([w for w, _ in worst]) < 8.0


@requires_cmu
def test_a_foot_on_its_heel_stands_on_the_floor():
    """CMU 05_03 (a dance), 0.40-0.72 s on its own floor: the left leg straight and still, the foot on its heel
    with the toes raised above the ankle. Its lowest joint is the ankle, 5.2 cm up, which read as a foot on
    air (pitch → dance floated 6.6 cm where its sources' limit was 5.1); the heel stands no higher than a
    planted ball does (FOOT_CLEARANCE), and the same foot lifted 30 cm still reads the lift."""
    m, _ = place_on_floor(read_bvh(cmu("05_03_dance"), drop_first=True))
    heel = m.resample(30).between(0.40, 0.72)
    ankle, toe = body_map(heel.skeleton).feet["left"]
    y = heel.positions[..., 1]
    assert (y[:, toe] > y[:, ankle]).all() and y[:, ankle].min() > 0.05  # toes up, the ankle 5 cm up or more
    assert 0.0 < floating_cm(heel) <= 100 * FOOT_CLEARANCE
    assert floating_cm(_lifted(heel, 0.30)) == pytest.approx(floating_cm(heel) + 30.0, abs=1.0)
