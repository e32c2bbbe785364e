"""N歩 before a stepping verb counts steps (docs/language.md §7.6): the gait clip plays that many
steps, not that many loops (issue 27). Real analyzer, real built-in library."""
from __future__ import annotations

import pytest

from text2anim import nlp
from text2anim.clip_search import DatabaseClips
from text2anim.core.contacts import detect_contacts
from text2anim.motiondb import MotionDB
from text2anim.scheduler import schedule
from text2anim.scheduler.clips import MIN_SWING, cycle_steps


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


def only_row(text: str, db: MotionDB):
    (row,) = schedule(nlp.analyze(text), DatabaseClips(db), 30.0).table.elements
    return row


def test_the_steps_of_a_cycle_come_from_the_contacts(db):
    assert {n: cycle_steps(db.info(n)) for n in ("walk", "walk_02_01", "walk_07_02", "run", "walk_back")} == \
        {"walk": 2, "walk_02_01": 2, "walk_07_02": 2, "run": 2, "walk_back": 4}
    assert cycle_steps(db.info("jump")) == 0  # not a loop


@pytest.mark.parametrize("text, steps", [("3歩歩く", 3), ("10歩歩く", 10), ("2歩進む", 2), ("3歩下がる", 3)])
def test_n_steps_play_n_steps(db, text, steps):
    row = only_row(text, db)
    info = db.info(row.clip)
    assert row.repeat == steps
    assert row.end - row.start == pytest.approx(steps / cycle_steps(info) * info.duration)


def test_counts_of_other_verbs_and_no_count_are_loops_as_before(db):
    walk = only_row("歩く", db)
    assert walk.end - walk.start >= 2.0  # MIN_LOOP: whole cycles for at least 2 s
    jumps = only_row("3回ジャンプする", db)
    assert jumps.end - jumps.start == pytest.approx(3 * db.info(jumps.clip).duration)


def test_three_steps_are_played(db):
    """Synthesised: the feet swing about three times in all (was twelve: three 2-second loops)."""
    from text2anim.pipeline import plan_text
    from text2anim.synthesis.constraint.engine import synthesize
    from text2anim.tracks import build_tracks

    (motion,) = synthesize(build_tracks(plan_text("3歩歩く", db), db, 30.0), 30.0).motions.values()
    contacts = detect_contacts(motion)
    swings = sum((b - a) / motion.fps >= MIN_SWING for side in ("left", "right") for a, b in contacts.moving(side))
    assert abs(swings - 3) <= 1, swings
