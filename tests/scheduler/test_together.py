"""Co-actors of one motion play it together, for the same time (:mod:`scheduler.together`).

Real analyser, scheduler and built-in library (``library_db``), through ``text2anim.plan``: the built-in
dances are captures of 6.0 and 3.2 s and the jumps of 1.0 and 1.1 s, so a variant of its own per
co-actor used to stop one of them early.
"""
from __future__ import annotations

import pytest

import text2anim
from text2anim.scheduler.repeats import played_rows


def _rows(planned, verb):
    return {e.actor: e for e in planned.table.elements if e.verb == verb}


@pytest.mark.parametrize("text", ["太郎と花子は一緒に踊る。", "健太は美咲と一緒に踊った。", "兄と弟は二人で踊った。"])
def test_dancers_together_dance_for_the_same_time(library_db, text):
    planned = text2anim.plan(text, db=library_db)
    rows = _rows(planned, "踊る")
    assert len(rows) == 2
    a, b = rows.values()
    assert (a.start, a.end) == (b.start, b.end)
    assert a.end - a.start == pytest.approx(6.0)  # the longer capture sets it: the first placed
    # each still dances a capture of its own (a loop plays for any time)
    assert {planned.clips[a.id].name, planned.clips[b.id].name} == {"dance", "dance_05_03"}
    # nobody stops and stands while the other dances on
    assert not [e for e in planned.table.elements if e.verb in ("止まる", "待つ") and e.start < a.end]


def test_repeated_jumps_together_are_as_long_repetition_by_repetition(library_db):
    planned = text2anim.plan("太郎と花子は一緒に3回ジャンプした。", db=library_db)
    rows = _rows(planned, "ジャンプする")
    assert (rows["太郎"].start, rows["太郎"].end) == (rows["花子"].start, rows["花子"].end)
    tracks = {t.actor: [p for p in t.rows if p.row.verb == "ジャンプする"] for t in played_rows(planned)}
    taro, hanako = tracks["太郎"], tracks["花子"]
    assert len(taro) == len(hanako) == 3
    for t, h in zip(taro, hanako):
        assert abs(h.clip.duration - t.clip.duration) <= 0.1 * t.clip.duration + 1e-9
        assert (h.row.start, h.row.end) == pytest.approx((t.row.start, t.row.end))
    # not clones: each repetition of 花子's is 太郎's clip mirrored, or another capture as long
    assert all(h.clip.name != t.clip.name or h.mirrored != t.mirrored for t, h in zip(taro, hanako))


def test_a_partner_joined_by_isshoni_acts_too_and_the_chain_stays_in_step(library_db):
    planned = text2anim.plan("健太は美咲と一緒に公園を歩いて、ベンチに座った。", db=library_db)
    walks, sits = _rows(planned, "歩く"), _rows(planned, "座る")
    assert set(walks) == set(sits) == {"健太", "美咲"}
    assert walks["健太"].start == walks["美咲"].start
    # each walk hands over to the sit at its own last footstep of the same walking time: they sit
    # down within a step of each other (two captured walks step at their own pace)
    assert abs(sits["健太"].start - sits["美咲"].start) < 0.3


def test_motions_of_different_words_keep_their_own_times(library_db):
    """Only co-actors of one motion are held together: two sentences about two dancers are not."""
    planned = text2anim.plan("太郎が踊る。花子も踊る。", db=library_db)
    rows = _rows(planned, "踊る")
    assert rows["花子"].start == pytest.approx(rows["太郎"].end)


def test_people_drinking_together_take_captures_about_as_long(library_db):
    """The captured drinks last 3.8, 3.6 and 2.9 s: two drinkers take the two that are about as long, and
    their rows last the same (the shorter holds its last pose), not one of 2.9 s ending 0.9 s early."""
    planned = text2anim.plan("太郎と花子が一緒に飲む。", db=library_db)
    rows = _rows(planned, "飲む")
    assert (rows["太郎"].start, rows["太郎"].end) == (rows["花子"].start, rows["花子"].end)
    clips = {a: planned.clips[e.id] for a, e in rows.items()}
    assert clips["太郎"].name != clips["花子"].name
    assert abs(clips["太郎"].duration - clips["花子"].duration) <= 0.1 * clips["太郎"].duration
