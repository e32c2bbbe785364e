"""Manner words: how a motion is done, read as a style of :data:`core.styles.STYLES` with an intensity.

Four shapes (docs/language.md §2.1; the words are in ``manners.json``):

- one phrase: an adverb or adverbial (大股で, 颯爽と, 小さく, 力なく) or a mimetic (しょんぼり, ドスドス);
- two phrases, the second a likeness or manner ending (嬉し + そうに, 疲れた + 様子で, 踊る + ように,
  元気 + よく): both are the manner word, neither a motion;
- an emotional て-form right before its motion, no comma between (怒って歩く, 疲れて座る): no motion
  of its own (怒って、部屋を出る keeps 怒る);
- a posture idiom in て-form that stays a motion (胸を張って歩く: chest_out, then the walk) and gives its
  style to the motion after it.

A degree word right before a manner word scales its intensity (とても疲れて: 1.4 times), within
:data:`core.styles.INTENSITY_RANGE`. The word nearest the verb wins when several modify one motion.
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from text2anim.core.styles import INTENSITY_RANGE, STYLES

from . import mimetics
from .bunsetsu import Phrase

DATA = Path(__file__).with_name("manners.json")


@dataclass(frozen=True, slots=True)
class Manner:
    """A manner word as written (a mimetic in hiragana), its style and intensity."""

    word: str
    style: str
    intensity: float


@lru_cache(maxsize=1)
def _data() -> dict[str, dict]:
    data = json.loads(DATA.read_text(encoding="utf-8"))
    for table in ("words", "pairs", "te", "passes"):
        unknown = {style for style, _ in data[table].values()} - set(STYLES)
        assert not unknown, f"manners.json {table}: unknown styles {unknown}"
    return data


def _entry(table: str, word: str, intensity: float = 1.0) -> Manner | None:
    found = _data()[table].get(word)
    if found is None:
        return None
    low, high = INTENSITY_RANGE
    return Manner(word, found[0], round(min(high, max(low, found[1] * intensity)), 2))


def find(phrases: list[Phrase]) -> dict[int, Manner | None]:
    """The phrases of ``phrases`` that are manner words, before any is read as a predicate: phrase index
    -> its manner (on the phrase nearest the verb), or None for the other phrases of the word (the stem of
    嬉しそうに, a degree word)."""
    out: dict[int, Manner | None] = {}
    for i, ph in enumerate(phrases):
        if i in out:
            continue
        nxt = phrases[i + 1] if i + 1 < len(phrases) else None
        joined = nxt is not None and nxt.sentence == ph.sentence and not ph.has_comma()
        table, key, last = "words", ph.key, i
        if joined and nxt is not None and ph.key + nxt.key in _data()["pairs"]:
            table, key, last = "pairs", ph.key + nxt.key, i + 1
        elif joined and ph.key in _data()["te"]:
            table = "te"
        else:
            spelled = _spelling(ph.key)
            if spelled is None:
                continue
            key = spelled
        degree = _data()["degree"].get(phrases[i - 1].key) if i and phrases[i - 1].sentence == ph.sentence else None
        if degree is not None:
            out[i - 1] = None
        out.update({k: None for k in range(i, last)})
        out[last] = _entry(table, key, degree or 1.0)
    return out


def _spelling(key: str) -> str | None:
    """How ``key`` is listed in ``words``: as written, as a mimetic (ドスドスと -> どすどす), or without
    a following と (おずおずと -> おずおず); None when it is not listed."""
    words = _data()["words"]
    for cand in (key, mimetics.word(key), key.removesuffix("と")):
        if cand in words:
            return cand
    return None


#: The second phrase of a likeness the dictionary splits off (不思議 + そうに, 夢見る + ように).
_LIKENESS = ("そうに", "ように", "げに", "様子で")


def unread(phrases: list[Phrase], i: int) -> str | None:
    """The manner word phrase ``i`` is, as written, when it has the shape of one but no list reads it
    (丁寧に, にこやかに, 不思議そうに, 懐かしく): the motion keeps it as a manner of no style, which the
    animation says it does not show, rather than dropping it in silence. None for any other phrase."""
    ph = phrases[i]
    toks = [t for t in ph.tokens if t.pos1 != "補助記号"]
    if ph.role or not toks:
        return None
    prev = phrases[i - 1] if i else None
    if ph.key in _LIKENESS and prev is not None and prev.sentence == ph.sentence and not prev.role \
            and not prev.has_comma() and prev.pred is None:
        return prev.key + ph.key
    if len(toks) >= 2 and toks[-1].pos1 == "助動詞" and toks[-1].cform == "連用形-ニ" \
            and all(t.pos1 == "形状詞" for t in toks[:-1]) and toks[0].pos2 == "一般":
        return ph.key  # 丁寧に, にこやかに
    if len(toks) == 1 and toks[0].pos1 == "形容詞" and toks[0].pos2 == "一般" and toks[0].cform.startswith("連用形") \
            and ph.key.endswith("く") and ph.key not in _data()["degree"]:
        return ph.key  # 懐かしく
    return None


def passed_on(written: str) -> Manner | None:
    """The style a posture idiom in て-form gives the motion after it (胸を張る: proud), or None."""
    return _entry("passes", written)
