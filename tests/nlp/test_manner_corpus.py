"""The manner corpus (issue 40): how a motion is done, through the real analyzer.

tests/corpus/manner_corpus.jsonl holds manner adverbs (大股で, 颯爽と), mimetics (のろのろ, ドスドス),
likenesses (嬉しそうに, 疲れた様子で, 踊るように), emotional て-forms (怒って), posture idioms that pass
their style on (胸を張って), degree words (とても) and texts that give no style (怒って、 with a comma;
にこにこ, a face; ゆっくり, a speed alone); docs/language.md §2.1. ``text2anim batch --check`` compares
every parse with its expectation.
"""
from __future__ import annotations

import json

from text2anim import nlp
from text2anim.cli.main import main
from text2anim.core.styles import STYLES
import corpus_lines

NAME = "manner_corpus.jsonl"
CLASSES = {"adverb": 10, "mimetic": 10, "likeness": 8, "te": 5, "posture": 2, "degree": 3, "none": 3}


def _items() -> list[dict]:
    return corpus_lines.items(NAME)


def test_corpus_is_large_new_and_covers_every_class_and_style():
    items = _items()
    assert len(items) >= 40
    assert not corpus_lines.short_classes(items, CLASSES)
    assert not corpus_lines.repeated(items, "nlp_corpus.jsonl", "typed_corpus.jsonl", "phrase_corpus.jsonl",
                                     "story_corpus.jsonl", "scene_corpus.jsonl")
    styles = [m["style"] for it in items for m in it["expect"]["motions"] if m["style"]]
    assert {s: styles.count(s) for s in STYLES if styles.count(s) < 2} == {}


def test_every_manner_parses_as_expected(capsys, tmp_path):
    path = corpus_lines.FOLDER / NAME
    code = main(["batch", str(path), "--check", "--out", str(tmp_path), "--parse-only"])
    out = capsys.readouterr().out
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert code == 0 and summary["passed"] == summary["total"] == len(_items()), out


def test_the_style_is_in_the_json_only_when_the_text_gives_one():
    plain = nlp.analyze("太郎は歩く。").to_dict()["motions"][0]
    styled = nlp.analyze("太郎はとても疲れて歩く。").to_dict()["motions"][0]
    assert "style" not in plain and "intensity" not in plain
    assert (styled["style"], styled["intensity"], styled["manner"]) == ("tired", 1.4, "疲れて")


def test_a_speed_word_keeps_its_speed_and_gives_no_style():
    slow = nlp.analyze("太郎はゆっくり歩く。").motions[0]
    hurried = nlp.analyze("太郎は急いで歩く。").motions[0]
    assert (slow.speed, slow.style) == (0.6, None)
    assert (hurried.speed, hurried.style) == (1.5, "hurried")
