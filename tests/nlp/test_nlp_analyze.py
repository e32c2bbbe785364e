"""nlp.analyze: the contract example, the head rule, errors, robustness."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from text2anim import nlp
from text2anim.nlp import MAX_CHARS, NLPError, analyze
from text2anim.nlp.lexicon import LIBRARY_VERBS

CORPUS = Path(__file__).parents[1] / "corpus" / "nlp_corpus.jsonl"
SENTENCES = [json.loads(line)["text"] for line in CORPUS.read_text(encoding="utf-8").splitlines()
             if line.startswith("{")]

CONTRACT_JSON = {
    "text": "太郎は走って、ボールを蹴る。そして喜ぶ。",
    "motions": [
        {"id": 1, "actor": "太郎", "verb": "走る", "object": None, "body_part": None,
         "repeat": 1, "speed": 1.0, "duration": None, "span": [3, 5]},
        {"id": 2, "actor": "太郎", "verb": "蹴る", "object": "ボール", "body_part": None,
         "repeat": 1, "speed": 1.0, "duration": None, "span": [11, 13]},
        {"id": 3, "actor": "太郎", "verb": "喜ぶ", "object": None, "body_part": None,
         "repeat": 1, "speed": 1.0, "duration": None, "span": [17, 19]},
    ],
    "constraints": [
        {"first": 1, "second": 2, "relation": "serial", "overlap": True, "delay": None,
         "method": "transition"},
        {"first": 2, "second": 3, "relation": "serial", "overlap": False, "delay": None,
         "method": "connection"},
    ],
}


def test_contract_example_exactly():
    analysis = analyze(CONTRACT_JSON["text"])
    assert analysis.to_dict() == CONTRACT_JSON
    assert json.loads(analysis.to_json()) == CONTRACT_JSON
    assert list(json.loads(analysis.to_json())) == ["text", "motions", "constraints"]


def test_types_are_frozen():
    analysis = analyze("太郎は歩く。")
    with pytest.raises(AttributeError):
        analysis.motions[0].verb = "走る"


def test_head_skips_nagara_clause():
    analysis = analyze("太郎は走って、右手を振りながら歩く。")
    heads = {b.text.rstrip("、。"): b.head for b in analysis.bunsetsu}
    texts = {b.index: b.text.rstrip("、。") for b in analysis.bunsetsu}
    assert texts[heads["走って"]] == "歩く"
    assert texts[heads["振りながら"]] == "歩く"
    run, wave, walk = (m.id for m in analysis.motions)
    by_pair = {frozenset((c.first, c.second)): c for c in analysis.constraints}
    assert by_pair[frozenset((run, walk))].method == "transition"
    assert by_pair[frozenset((run, walk))].first == run
    assert by_pair[frozenset((wave, walk))].method == "composition"


def test_explain_says_why():
    analysis = analyze("太郎は走って、右手を振りながら歩く。")
    run = next(b for b in analysis.bunsetsu if b.text.startswith("走って"))
    assert "skipping 振りながら" in run.why


def test_mae_reverses_the_order():
    sit, wave = analyze("座る前に手を振る。").motions
    (c,) = analyze("座る前に手を振る。").constraints
    assert (c.first, c.second, c.method) == (wave.id, sit.id, "connection")


def test_te_clause_before_mae_clause_goes_first():
    analysis = analyze("太郎は走って、座る前に手を振る。")
    run, sit, wave = analysis.motions
    pairs = [(c.first, c.second) for c in analysis.constraints]
    assert pairs == [(run.id, wave.id), (wave.id, sit.id)]


def test_tamama_holds_the_first_motion():
    raise_hand, walk = analyze("右手を上げたまま歩く。").motions
    assert raise_hand.hold and not walk.hold


def test_default_pause_is_two_seconds():
    (c,) = analyze("座る。しばらくして立つ。").constraints
    assert c.delay == 2.0 and c.method == "connection"


def test_reading_for_database_fallback():
    (m,) = analyze("ボールをける。").motions
    assert m.verb == "蹴る" and m.reading == "ケル"


@pytest.mark.parametrize("verb", sorted(LIBRARY_VERBS))
def test_library_verbs_normalise_to_themselves(verb):
    (m,) = analyze(f"太郎は{verb}。").motions
    assert m.verb == verb


@pytest.mark.parametrize("text, verbs", [
    ("ジャンプをする。", ["ジャンプする"]),
    ("伸びをする。", ["伸びする"]),
    ("お辞儀をする。", ["お辞儀する"]),
    ("歩いて行く。", ["歩く"]),
    ("箱を持ち上げて置く。", ["持ち上げる", "置く"]),
    ("走ったり跳んだりする。", ["走る", "跳ぶ"]),
    ("「走れ」と言う。", ["言う"]),
    ("しばらくして座る。", ["座る"]),
])
def test_what_is_a_motion(text, verbs):
    assert [m.verb for m in analyze(text).motions] == verbs


# ---------------------------------------------------------------- errors


@pytest.mark.parametrize("text", ["", "   ", "\n\t", "\x00\x01"])
def test_empty_text_is_an_error(text):
    with pytest.raises(NLPError, match="empty"):
        analyze(text)


def test_too_long_text_is_an_error():
    with pytest.raises(NLPError, match=str(MAX_CHARS)):
        analyze("歩く。" * (MAX_CHARS // 3 + 1))


def test_longest_accepted_text_works():
    text = ("歩く。" * MAX_CHARS)[:MAX_CHARS]
    assert len(analyze(text).motions) > 600


@pytest.mark.parametrize("text", ["これは本です。", "Hello world", "😀", "太郎は走らない。"])
def test_no_motion_is_an_error(text):
    with pytest.raises(NLPError, match="no motion"):
        analyze(text)


def test_error_is_user_facing_value_error():
    assert issubclass(NLPError, ValueError) and NLPError.user_facing is True


def test_non_string_is_an_error():
    with pytest.raises(NLPError):
        analyze(None)


# ---------------------------------------------------------------- invariants


def check_invariants(text: str, analysis: nlp.Analysis) -> None:
    ids = [m.id for m in analysis.motions]
    assert ids == list(range(1, len(ids) + 1))
    seconds = [c.second for c in analysis.constraints]
    assert len(seconds) == len(set(seconds)), "a motion with two incoming links"
    assert len(analysis.constraints) == len(ids) - 1, "not a single tree"
    parent = {c.second: c.first for c in analysis.constraints}
    for node in ids:  # no cycles: every chain of parents ends
        seen = set()
        while node in parent:
            assert node not in seen
            seen.add(node)
            node = parent[node]
    for c in analysis.constraints:
        assert c.method in ("connection", "transition", "composition")
        assert (c.relation == "parallel") == (c.method == "composition")
        assert (c.overlap is None) == (c.relation == "parallel")
    for m in analysis.motions:
        a, b = m.span
        assert 0 <= a < b <= len(text) and text[a:b].strip()


@pytest.mark.parametrize("text", SENTENCES)
def test_corpus_invariants(text):
    try:
        analysis = analyze(text)
    except NLPError:
        return
    check_invariants(text, analysis)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.sampled_from(SENTENCES), min_size=1, max_size=5), st.data())
def test_concatenated_sentences_keep_invariants(parts, data):
    text = "".join(parts)
    if data.draw(st.booleans()):
        k = data.draw(st.integers(0, len(text)))
        text = text[:k] + data.draw(st.sampled_from(["、", "。", "て", "😀", "ﾞ", "\x00", " "])) + text[k:]
    try:
        analysis = analyze(text)
    except NLPError:
        return
    check_invariants(text, analysis)


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=60))
def test_any_text_gives_an_analysis_or_nlp_error(text):
    try:
        analysis = analyze(text)
    except NLPError:
        return
    check_invariants(text, analysis)


JAPANESE_ISH = st.text(
    alphabet=st.sampled_from(list("太郎はがをにで走歩振蹴てっながらまま前後間同時秒回三3３。、！？\n"
                                  "るくうすしたいのとabc😀ﾀﾞ\x00\u3099")),
    max_size=40)


@settings(max_examples=300, deadline=None)
@given(JAPANESE_ISH)
def test_japanese_like_noise_never_crashes(text):
    try:
        analysis = analyze(text)
    except NLPError:
        return
    check_invariants(text, analysis)


def test_deterministic():
    text = "太郎は走って、右手を振りながら歩く。花子が座る前に3秒間踊る。"
    assert analyze(text).to_json() == analyze(text).to_json()
