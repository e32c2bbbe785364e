"""An actor who leaves the person it faced turns its back first (:mod:`scheduler.facing`).

Real analyser, scheduler and built-in library (``library_db``), through ``text2anim.plan``.
"""
from __future__ import annotations

import pytest

import text2anim


def _sequence(planned, actor):
    """The actor's whole-body rows in playing order, as (verb, clip)."""
    rows = sorted((e for e in planned.table.elements if e.actor == actor and e.method != "composition"),
                  key=lambda e: e.start)
    return [(e.verb, planned.clips[e.id].name) for e in rows]


@pytest.mark.parametrize("text, actor, faced, leaving", [
    ("太郎は花子に手を振って、立ち去った。", "太郎", "wave_hand", "walk"),
    ("次郎は先生にお辞儀をして、走り去った。", "次郎", "bow", "run"),
    ("花子は太郎に近づいて、離れた。", "花子", "walk", "walk"),
])
def test_leaving_the_person_just_faced_turns_away_first(library_db, text, actor, faced, leaving):
    planned = text2anim.plan(text, db=library_db)
    clips = [clip for _verb, clip in _sequence(planned, actor)]
    k = clips.index("turn_away")
    assert clips[k - 1] == faced and clips[k + 1] == leaving
    turn = next(e for e in planned.table.elements if planned.clips[e.id].name == "turn_away")
    after = min((e for e in planned.table.elements if e.actor == actor and e.start >= turn.end), key=lambda e: e.start)
    assert after.start == pytest.approx(turn.end)  # the leaving sets off as the turn ends


@pytest.mark.parametrize("text", [
    "太郎は花子から離れた。",  # nothing faced her before
    "太郎は花子の隣に立って、離れた。",  # beside her, not facing her
    "太郎は花子に手を振って、歩いた。",  # a walk that leaves no one
])
def test_no_turn_where_nobody_faced_is_left(library_db, text):
    planned = text2anim.plan(text, db=library_db)
    assert "turn_away" not in {planned.clips[e.id].name for e in planned.table.elements}
