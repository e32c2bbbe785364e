"""The phrase corpus (issue 39): what a phrase means, loan verbs and mimetics, through the real analyzer
and the real planner on the built-in library.

tests/corpus/phrase_corpus.jsonl holds idioms whose action is not their verb's (腰を上げる stands up,
肩を落とす droops), katakana verbs (ハイタッチする, ストレッチする) and mimetics (ぱちぱち repeats the
clap, よろよろ is a manner of the walk); docs/language.md §1, §2 and §7.8-§7.10. ``text2anim batch
--check`` compares every parse with its expectation; the planner must then play the clip each line
names (``"clip"``), insert no other clip between them where ``"added"`` says so, or refuse with
the words of ``"plan_error"``, with ``--fallback nearest`` too: no clip of another sense of the verb.
"""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import text2anim
from text2anim.cli.main import main
from text2anim.motiondb import MotionDB, UnknownVerbError
import corpus_lines

CORPUS = Path(__file__).parents[1] / "corpus" / "phrase_corpus.jsonl"

#: The classes of issue 39 this corpus covers, each with at least this many texts.
CLASSES = {"idiom": 20, "loanword": 12, "mimetic": 20}


def _items() -> list[dict]:
    return corpus_lines.items(CORPUS.name)


def test_corpus_is_large_new_and_covers_every_class():
    items = _items()
    assert len(items) >= 45
    assert not corpus_lines.short_classes(items, CLASSES)
    assert not corpus_lines.repeated(items, "nlp_corpus.jsonl", "typed_corpus.jsonl")


def test_every_phrase_parses_as_expected(capsys, tmp_path):
    code = main(["batch", str(CORPUS), "--check", "--out", str(tmp_path), "--parse-only"])
    out = capsys.readouterr().out
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert code == 0 and summary["passed"] == summary["total"] == len(_items()), out


def _id(item: dict) -> str:
    """A test id for a corpus line: its class and the line number in the file."""
    lines = CORPUS.read_text(encoding="utf-8").splitlines()
    return f"{item['category']}-line{lines.index(json.dumps(item, ensure_ascii=False)) + 1}"


def _base(clip: str) -> str:
    """A captured variant's base clip (``walk_02_01`` -> ``walk``)."""
    return re.sub(r"(_\d+)+$", "", clip)


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


@pytest.mark.parametrize("item", [it for it in _items() if "clip" in it], ids=_id)
def test_the_planner_plays_the_phrase_s_action(item, db):
    planned = text2anim.plan(item["text"], db)
    n = len(item["expect"]["motions"])
    played = {e.id: _base(e.clip) for e in planned.table.elements}
    for i, want in enumerate(item["clip"], 1):
        assert played[i] in ([want] if isinstance(want, str) else want), (i, played)
    if "added" in item:
        added = [clip for i, clip in played.items() if i > n and i not in planned.fillers]
        assert added == item["added"], played


@pytest.mark.parametrize("item", [it for it in _items() if "plan_error" in it], ids=_id)
@pytest.mark.parametrize("fallback", ["strict", "nearest"])
def test_a_phrase_no_clip_does_is_refused_by_name(item, fallback, db):
    with pytest.raises(UnknownVerbError) as refused:
        text2anim.plan(item["text"], db, fallback=fallback)
    assert item["plan_error"] in str(refused.value)
