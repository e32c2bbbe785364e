"""Nothing that looks like an action is dropped in silence (issue 39).

Over every corpus text (tests/corpus/*.jsonl), each word the dictionary reads as a verb (a verb, the
する of a サ変 or katakana noun) and each kanji written as a verb's stem but read as a noun (歩るいて: 歩
+ る + いて) is accounted for by the real analyzer: it lies in a motion's phrase, in a phrase that is
no motion for a documented reason (``endings.NOT_MOTION``: potential, negation, relative clause, ...)
or in a documented role (a manner word, a connective, an action noun), or a note says how it was read
(``Analysis.notes``); a text with no motion at all is refused, the refusal naming why.
"""
from __future__ import annotations

import json
from dataclasses import replace
from functools import lru_cache
from pathlib import Path

import pytest

from text2anim.nlp import Analysis, NLPError, analyze
from text2anim.nlp.endings import NOT_MOTION
from text2anim.nlp.tagging import tag
from text2anim.nlp.tokens import normalize

CORPORA = sorted((Path(__file__).parents[1] / "corpus").glob("*.jsonl"))
#: Roles a phrase holding a verb may have besides a motion's: words the lexicon documents.
DOCUMENTED = {"manner", "connective", "speed", "repeat", "delay", "duration", "steps", "action noun"}


def _texts() -> list[str]:
    return [json.loads(x)["text"] for path in CORPORA
            for x in path.read_text(encoding="utf-8").splitlines() if x.startswith("{")]


@lru_cache(maxsize=None)
def _stem_of_a_verb(kanji: str) -> bool:
    """The dictionary reads ``kanji`` + a dictionary-form ending as one verb (歩 + く, 座 + る)."""
    return any(len(w := tag(kanji + end, 0)) == 1 and w[0].pos1 == "動詞" for end in "るくうむすぶつぐ")


def looks_like_an_action(text: str) -> list[tuple[str, tuple[int, int]]]:
    """(word, span in ``text``) of every verb the dictionary reads in ``text``, every one-kanji noun
    that is a verb's stem written with kana right after it (歩るいて, 座わって), and every action noun
    ending its sentence without する (最後にお辞儀, ジャンプ！)."""
    norm, offsets = normalize(text)
    words = tag(norm, 0)
    out = []
    for k, w in enumerate(words):
        nxt = words[k + 1] if k + 1 < len(words) else None
        misspelt = (w.pos1 == "名詞" and len(w.surface) == 1 and "\u4e00" <= w.surface <= "\u9fff"
                    and nxt is not None and nxt.start == w.end and "\u3041" <= nxt.surface[0] <= "\u309f"
                    and nxt.pos2 not in ("格助詞", "係助詞") and nxt.lemma not in ("だ", "です")
                    and _stem_of_a_verb(w.surface))  # 急に: a noun and the copula's に
        command = (w.pos1 == "名詞" and w.pos3 == "サ変可能" and (nxt is None or nxt.pos2 == "句点"))
        if w.pos1 == "動詞" or misspelt or command:
            out.append((w.surface, offsets.span(w.start, w.end)))
    return out


def unaccounted(text: str, analysis: Analysis | None = None) -> list[str]:
    """The words of ``text`` that look like an action and that its analysis (by default the real
    analyzer's) does not account for."""
    if analysis is None:
        try:
            analysis = analyze(text)
        except NLPError as exc:
            return [] if "no motion found" in str(exc) or "empty" in str(exc) else [f"refused: {exc}"]
    missing = []
    for word, (start, _) in looks_like_an_action(text):
        phrase = next((b for b in analysis.bunsetsu if b.span[0] <= start < b.span[1]), None)
        role = phrase.role if phrase is not None else ""
        reason = role.removeprefix("not a motion: ") if role.startswith("not a motion: ") else None
        if role == "motion" or role in DOCUMENTED or reason in NOT_MOTION:
            continue
        if any(word in note for note in analysis.notes):
            continue
        missing.append(f"{word} (phrase {phrase.text if phrase else None!r}, role {role!r})")
    return missing


def test_every_word_that_looks_like_an_action_is_accounted_for_in_every_corpus():
    texts = _texts()
    assert len(texts) >= 480 and len(CORPORA) >= 3
    found = {t: unaccounted(t) for t in texts}
    assert not {t: m for t, m in found.items() if m}


@pytest.mark.parametrize("text, word", [
    ("1. 座る\n2. 最後にお辞儀", "辞儀"),  # a command without a verb ending: a motion
    ("太郎は歩るいて、ころぶ。", "歩"),  # repaired: a walk, said in a note
    ("太郎は歩るて、転ぶ。", "歩"),  # not repaired: said to be unread
    ("花子は手を叩た。", "叩"),
])
def test_the_check_sees_misspelt_verbs_and_commands_and_the_analysis_reads_them(text, word):
    assert word in [w[0] for w in looks_like_an_action(text)]
    assert unaccounted(text) == []
    analysis = analyze(text)
    assert any(word in n for n in analysis.notes) or any(word in m.verb for m in analysis.motions)


def test_a_word_dropped_in_silence_is_caught():
    """The check fails where a verb is dropped and nothing says so: the analysis of a verb no repair
    reads, with its note taken away (as the analyzer was before it said it)."""
    text = "太郎は歩るて、転ぶ。"
    assert unaccounted(text) == []
    assert [m.split(" ")[0] for m in unaccounted(text, replace(analyze(text), notes=()))] == ["歩"]
