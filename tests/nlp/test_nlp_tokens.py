"""The traps of fugashi + unidic-lite (docs/unidic-notes.md), each confirmed here,
and how the tokens layer deals with them."""
from __future__ import annotations

import pytest

from text2anim.nlp.bunsetsu import chunk, split_sentences
from text2anim.nlp.numbers import kanji_to_int, number_value
from text2anim.nlp.tokens import is_name, normalize, tagger, tokenize


def raw(text):
    return [(w.surface, w.feature) for w in tagger()(text)]


# ---------------------------------------------------------------- raw UniDic facts


def test_digits_are_unknown_tokens_without_lemma():
    (surface, f), *_ = raw("3回")
    assert surface == "3" and f.lemma is None and f.orthBase is None


def test_decimal_point_is_tagged_as_sentence_end():
    words = raw("0.5秒")
    assert [s for s, _ in words[:3]] == ["0", ".", "5"]
    assert words[1][1].pos2 == "句点"


def test_kanji_numerals_split_but_have_lemmas():
    words = raw("十五秒")
    assert [s for s, _ in words[:2]] == ["十", "五"]
    assert words[0][1].lemma == "十"


def test_tobu_spellings_share_one_lemma_but_not_orthbase():
    lemmas = {raw(f"太郎は{v}。")[2][1].lemma for v in ("跳ぶ", "飛ぶ", "とぶ")}
    orths = {raw(f"太郎は{v}。")[2][1].orthBase for v in ("跳ぶ", "飛ぶ", "とぶ")}
    assert lemmas == {"飛ぶ"} and orths == {"跳ぶ", "飛ぶ", "とぶ"}


def test_ageru_written_with_other_kanji_has_lemma_ageru():
    assert raw("手を挙げる")[2][1].lemma == "上げる"


def test_sahen_noun_and_suru():
    (_, noun), (_, suru) = raw("ジャンプする")
    assert noun.pos3 == "サ変可能" and suru.lemma == "為る" and suru.cType == "サ行変格"


def test_guts_pose_is_two_general_nouns():
    words = raw("ガッツポーズする")
    assert [s for s, _ in words] == ["ガッツ", "ポーズ", "する"]
    assert words[0][1].pos3 == "一般"


def test_ojigi_is_prefix_plus_noun():
    words = raw("お辞儀をする")
    assert words[0][1].pos1 == "接頭辞" and words[1][0] == "辞儀"


def test_list_item_renyoukei_is_sometimes_a_noun():
    words = raw("走り、跳び、転ぶ")
    assert words[2][0] == "跳び" and words[2][1].pos1 == "名詞"


def test_teiru_and_teru():
    assert [s for s, _ in raw("走っている")] == ["走っ", "て", "いる"]
    assert raw("走ってる")[1][1].pos1 == "助動詞"


def test_byoukan_and_aida_differ_by_reading():
    assert raw("5秒間")[1][1].kana == "ビョウカン"
    assert raw("歩いている間に")[3][1].kana == "アイダ"


def test_taro_is_sometimes_a_common_noun():
    # 同時に太郎は: the name comes out as 普通名詞 (is_name recovers it)
    words = raw("座るのと同時に太郎は立つ")
    taro = next(f for s, f in words if s == "太郎")
    assert taro.pos2 == "普通名詞"
    assert is_name("太郎") and is_name("さくら") and not is_name("ボール")


# ---------------------------------------------------------------- our tokens


def test_nfkc_full_width_ten_is_a_number():
    toks = tokenize(normalize("１０秒")[0])
    assert toks[0].surface == "10" and toks[0].value == 10.0


def test_decimal_merged_before_sentence_split():
    toks = tokenize(normalize("0.5秒後に座る。")[0])
    assert toks[0].surface == "0.5" and toks[0].value == 0.5
    assert len(split_sentences(toks)) == 1


def test_kanji_numeral_run_merged():
    toks = tokenize("十五秒")
    assert toks[0].surface == "十五" and toks[0].value == 15.0


def test_list_item_retagged_as_verb():
    toks = tokenize("走り、跳び、転ぶ")
    tobi = toks[2]
    assert tobi.pos1 == "動詞" and tobi.orth == "跳ぶ"


def test_real_noun_before_comma_not_retagged():
    toks = tokenize("ボール、バット")
    assert toks[0].pos1 == "名詞"


@pytest.mark.parametrize("text, value", [
    ("三", 3), ("十", 10), ("十五", 15), ("二十", 20), ("百二十", 120), ("二百三", 203),
    ("千", 1000), ("一万二千", 12000), ("二〇", 20),
])
def test_kanji_to_int(text, value):
    assert kanji_to_int(text) == value


def test_number_value_rejects_words():
    assert number_value("abc") is None and kanji_to_int("本") is None


def test_normalize_maps_offsets_back():
    text = "ﾀﾞﾝｻｰは１０秒"
    norm, offsets = normalize(text)
    assert norm == "ダンサーは10秒"
    assert offsets.span(0, 4) == (0, 5)  # ダンサー <- ﾀﾞﾝｻｰ (5 characters)
    assert offsets.span(5, 7) == (6, 8)  # 10 <- １０


def test_normalize_replaces_control_characters():
    norm, _ = normalize("走る\x00。\t歩く\r")
    assert "\x00" not in norm and "\t" not in norm and norm.endswith("\n")


def test_sentences_split_at_punctuation_and_newline_not_inside_quotes():
    toks = tokenize(normalize("歩く。走る！「止まれ。」と言う\n座る")[0])
    sentences = split_sentences(toks)
    assert len(sentences) == 4


def test_bunsetsu_keep_connective_nouns_with_their_predicate():
    phrases = chunk(split_sentences(tokenize("太郎は座る前に手を上げたまま歩く。")))
    assert [p.surface for p in phrases] == ["太郎は", "座る前に", "手を", "上げたまま", "歩く。"]


def test_bunsetsu_number_with_counter_stands_alone():
    phrases = chunk(split_sentences(tokenize("3回ジャンプする")))
    assert [p.surface for p in phrases] == ["3回", "ジャンプする"]


def test_reading_table_matches_the_tagger():
    from text2anim.nlp.lexicon import LIBRARY_BY_READING, VERB_ALIASES

    for reading, verb in LIBRARY_BY_READING.items():
        kana = raw(f"太郎は{verb}。")[2][1].kanaBase
        assert kana == reading, verb
    assert LIBRARY_BY_READING["トブ"] == VERB_ALIASES["とぶ"]


def test_hiragana_tatsu_is_read_as_another_verb():
    assert raw("太郎はたつ。")[2][1].lemma == "経つ"  # the analyzer maps it to 立つ by reading
