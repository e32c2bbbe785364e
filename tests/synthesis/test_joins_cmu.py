"""Joins of real captures (CMU) meet issue 11's criteria against their own two source clips.

Clips are cut as ``benchmarks/bench_quality.py`` cuts them, imported into a throw-away SQLite motion
database and read back at 30 fps; the time table follows the scheduler (a transition at the last
step of a looping first clip, else a connection when the first ends). The output of the default engine
(optimal blending, and the constraint engine it may fall back to) is compared with the two sources by
:func:`core.metrics.against_sources`: skating ratio <= the sources' larger + 0.01, root pop and joint
jerk p99 <= 1.2 x the sources' larger, floor penetration <= 1 cm, frozen frames <= 5 %.
(The figures of all pairs and methods are in the benchmark, not here.)
"""
from __future__ import annotations

import pytest

from text2anim.core import read_bvh
from text2anim.core.metrics import against_sources, quality
from text2anim.motiondb import ClipRecord, MotionDB
from text2anim.pipeline import timing
from text2anim.scheduler.lengths import transition_window
from text2anim.synthesis.engines import synthesize_with
from text2anim.synthesis.plan import Clip, Element, Track
from text2anim.synthesis.timing import gait_cycle

from shared_data import cmu, requires_cmu

pytestmark = requires_cmu
FPS = 30.0

#: name: (file stem, cut (s) or None for one gait cycle, core (s, in the cut))
CUTS = {"walk": ("02_01_walk", None, None), "run": ("02_03_run", None, None),
        "pitch": ("124_01_throw", (1.8, 5.3), (0.6, 2.2)), "pickup": ("02_06_pickup", (0.2, 2.6), (0.5, 1.8)),
        "frontkick": ("135_04_kick", (1.7, 4.0), (0.8, 1.9)), "dance": ("05_03_dance", (0.0, 3.6), (0.5, 3.0)),
        "run127": ("127_07_run", None, None), "shot": ("06_14_throw", (1.8, 4.0), (0.4, 1.5))}


@pytest.fixture(scope="module")
def clips(tmp_path_factory):
    records = []
    for name, (stem, cut, core) in CUTS.items():
        m = read_bvh(cmu(stem), drop_first=True)
        if cut is None:
            a, b = gait_cycle(m)
            m, core = m[a:b], (0.0, (b - a) / m.fps)
        else:
            m = m.between(*cut)
        records.append(ClipRecord(name=name, motion=m, verbs=("動く",), core=core, cyclic=cut is None,
                                  character="cmu", source=str(cmu(stem))))
    url = f"sqlite:///{tmp_path_factory.mktemp('db')}/cmu.sqlite"
    with MotionDB.open(url, seed=False) as db:
        db.add(records)
        out = {}
        for info in db.clips():
            m = db.load(info)
            out[info.name] = (info, Clip(info.name, m.resample(FPS) if m.fps != FPS else m, tuple(info.core),
                                         info.cyclic))
    return out


#: seconds a looping clip plays, as in the benchmark
LOOPED = {"walk": 3.0, "run": 2.4, "run127": 2.4}


def track_of(clips, first: str, second: str) -> Track:
    (ia, ca), (ib, cb) = clips[first], clips[second]
    la = LOOPED[first] if ca.cyclic else ca.motion.duration
    lb = LOOPED[second] if cb.cyclic else cb.motion.duration
    how, start, end_a = "connection", la, la
    if ca.cyclic:
        win = transition_window(timing(ia), 1.0, 1, la)
        if win is not None:
            how, (start, end_a) = "transition", win
    return Track(None, (Element(1, ca, 0.0, end_a, "initial"), Element(2, cb, start, start + lb, how, prev=1)))


@pytest.mark.parametrize("first, second", [("walk", "run"), ("run", "pickup"), ("walk", "pitch"),
                                           ("frontkick", "walk"), ("dance", "walk")])
def test_default_engine_joins_real_capture_within_its_sources(clips, first, second):
    res = synthesize_with("optimal", [track_of(clips, first, second)], FPS)
    out = quality(res.motions[None])
    meets = against_sources(out, [quality(clips[first][1].motion), quality(clips[second][1].motion)])
    assert all(meets.values()), (meets, out)
    # every join says what the post-pass did to it (retiming, smoothing) next to the sources' figures
    post = [j.metrics["post"] for j in res.joins if "post" in j.metrics]
    assert post and all({"stretch", "smoothing_frames", "source_root_pop"} <= set(p) for p in post)


def test_a_run_that_stops_brakes_over_its_own_steps(clips):
    """run → pick-up: the hips do not go from running speed to standing in a few frames; the run's
    last steps are slowed (the join takes longer than scheduled) and the hips' deceleration stays within
    what the clips themselves do."""
    track = track_of(clips, "run", "pickup")
    res = synthesize_with("optimal", [track], FPS)
    (join,) = res.joins
    assert join.metrics["post"]["added_s"] > 0.2  # braking steps: time the schedule did not have
    out = quality(res.motions[None])
    assert out.root_pop <= 1.2 * max(quality(c.motion).root_pop for _, c in (clips["run"], clips["pickup"]))


def test_a_join_rendered_by_the_fallback_engine_says_so(clips):
    """run127 → basketball shot: optimal blending leaves a foot skating in its blend, so the actor is
    rendered by the constraint engine; the warnings and every join of that actor say which engine made it."""
    res = synthesize_with("optimal", [track_of(clips, "run127", "shot")], FPS)
    (join,) = res.joins
    assert (join.metrics["engine"], join.metrics["fallback_from"]) == ("constraint", "optimal")
    assert any("rendered with the constraint engine" in w for w in res.warnings)
    assert "post" in join.metrics  # the fallback runs the same join post-pass
