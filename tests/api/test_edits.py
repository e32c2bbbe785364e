"""Time-table edits kept as constraints on the analysis (text2anim.edits), through the real pipeline."""
from __future__ import annotations

import pytest

import text2anim
from text2anim.edits import Edit, EditError
from text2anim.motiondb import MotionDB

TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。"


def _rows(db, text=TEXT, edits=()):
    return {e.verb: e for e in text2anim.plan(text, db).table.elements} if not edits else \
        {e.verb: e for e in text2anim.animate(text, db=db, edits=edits).table.elements}


def test_a_shift_a_duration_and_a_join_method_change_the_time_table(library_db):
    with MotionDB.open(library_db) as db:
        base = _rows(db)
        later = _rows(db, edits=[Edit("喜ぶ", shift=1.0)])
        longer = _rows(db, edits=[Edit("走る", duration=4.0)])
        joined = _rows(db, edits=[Edit("蹴る", method="connection")])
    assert later["喜ぶ"].start == pytest.approx(base["喜ぶ"].start + 1.0, abs=0.05)
    assert longer["走る"].end - longer["走る"].start == pytest.approx(4.0, abs=0.05)
    assert joined["蹴る"].method == "connection" and joined["蹴る"].start >= joined["走る"].end - 1e-6


def test_an_edit_follows_its_motion_through_text_edits_and_is_dropped_with_it(library_db):
    with MotionDB.open(library_db) as db:
        edits = [Edit("喜ぶ", shift=1.0), Edit("泣く", shift=2.0)]  # no 泣く in the text: dropped
        base = _rows(db, "太郎は歩く。そして喜ぶ。")
        moved = _rows(db, "太郎は歩く。そして喜ぶ。", edits)
    assert moved["喜ぶ"].start == pytest.approx(base["喜ぶ"].start + 1.0, abs=0.05)


@pytest.mark.parametrize("bad", [{"verb": "歩く", "method": "teleport"}, {"verb": "歩く", "shift": 1e9},
                                 {"verb": "歩く", "duration": 0}, {"shift": 1}])
def test_a_bad_edit_is_refused_with_a_reason(bad):
    with pytest.raises(EditError):
        Edit.from_dict(bad)
