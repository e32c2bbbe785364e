"""Mimetics: a repeating one repeats the motion, a manner one says how it is done.

ぱちぱちと拍手する claps again and again (``repeat`` 3, as 何度も, unless the text counts:
ぴょんぴょん5回跳ぶ hops 5 times); よろよろ歩く is a walk whose ``manner`` is よろよろ (recorded
for the synthesis to read; nothing else changes). Both kinds are recorded as the manner. A mimetic
+ する is a verb (きょろきょろする, しょんぼりする), or the action ``mimetics.json`` names for it
(うろうろする walks). The words are in ``mimetics.json``; docs/language.md §7.9 has the rules.
"""
from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

from .bunsetsu import Phrase
from .lexicon import REPEAT_WORDS
from .types import Token

DATA = Path(__file__).with_name("mimetics.json")

#: Repeats of a repeating mimetic: as many as 何度も asks for.
REPEATS = REPEAT_WORDS["何度も"]


@lru_cache(maxsize=1)
def _data() -> tuple[frozenset[str], frozenset[str], dict[str, str]]:
    data = json.loads(DATA.read_text(encoding="utf-8"))
    return frozenset(data["repeat"]), frozenset(data["manner"]), dict(data["verbs"])


def _hiragana(text: str) -> str:
    return "".join(chr(ord(c) - 0x60) if "\u30a1" <= c <= "\u30f6" else c for c in text)


def word(text: str) -> str | None:
    """The mimetic ``text`` is (パチパチと -> ぱちぱち, くるっと -> くるっと), or None."""
    repeat, manner, _ = _data()
    w = _hiragana(text)
    for cand in (w, w.removesuffix("と")):
        if cand in repeat or cand in manner:
            return cand
    return None


def repeats(mimetic: str) -> bool:
    """Does ``mimetic`` say the motion is done again and again?"""
    return mimetic in _data()[0]


def as_verb(adverb: Token) -> tuple[str, str, str] | None:
    """``(verb, written, mimetic)`` of ``adverb`` + する when the adverb is a mimetic of motion:
    きょろきょろ -> (きょろきょろする, きょろきょろする, きょろきょろ), うろうろ -> (歩く, うろうろする,
    うろうろ); None for any other adverb (しばらくして, そうする)."""
    if adverb.pos1 != "副詞":
        return None
    mimetic = word(adverb.surface)
    if mimetic is None:
        return None
    written = adverb.surface + "する"
    return _data()[2].get(mimetic, written), written, mimetic


def apply(found: list[Phrase], phrases: list[Phrase]) -> None:
    """Record each mimetic phrase of ``found`` on the motion it modifies: its manner, and for a
    repeating one ``REPEATS`` repeats unless a count (N回, 何度も) modifies the same motion;
    ``phrases`` are the text's."""
    if not found:
        return
    counted = {ph.head for ph in phrases if ph.role == "repeat"}
    for ph in found:
        if ph.head is None:
            continue
        pred = phrases[ph.head].pred  # phrase indices are list positions
        mimetic = word(ph.key)
        if pred is None or not pred.motion or mimetic is None:
            continue
        pred.manner = mimetic
        if repeats(mimetic) and ph.head not in counted:
            pred.repeat = REPEATS
