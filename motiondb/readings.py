"""Katakana readings of verbs and nouns, and nearest-reading suggestions.

A reading is the word's pronunciation in katakana, as MeCab (fugashi) with
the UniDic-lite dictionary gives it: ``跳ぶ`` and ``飛ぶ`` → ``トブ``,
``ジャンプする`` → ``ジャンプスル``, ``とぶ`` → ``トブ``. Words written in kana
only are converted directly (hiragana → katakana) without the analyser, so a
kana spelling always meets the word it spells. Input is NFKC-normalised first
(half-width katakana, full-width letters).

The first morpheme is read in its dictionary form when it is written in that
form (``箱`` → ``ハコ``, not the compound form ``バコ``); later morphemes as
written (``歩き出す`` → ``アルキダス``).

:func:`romaji` writes a reading in Latin letters (Hepburn: ``オドル`` → ``odoru``,
``ジャンプスル`` → ``janpusuru``), for figures drawn without a Japanese font.
"""
from __future__ import annotations

import difflib
import re
import unicodedata
from functools import lru_cache

_KANA_ONLY = re.compile(r"^[\u3041-\u3096\u30a1-\u30fa\u30fc\u30fd\u30fe\u309d\u309e]+$")


def normalize(word: str) -> str:
    """NFKC form without surrounding white space (how lemmas are stored and compared)."""
    return unicodedata.normalize("NFKC", word).strip()


def to_katakana(text: str) -> str:
    """Hiragana → katakana; everything else unchanged."""
    return "".join(chr(ord(c) + 0x60) if "\u3041" <= c <= "\u3096" or c in "\u309d\u309e" else c for c in text)


@lru_cache(maxsize=1)
def _tagger():
    import fugashi  # imported lazily: reading a clip needs no analyser

    return fugashi.Tagger()


def _usable(kana) -> bool:
    return bool(kana) and kana != "*"


@lru_cache(maxsize=4096)
def reading(word: str) -> str:
    """The katakana reading of ``word`` (see the module docstring); ``""`` for an empty word."""
    w = normalize(word)
    if not w:
        return ""
    if _KANA_ONLY.match(w):
        return to_katakana(w)
    parts = []
    for k, tok in enumerate(_tagger()(w)):
        f = tok.feature
        kana = None
        if k == 0 and getattr(f, "orthBase", None) == tok.surface and _usable(getattr(f, "kanaBase", None)):
            kana = f.kanaBase
        elif _usable(getattr(f, "kana", None)):
            kana = f.kana
        parts.append(kana if kana else to_katakana(tok.surface))
    return "".join(parts)


@lru_cache(maxsize=4096)
def word_key(word: str) -> tuple[str, ...]:
    """The UniDic lemmas of ``word``'s morphemes: one key for every spelling of one word
    (後ずさりする, 後退りする and あとずさりする → ``("後退り", "為る")``), different keys for
    homophones that are other words (吹く ``("吹く",)``, 拭く ``("拭く",)``)."""
    w = normalize(word)
    return tuple((tok.feature.lemma or tok.surface).split("-", 1)[0] for tok in _tagger()(w)) if w else ()


def same_word(a: str, b: str) -> bool:
    """Whether ``a`` and ``b`` spell one word: the same reading and UniDic lemmas
    (:func:`word_key`), and the kanji of one among the kanji of the other — a
    spelling writes more or less of the word in kana (後ずさり / 後退り, うなずく /
    頷く), while a different kanji is another word UniDic files under one lemma
    (撮る and 取る are both 取る, 閉める and 締める both 締める)."""
    a, b = normalize(a), normalize(b)
    if a == b:
        return True
    if reading(a) != reading(b) or word_key(a) != word_key(b):
        return False
    ka, kb = _kanji(a), _kanji(b)
    return ka <= kb or kb <= ka


def _kanji(word: str) -> set[str]:
    return {ch for ch in word if "\u4e00" <= ch <= "\u9fff" or ch == "\u3005"}


