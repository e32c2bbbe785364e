"""Stand-ins that never lie (issue 27) and help (issue 39): ``--fallback nearest`` plays a clip for a verb
the library lacks only when the clip does what the verb means, judged on the sets of
tests/corpus/standin_set.json and tests/corpus/standin_unseen.json (written before the code it scores).

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

CORPUS = Path(__file__).resolve().parents[1] / "corpus"
SETS = {name: json.loads((CORPUS / name).read_text(encoding="utf-8"))
        for name in ("standin_set.json", "standin_unseen.json")}
SET = SETS["standin_set.json"]


def _played(verb: str, db: MotionDB) -> str | None:
    try:
        return text2anim.plan(verb + "。", db, fallback="nearest").table.elements[0].clip
    except UnknownVerbError:
        return None


@pytest.mark.parametrize("name", SETS)
def test_the_set_is_of_verbs_the_library_lacks(name, library_db):
    with MotionDB.open(library_db) as db:
        known = [v for v in [*SETS[name]["acceptable"], *SETS[name]["refuse"]] if _known(v, db)]
    assert known == []


def test_the_sets_are_apart():
    old, new = SETS.values()
    assert not {*old["acceptable"], *old["refuse"]} & {*new["acceptable"], *new["refuse"]}


def _known(verb: str, db: MotionDB) -> bool:
    try:
        text2anim.plan(verb + "。", db)
        return True
    except UnknownVerbError:
        return False


@pytest.mark.parametrize("name, size", [("standin_set.json", 40), ("standin_unseen.json", 60)])
def test_no_stand_in_is_wrong_and_two_thirds_are_right(name, size, library_db):
    judged = SETS[name]
    right, wrong = [], []
    with MotionDB.open(library_db) as db:
        for verb, accepted in judged["acceptable"].items():
            clip = _played(verb, db)
            if clip is not None:
                (right if re.sub(r"(_\d+)+$", "", clip) in accepted else wrong).append((verb, clip))
        wrong += [(verb, clip) for verb in judged["refuse"] if (clip := _played(verb, db)) is not None]
    assert wrong == []
    assert len(right) >= 2 / 3 * len(judged["acceptable"]) and len(judged["acceptable"]) >= size


def test_a_refusal_says_what_was_looked_for(library_db):
    with MotionDB.open(library_db) as db, pytest.raises(UnknownVerbError) as exc:
        text2anim.plan("太郎は泳いで、逆立ちする。", db, fallback="nearest")
    msg = str(exc.value)
    assert "泳ぐ" in msg and "no clip does swim" in msg
    assert "逆立ちする" in msg and "not in the lexicon" in msg


def test_a_compound_verb_plays_as_its_first_verb_when_the_clip_does_that(library_db):
    """殴りかかる (go at someone with fists) is 殴る + かかる; 叩きのめす (beat up) is not played as 叩く's clap."""
    with MotionDB.open(library_db) as db:
        planned = text2anim.plan("太郎は殴りかかる。", db, fallback="nearest")
        assert planned.table.elements[0].clip == "punch"
        assert "殴りかかる is 殴る + かかる" in planned.fallbacks[0].reason
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


def test_a_refused_text_pickles_with_its_message(library_db):
    """A batch worker's refusal reaches the runner pickled, message and missing verbs as they were."""
    import pickle

    from text2anim.fallback import UnknownVerbsError

    with pytest.raises(UnknownVerbsError) as err:
        text2anim.plan("花子は腰を回す。", library_db)
    back = pickle.loads(pickle.dumps(err.value))
    assert type(back) is UnknownVerbsError and str(back) == str(err.value) and "腰を回す" in str(back)
    assert back.missing == err.value.missing and back.verb == err.value.verb
