"""A posture carries on until the text changes it (issue 27): seated actions, starting seated; kneeling ones.

Real analyzer, real built-in library, the scheduler's own entry point; one sentence is
synthesised to see the actor stay on the chair.
"""
from __future__ import annotations

import pytest

from text2anim import nlp
from text2anim.clip_search import DatabaseClips
from text2anim.motiondb import MotionDB, classify_posture
from text2anim.scheduler import schedule
from text2anim.scheduler.seated import plays_in


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


def rows(text: str, db: MotionDB):
    """The time table of ``text`` as (clip, method, prev clip, body part, start, end), in playing order."""
    table = schedule(nlp.analyze(text), DatabaseClips(db), 30.0).table
    clip = {e.id: e.clip for e in table.elements}
    return [(e.clip, e.method, clip.get(e.prev) if e.prev is not None else None, e.body_part,
             round(e.start, 2), round(e.end, 2))
            for e in sorted(table.elements, key=lambda e: (e.start, e.method == "composition", e.id))]


def test_which_library_clips_can_be_played_seated(db):
    seatable = {c.name for c in db.clips() if plays_in(c, "seated")}
    assert {"read", "drink", "eat", "write", "clap", "wave_hand", "nod", "wait_seated"} <= seatable
    assert not seatable & {"walk", "run", "jump", "crouch", "kick", "dance", "sit_down", "stand_up", "wait"}
    kneelable = {c.name for c in db.clips() if plays_in(c, "kneeling")}
    assert {"pray", "read", "clap", "wait_kneeling"} <= kneelable and not kneelable & {"wait_seated", "kneel", "walk"}


def test_reading_after_sitting_is_read_seated(db):
    read = db.info("read").duration
    assert rows("椅子に座って本を読む", db) == [
        ("sit_down", "initial", None, None, 0.0, 2.3),
        ("wait_seated", "transition", "sit_down", None, 2.3, round(2.3 + read, 2)),
        ("read", "composition", "wait_seated", "upper", 2.3, round(2.3 + read, 2)),
    ]


def test_a_partial_action_after_sitting_keeps_its_own_part(db):
    table = rows("座って手を叩く", db)
    assert [r[0] for r in table] == ["sit_down", "wait_seated", "clap"]
    assert table[2][1:4] == ("composition", "wait_seated", "both_arms")


def test_an_action_that_needs_the_legs_stands_up_first(db):
    table = rows("座って本を読んで歩く", db)
    assert [(r[0], r[1]) for r in table] == [
        ("sit_down", "initial"), ("wait_seated", "transition"), ("read", "composition"),
        ("stand_up", "connection"), ("walk", "transition")]
    assert table[3][4] == table[1][5]  # stands up when the reading is done
    assert [r[0] for r in rows("座って、歩く。", db)] == ["sit_down", "stand_up", "walk"]


def test_praying_after_kneeling_is_done_on_the_knee_and_the_actor_rises_from_it(db):
    """膝をついて、祈る。そして立ち上がる (written here ひざまずいて: the phrase is mapped by the analyzer):
    the prayer's upper body on the kneeling idle, then up from the knee, never a stand and a sit between."""
    pray = db.info("pray").duration
    kneel = db.info("kneel").duration
    table = rows("ひざまずいて、祈る。そして立ち上がる。", db)
    assert [(r[0], r[1], r[3]) for r in table] == [
        ("kneel", "initial", None), ("wait_kneeling", "transition", None), ("pray", "composition", "upper"),
        ("stand_from_kneel", "connection", None)]
    assert table[2][4:] == (round(kneel, 2), round(kneel + pray, 2)) and table[3][4] == table[1][5]


def test_a_gesture_that_needs_the_legs_after_kneeling_rises_first(db):
    assert [r[0] for r in rows("ひざまずいて、歩く。", db)] == ["kneel", "stand_from_kneel", "walk"]


def test_the_praying_actor_stays_on_the_knee(db):
    """Synthesised: kneeling from the kneel's end until the prayer is over, then standing at the end."""
    from text2anim.synthesis.constraint.engine import synthesize
    from text2anim.pipeline import plan_text
    from text2anim.tracks import build_tracks

    planned = plan_text("ひざまずいて、祈る。そして立ち上がる。", db)
    result = synthesize(build_tracks(planned, db, 30.0), 30.0)
    (motion,) = result.motions.values()
    pray = next(e for e in planned.table.elements if e.clip == "pray")
    kneeling = {classify_posture(motion, f) for f in range(int(pray.start * 30) + 3, int(pray.end * 30) - 3)}
    assert kneeling == {"kneeling"}
    assert classify_posture(motion, motion.n_frames - 1) == "standing"


def test_a_later_stand_up_starts_the_actor_seated(db):
    drink = db.info("drink").duration
    up = db.info("stand_up").duration
    assert rows("コーヒーを飲んで立ち上がる", db) == [
        ("wait_seated", "initial", None, None, 0.0, round(drink, 2)),
        ("drink", "composition", "wait_seated", "upper", 0.0, round(drink, 2)),
        ("stand_up", "connection", "wait_seated", None, round(drink, 2), round(drink + up, 2)),
    ]


def test_a_motion_that_needs_standing_before_the_stand_up_keeps_the_old_way(db):
    """Walking first: the actor was standing, so it sits down before it stands up (nothing seated)."""
    assert [r[0] for r in rows("歩いて、立ち上がる", db)] == ["walk", "sit_down", "stand_up"]


@pytest.mark.parametrize("text, clips", [
    ("座ったまま手を振る", ["sit_down", "wave_hand"]),   # たまま composes already
    ("本を読む", ["read"]),                              # nothing says seated
    ("座って、立ち上がる。", ["sit_down", "stand_up"]),
])
def test_texts_the_rule_leaves_alone(db, text, clips):
    assert [r[0] for r in rows(text, db)] == clips


def test_the_reader_stays_on_the_chair(db):
    """Synthesised: after sitting down the actor is seated for the whole reading (no stand-up)."""
    from text2anim.synthesis.constraint.engine import synthesize
    from text2anim.pipeline import plan_text
    from text2anim.tracks import build_tracks

    result = synthesize(build_tracks(plan_text("椅子に座って本を読む", db), db, 30.0), 30.0)
    (motion,) = result.motions.values()
    seated = [classify_posture(motion, f) for f in range(80, motion.n_frames)]
    assert set(seated) == {"seated"}
