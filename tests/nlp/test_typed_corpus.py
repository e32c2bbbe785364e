"""The typed corpus (issue 27): sentences written the way users type them, through the real analyzer.

tests/corpus/typed_corpus.jsonl holds scripts with speaker labels and stage directions, names as
written, non-actions, casual typing, spelling variants, time and repetition words, noun + をする
and everyday actions of several characters (docs/language.md §7); ``text2anim batch --check`` compares
every parse with its expectation."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from text2anim.cli.main import main
from text2anim.nlp import NLPError, analyze
import corpus_lines

CORPUS = Path(__file__).parents[1] / "corpus" / "typed_corpus.jsonl"

#: The classes of issue 27 the corpus covers, each with at least this many sentences.
CLASSES = {"script": 15, "names": 10, "nonaction": 15, "casual": 15, "variants": 8, "time": 10,
           "noun_suru": 8, "everyday": 12}


def _items() -> list[dict]:
    return corpus_lines.items(CORPUS.name)


def test_corpus_is_large_and_covers_every_class():
    items = _items()
    assert len(items) >= 100
    assert not corpus_lines.short_classes(items, CLASSES)
    assert not corpus_lines.repeated(items, "nlp_corpus.jsonl")


def test_every_typed_sentence_parses_as_expected(capsys, tmp_path):
    code = main(["batch", str(CORPUS), "--check", "--out", str(tmp_path), "--parse-only"])
    out = capsys.readouterr().out
    assert code == 0, out
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["passed"] == summary["total"] == len(_items())


@pytest.mark.parametrize("text, note", [
    ("太郎わ歩く。", "太郎わ as 太郎は"),
    ("ボールお蹴る。", "ボールお蹴る as ボールを蹴る"),
    ("手を降る。", "降る as 振る"),
])
def test_what_was_read_differently_is_said(text, note):
    assert any(note in n for n in analyze(text).notes)


def test_text_as_written_says_nothing():
    assert analyze("雨が降る中、太郎は手を振る。").notes == ()


def test_parse_says_on_stderr_and_in_explain(capsys):
    assert main(["parse", "花子わ右手を降る。", "--explain"]) == 0
    out, err = capsys.readouterr()
    assert "read 花子わ as 花子は" in err and "read 降る as 振る" in err
    assert "read differently from how it is written:" in out and "read 降る as 振る" in out


@pytest.mark.parametrize("text, why", [
    ("太郎は泳げる。", "potential form"),
    ("雨が降る。", "subject is not a person"),
    ("走ろうと思う。", "quoted speech"),
])
def test_no_motion_error_says_why(text, why):
    with pytest.raises(NLPError, match=f"no motion found.*{why}"):
        analyze(text)


def test_script_label_holds_for_its_line_only():
    a = analyze("花子：座る。\n太郎：走る。")
    assert [(m.actor, m.verb) for m in a.motions] == [("花子", "座る"), ("太郎", "走る")]
    assert [m.span for m in a.motions] == [(3, 5), (10, 12)]


def test_a_quotation_in_brackets_inside_a_sentence_stays_quoted():
    (m,) = analyze("太郎は(走れ)と言う。").motions
    assert m.verb == "言う"
