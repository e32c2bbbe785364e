"""The join post-pass's candidates (synthesis.join.smoothing): their figures are the quality metrics' own bits,
the bounds the search prunes by hold, and re-planting several widths at once is re-planting each alone."""
from __future__ import annotations

import numpy as np
import pytest

from shared_data import library_motion
from text2anim.core.contacts import detect_contacts
from text2anim.core.metrics import jerk_p99, joint_jerk, peak_hips_acceleration, quality
from text2anim.core.motion import Motion
from text2anim.synthesis.join.smoothing import Stretch, low_pass_all, plant_all

WIDTHS = (0.0, 1.0, 2.0, 4.0, 8.0)


@pytest.fixture(scope="module")
def kick():
    return library_motion("kick")  # 54 frames: steps in, kicks on one foot, steps back


def _stretch(motion, lo=10, hi=44):
    """A real region of ``motion``: smoothed over ``[lo, hi)``, its feet kept where its contacts are."""
    contacts = detect_contacts(motion)
    planted = {side: contacts.of(side)[:motion.n_frames] for side in ("left", "right")}
    return Stretch(motion, motion, lo, hi, planted)


@pytest.mark.parametrize("name", ["run", "walk", "kick"])
def test_figures_are_the_quality_metrics_bits(name):
    m = library_motion(name)
    for a, b in [(0, m.n_frames), (10, 40), (5, 9), (5, 8), (3, 6)]:  # whole, a window, and too short for one
        part = m[a:b]
        q = quality(part, None)
        assert jerk_p99(joint_jerk(part.positions, part.fps)) == q.jerk_p99
        assert peak_hips_acceleration(part.root_positions, part.fps) == q.root_pop


def test_jerk_floor_and_pop_bound_the_planted_figures(kick):
    st = _stretch(kick)
    assert len(st.feet) == 2, "both feet touch the floor in the region: they are kept"
    widths = [st.smoothed(s, 6, 6) for s in WIDTHS]
    before = [(w.pop, w.jk_floor) for w in widths]
    plant_all(widths)
    for (pop, floor), w in zip(before, widths):
        jk, planted_pop = w.plant()
        assert planted_pop == pop  # re-planting the feet moves no hips: the pop is exact before
        assert 0.0 < floor <= jk  # and the jerk of the joints the leg IK leaves alone bounds the p99
        q = quality(w.motion()[st.a:st.b], None)  # the whole candidate, measured as the metrics do
        assert (q.jerk_p99, q.root_pop) == (jk, pop)


def test_widths_replanted_together_are_each_replanted_alone(kick):
    st = _stretch(kick)
    together = [st.smoothed(s, 6, 6) for s in WIDTHS]
    plant_all(together)
    for s, w in zip(WIDTHS, together):
        alone = st.smoothed(s, 6, 6)
        assert alone.plant() == w.plant()
        assert alone.motion().rotations.tobytes() == w.motion().rotations.tobytes()
    moved = together[2].motion().rotations != together[2].stretch.base.rotations
    assert moved[st.lo:st.hi].any() and not moved[:st.lo].any() and not moved[st.hi:].any()
    # the feet are back where the reference has them on their contact frames, however wide the smoothing
    for _side, ankle, c, target, _ in st.feet:
        on = np.flatnonzero(c == 1.0)
        for w in together:
            assert len(on) and np.abs(w.sub.positions[on, ankle] - target[on]).max() < 1e-9


def test_widths_low_passed_together_are_each_low_passed_alone(kick):
    st = _stretch(kick)
    together = [st.smoothed(s, 6, 6) for s in WIDTHS]
    low_pass_all(together)
    for s, w in zip(WIDTHS, together):
        alone = st.smoothed(s, 6, 6)
        assert alone.sub.rotations.tobytes() == w.sub.rotations.tobytes()
        assert alone.sub.positions.tobytes() == w.sub.positions.tobytes()  # their kinematics, run at once
        assert (alone.jk_floor, alone.plant()) == (w.jk_floor, w.plant())


def testsource_figures_are_remembered_by_content_not_by_object():
    from text2anim.synthesis.join.joinpass import source_figures

    kick = library_motion("kick")
    q = quality(kick, 30.0)
    assert source_figures(kick, 30.0) == (q.jerk_p99, q.root_pop)
    faster = kick.replace(root_positions=kick.root_positions * 1.5)  # same frame count, other content
    q2 = quality(faster, 30.0)
    assert source_figures(faster, 30.0) == (q2.jerk_p99, q2.root_pop) != (q.jerk_p99, q.root_pop)
    copy = Motion(kick.skeleton, kick.fps, kick.root_positions.copy(), kick.rotations.copy())
    assert source_figures(copy, 30.0) == (q.jerk_p99, q.root_pop)  # a copy: the same figures
    q60 = quality(kick, 60.0)
    assert source_figures(kick, 60.0) == (q60.jerk_p99, q60.root_pop)


