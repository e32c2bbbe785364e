"""A verb's clip of another sense never plays a phrase about the body (issue 39, api/phrase_sense.py):
the real analyzer, the real planner, the built-in library and a database of a user's own clips."""
from __future__ import annotations

import pytest

import text2anim
from text2anim.motiondb import ClipRecord, MotionDB, UnknownVerbError


def _clips(text: str, db) -> list[str]:
    planned = text2anim.plan(text, db)
    return [planned.table.elements[i].clip for i in range(len(planned.analysis.motions))]


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


def test_the_clip_declared_for_the_phrase_plays_it(db):
    assert _clips("太郎は手を振った。", db) == ["wave_hand"]
    assert _clips("太郎は首を振った。", db) == ["head_shake"]
    assert _clips("花子は両手を上げた。", db) == ["banzai"]
    assert _clips("花子は右手を上げた。", db) == ["raise_hand"]


@pytest.mark.parametrize("text, phrase", [
    ("太郎は左足を上げた。", "左足を上げる"),  # the clips of 上げる raise a hand (手を上げる)
    ("花子は額を拭いた。", "額を拭く"),  # the wipe clip wipes things (窓, 黒板), not a forehead
    ("太郎は膝を叩いた。", "膝を叩く"),  # the clap clip claps hands (手を叩く)
])
def test_a_clip_of_another_sense_is_refused_naming_the_phrase(text, phrase, db):
    for fallback in ("strict", "nearest"):
        with pytest.raises(UnknownVerbError, match=phrase):
            text2anim.plan(text, db, fallback=fallback)


def test_the_same_verb_on_a_thing_plays_its_clip(db):
    assert _clips("花子は窓を拭いた。", db) == ["wipe"]
    assert _clips("太郎は旗を振った。", db) == ["wave_hand"]


def test_a_user_s_clip_declaring_a_phrase_plays_it(tmp_path, db):
    """A clip imported as 肩を回す (no clip lists 回す) plays 肩を回す, and only that phrase."""
    twist = db.load("twist")
    with MotionDB.open(tmp_path / "own.sqlite", seed=False) as own:
        own.add([ClipRecord("shoulder_roll", twist, ("肩を回す",))])
        assert _clips("太郎は肩を回した。", own) == ["shoulder_roll"]
        with pytest.raises(UnknownVerbError):
            text2anim.plan("太郎は腕を回した。", own)


def test_両膝_and_膝_are_the_same_knees(tmp_path, db):
    """A kneeling clip declaring 膝をつく plays 両膝をつく: 両 says how many, not another part."""
    crouch = db.load("crouch_down")
    with MotionDB.open(tmp_path / "own.sqlite", seed=False) as own:
        own.add([ClipRecord("my_kneel", crouch, ("ひざまずく", "膝をつく"))])
        assert _clips("太郎は床に両膝をついた。", own) == ["my_kneel"]
        assert _clips("花子はひざをついた。", own) == ["my_kneel"]

