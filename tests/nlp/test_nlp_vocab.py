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
    with MotionDB.open(library_db) as db, pytest.raises(UnknownVerbError) as exc:
        text2anim.plan("太郎は山に登って、本を読む。そして座る。", db)
    msg = str(exc.value)
    assert "登る" in msg and "読む" in msg and "上る" not in msg
    assert "nearest by meaning" in msg and "見る" in msg.split("読む")[1]


def test_fallback_nearest_animates_and_says_so(library_db, tmp_path):
    out, report = tmp_path / "a.bvh", tmp_path / "r.json"
    strict = run("太郎は山に登る。", "-o", out, "--db", library_db)
    assert strict.returncode == 2 and not out.exists() and "登る" in strict.stderr
    proc = run("太郎は山に登る。", "-o", out, "--db", library_db, "--fallback", "nearest", "--report", report)
    assert proc.returncode == 0, proc.stderr
    assert "fallback: 登る → 歩く" in proc.stderr
    data = json.loads(report.read_text())
    assert [(f["id"], f["asked"], f["animated_as"]) for f in data["fallbacks"]] == [(1, "登る", "歩く")]
    assert data["fallbacks"][0]["similarity"] >= meaning.MIN_SIMILARITY
    assert [e["verb"] for e in data["time_table"]] == ["歩く"]


@pytest.mark.parametrize("text, verb", [("太郎は掃除する。", "掃除する"), ("太郎は本を読む。", "読む")])
def test_fallback_refuses_a_verb_nothing_is_near(library_db, text, verb):
    """掃除する: no library verb is even loosely near; 読む: 見る (look around) is the
    nearest library verb but only its ~60th neighbour, so no stand-in is played."""
    with MotionDB.open(library_db) as db, pytest.raises(UnknownVerbError) as exc:
        plan_text(text, db, fallback="nearest")
    assert verb in str(exc.value) and "near enough" in str(exc.value)


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