@pytest.mark.parametrize(("lims", "fewer"), [((100.0, 0.5, 50.0, 0.4), True),  # the pop decides: bounds prune
                                             ((1.0, 100.0, 1.0, 50.0), False),  # the jerk decides
                                             ((1e-9, 1e-9, 1e-9, 1e-9), False)])  # scores ~1e12: rounding
def test_the_fallback_chooses_as_re_planting_every_width_does(kick, lims, fewer):
    """No width within the limits: the least score, first in order, is chosen; found from bounds (with
    fewer widths re-planted where the bounds allow), it is the plain scan's over every exact score."""
    from text2anim.synthesis.join.pruning import least

    def tried():
        stretches = [_stretch(kick, 10, 44), _stretch(kick, 12, 40)]
        return [(s, k, st.smoothed(s, 6, 6), st.hi) for k, st in enumerate(stretches) for s in WIDTHS]

    plain = tried()
    best = None
    for s, k, c, h in plain:
        jk, pop = c.plant()
        score = max(jk / lims[0], pop / lims[1])
        if best is None or score < best[0] - 1e-9:
            best = (score, s, k, c, jk, pop, h)
    lazy = tried()
    got = least(lazy, lims)
    assert got[1:3] == best[1:3] and got[4:] == best[4:] and got[0] == best[0]
    assert (sum(c.jk is not None for _s, _k, c, _h in lazy) < len(lazy)) == fewer


def test_a_deferred_stretch_is_the_stretch_its_frames_make(kick):
    """A stretch whose frames are retimed only when a width's rotations are asked (the post-pass's): the same pops
    from the hips' path alone, sampled as the retiming samples it, and the same candidates once made."""
    from text2anim.synthesis.join.blend import sample_path
    from text2anim.synthesis.join.joinpass import replay, warp_frames
    from text2anim.synthesis.join.smoothing import Deferred

    lo, hi = 10, 44
    src = warp_frames(hi - lo, 47)
    retimed = replay(kick, lo, hi, src)
    contacts = detect_contacts(kick)
    idx = np.round(np.concatenate([np.arange(lo), lo + src, np.arange(hi, kick.n_frames)])).astype(int)
    planted = {side: contacts.of(side)[:kick.n_frames][idx] for side in ("left", "right")}
    path = kick.root_positions
    made = []

    def make():
        made.append(True)
        return retimed, retimed

    root = np.concatenate([path[:lo], sample_path(path, lo + src), path[hi:]])
    assert root.tobytes() == retimed.root_positions.tobytes()
    h2 = lo + len(src)
    eager, deferred = Stretch(retimed, retimed, lo, h2, planted), Stretch(Deferred(root, kick.fps, make), None, lo, h2,
                                                                          planted)
    widths = [(s, 6, 6) for s in WIDTHS]
    pops = [deferred.smoothed(*w).pop for w in widths]
    assert not made, "the pops need no retimed rotations"
    assert pops == [eager.smoothed(*w).pop for w in widths]
    for w in widths:
        a, b = eager.smoothed(*w), deferred.smoothed(*w)
        assert a.plant() == b.plant()
        assert a.motion().rotations.tobytes() == b.motion().rotations.tobytes()
    assert made == [True]


@pytest.mark.parametrize("origin", [0, 37])
def test_the_engine_output_retimed_beside_the_seamed_region_is_its_own_replay(kick, origin):
    """The post-pass retimes the seamed region and the engine's output alike (:func:`joinpass.replay_both`), the
    second sampled only where the seams changed frames: both are :func:`joinpass.replay`'s, bit for bit, also on a
    window of a track (``origin``)."""
    from text2anim.synthesis.join.inertialize import inertialize_at
    from text2anim.synthesis.join.joinpass import replay, replay_both, warp_frames

    lo, hi = 10, 44
    seamed = inertialize_at(kick, 30, 0.3)  # frames from the seam on changed, those before it not
    assert (seamed.rotations[:30] == kick.rotations[:30]).all() and (seamed.rotations[31:40] != kick.rotations[31:40]).any()
    src = warp_frames(hi - lo, 50)
    base, ref = replay_both(seamed, kick, lo, hi, src, origin)
    for got, motion in ((base, seamed), (ref, kick)):
        want = replay(motion, lo, hi, src, origin)
        assert got.root_positions.tobytes() == want.root_positions.tobytes()
        assert got.rotations.tobytes() == want.rotations.tobytes()
