"""Search: synonyms and readings meet on the same clips; the documented ranking; unknown verbs."""
from __future__ import annotations

import pytest

from text2anim.motiondb import DBError, UnknownCharacterError, UnknownVerbError


def names(hits):
    return [h.name for h in hits]


def test_verb_and_object_rank_over_verb_over_synonym(empty_db, record):
    empty_db.add([
        record("stomp", ("踏む", "蹴る")),                       # synonym, no object
        record("kick", ("蹴る", "キックする")),                   # primary, no object
        record("shoot", ("シュートする", "蹴る"), objects=("ボール",)),  # synonym + object
        record("kick_ball", ("蹴る", "キックする"), objects=("ボール",)),  # primary + object
        record("kick_box", ("蹴る",), objects=("箱",)),            # primary, another object
    ])
    assert names(empty_db.search("蹴る", object="ボール")) == ["kick_ball", "shoot", "kick", "stomp", "kick_box"]
    # no object asked: clips without one first, then primary over synonym, then by name
    assert names(empty_db.search("蹴る")) == ["kick", "stomp", "kick_ball", "kick_box", "shoot"]
    # the object also matches by reading; an object nobody has ranks object-less clips first
    assert names(empty_db.search("蹴る", object="ぼーる"))[:2] == ["kick_ball", "shoot"]
    assert names(empty_db.search("蹴る", object="椅子"))[:2] == ["kick", "stomp"]
    assert names(empty_db.search("キックする", object="ボール")) == ["kick_ball", "kick"]
    assert names(empty_db.search("蹴る", object="ボール", limit=2)) == ["kick_ball", "shoot"]


def test_the_previous_clips_character_comes_first(empty_db, record):
    empty_db.add([
        record("alice_walk", ("歩く",), character="alice"),
        record("bob_stroll", ("散歩する", "歩く"), character="bob"),
        record("bob_walk", ("歩く",), character="bob"),
    ])
    assert names(empty_db.search("歩く")) == ["alice_walk", "bob_walk", "bob_stroll"]
    assert names(empty_db.search("歩く", prefer_character="bob")) == ["bob_walk", "bob_stroll", "alice_walk"]
    assert names(empty_db.search("歩く", character="alice")) == ["alice_walk"]
    assert names(empty_db.search("歩く", prefer_character="nobody")) == ["alice_walk", "bob_walk", "bob_stroll"]
    with pytest.raises(UnknownCharacterError, match="'carol'.*alice, bob"):
        empty_db.search("歩く", character="carol")
    assert empty_db.search("散歩する", character="alice") == []  # known verb, nothing passes the filter


def test_synonyms_and_kana_spellings_meet_on_the_same_clips(empty_db, record):
    empty_db.add([
        record("jump", ("ジャンプする", "跳ぶ", "飛ぶ")),
        record("hop", ("跳ぶ",)),
        record("fly", ("飛ぶ",)),
        record("walk", ("歩く",)),
    ])
    for query in ("ジャンプする", "じゃんぷする", "ｼﾞｬﾝﾌﾟする", "跳ぶ", "飛ぶ", "とぶ", "トブ"):
        assert "jump" in names(empty_db.search(query)), query
    assert names(empty_db.search("ジャンプする")) == ["jump"]
    # exact lemma (primary, then synonym) before clips that only share the reading
    assert names(empty_db.search("跳ぶ")) == ["hop", "jump", "fly"]
    assert names(empty_db.search("飛ぶ")) == ["fly", "jump", "hop"]
    assert names(empty_db.search("とぶ")) == ["fly", "hop", "jump"]  # reading only: primary over synonym
    verbs = {v.lemma: v for v in empty_db.verbs()}
    assert verbs["跳ぶ"].reading == verbs["飛ぶ"].reading == "トブ"
    assert verbs["ジャンプする"].reading == "ジャンプスル"
    assert (verbs["跳ぶ"].clips, verbs["跳ぶ"].primary) == (2, 1)


def test_a_clip_declaring_the_verb_ranks_before_a_homophones_whatever_the_objects(empty_db, record):
    """取る and 撮る share the reading トル: another word, so the clip that declares the query comes
    first even when it declares an object and the homophone's clip declares none."""
    empty_db.add([
        record("pick_up", ("拾う", "取る"), objects=("ボール",)),
        record("take_photo", ("撮る",)),
    ])
    assert names(empty_db.search("取る")) == ["pick_up", "take_photo"]
    assert names(empty_db.search("取る", object="本")) == ["pick_up", "take_photo"]
    assert names(empty_db.search("撮る")) == ["take_photo", "pick_up"]
    assert names(empty_db.search("とる")) == ["take_photo", "pick_up"]  # kana: reading only, objects decide


