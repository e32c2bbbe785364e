"""Given names written in hiragana read as names (docs/language.md §9.1).

Children's and friends' names are often written in hiragana, and UniDic reads most of them as
something else: はると as the auxiliary はる + と, ゆうとくん as ゆう + と + 来る, そうた as そう + た, あかり
as 明かり, さくら as 桜.  A name of :data:`lexicon.KANA_NAMES` that stands at a word boundary (the start
of a line, after anything but hiragana, or after a particle) and is followed by an honorific (くん, ちゃん, さん, ...), a
particle or punctuation becomes one token tagged a given name (``固有名詞 / 人名``), and a くん that
UniDic read as 来る becomes the honorific.  A name UniDic read as one common noun (あかり, さくら) is read
as a name only before an honorific or the particle of an actor (は, が, も): さくらを見た is still the
cherry blossom.  Every reading is said in ``notes``.
"""
from __future__ import annotations

import re
from dataclasses import replace
from functools import lru_cache

from .lexicon import HONORIFICS, KANA_NAMES
from .tagging import is_hiragana, katakana
from .types import Token

#: What may follow a name: an honorific, a particle or punctuation.
_AFTER = ("さん", "ちゃん", "くん", "君", "様", "さま", "は", "が", "も", "の", "と", "に", "を", "へ", "で", "、", "。",
          "!", "?", ":", ")", "」", " ")
#: After a name UniDic read as one common noun: only an honorific or an actor's particle.
_AFTER_NOUN = ("さん", "ちゃん", "くん", "君", "様", "さま", "は", "が", "も")


@lru_cache(maxsize=1)
def _pattern() -> re.Pattern[str]:
    names = sorted(KANA_NAMES, key=len, reverse=True)
    return re.compile("|".join(map(re.escape, names)))


def may_apply(line: str) -> bool:
    """Does ``line`` contain a name of the list at all (cheap: most lines do not)?"""
    return _pattern().search(line) is not None


def read_names(line: str, offset: int, tokens: list[Token], notes: list[str]) -> list[Token]:
    """The tokens of ``line`` (starting at ``offset`` in the text) with hiragana names read as names."""
    starts = {t.start: k for k, t in enumerate(tokens)}
    ends = {t.end: k for k, t in enumerate(tokens)}
    out = list(tokens)
    merged: list[tuple[int, int, Token]] = []
    for m in _pattern().finditer(line):
        a, b = offset + m.start(), offset + m.end()
        if a not in starts or b not in ends or not _opens_word(line, m.start(), out, starts[a]):
            continue
        rest = line[m.end():]
        first, last = starts[a], ends[b]
        one_noun = first == last and out[first].pos1 == "名詞"
        if (one_noun and out[first].pos3 == "人名") or not (rest == "" or rest.startswith(
                _AFTER_NOUN if one_noun else _AFTER)):
            continue
        name = m.group()
        merged.append((first, last, Token(name, "名詞", "固有名詞", "人名", "*", "*", name, name,
                                          katakana(name), a, b, kana_form=katakana(name))))
    for first, last, tok in reversed(merged):
        out[first:last + 1] = [tok]
        nxt = first + 1
        if nxt < len(out) and out[nxt].surface in HONORIFICS and out[nxt].pos1 != "接尾辞":
            out[nxt] = replace(out[nxt], pos1="接尾辞", pos2="名詞的", pos3="一般", ctype="*", cform="*",
                               lemma=out[nxt].surface, orth=out[nxt].surface)  # ゆうとくん: くん is no 来る
            notes.append(f"read {tok.surface}{out[nxt].surface} as a name and its honorific")
        else:
            notes.append(f"read {tok.surface} as a name")
    return out


def _opens_word(line: str, i: int, tokens: list[Token], k: int) -> bool:
    """Does a word start at ``line[i]`` (token ``k``): the line's start, after anything but hiragana, or
    after a particle (そこではるとが: で)?"""
    return i == 0 or not is_hiragana(line[i - 1]) or (k > 0 and tokens[k - 1].pos1 == "助詞")
