"""Numbers: merge digit runs and kanji numerals into one token with a value.

UniDic splits ``0.5`` into 0 / . / 5 (the dot tagged as a sentence end) and
十五 into 十 / 五, and leaves Arabic digits without a lemma.  Merging happens
before sentences are split, so a decimal point never ends a sentence.
"""
from __future__ import annotations

import math
from dataclasses import replace

from .types import Token

_KANJI_DIGITS = {"〇": 0, "零": 0, "一": 1, "二": 2, "三": 3, "四": 4, "五": 5,
                 "六": 6, "七": 7, "八": 8, "九": 9, "壱": 1, "弐": 2, "参": 3}
_KANJI_UNITS = {"十": 10, "百": 100, "千": 1000}
_KANJI_BIG = {"万": 10_000, "億": 100_000_000}


def kanji_to_int(text: str) -> int | None:
    """Value of a kanji numeral (三, 十五, 二百三, 一万二千); ``None`` if not one."""
    if not text:
        return None
    total = section = digit = 0
    seen_digit = False
    for ch in text:
        if ch in _KANJI_DIGITS:
            digit = digit * 10 + _KANJI_DIGITS[ch]  # 二〇 style positional digits
            seen_digit = True
        elif ch in _KANJI_UNITS:
            section += (digit if seen_digit else 1) * _KANJI_UNITS[ch]
            digit, seen_digit = 0, False
        elif ch in _KANJI_BIG:
            section += digit
            total += (section or 1) * _KANJI_BIG[ch]
            section = digit = 0
            seen_digit = False
        else:
            return None
    return total + section + digit


def number_value(surface: str) -> float | None:
    """Value of an Arabic (after NFKC) or kanji numeral, else ``None``; a numeral beyond a float's range
    (309 digits of 九) is infinity, which the limits refuse with a reason (it raised OverflowError)."""
    if surface.isascii():
        try:
            return float(surface)
        except ValueError:
            return None
    value = kanji_to_int(surface)
    if value is None:
        return None
    try:
        return float(value)
    except OverflowError:
        return math.inf


def _is_digits(tok: Token) -> bool:
    return tok.surface.isascii() and tok.surface.isdigit()


def _is_numeral(tok: Token) -> bool:
    return tok.pos2 == "数詞" or _is_digits(tok)


def merge_numbers(tokens: list[Token]) -> list[Token]:
    """Join ``digits . digits`` and runs of kanji numerals into single tokens."""
    if not any(t.pos2 == "数詞" or t.surface[:1].isdigit() for t in tokens):
        return tokens  # most texts count nothing
    out: list[Token] = []
    i, n = 0, len(tokens)
    while i < n:
        tok = tokens[i]
        if not _is_numeral(tok):
            out.append(tok)
            i += 1
            continue
        j = i + 1
        if _is_digits(tok):
            if (j + 1 < n and tokens[j].surface == "." and _is_digits(tokens[j + 1])
                    and tokens[j].start == tok.end and tokens[j + 1].start == tokens[j].end):
                j += 2
        else:
            while j < n and tokens[j].pos2 == "数詞" and not _is_digits(tokens[j]) \
                    and tokens[j].start == tokens[j - 1].end:
                j += 1
        out.append(_merged(tokens[i:j]))
        i = j
    return out


def _merged(run: list[Token]) -> Token:
    surface = "".join(t.surface for t in run)
    value = number_value(surface)
    first = run[0]
    return replace(first, surface=surface, pos1="名詞", pos2="数詞", lemma=surface,
                   orth=surface, kana=first.kana or "", end=run[-1].end, value=value)
