"""Katakana readings of verbs and nouns, and nearest-verb suggestions."""
from __future__ import annotations

import pytest

from text2anim.motiondb.readings import nearest, normalize, reading, same_word, to_katakana, word_key


@pytest.mark.parametrize("word, expected", [
    ("跳ぶ", "トブ"), ("飛ぶ", "トブ"), ("とぶ", "トブ"), ("トブ", "トブ"),
    ("ジャンプする", "ジャンプスル"), ("じゃんぷする", "ジャンプスル"), ("ｼﾞｬﾝﾌﾟする", "ジャンプスル"),
    ("歩き出す", "アルキダス"), ("前進する", "ゼンシンスル"), ("お辞儀する", "オジギスル"),
    ("箱", "ハコ"), ("はこ", "ハコ"), ("ボール", "ボール"), ("手を振る", "テヲフル"),
    ("  歩く ", "アルク"), ("", ""),
])
def test_readings(word, expected):
    assert reading(word) == expected


def test_normalize_and_katakana():
    assert normalize(" ｼﾞｬﾝﾌﾟ ") == "ジャンプ"
    assert to_katakana("あるく ABC ー") == "アルク ABC ー"


def test_nearest_compares_readings_and_is_deterministic():
    verbs = {"転ぶ": "コロブ", "走る": "ハシル", "歩く": "アルク", "倒れる": "タオレル"}
    assert nearest("ころがる", verbs)[0] == "転ぶ"
    assert nearest("はしりだす", verbs)[0] == "走る"
    assert nearest("あるく", verbs)[0] == "歩く"
    assert nearest("ぱぴぷぺぽ", verbs) == []
    assert nearest("ころがる", verbs) == nearest("ころがる", dict(reversed(list(verbs.items()))))


@pytest.mark.parametrize("a, b", [("後退りする", "後ずさりする"), ("あとずさりする", "後ずさりする"),
                                  ("頷く", "うなずく"), ("指差す", "指さす"), ("ジャンプする", "ジャンプする")])
def test_spellings_of_one_word_are_the_same_word(a, b):
    assert same_word(a, b) and word_key(a) == word_key(b)


@pytest.mark.parametrize("a, b", [("吹く", "拭く"), ("吐く", "掃く"), ("撮る", "取る"), ("閉める", "締める"),
                                  ("歩く", "走る")])
def test_homophones_and_other_words_are_not(a, b):
    assert not same_word(a, b)