def test_an_unknown_verb_lists_the_nearest_verbs_by_reading(empty_db, record):
    with pytest.raises(UnknownVerbError, match="no verbs yet"):
        empty_db.search("歩く")
    empty_db.add([record("walk", ("歩く",)), record("fall", ("転ぶ", "倒れる")), record("run", ("走る",))])
    with pytest.raises(UnknownVerbError) as err:
        empty_db.search("ころがる")
    e = err.value
    assert e.user_facing and e.verb == "ころがる"
    assert e.suggestions[0] == ("転ぶ", "コロブ")
    assert "nearest verbs: 転ぶ (コロブ)" in str(e)
    with pytest.raises(UnknownVerbError) as err:
        empty_db.search("はしりだす")
    assert err.value.suggestions[0] == ("走る", "ハシル")
    with pytest.raises(DBError, match="needs a verb"):
        empty_db.search("  ")


def test_an_unknown_verb_error_crosses_processes_whole(empty_db, record):
    """A batch worker's refusal reaches the runner pickled: its verb, suggestions and message as they were
    (the suggestions are found when first read, not when the error is made)."""
    import pickle

    empty_db.add([record("fall", ("転ぶ", "倒れる"))])
    with pytest.raises(UnknownVerbError) as err:
        empty_db.search("ころがる")
    back = pickle.loads(pickle.dumps(err.value))
    assert type(back) is UnknownVerbError and back.verb == "ころがる"
    assert back.suggestions == err.value.suggestions and back.suggestions[0] == ("転ぶ", "コロブ")
    assert str(back) == str(err.value)


def test_body_part_requests_take_the_part_then_its_mirror_then_whole_body(empty_db, record):
    empty_db.add([
        record("wave_right", ("振る", "手を振る"), body_part="right_arm"),
        record("shake_head", ("首を振る", "振る"), body_part="head"),
        record("swing", ("振る",)),
    ])
    assert names(empty_db.search("振る", body_part="right_arm")) == ["wave_right", "swing"]
    left = empty_db.search("振る", body_part="left_arm")
    assert names(left) == ["wave_right", "swing"] and left[0].body_part == "right_arm"  # to be mirrored
    assert names(empty_db.search("振る", body_part="head")) == ["shake_head", "swing"]
    assert names(empty_db.search("振る")) == ["swing", "wave_right", "shake_head"]
    with pytest.raises(DBError, match="unknown body part 'tail'"):
        empty_db.search("振る", body_part="tail")


def test_a_start_posture_ranks_after_the_character_and_before_objects_and_verbs(empty_db):
    from text2anim.motiondb import ClipRecord
    from text2anim.motiondb.library import build_all

    motion = {b.record.name: b.record.motion for b in build_all(30.0)}
    empty_db.add([
        ClipRecord("chair_up", motion["stand_up"], ("立ち上がる",)),
        ClipRecord("squat_up", motion["stand_from_crouch"], ("立ち上がる",), objects=("椅子",)),
        ClipRecord("floor_up", motion["get_up"], ("起き上がる", "立ち上がる")),
        ClipRecord("bob_floor_up", motion["get_up"], ("立ち上がる",), character="bob"),
    ])
    assert {c.name: c.start_posture for c in empty_db.clips()} == {
        "bob_floor_up": "lying", "chair_up": "seated", "floor_up": "lying", "squat_up": "crouched"}
    assert names(empty_db.search("立ち上がる")) == ["bob_floor_up", "chair_up", "floor_up", "squat_up"]
    # the posture goes before the verb tier (floor_up has 立ち上がる as a synonym only) ...
    assert names(empty_db.search("立ち上がる", prefer_start_posture="lying")) == [
        "bob_floor_up", "floor_up", "chair_up", "squat_up"]
    # ... and before the object (squat_up declares 椅子) ...
    assert names(empty_db.search("立ち上がる", object="椅子", prefer_start_posture="crouched"))[0] == "squat_up"
    assert names(empty_db.search("立ち上がる", object="椅子", prefer_start_posture="seated"))[:2] == [
        "chair_up", "squat_up"]
    # ... but after the character
    assert names(empty_db.search("立ち上がる", prefer_character="default", prefer_start_posture="lying")) == [
        "floor_up", "chair_up", "squat_up", "bob_floor_up"]
    assert names(empty_db.search("立ち上がる", prefer_start_posture="kneeling")) == names(empty_db.search("立ち上がる"))
    assert names(empty_db.search("立ち上がる", prefer_start_posture="lying", limit=1)) == ["bob_floor_up"]
    with pytest.raises(DBError, match="unknown posture 'sitting'"):
        empty_db.search("立ち上がる", prefer_start_posture="sitting")


def _selects(db):
    """A list that collects the SELECT statements ``db`` runs from now on."""
    from sqlalchemy import event

    seen: list[str] = []
    event.listen(db.engine, "before_cursor_execute",
                 lambda conn, cur, statement, *a: seen.append(statement) if statement.lstrip().upper()
                 .startswith("SELECT") else None)
    return seen


