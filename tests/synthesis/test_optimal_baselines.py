"""The comparison's baselines (``pose``, ``crossfade``) and the dispatcher, on real captures (CMU)."""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from text2anim.core import read_bvh
from text2anim.synthesis.baselines import BLEND, closest_pair
from text2anim.synthesis.registry import METHODS, UnknownMethodError, synthesize_with
from text2anim.synthesis.tracks import Clip, Element, Track
from text2anim.synthesis.optimal.posedist import distance, features
from text2anim.synthesis.join.cycles import find_cycle

from shared_data import cmu, requires_cmu

pytestmark = requires_cmu
FPS = 30


@lru_cache(maxsize=None)
def track() -> Track:
    walk = read_bvh(cmu("16_15_walk"), drop_first=True).resample(FPS)
    a, b = find_cycle(walk)
    kick = read_bvh(cmu("10_03_kick"), drop_first=True).resample(FPS).between(0, 2.8)
    w = Clip("walk", walk[a:b], (0.0, (b - a) / FPS), cyclic=True)
    k = Clip("kick", kick, (0.7, 1.5))
    return Track(None, (Element(1, w, 0.0, 3.0, "initial"), Element(2, k, 3.0, 5.8, "connection", prev=1)))


def test_the_pose_baseline_centres_its_blend_on_the_closest_poses():
    walk = track().elements[0].clip.motion
    kick = track().elements[1].clip.motion
    i, j, d = closest_pair(walk, (5, 25), kick, (0, 15))
    joints = list(range(walk.skeleton.n_joints))
    brute = min((distance(features(walk, joints, [x])[0], features(kick, joints, [y])[0]), x, y)
                for x in range(5, 26) for y in range(0, 16))
    assert (d, i, j) == pytest.approx(brute)
    res = synthesize_with("pose", [track()], FPS)
    (jr,) = res.joins
    iv = jr.intervals[0]
    assert jr.blend == "pose" and iv.kind == "motion-motion"
    assert iv.end - iv.begin == pytest.approx(BLEND, abs=1 / FPS)  # fixed length
    centre = jr.metrics["closest_s"][0]
    assert (iv.begin + iv.end) / 2 == pytest.approx(centre, abs=1 / FPS)


def test_the_crossfade_starts_when_the_next_motion_is_scheduled():
    res = synthesize_with("crossfade", [track()], FPS)
    (jr,) = res.joins
    assert jr.blend == "crossfade"
    assert jr.intervals[0].begin == pytest.approx(3.0, abs=1 / FPS)
    assert jr.intervals[0].end - jr.intervals[0].begin == pytest.approx(BLEND, abs=1 / FPS)


@pytest.mark.parametrize("method", METHODS)
def test_every_method_gives_one_motion_with_a_report(method):
    res = synthesize_with(method, [track()], FPS)
    m = res.motions[None]
    assert m.fps == FPS and m.n_frames >= round(5.5 * FPS)
    assert np.isfinite(m.rotations).all() and np.isfinite(m.root_positions).all()
    (jr,) = res.joins
    assert {"skating_ratio", "jerk_max", "jerk_rms", "core_fidelity_cm"} <= set(jr.metrics)


def test_an_unknown_method_is_the_users_error():
    with pytest.raises(UnknownMethodError, match="warp"):
        synthesize_with("warp", [track()], FPS)
    assert UnknownMethodError.user_facing


@pytest.mark.parametrize("method", METHODS)
def test_a_repeated_partial_motion_over_a_slow_walk_renders_with_every_method(method, library_db):
    """The pose baseline searched the previous clip past the end of the track it had laid (an
    IndexError on this corpus sentence once the built-in walk became a captured cycle)."""
    import text2anim

    anim = text2anim.animate("太郎はゆっくり歩きながら、右手を3回振る。", db=library_db, blend=method)
    (motion,) = anim.motions.values()
    assert motion.n_frames > 0 and np.all(np.isfinite(motion.positions))
