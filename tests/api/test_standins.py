"""Stand-ins that never lie (issue 27): ``--fallback nearest`` plays a clip for a verb the library lacks
only when the clip does what the verb means, judged on the set of tests/corpus/standin_set.json.

Each verb goes through the real analyser, the real built-in database and the planner, as a user's
``text2anim "VERB。" --fallback nearest`` does; benchmarks/bench_standins.py prints the same scores.
"""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import text2anim
from text2anim.motiondb import ClipRecord, MotionDB, UnknownVerbError
from text2anim.nlp import senses

SET = json.loads((Path(__file__).resolve().parents[1] / "corpus" / "standin_set.json").read_text(encoding="utf-8"))


def _played(verb: str, db: MotionDB) -> str | None:
    try:
        return text2anim.plan(verb + "。", db, fallback="nearest").table.elements[0].clip
    except UnknownVerbError:
        return None


def test_the_set_is_of_verbs_the_library_lacks(library_db):
    with MotionDB.open(library_db) as db:
        known = [v for v in [*SET["acceptable"], *SET["refuse"]] if _known(v, db)]
    assert known == []


def _known(verb: str, db: MotionDB) -> bool:
    try:
        text2anim.plan(verb + "。", db)
        return True
    except UnknownVerbError:
        return False


def test_no_stand_in_is_wrong_and_two_thirds_are_right(library_db):
    right, wrong = [], []
    with MotionDB.open(library_db) as db:
        for verb, accepted in SET["acceptable"].items():
            clip = _played(verb, db)
            if clip is not None:
                (right if re.sub(r"(_\d+)+$", "", clip) in accepted else wrong).append((verb, clip))
        wrong += [(verb, clip) for verb in SET["refuse"] if (clip := _played(verb, db)) is not None]
    assert wrong == []
    assert len(right) >= 2 / 3 * len(SET["acceptable"]) and len(SET["acceptable"]) >= 40


def test_a_refusal_says_what_was_looked_for(library_db):
    with MotionDB.open(library_db) as db, pytest.raises(UnknownVerbError) as exc:
        text2anim.plan("太郎は泳いで、腕相撲する。", db, fallback="nearest")
    msg = str(exc.value)
    assert "泳ぐ" in msg and "no clip does swim" in msg
    assert "腕相撲する" in msg and "not in the lexicon" in msg


def test_a_compound_verb_plays_as_its_first_verb_when_the_clip_does_that(library_db):
    """走り回る (run around) is 走る + 回る; 叩きのめす (beat up) is not played as 叩く's clap."""
    with MotionDB.open(library_db) as db:
        planned = text2anim.plan("太郎は走り回る。", db, fallback="nearest")
        assert planned.table.elements[0].clip == "run"
        assert "走り回る is 走る + 回る" in planned.fallbacks[0].reason
        assert _played("叩きのめす", db) is None


def test_an_imported_clip_stands_in_by_its_own_verb(tmp_path, library_db):
    """A user's clip without declared actions is described by its primary verb's sense: a stroll
    clip stored as 歩く stands in for ぶらつく in a database of the user's own clips."""
    with MotionDB.open(library_db) as lib:
        walk = lib.load("walk")
    with MotionDB.open(tmp_path / "own.sqlite", seed=False) as db:
        db.add([ClipRecord("my_walk", walk, ("歩く",), cyclic=True)])
        assert db.info("my_walk").description.actions == ()  # nothing declared: read from 歩く when needed
        assert db.info("my_walk").description.locomotion
        assert text2anim.plan("ぶらつく。", db, fallback="nearest").table.elements[0].clip == "my_walk"


def test_every_built_in_action_is_a_known_wordnet_verb_sense(library_db):
    with MotionDB.open(library_db) as db:
        actions = {c.name: c.description.actions for c in db.clips()}
    assert all(senses.known(a) for acts in actions.values() for a in acts)
    assert sum(1 for acts in actions.values() if acts) >= 100  # most clips stand in for their actions