def test_a_search_is_one_query_and_its_hits_carry_every_field(empty_db, record):
    empty_db.add([
        record("kick_ball", ("蹴る", "キックする"), objects=("ボール", "箱"), character="kenji"),
        record("stomp", ("踏む", "蹴る"), character="kenji"),
        record("wave_r", ("振る",), body_part="right_arm"),
    ])
    seen = _selects(empty_db)
    hits = empty_db.search("蹴る", object="ボール", prefer_character="kenji", limit=5)
    assert len(seen) == 1
    assert names(hits) == ["kick_ball", "stomp"]
    assert hits == [empty_db.info("kick_ball"), empty_db.info("stomp")]  # verbs, objects, contacts in order
    seen.clear()
    assert names(empty_db.search("振る", body_part="left_arm", prefer_start_posture="standing")) == ["wave_r"]
    assert len(seen) == 1


def test_memoised_searches_ask_the_database_once_until_something_changes(empty_db, record):
    empty_db.add([record("walk", ("歩く",))])
    with empty_db.memoised():
        first = empty_db.search("歩く")
        seen = _selects(empty_db)
        assert empty_db.search("歩く") == first and seen == []
        empty_db.add([record("stroll", ("歩く",))])
        assert names(empty_db.search("歩く")) == ["stroll", "walk"]
    seen.clear()
    empty_db.search("歩く")
    assert len(seen) == 1  # outside the block every search asks the database


def test_memoised_answers_outlive_the_block_until_another_connection_changes_the_database(db_url, record):
    """A warm process plans sentence after sentence: each plan's ``memoised()`` block answers from the
    one before while nothing changed, and a change by another connection (another process's import) or
    by this object is seen by the next block: new clips, a verb that was missing, the listings."""
    from text2anim.motiondb import MotionDB

    with MotionDB.open(db_url, seed=False) as mine, MotionDB.open(db_url, seed=False) as other:
        mine.add([record("walk", ("歩く",))])
        with mine.memoised():
            assert names(mine.search("歩く")) == ["walk"]
            with pytest.raises(UnknownVerbError):
                mine.search("跳ぶ")
            assert names(mine.clips()) == ["walk"]
        seen = _selects(mine)
        with mine.memoised():
            assert names(mine.search("歩く")) == ["walk"]
            with pytest.raises(UnknownVerbError) as err:
                mine.search("跳ぶ")
            assert err.value.verb == "跳ぶ" and [v.lemma for v in mine.verbs()] == ["歩く"]
        if mine.backend == "sqlite":
            assert len(seen) == 1  # the verbs only: nothing else asked again
        other.add([record("stroll", ("歩く",)), record("hop", ("跳ぶ",))])
        with mine.memoised():
            assert names(mine.search("歩く")) == ["stroll", "walk"]
            assert names(mine.search("跳ぶ")) == ["hop"]
            assert names(mine.clips()) == ["hop", "stroll", "walk"]
        mine.remove("hop")
        with mine.memoised():
            with pytest.raises(UnknownVerbError):
                mine.search("跳ぶ")
            assert sorted(v.lemma for v in mine.verbs()) == ["歩く"]


def test_memoised_searches_rank_the_preferences_as_the_database_does(empty_db, record):
    """Inside ``memoised()`` a verb is asked once; the preferred character and posture are ranked in
    Python (:func:`motiondb.search.prefer`), which must give the query's own order for every combination."""
    empty_db.add([
        record("wave_r", ("振る",), body_part="right_arm"),
        record("wave_l", ("振る",), body_part="left_arm", character="bob"),
        record("wave_body", ("振る", "揺らす")),
        record("shake", ("揺らす", "振る"), character="bob", start_posture="seated"),
        record("wave_seated", ("振る",), start_posture="seated", objects=("旗",)),
        record("wave_flag", ("振る",), character="bob", objects=("旗",), body_part="right_arm"),
    ])
    combos = [dict(object=o, body_part=p, prefer_character=c, prefer_start_posture=s, limit=n)
              for o in (None, "旗") for p in (None, "right_arm", "left_arm") for c in (None, "bob", "default")
              for s in (None, "seated", "standing") for n in (None, 2)]
    direct = {i: names(empty_db.search("振る", **c)) for i, c in enumerate(combos)}
    assert len({tuple(v) for v in direct.values()}) > 10  # the preferences do reorder these clips
    with empty_db.memoised():
        seen = _selects(empty_db)
        for i, c in enumerate(combos):
            assert names(empty_db.search("振る", **c)) == direct[i], c
    assert len(seen) == 2 * 3  # one query per (object, body part)


def test_planning_a_text_asks_the_database_once_per_motion(library_db):
    from text2anim.motiondb import MotionDB
    from text2anim.pipeline import plan_text

    with MotionDB.open(library_db) as db:
        seen = _selects(db)
        planned = plan_text("太郎は走って、ボールを蹴る。そして喜ぶ。それから歩いて、座る。", db)
    assert len(planned.analysis.motions) == 5
    assert len(seen) == 5
