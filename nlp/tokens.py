"""Tokens: NFKC normalisation with an offset map, the cached fugashi Tagger,
re-tagging of list-item 連用形, and number merging.
"""
from __future__ import annotations

import unicodedata
from functools import lru_cache

from .numbers import merge_numbers
from .types import Token

_TAGGER = None

#: Half-width voiced sound marks: NFKC composes them with the kana before.
_HALFWIDTH_MARKS = {"\uff9e", "\uff9f"}


def tagger():
    """The process-wide fugashi Tagger, created on first use (a few ms)."""
    global _TAGGER
    if _TAGGER is None:
        import fugashi  # imported lazily: `text2anim --help` need not pay for it

        _TAGGER = fugashi.Tagger()
    return _TAGGER


class OffsetMap:
    """Maps ranges of the normalised text back to the original text."""

    __slots__ = ("starts", "ends", "length")

    def __init__(self, starts: list[int], ends: list[int], length: int):
        self.starts = starts  # original start of the piece each character came from
        self.ends = ends  # original end of that piece
        self.length = length

    def span(self, a: int, b: int) -> tuple[int, int]:
        """Original ``(start, end)`` of normalised ``[a, b)``."""
        if a >= len(self.starts):
            return (self.length, self.length)
        start = self.starts[a]
        return (start, self.ends[b - 1]) if b > a else (start, start)


def normalize(text: str) -> tuple[str, OffsetMap]:
    """NFKC-normalise ``text``; return it with the map back to ``text``.

    Each base character is normalised together with the combining marks after
    it, so every normalised range maps back to whole original characters
    (ﾀﾞ -> ダ, １０ -> 10, ㌢ -> センチ).  Control characters, surrogates and
    private-use characters become spaces (the tagger is a C library; a NUL
    would cut the string), CR a newline.
    """
    if text.isascii() or unicodedata.is_normalized("NFKC", text):
        n = len(text)
        return _sanitize(text), OffsetMap(list(range(n)), list(range(1, n + 1)), n)
    parts: list[str] = []
    starts: list[int] = []
    ends: list[int] = []
    seg_start = 0
    for i in range(1, len(text) + 1):
        if i < len(text) and (unicodedata.combining(text[i]) or text[i] in _HALFWIDTH_MARKS):
            continue
        piece = unicodedata.normalize("NFKC", text[seg_start:i])
        parts.append(piece)
        starts.extend([seg_start] * len(piece))
        ends.extend([i] * len(piece))
        seg_start = i
    return _sanitize("".join(parts)), OffsetMap(starts, ends, len(text))


def _sanitize(norm: str) -> str:
    if norm.isprintable():
        return norm
    out = []
    for ch in norm:
        if ch in "\n\r":
            out.append("\n")
        elif ch.isprintable():
            out.append(ch)
        elif unicodedata.category(ch) in ("Zs", "Zl", "Zp", "Cc", "Cf", "Cs", "Co", "Cn"):
            out.append(" ")
        else:
            out.append(ch)
    return "".join(out)


def tokenize(norm: str) -> list[Token]:
    """Tag ``norm`` line by line; newlines become sentence-end tokens."""
    tokens: list[Token] = []
    pos = 0
    for line in norm.split("\n"):
        if line.strip():
            tokens.extend(_tag_line(line, pos))
        end = pos + len(line)
        if end < len(norm):
            tokens.append(Token("\n", "補助記号", "句点", "*", "*", "*", "\n", "\n", "", end, end + 1))
        pos = end + 1
    return merge_numbers(_retag_list_items(tokens))


def _tag_line(line: str, offset: int) -> list[Token]:
    out = []
    pos = 0
    for word in tagger()(line):
        surface = word.surface
        found = line.find(surface, pos)
        start = found if found >= 0 else pos
        pos = start + len(surface)
        out.append(_make_token(surface, word.feature, offset + start, offset + pos))
    return out


def _make_token(surface: str, f, start: int, end: int) -> Token:
    lemma = f.lemma or surface
    if "-" in lemma and not lemma.startswith("-"):
        lemma = lemma.split("-", 1)[0]  # ボール-ball, 引く-他動詞
    return Token(surface, f.pos1 or "", f.pos2 or "", f.pos3 or "", f.cType or "*",
                 f.cForm or "*", lemma, f.orthBase or surface, f.kanaBase or f.kana or "",
                 start, end, None, f.kana or "")


def _retag_list_items(tokens: list[Token]) -> list[Token]:
    """走り、跳び、転ぶ: UniDic tags 跳び as a noun; ``跳びます`` shows the verb."""
    out = list(tokens)
    for i, tok in enumerate(tokens[:-1]):
        nxt = tokens[i + 1]
        if (tok.pos1 == "名詞" and tok.pos2 == "普通名詞" and nxt.pos2 == "読点"
                and _ends_in_hiragana(tok.surface)):
            verb = _as_verb(tok)
            if verb is not None:
                out[i] = verb
    return out


def _ends_in_hiragana(s: str) -> bool:
    return "\u3041" <= s[-1] <= "\u309f"


def _as_verb(tok: Token) -> Token | None:
    words = tagger()(tok.surface + "ます")
    if len(words) != 2 or words[0].surface != tok.surface:
        return None
    f = words[0].feature
    if f.pos1 != "動詞" or not (f.cForm or "").startswith("連用形"):
        return None
    return _make_token(tok.surface, f, tok.start, tok.end)


@lru_cache(maxsize=4096)
def is_name(surface: str) -> bool:
    """Can ``surface`` be a person's name?  UniDic tags 太郎 as a common noun
    in some contexts (同時に太郎は); with an honorific after it, a word that
    can be a given name is tagged 人名, a common noun (ボール, 公園) is not."""
    words = tagger()(surface + "さん")
    return len(words) == 2 and words[0].surface == surface and words[0].feature.pos3 == "人名"
