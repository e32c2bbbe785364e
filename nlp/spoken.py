"""Spoken and terse writing read as the action it asks for (docs/language.md §9).

Run on the tokens of the text before chunking (after :mod:`keigo`), the offsets kept:

- a word drawn out with ー or a small vowel (ゆーっくり, そーっと, 手ぇ) is read as the word UniDic
  gives as its lemma, so the speed words and body parts find it (the verb endings 〜はる, 〜とる,
  〜てん, 〜ちゃう and ねん are auxiliaries and particles UniDic already knows);
- はよ (Kansai 早く, two particles to UniDic) before a verb is a manner adverb;
- chat's ガチで (seriously), which UniDic reads as the noun ガチ + で and joins to the noun before it
  (先生ガチで怒ってた: no actor 先生), is tagged as まじで is: an adjectival word + で;
- a command without a verb ending: an action noun ending its sentence (ジャンプ！, はい、お辞儀！,
  ``3) お辞儀``) is the noun + する, and a verb's 連用形 there (走り！, 座りな, 走りや: the spoken
  and Kansai imperative) is the verb, when it is a bodily action (a library verb or near one in meaning, :func:`meaning.bodily`),
  so 注意！ or 成功！ stay exclamations.

Drawn-out verbs that UniDic cannot tag at all (おどろー) are read again by :mod:`spelling`.
"""
from __future__ import annotations

from dataclasses import replace

from .lexicon import CONNECTIVES, LIBRARY_VERBS
from .tagging import as_verb
from .types import Token

#: Marks that draw a word out: the long-vowel mark, wave dashes, small vowels.
DRAWL = "ー〜～ぁぃぅぇぉ"
_DRAWL = str.maketrans("", "", DRAWL)
_DRAWL_CHARS = frozenset(DRAWL)
#: A chat adverb UniDic tags as a noun; before で it is tagged as まじ is (形状詞).
CHAT_ADVERB = "ガチ"
#: Particles that soften a 連用形 command at the end of a sentence: 座りな, 走りや, 立ちよ.
SOFTENERS = frozenset("な や よ".split())


def may_apply(text: str, tokens: list[Token]) -> bool:
    """Could :func:`plain` change anything in ``tokens`` (of ``text``): is a word drawn out, or does a
    noun end a sentence (or come before a particle that does)?"""
    if not _DRAWL_CHARS.isdisjoint(text) or CHAT_ADVERB + "で" in text:
        return True
    prev = None
    for t in tokens:
        if t.pos2 == "句点" and prev is not None and (prev.pos1 == "名詞" or prev.surface in SOFTENERS):
            return True
        prev = t
    return prev is not None and (prev.pos1 == "名詞" or prev.surface in SOFTENERS)


def plain(tokens: list[Token]) -> list[Token]:
    """``tokens`` with drawn-out words, はよ and verbless commands read as the module docstring says."""
    out: list[Token] = []
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        if tok.pos1 not in ("名詞", "副詞", "助詞"):  # the only tokens this pass reads again
            out.append(tok)
            i += 1
            continue
        if _hayo(tokens, i):
            out.append(replace(tok, surface="はよ", pos1="副詞", pos2="*", pos3="*", lemma="はよ", orth="はよ",
                               kana="ハヨ", kana_form="ハヨ", end=tokens[i + 1].end))
            i += 2
            continue
        if tok.surface == CHAT_ADVERB and i + 1 < len(tokens) and tokens[i + 1].surface == "で":
            out.append(replace(tok, pos1="形状詞", pos2="一般", pos3="*"))  # 先生ガチで怒ってた
            i += 1
            continue
        command = _command(tokens, i, out)
        if command is not None:
            if out and command.start == out[-1].start:
                out.pop()  # お辞儀！: the prefix is part of the command's verb
            out.append(command)
            if not _ends_sentence(tokens, i):  # 座りな: the particle that softens it
                i += 1
                out.append(replace(tokens[i], pos1="助詞", pos2="終助詞", pos3="*"))
        else:
            out.append(_undrawn(tok))
        i += 1
    return out


