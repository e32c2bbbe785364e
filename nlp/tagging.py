"""The fugashi Tagger (UniDic) and the :class:`types.Token` it gives, for every module that tags text."""
from __future__ import annotations

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
        out.append(make_token(surface, word.feature, offset + start, offset + pos))
    return out


def make_token(surface: str, f, start: int, end: int) -> Token:
    """A token of ``surface`` with the UniDic features ``f`` (a lemma's English gloss dropped)."""
    lemma = f.lemma or surface
    if "-" in lemma and not lemma.startswith("-"):
        lemma = lemma.split("-", 1)[0]  # ボール-ball, 引く-他動詞
    return Token(surface, f.pos1 or "", f.pos2 or "", f.pos3 or "", f.cType or "*",
                 f.cForm or "*", lemma, f.orthBase or surface, f.kanaBase or f.kana or "",
                 start, end, None, f.kana or "")


def as_verb(tok: Token) -> Token | None:
    """``tok`` read as the 連用形 of a verb (跳び, 座り: UniDic tags them nouns in some places), or ``None``:
    ``跳びます`` shows the verb."""
    words = tagger()(tok.surface + "ます")
    if len(words) != 2 or words[0].surface != tok.surface:
        return None
    f = words[0].feature
    if f.pos1 != "動詞" or not (f.cForm or "").startswith("連用形"):
        return None
    return make_token(tok.surface, f, tok.start, tok.end)
