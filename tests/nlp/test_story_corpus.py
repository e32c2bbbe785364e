"""The story corpus (issue 39): stories, keigo, instructions, spoken text, typos and actors together,
through the real analyzer and the real planner (the built-in library), and the rules behind them
(docs/language.md §9)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from text2anim.cli.main import main
from text2anim.nlp import NLPError, analyze
import corpus_lines

CORPUS = Path(__file__).parents[1] / "corpus" / "story_corpus.jsonl"

#: The classes of issue 39 the corpus covers, each with at least this many texts.
CLASSES = {"story": 15, "keigo": 12, "instruction": 12, "spoken": 12, "typo": 12, "together": 12}


def _items() -> list[dict]:
    return corpus_lines.items(CORPUS.name)


def test_corpus_is_large_new_and_covers_every_class():
    items = _items()
    assert len(items) >= 80
    assert not corpus_lines.short_classes(items, CLASSES)
    others = [p.name for p in CORPUS.parent.glob("*.jsonl") if p != CORPUS]
    assert not corpus_lines.repeated(items, *others)
    # most lines also say which clip plays: the text is checked end to end
    assert sum(any("clip" in m for m in it["expect"].get("motions", [])) for it in items) >= 90


def test_every_story_parses_and_plans_as_expected(capsys, tmp_path):
    code = main(["batch", str(CORPUS), "--check", "--out", str(tmp_path), "--parse-only"])
    out = capsys.readouterr().out
    assert code == 0, out
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["passed"] == summary["total"] == len(_items())


# ---------------------------------------------------------------- who


def _bunsetsu(text: str, starts: str):
    return next(b for b in analyze(text).bunsetsu if b.text.startswith(starts))


@pytest.mark.parametrize("text, mention, persons", [
    ("太郎は花子に会った。彼女に手を振った。", "彼女に", ("花子",)),  # a target, not only an actor
    ("花子と健一が来た。彼は座った。", "彼は", ("健一",)),
    ("兄が弟を起こした。彼は起き上がった。", "彼は", ("弟",)),  # the last man named, whatever his case
    ("店長が来た。その人は座った。", "その人は", ("店長",)),
    ("記者が来た。あの人は座った。", "あの人は", ("記者",)),
    ("太郎は走った。次郎も走った。二人はそこで止まった。", "二人は", ("太郎", "次郎")),
    ("先輩と後輩と新人が来た。みんなで踊った。", "みんなで", ("先輩", "後輩", "新人")),
    ("係の人が来た。", "人が", ("係の人",)),
    ("新入社員の山田さんが来た。", "山田さんが", ("山田",)),
    # a が-subject of the clause before is someone else than the main clause's 彼は / 彼も
    ("父は新聞を読んでいた。息子が帰ってくると、彼は顔を上げた。", "彼は", ("父",)),
    ("次郎は兄と歩いた。兄が止まると、彼も止まった。", "彼も", ("次郎",)),
    ("花子が来ると、彼女は座った。", "彼女は", ("花子",)),  # no one else: still her
    # 本 is also a surname: as a を-object it is a thing, not the woman 彼女 refers to
    ("みきは本を棚から取った。彼女はそれを机に置いた。", "彼女は", ("みき",)),
])
def test_every_phrase_naming_a_person_says_whom(text, mention, persons):
    assert _bunsetsu(text, mention).persons == persons


def test_a_pronoun_read_as_a_person_is_said_in_the_notes_and_on_stderr(capsys):
    analysis = analyze("花子は傘を開いた。それから彼女は走り出した。")
    assert [(m.actor, m.verb) for m in analysis.motions][-1] == ("花子", "走る")
    assert "read 彼女 as 花子 (the last woman named)" in analysis.notes
    assert main(["parse", "二郎と花子が来た。二人は座った。", "--explain"]) == 0
    out, err = capsys.readouterr()
    assert "read 二人 as 二郎、花子" in err and "read 二人 as 二郎、花子" in out


@pytest.mark.parametrize("text, actors", [
    ("太郎は彼に手を振った。", ["太郎"]),  # 彼 is not the actor of its own clause: someone else
    ("太郎は歩いた。彼女は座った。", ["太郎", "太郎"]),  # the only candidate, whatever its name's ending
    ("父が来た。彼女は座った。", ["父", "彼女"]),  # 父 is a man by the word: 彼女 is someone new
    ("彼は立ち上がる。彼女は拍手する。", ["彼", "彼女"]),  # nobody named: each a character of its own
    ("二人は一緒に歩いた。", ["一人目", "二人目"]),  # a counted group of no one named: two new characters
    ("太郎は3人で踊った。", ["太郎", "二人目", "三人目"]),  # 太郎 and two more
    ("みんなで踊った。", [None]),  # an uncounted group of no one named names no one
    ("私は太郎に会った。彼は笑った。", ["私", "太郎"]),  # 彼 never refers to the speaker
])
def test_who_a_pronoun_refers_to(text, actors):
    assert [m.actor for m in analyze(text).motions] == actors


@pytest.mark.parametrize("text", [
    "身長が伸びた。", "延長が決まった。", "定員が増えた。", "成長が止まった。", "全長が伸びる。",
])
def test_words_with_a_person_ending_that_name_no_one_are_no_actors(text):
    """〜長, 〜員 are persons in 店長 and 駅員, not in 身長 or 定員: their predicate is no one's action."""
    with pytest.raises(NLPError, match="subject is not a person"):
        analyze(text)


