"""The fugashi Tagger (UniDic) and the :class:`types.Token` it gives, for every module that tags text."""
from __future__ import annotations

from functools import lru_cache

from .types import Token

_TAGGER = None


def tagger():
    """The process-wide fugashi Tagger, created on first use (a few ms)."""
    global _TAGGER
    if _TAGGER is None:
        import fugashi  # imported lazily: `text2anim --help` need not pay for it

        _TAGGER = fugashi.Tagger()
    return _TAGGER


def tag(line: str, offset: int) -> list[Token]:
    """The tokens of ``line``, their offsets counted from ``offset``."""
    out = []
    pos = 0
    for word in tagger()(line):
        surface = word.surface
        found = line.find(surface, pos)
        start = found if found >= 0 else pos
        pos = start + len(surface)
        f = _read(surface, word.feature_raw)
        out.append(Token(f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8], offset + start, offset + pos, None,
                         f[9]))
    return out


@lru_cache(maxsize=8192)
def _read(surface: str, raw: str) -> tuple[str, ...]:
    """A word's :class:`Token` fields but its offsets and value (surface, pos1-3, ctype, cform, lemma, orth,
    kana, kana_form) from its feature string (:func:`make_token` reads them), kept: most words of a text
    (particles, the common verbs) recur in every text."""
    t = make_token(surface, raw.split(",", _KANA_BASE + 1), 0, 0)
    return t.surface, t.pos1, t.pos2, t.pos3, t.ctype, t.cform, t.lemma, t.orth, t.kana, t.kana_form


#: Where UniDic's features sit in a word's feature string (fugashi's UnidicFeatures29 names them).
_POS1, _POS2, _POS3, _CTYPE, _CFORM, _LEMMA, _ORTH_BASE, _KANA, _KANA_BASE = 0, 1, 2, 4, 5, 7, 10, 17, 18


def features(word) -> list[str]:
    """The features of a tagged ``word`` up to its base form's reading: its feature string cut at
    the commas (fugashi's ``word.feature`` builds all 29 fields, a third of the time the analysis
    spends tagging; the fields read here never hold a comma, the later accent fields may).  An
    unknown word has only its six part-of-speech fields."""
    return word.feature_raw.split(",", _KANA_BASE + 1)


def make_token(surface: str, f: list[str], start: int, end: int) -> Token:
    """A token of ``surface`` with the UniDic features ``f`` (:func:`features`; a lemma's English
    gloss dropped)."""
    known = len(f) > _KANA_BASE
    lemma = f[_LEMMA] if known and f[_LEMMA] != "*" else surface
    if "-" in lemma and not lemma.startswith("-"):
        lemma = lemma.split("-", 1)[0]  # ボール-ball, 引く-他動詞
    kana = f[_KANA] if known and f[_KANA] != "*" else ""
    kana_base = f[_KANA_BASE] if known and f[_KANA_BASE] != "*" else ""
    return Token(surface, f[_POS1], f[_POS2], f[_POS3], f[_CTYPE], f[_CFORM], lemma,
                 f[_ORTH_BASE] if known and f[_ORTH_BASE] != "*" else surface, kana_base or kana,
                 start, end, None, kana)


def as_verb(tok: Token) -> Token | None:
    """``tok`` read as the 連用形 of a verb (跳び, 座り: UniDic tags them nouns in some places), or ``None``:
    ``跳びます`` shows the verb."""
    words = tagger()(tok.surface + "ます")
    if len(words) != 2 or words[0].surface != tok.surface:
        return None
    made = make_token(tok.surface, features(words[0]), tok.start, tok.end)
    return made if made.pos1 == "動詞" and made.cform.startswith("連用形") else None


def katakana(s: str) -> str:
    """``s`` with its hiragana written in katakana (はると -> ハルト): the form of UniDic's readings."""
    return "".join(chr(ord(ch) + 0x60) if "\u3041" <= ch <= "\u3096" else ch for ch in s)


def is_hiragana(s: str) -> bool:
    """Is every character of ``s`` hiragana (one character or a word)?"""
    return all("\u3041" <= ch <= "\u309f" for ch in s)
