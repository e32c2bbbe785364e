"""Issue 14: words users write — verbs outside the library (meaning, fallback) and the opening delay."""
from __future__ import annotations

import json

import pytest

import text2anim
from cli_run import text2anim as run
from text2anim.motiondb import MotionDB, UnknownVerbError
from text2anim.nlp import analyze, meaning
from text2anim.pipeline import plan_text


def test_meaning_ranks_by_sense_not_by_sound():
    """読む is not near 屈む/進む (the old suggestions by sound); 見る is its nearest library verb."""
    cands = ["屈む", "進む", "佇む", "見る", "蹴る"]
    assert meaning.nearest("読む", cands, n=1)[0][0] == "見る"
    assert meaning.nearest("散歩する", ["歩く", "座る", "泣く"], n=1)[0][0] == "歩く"
    assert meaning.nearest("歌う", ["踊る", "座る", "押す"], n=1)[0][0] == "踊る"


def test_meaning_looks_up_spellings_and_phrases():
    assert meaning.vector("うなずく") is not None  # via UniDic's lemma 頷く
    assert "振る" in meaning.forms("手を振る") and "ポーズ" in meaning.forms("ファイティングポーズをとる")
    assert meaning.nearest("ｘｙｚ", ["歩く"]) == []
    near = meaning.nearest("走る", ["駆ける", "歩く", "座る"], n=3)
    assert [s for _, s in near] == sorted((s for _, s in near), reverse=True)


def test_written_form_is_kept_beside_the_lemma():
    spec = analyze("太郎は山に登る。").motions[0]
    assert (spec.verb, spec.written) == ("上る", "登る")


def test_error_names_every_missing_verb_as_written(library_db):
    """およぐ is analysed as the lemma 泳ぐ, 宙返り as 宙返りする: the error says what the user wrote."""
    with MotionDB.open(library_db) as db, pytest.raises(UnknownVerbError) as exc:
        text2anim.plan("太郎はおよいで、宙返りする。そして座る。", db)
    msg = str(exc.value)
    assert "およぐ" in msg and "宙返りする" in msg and "泳ぐ" not in msg
    assert "nearest by meaning" in msg and "no stand-in" in msg.split("およぐ")[1]


def test_fallback_nearest_animates_a_clip_that_does_the_same_and_says_why(library_db, tmp_path):
    """ぶらつく (stroll) has no clip; strolling is a kind of walking (WordNet) and 歩く is among its
    nearest words (chiVe), so the walk plays, and stderr and the report say so and why."""
    out, report = tmp_path / "a.bvh", tmp_path / "r.json"
    strict = run("太郎は公園をぶらつく。", "-o", out, "--db", library_db)
    assert strict.returncode == 2 and not out.exists() and "ぶらつく" in strict.stderr
    assert "--fallback nearest would play 歩く: stroll is a kind of walk" in strict.stderr
    proc = run("太郎は公園をぶらつく。", "-o", out, "--db", library_db, "--fallback", "nearest", "--report", report)
    assert proc.returncode == 0, proc.stderr
    assert "fallback: ぶらつく → 歩く (stroll is a kind of walk;" in proc.stderr
    data = json.loads(report.read_text())
    assert [(f["id"], f["asked"], f["animated_as"], f["because"]) for f in data["fallbacks"]] == \
        [(1, "ぶらつく", "歩く", "stroll is a kind of walk")]
    assert [e["verb"] for e in data["time_table"]] == ["歩く"]


@pytest.mark.parametrize("text, verb, why", [
    ("太郎は泳ぐ。", "泳ぐ", "no clip does swim or what it is a kind of"),  # 潜る (duck) is only near in the vectors
    ("太郎は宙返りする。", "宙返りする", "no clip does somersault"),  # the vectors played a kick
    ("太郎は絵を写生する。", "写生する", "not near it in meaning"),  # gloss "draw" is WordNet's pull
])
def test_fallback_refuses_what_no_clip_does_and_says_what_it_looked_for(library_db, text, verb, why):
    proc = run(text, "-o", "x.bvh", "--db", library_db, "--fallback", "nearest")
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert verb in proc.stderr and why in proc.stderr and "nothing was animated" in proc.stderr