@pytest.mark.parametrize("text, actor", [
    ("運転手が歩く。", "運転手"), ("参加者が走る。", "参加者"), ("駅員さんが手を振る。", "駅員さん"),
    ("おまわりさんが止まる。", "おまわりさん"), ("受付係が座る。", "受付係"), ("管理人が歩く。", "管理人"),
    ("校長先生が座る。", "校長先生"), ("隣の人が立つ。", "隣の人"),
])
def test_person_nouns_beyond_the_list(text, actor):
    assert analyze(text).motions[0].actor == actor


def test_a_person_suffix_in_an_object_is_no_actor():
    (m,) = analyze("太郎は切手を貼った。").motions
    assert (m.actor, m.object) == ("太郎", "切手")


# ---------------------------------------------------------------- together


@pytest.mark.parametrize("text, actors", [
    ("太郎は花子と一緒に歩く。", ["太郎", "花子"]),
    ("太郎は花子と歩く。", ["太郎", "花子"]),  # と alone: 花子 is his partner, who acts too (§8)
    ("太郎は花子に会った。彼女と握手した。", ["太郎", "太郎", "花子"]),  # the partner 彼女 is 花子
    ("太郎と花子は一緒に歩く。", ["太郎", "花子"]),
    ("花子は友達と二人でジャンプした。", ["花子", "友達"]),
    ("みんなで踊ろう。", [None]),
])
def test_acting_together(text, actors):
    assert [m.actor for m in analyze(text).motions] == actors


# ---------------------------------------------------------------- keigo, instructions, spoken


@pytest.mark.parametrize("text, verb", [
    ("先生がお座りになった。", "座る"), ("社長がお見えになった。", "来る"), ("先生が散歩なさる。", "散歩する"),
    ("ご着席ください。", "着席する"), ("お客様がいらっしゃった。", "来る"), ("先生が歩いていらっしゃる。", "歩く"),
    ("部長がお茶を召し上がる。", "飲む"), ("部長がケーキを召し上がる。", "食べる"), ("ご覧ください。", "見る"),
    ("しゃがめ！", "しゃがむ"), ("はい、ジャンプ！", "ジャンプする"), ("座りな。", "座る"), ("はよ走り！", "走る"),
    ("最後にお辞儀", "お辞儀する"),
    ("ゆーっくり歩く。", "歩く"),
])
def test_polite_spoken_and_terse_forms_are_the_plain_action(text, verb):
    assert [m.verb for m in analyze(text).motions] == [verb]


@pytest.mark.parametrize("text, why", [
    ("走るな！", "prohibition"), ("注意！", "no motion found"), ("先生でいらっしゃる。", "state"),
])
def test_what_asks_for_no_action_is_refused_with_its_reason(text, why):
    with pytest.raises(NLPError, match=why):
        analyze(text)


# ---------------------------------------------------------------- typos


@pytest.mark.parametrize("text, verbs, note", [
    ("花子は走しって、止まった。", ["走る", "止まる"], "read 走しって as 走って"),
    ("花子は手を叩た。", ["叩く"], "read 叩た as 叩いた"),
    ("太郎は壁を指刺した。", ["指さす"], "read 指刺す as 指さす"),
    ("太郎は歩るて、転ぶ。", ["転ぶ"], "could not read 歩るて"),
    ("太郎は歩るいて、ゆーっくり座わった。", ["歩く", "座る"], "read 座わった as 座った"),  # two in a line
])
def test_misspelt_verbs_are_read_or_said_unread(text, verbs, note):
    analysis = analyze(text)
    assert [m.verb for m in analysis.motions] == verbs
    assert any(note in n for n in analysis.notes)


@pytest.mark.parametrize("text", ["ジャンプを3回する。", "今日は本を読む。", "私らは歩いた。", "水たまりを歩く。"])
def test_text_as_written_is_not_repaired(text):
    assert analyze(text).notes == ()


@pytest.mark.parametrize("text, actors", [
    ("あかりは公園へ走った。そこではるとが待っていた。", ["あかり", "はると"]),
    ("ゆうとくんは朝ごはんを食べてから、歯を磨いた。", ["ゆうと", "ゆうと"]),  # くん is no 来る
    ("そうたは走った。れんも走った。", ["そうた", "れん"]),
    ("さくらちゃんが笑った。", ["さくら"]),
])
def test_a_name_written_in_hiragana_is_a_person(text, actors):
    analysis = analyze(text)
    assert [m.actor for m in analysis.motions if m.verb != "待つ" or m.actor in actors][:len(actors)] == actors
    assert any(n.startswith(f"read {actors[0]}") and "as a name" in n for n in analysis.notes)


@pytest.mark.parametrize("text, verb", [("太郎はさくらを見た。", "見る"), ("ゆきが降ってきた。太郎は走った。", "走る")])
def test_a_word_that_is_also_a_hiragana_name_keeps_its_meaning(text, verb):
    analysis = analyze(text)
    assert [m.actor for m in analysis.motions] == ["太郎"] and analysis.motions[0].verb == verb
    assert not any("as a name" in n for n in analysis.notes)
