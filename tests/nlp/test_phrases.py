"""What a phrase means and what a mimetic says (issue 39), through the real analyzer: docs/language.md
§2 ("What a phrase means") and §7.9 (mimetics)."""
from __future__ import annotations

import json

import pytest

from text2anim.nlp import analyze


def _motion(text: str):
    (m,) = analyze(text).motions
    return m


@pytest.mark.parametrize("text, verb, written", [
    ("太郎は腰を上げた。", "立ち上がる", "腰を上げる"),  # 上げる alone raises a hand
    ("花子はこしをおろした。", "座る", "こしをおろす"),  # kana spellings meet on the same idiom
    ("太郎は両膝をついた。", "ひざまずく", "両膝をつく"),
    ("花子はそっぽを向いた。", "背を向ける", "そっぽを向く"),
    ("太郎は首を縦に振った。", "うなずく", "首を縦に振る"),
])
def test_an_idiom_is_the_action_it_means_and_keeps_the_phrase(text, verb, written):
    m = _motion(text)
    assert (m.verb, m.written, m.object) == (verb, written, None)


def test_a_phrase_that_means_its_verb_keeps_the_verb_and_names_the_phrase():
    m = _motion("花子は首を横に振った。")
    assert (m.verb, m.body_part, m.phrase) == ("振る", "head", "首を振る")
    assert _motion("太郎はボールを蹴った。").phrase == "ボールを蹴る"
    assert _motion("太郎は走った。").phrase == ""


def test_an_idiom_of_the_whole_body_drops_the_body_part():
    assert _motion("太郎は腰を上げた。").body_part is None  # torso would lay only the torso onto a walk
    assert _motion("花子は顔を上げた。").body_part == "head"  # 見上げる is done with the head


@pytest.mark.parametrize("text, repeat, manner", [
    ("観客はぱちぱちと拍手した。", 3, "ぱちぱち"),
    ("花子は手をパチパチ叩いた。", 3, "ぱちぱち"),  # katakana is read as its hiragana
    ("太郎はぴょんぴょん5回跳んだ。", 5, "ぴょんぴょん"),  # a count wins
    ("太郎は何度かくるくる回った。", 2, "くるくる"),
    ("太郎はよろよろと歩いた。", 1, "よろよろ"),  # a manner, not a repetition
    ("花子はくるりと振り向いた。", 1, "くるり"),
])
def test_a_mimetic_repeats_the_motion_or_says_its_manner(text, repeat, manner):
    m = _motion(text)
    assert (m.repeat, m.manner) == (repeat, manner)


@pytest.mark.parametrize("text, verb, manner", [
    ("花子はきょろきょろした。", "きょろきょろする", "きょろきょろ"),
    ("太郎は公園をうろうろした。", "歩く", "うろうろ"),
])
def test_a_mimetic_and_suru_is_a_verb(text, verb, manner):
    m = _motion(text)
    assert (m.verb, m.manner) == (verb, manner)


def test_a_feeling_and_suru_is_no_motion():
    (m,) = analyze("花子はわくわくして走った。").motions
    assert m.verb == "走る"


def test_the_manner_is_in_the_json_only_when_the_text_gives_one():
    plain = json.loads(analyze("太郎は歩いた。").to_json())["motions"][0]
    mimetic = json.loads(analyze("太郎はとぼとぼ歩いた。").to_json())["motions"][0]
    assert "manner" not in plain and mimetic["manner"] == "とぼとぼ"