def test_plan_takes_fallback_nearest_too(library_db):
    """``text2anim plan --fallback nearest`` plans the stand-in and says so; strict refuses (exit 2)."""
    strict = run("plan", "太郎は公園をぶらついて、座る。", "--db", library_db)
    assert strict.returncode == 2 and "ぶらつく" in strict.stderr and strict.stdout == ""
    proc = run("plan", "太郎は公園をぶらついて、座る。", "--db", library_db, "--fallback", "nearest", "--json")
    assert proc.returncode == 0, proc.stderr
    assert "fallback: ぶらつく → 歩く" in proc.stderr
    table = json.loads(proc.stdout)
    assert "歩く" in json.dumps(table, ensure_ascii=False) and "ぶらつく" not in json.dumps(table, ensure_ascii=False)
    bad = run("plan", "太郎は歩く。", "--db", library_db, "--fallback", "closest")
    assert bad.returncode == 2 and "--fallback" in bad.stderr


@pytest.mark.parametrize("text, verb", [("太郎は花びらを散らす。", "散らす"), ("太郎はガムを噛む。", "噛む")])
def test_fallback_refuses_a_verb_nothing_is_near(library_db, text, verb):
    """散らす (scatter), 噛む (bite): no clip scatters or bites, whatever the vectors' neighbours."""
    with MotionDB.open(library_db) as db, pytest.raises(UnknownVerbError) as exc:
        plan_text(text, db, fallback="nearest")
    assert verb in str(exc.value) and "no stand-in: no clip does" in str(exc.value)


@pytest.mark.parametrize("text, clip", [
    ("太郎は写真を撮る。", "take_photo"),   # lemma 取る: the spelling as written decides
    ("太郎は本を取る。", "pick_up"),        # not 撮る's clip, though 本 is no object of pick_up
    ("花子はドアを閉める。", "close_door"),  # lemma 締める
    ("太郎は右手で指す。", "point"),        # lemma 差す, also the reading of 刺す (stab)
    ("太郎は歯を磨く。", "brush_teeth"),    # the object picks among the clips of 磨く
    ("はなこはたべる。", "eat"),            # kana: found by its reading
    ("太郎は後退りする。", "walk_back"),     # UniDic's spelling of the library's 後ずさりする: one word
    ("あとずさりする。", "walk_back"),
])
def test_the_clip_is_the_word_written_not_a_homophone(library_db, text, clip):
    with MotionDB.open(library_db) as db:
        assert [e.clip for e in text2anim.plan(text, db).table.elements] == [clip]


def test_a_kanji_verb_is_not_animated_as_another_word_of_the_same_sound(library_db):
    """吐く (spit) sounds as 掃く (sweep, in the library): it is a missing verb, not a sweep."""
    with MotionDB.open(library_db) as db, pytest.raises(UnknownVerbError) as exc:
        text2anim.plan("太郎はつばを吐く。", db)
    assert "吐く" in str(exc.value)


def test_neighbour_rank_is_required_beside_the_cosine():
    lib = ["歩く", "走る", "見る", "座る"]
    assert meaning.nearest("読む", lib, n=1, floor=meaning.MIN_SIMILARITY) == [("見る", pytest.approx(0.61, abs=0.02))]
    assert meaning.nearest("読む", lib, n=1, floor=meaning.MIN_SIMILARITY, within=meaning.MAX_RANK) == []
    assert meaning.nearest("登る", lib, n=1, within=meaning.MAX_RANK)[0][0] == "歩く"


def test_delay_that_opens_the_text_delays_the_first_motion(library_db):
    with MotionDB.open(library_db) as db:
        late = text2anim.plan("3秒後に太郎が歩く。そして座る。", db).table.elements
        now = text2anim.plan("太郎が歩く。そして座る。", db).table.elements
    assert late[0].start == pytest.approx(3.0) and now[0].start == 0.0
    assert late[1].start - late[0].start == pytest.approx(now[1].start - now[0].start)


def test_parse_json_shows_the_opening_delay_only_when_there_is_one():
    assert analyze("3秒後に歩く。").to_dict()["motions"][0]["delay"] == 3.0
    assert "delay" not in analyze("歩く。").to_dict()["motions"][0]