def nearest(word: str, candidates: dict[str, str], n: int = 5, cutoff: float = 0.5) -> list[str]:
    """The keys of ``candidates`` (word → reading) whose readings are closest to ``word``'s.

    Similarity is :class:`difflib.SequenceMatcher`'s ratio on katakana readings
    (the surface spellings break ties: ``max`` of both ratios); at most ``n``
    words with a ratio of at least ``cutoff``, best first, ties by reading then word.
    """
    r = reading(word)
    w = normalize(word)
    scored = []
    by_reading = difflib.SequenceMatcher(None, r)  # the word on the first side, each candidate on the second
    by_word = difflib.SequenceMatcher(None, w)
    for cand, cand_reading in candidates.items():
        # a ratio whose upper bound (quick_ratio) is under the cutoff cannot be the score of a kept word: the
        # score is the larger ratio, and a kept one's is at least the cutoff (the same words and scores)
        score = _ratio(by_reading, cand_reading, cutoff) if r and cand_reading else 0.0
        score = max(score, _ratio(by_word, cand, cutoff))
        if score >= cutoff:
            scored.append((-score, cand_reading, cand))
    scored.sort()
    return [c for _, _, c in scored[:n]]


def _ratio(sm: difflib.SequenceMatcher, b: str, cutoff: float) -> float:
    """``sm``'s ratio of its first string against ``b``, or 0 when even its upper bounds are under ``cutoff``
    (as :func:`difflib.get_close_matches` skips them)."""
    sm.set_seq2(b)
    if sm.real_quick_ratio() < cutoff or sm.quick_ratio() < cutoff:
        return 0.0
    return sm.ratio()


_GOJUON = ("a i u e o ka ki ku ke ko sa shi su se so ta chi tsu te to na ni nu ne no "
           "ha hi fu he ho ma mi mu me mo ya yu yo ra ri ru re ro wa wi we wo n "
           "ga gi gu ge go za ji zu ze zo da ji zu de do ba bi bu be bo pa pi pu pe po vu").split()
_KANA = ("アイウエオカキクケコサシスセソタチツテトナニヌネノハヒフヘホマミムメモヤユヨラリルレロワヰヱヲン"
         "ガギグゲゴザジズゼゾダヂヅデドバビブベボパピプペポヴ")
_ROMAJI = dict(zip(_KANA, _GOJUON))
_ROMAJI.update({"ァ": "a", "ィ": "i", "ゥ": "u", "ェ": "e", "ォ": "o", "ャ": "ya", "ュ": "yu", "ョ": "yo", "ヮ": "wa"})
_SMALL_Y = {"ャ": "a", "ュ": "u", "ョ": "o"}


def romaji(text: str) -> str:
    """``text``'s kana in Latin letters (Hepburn; katakana or hiragana), anything else kept:
    ``キャッチスル`` → ``kyatchisuru``, ``シャ`` → ``sha``; ``ー`` repeats the vowel before it (``ポーズ`` → ``poozu``)."""
    kana = to_katakana(normalize(text))
    out: list[str] = []
    i = 0
    double = False
    while i < len(kana):
        c = kana[i]
        nxt = kana[i + 1] if i + 1 < len(kana) else ""
        if c == "ッ":
            double = True
            i += 1
            continue
        if c == "ー":
            out.append(out[-1][-1] if out and out[-1][-1] in "aeiou" else "-")
            i += 1
            continue
        syl = _ROMAJI.get(c, c)
        if nxt in _SMALL_Y and c in _ROMAJI and syl.endswith("i") and len(syl) > 1:  # キャ kya, シャ sha, ジャ ja
            stem = syl[:-1]
            syl = stem + ("" if stem in ("sh", "ch", "j") else "y") + _SMALL_Y[nxt]
            i += 1
        if double and syl[:1].isalpha():
            syl = ("t" if syl.startswith("ch") else syl[0]) + syl
        double = False
        out.append(syl)
        i += 1
    return "".join(out)