def _undrawn(tok: Token) -> Token:
    """ゆーっくり -> ゆっくり, 手ぇ -> 手: a drawn-out noun or adverb whose lemma is the word without the drawl."""
    if tok.pos1 not in ("名詞", "副詞") or tok.surface == tok.lemma:
        return tok
    bare = tok.surface.translate(_DRAWL)
    return replace(tok, surface=bare) if bare != tok.surface and bare in (tok.lemma, tok.orth) else tok


def _hayo(tokens: list[Token], i: int) -> bool:
    """は + よ opening a phrase before a verb or a 連用形: はよ走り！, はよ来て."""
    if i + 2 >= len(tokens) or tokens[i].surface != "は" or tokens[i + 1].surface != "よ":
        return False
    before = tokens[i - 1] if i else None
    after = tokens[i + 2]
    return (before is None or before.pos1 == "補助記号") and after.pos1 in ("動詞", "名詞")


def _command(tokens: list[Token], i: int, before: list[Token]) -> Token | None:
    """The verb of a command written without a verb ending at ``i`` (ジャンプ！, お辞儀, 走り！), or ``None``.

    ``before`` are the tokens already read; a prefix (お辞儀) is in the verb only when the library
    names the verb with it, as :func:`predicates.sahen_verb` does."""
    tok = tokens[i]
    softened = _softened(tokens, i)
    if tok.pos1 != "名詞" or tok.is_number or not (_ends_sentence(tokens, i) or softened):
        return None
    prefix = before[-1] if before and before[-1].pos1 == "接頭辞" else None
    head = before[:-1] if prefix is not None else before
    if head and not (_opens(head[-1]) or _after_connective(head)):
        return None  # 太郎のジャンプ。: a noun of the sentence, not a command
    if tok.pos3 == "サ変可能" and not softened:
        whole = (prefix.surface if prefix is not None else "") + tok.lemma + "する"
        if prefix is not None and whole in LIBRARY_VERBS:
            made = replace(tok, surface=prefix.surface + tok.surface, start=prefix.start, lemma=whole, orth=whole)
        else:
            made = replace(tok, lemma=tok.lemma + "する", orth=tok.lemma + "する")
        made = replace(made, ctype="サ行変格", kana=tok.kana + "スル", kana_form=tok.kana_form + "スル")
    elif prefix is None and "\u3041" <= tok.surface[-1] <= "\u309f":
        found = as_verb(tok)  # 走り！: the 連用形 UniDic tags a noun
        if found is None:
            return None
        made = found
    else:
        return None
    if not _bodily(made.lemma):
        return None
    return replace(made, pos1="動詞", pos2="一般", pos3="*", cform="命令形")


def _after_connective(before: list[Token]) -> bool:
    """The tokens before end with a connective (最後にお辞儀, そしてジャンプ！: ``lexicon.CONNECTIVES``)."""
    return any("".join(t.surface for t in before[-n:]) in CONNECTIVES for n in (1, 2, 3))


def _softened(tokens: list[Token], i: int) -> bool:
    """A softening particle (``SOFTENERS``) ends the sentence right after ``tokens[i]``: 座りな。"""
    return i + 1 < len(tokens) and tokens[i + 1].surface in SOFTENERS and _ends_sentence(tokens, i + 1)


def _opens(tok: Token) -> bool:
    """Can a command follow ``tok`` in its sentence: a mark (、・) -), a number (1.), はい, an adverb,
    the を of its object (ボールをキャッチ！)?  (Or a connective: :func:`_after_connective`.)"""
    return tok.pos1 in ("補助記号", "感動詞", "記号", "副詞") or tok.is_number or tok.surface == "を"


def _ends_sentence(tokens: list[Token], i: int) -> bool:
    """``tokens[i]`` is the last word of its sentence: an end mark (。！？ or a newline) or nothing follows."""
    nxt = tokens[i + 1] if i + 1 < len(tokens) else None
    return nxt is None or nxt.pos2 == "句点"


def _bodily(verb: str) -> bool:
    from . import meaning  # the vectors load on first use only

    return meaning.bodily(verb, LIBRARY_VERBS)
