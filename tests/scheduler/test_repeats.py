"""A repeated motion plays as one row per repetition (:func:`scheduler.repeats.played_rows`).

Real analyser, scheduler and built-in library (``library_db``), through ``text2anim.plan``.
"""
from __future__ import annotations

import pytest

import text2anim
from text2anim.scheduler.repeats import played_rows


def test_a_repeated_jump_is_three_rows_and_the_next_motion_joins_the_last(library_db):
    planned = text2anim.plan("太郎は3回跳ぶ。そして歩く。", db=library_db)
    jump = next(e for e in planned.table.elements if e.verb == "跳ぶ")
    walk = next(e for e in planned.table.elements if e.verb == "歩く")
    (taro,) = played_rows(planned)
    rows = [p.row for p in taro.rows]
    reps = [r for r in rows if r.verb == "跳ぶ"]
    assert len(reps) == jump.repeat == 3
    # the first keeps the table's id and link; the others get ids above the table's, each joined to the last
    top = max(e.id for e in planned.table.elements)
    assert reps[0].id == jump.id and (reps[0].method, reps[0].prev) == (jump.method, jump.prev)
    assert [r.id for r in reps[1:]] == [top + 1, top + 2]
    assert [(r.method, r.prev) for r in reps[1:]] == [("connection", reps[0].id), ("connection", reps[1].id)]
    # equal parts of the row's span, end to end, each played once and not held
    assert reps[0].start == jump.start and reps[-1].end == pytest.approx(jump.end)
    assert all(a.end == pytest.approx(b.start) for a, b in zip(reps, reps[1:]))
    assert len({round(r.end - r.start, 9) for r in reps}) == 1
    assert all(r.repeat == 1 and not r.hold for r in reps)
    # each repetition is the variant the scheduler picked for it
    played = [(p.clip.name, p.mirrored) for p in taro.rows if p.row.verb == "跳ぶ"]
    assert played == [(p.clip.name, p.mirrored) for p in planned.repeats[jump.id]]
    # the walk, linked to the jump in the table, joins the last repetition
    (walked,) = [r for r in rows if r.id == walk.id]
    assert walk.prev == jump.id and walked.prev == reps[-1].id


def test_rows_that_are_not_repeated_play_as_the_table_has_them(library_db):
    planned = text2anim.plan("太郎は走る。3秒後に歩く。", db=library_db)
    (taro,) = played_rows(planned)
    assert sorted((p.row for p in taro.rows), key=lambda r: r.id) == list(planned.table.elements)
    assert all(p.clip == planned.clips[p.row.id] for p in taro.rows)
    # the posture the actor ends in is its last whole-body row's clip's (the idle filling the wait to the end)
    last = max((e for e in planned.table.elements if e.method != "composition"), key=lambda e: e.start)
    assert taro.last == planned.clips[last.id]
