"""Everyday actions from real capture (CMU subjects 13 and 14, cgspeed's Daz-friendly BVH in
../shared/mocap/cmu_everyday) replace keyframes: drinking, wiping, boxing, directing traffic, exercises,
and add everyday verbs no keyframes had: jumping jacks, twists, stepping in place, forward bends, washing
oneself, reaching up on tiptoe, hopping up to grab, sitting lost in thought."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from text2anim.core.contacts import detect_contacts
from text2anim.core.floor import FOOT_CLEARANCE, lowest_foot_heights
from text2anim.motiondb import MotionDB
from text2anim.motiondb.library import capture
from shared_data import EVERYDAY_DIR, requires_everyday

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "library"))  # the build scripts (not installed)
import build_capture as build  # noqa: E402

EVERYDAY = {"drink": "飲む", "wipe": "拭く", "box": "ボクシングする", "direct_traffic": "合図する",
            "exercise": "体操する", "squat": "スクワットする", "jumping_jacks": "ジャンピングジャックする",
            "twist": "体をひねる", "step_in_place": "足踏みする", "bend_over": "前屈する", "wash_body": "体を洗う",
            "reach_up": "背伸びする", "jump_grab": "飛びつく", "ponder_seated": "考え込む"}
SEATED = {"ponder_seated"}  # sits on a step stool throughout: the hips rest, the feet are down
ON_TOES = {"reach_up", "step_in_place"}  # on tiptoe, on the balls of the feet: the toe joints 1-2 cm higher
CUTS = {c.name: c for c in capture.cut_list()}


@pytest.mark.parametrize("name", sorted(EVERYDAY))
def test_an_everyday_verb_plays_its_captured_clip(name, library_db):
    cut = CUTS[name]
    assert cut.folder == "cmu_everyday"
    with MotionDB.open(library_db) as db:
        best = db.search(EVERYDAY[name])[0]
        assert best.name == name and best.source.startswith(f"builtin:capture:CMU {cut.trial} ")
        clip = db.load(name)
    planted = detect_contacts(clip)
    low = lowest_foot_heights(clip)
    both = np.concatenate([low[planted.left, 0], low[planted.right, 1]])
    assert len(both) > 0.5 * clip.n_frames  # a foot is down most of the time
    toes = 0.03 if name in ON_TOES else 0.01
    assert 0.0 < np.median(both) < FOOT_CLEARANCE + toes  # on the floor (a deep squat rolls onto the toes: 1.3 cm)
    assert low.min() > -0.01  # never through it
    hips = clip.root_positions
    assert np.ptp(hips[:, 1]) > 0.01 or np.ptp(hips[:, [0, 2]], axis=0).max() > 0.02  # a living body, not frozen legs
    assert (best.start_posture == "seated") == (name in SEATED)


def test_at_least_35_verbs_are_served_by_capture(library_db):
    """Issue 24: the verbs whose first clip is real capture (the primary verbs of the captured clips)."""
    with MotionDB.open(library_db) as db:
        captured = {c.verb for c in db.clips() if c.source.startswith("builtin:capture")}
        served = {v for v in captured if db.search(v)[0].source.startswith("builtin:capture")}
    assert len(served) >= 35, sorted(served)


def test_captured_clips_stand_in_for_the_keyframed_drink_and_wipe(library_db):
    with MotionDB.open(library_db) as db:
        sources = {c.name: c.source for c in db.search("飲む") + db.search("拭く")}
    assert not any(s.startswith("keyframed:") for s in sources.values()), sources


@requires_everyday
def test_rebuilding_an_everyday_clip_gives_the_shipped_arrays():
    """The Daz-friendly take is read by name (no joint map), cut, retargeted and floored bit for bit again."""
    c = CUTS["drink"]
    m = build.cut_clip(*build.load_take(EVERYDAY_DIR / c.file), c)
    with np.load(capture.ARRAYS) as shipped:
        assert np.array_equal(m.rotations.astype(np.float32), shipped["drink.rot"])
        assert np.array_equal(m.root_positions.astype(np.float32), shipped["drink.root"])


def test_a_verb_with_several_takes_gives_co_actors_and_repeats_different_drinks(library_db):
    """Three subjects' drinks (14_37, 13_09, 14_05): two people drinking, or one drinking again, are no clones."""
    import text2anim

    with MotionDB.open(library_db) as db:
        table = text2anim.plan("太郎と花子が飲む。", db).table.elements
        again = text2anim.plan("太郎は3回飲む。", db)
    assert len({e.clip for e in table if e.verb == "飲む"}) == 2
    (drink,) = [e for e in again.table.elements if e.verb == "飲む"]
    assert len(set(again.repeats.get(drink.id, ()))) >= 2


@pytest.mark.parametrize("text, clip", [("はしごを登る。", "climb_ladder"), ("階段を上る。", "climb_steps"),
                                        ("階段を上がる。", "climb_steps"), ("山に登る。", "walk"), ("登る。", "walk")])
def test_a_climb_is_mimed_on_the_floor(library_db, text, clip):
    """The scene has no ladder or stairs: a climb keeps its hips at standing height and a foot on the floor
    (the climbed height taken out of the hips), a knee lifting to each rung or step; climbing a hill is walked."""
    import text2anim

    with MotionDB.open(library_db) as db:
        planned = text2anim.plan(text, db)
        assert planned.table.elements[0].clip == clip
        if not clip.startswith("climb"):
            return
        m = db.load(clip)
    low = lowest_foot_heights(m)
    assert low.min() > -0.01 and np.median(low.min(axis=1)) < FOOT_CLEARANCE + 0.02  # a foot on the floor
    assert low.max() > 0.2  # the other lifted to the next rung or step
    hips = m.root_positions[:, 1]
    assert np.ptp(hips) < 0.15  # not climbing into the air (the capture rose 0.6-0.8 m)
