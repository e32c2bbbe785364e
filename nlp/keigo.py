"""Keigo: honorific and humble forms read as the plain action (docs/language.md §9).

Run on the tokens of the text before chunking, it rewrites each form into tokens the rest of the
analyzer reads as it reads plain text, the offsets kept (the motion's span is what was written):

- お / ご + a verb's 連用形 + に + なる (お座りになる, お歩きになった), お + 連用形 + する / いたす
  (お持ちします, お待ちいたします): one verb token of that verb, conjugated as なる / する were;
  お越しになる, お見えになる, おいでになる are 来る (``lexicon.PREFIXED_HONORIFIC_VERBS``);
- お / ご + a サ変 noun + に + なる / する / いたす / ください (ご着席ください, ご案内します): one verb
  token of the noun + する (着席する: the honorific prefix is not part of the verb, unless the
  library names the verb with it, as お辞儀する);
- ご覧になる / ご覧ください: 見る;
- なさる and いたす after a noun or its を are する (散歩なさる, ダンスをなさいました);
- いらっしゃる is 来る, or いる after a て-form or で (歩いていらっしゃる, 先生でいらっしゃる);
  召し上がる is 飲む with a drink as its object (``lexicon.DRINKS``: お茶を召し上がる), else 食べる;
  おっしゃる is 言う (``lexicon.HONORIFIC_VERBS``).

The honorific passive (座られる, 散歩される) needs no rewrite: the verb is read with its auxiliary.
"""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

from .lexicon import DRINKS, HONORIFIC_VERBS, LIBRARY_VERBS, PREFIXED_HONORIFIC_VERBS
from .tagging import as_verb, tag
from .types import Token

_PREFIXES = frozenset(["お", "ご", "御"])
_LIGHT = frozenset(["為る", "致す"])  # する, いたす after お + 連用形 or a サ変 noun
_POLITE_LIGHT = frozenset(["為さる", "致す"])  # なさる, いたす: する after a noun or を
#: Lemmas whose presence makes a text worth the pass, and what the text must hold to have one of
#: them or a prefix (a fast test on the text first: most texts have none).
_TRIGGERS = frozenset(["為さる", "致す", "いらっしゃる", "召し上がる", "仰る", "御覧"])
_IN_TEXT = ("お", "ご", "御", "なさ", "為さ", "致", "いたさ", "いたし", "いたす", "いたせ", "いたそ", "いらっしゃ",
            "召", "めしあが", "覧")


def may_apply(text: str, tokens: list[Token]) -> bool:
    """Could :func:`plain` change anything in ``tokens`` (of ``text``)?"""
    for word in _IN_TEXT:  # a loop, not a regular expression: importing re costs a cold start 10 ms
        if word in text:
            break
    else:
        return False
    for t in tokens:
        if t.lemma in _TRIGGERS or (t.pos1 == "接頭辞" and t.surface in _PREFIXES):
            return True
    return False


def plain(tokens: list[Token]) -> list[Token]:
    """``tokens`` with every honorific or humble form rewritten as the plain verb (module docstring)."""
    out: list[Token] = []
    i = 0
    while i < len(tokens):
        took = _prefixed(tokens, i) or _goran(tokens, i)
        if took is not None:
            made, i = took
            out.extend(made)
            continue
        out.append(_relemma(tokens, i, out))
        i += 1
    return out


def _prefixed(tokens: list[Token], i: int) -> tuple[list[Token], int] | None:
    """お / ご + 連用形 or サ変 noun + に なる / する / いたす / ください: (new tokens, next index)."""
    pre = tokens[i]
    if pre.pos1 != "接頭辞" or pre.surface not in _PREFIXES or i + 2 >= len(tokens):
        return None
    word = tokens[i + 1]
    verb = word if word.pos1 == "動詞" and word.cform.startswith("連用形") else None
    if verb is None and word.pos1 == "名詞" and word.pos3 != "サ変可能":
        verb = as_verb(word)  # お座り, お休み: UniDic tags the 連用形 a noun here
    sahen = verb is None and word.pos1 == "名詞" and word.pos3 == "サ変可能"
    if not (verb or sahen) or (sahen and pre.surface + word.lemma + "する" in LIBRARY_VERBS):
        return None  # お辞儀する: the library's verb keeps its prefix
    if verb is not None:
        meant = PREFIXED_HONORIFIC_VERBS.get(verb.lemma)
        plain_verb = _dictionary_form(meant) if meant else verb
    else:
        plain_verb = replace(word, lemma=word.lemma + "する", orth=word.lemma + "する",
                             kana=word.kana + "スル", kana_form=word.kana_form + "スル")
    nxt = tokens[i + 2]
    if nxt.surface == "に" and i + 3 < len(tokens) and tokens[i + 3].lemma == "成る":
        return [_as(plain_verb, tokens[i:i + 4], tokens[i + 3])], i + 4
    if nxt.pos1 == "動詞" and nxt.lemma in _LIGHT:
        return [_as(plain_verb, tokens[i:i + 3], nxt)], i + 3
    if nxt.pos1 == "動詞" and nxt.lemma == "下さる" and sahen:
        return [_as(plain_verb, tokens[i:i + 2], _RENYOU_SAHEN), nxt], i + 3
    return None


def _goran(tokens: list[Token], i: int) -> tuple[list[Token], int] | None:
    """ご覧になる / ご覧ください: 見る."""
    tok = tokens[i]
    if tok.lemma != "御覧" or i + 1 >= len(tokens):
        return None
    see = _dictionary_form("見る")
    nxt = tokens[i + 1]
    if nxt.surface == "に" and i + 2 < len(tokens) and tokens[i + 2].lemma == "成る":
        return [_as(see, tokens[i:i + 3], tokens[i + 2])], i + 3
    if nxt.lemma == "下さる":
        return [_as(see, [tok], replace(see, cform="連用形-一般")), nxt], i + 2
    return None


#: The conjugation of する's 連用形, for ご + noun + ください (ご着席ください = 着席してください).
_RENYOU_SAHEN = Token("", "動詞", "非自立可能", "*", "サ行変格", "連用形-一般", "為る", "する", "スル", 0, 0)


def _as(verb: Token, covered: list[Token], form: Token) -> Token:
    """``verb``'s lemma, spelling and reading over the ``covered`` tokens, conjugated as ``form``."""
    return replace(verb, surface="".join(t.surface for t in covered), pos1="動詞", pos2="一般", pos3="*",
                   ctype=form.ctype, cform=form.cform, start=covered[0].start, end=covered[-1].end, honorific=True)


@lru_cache(maxsize=64)
def _dictionary_form(verb: str) -> Token:
    """The token of the plain ``verb`` (見る, 来る) in its dictionary form."""
    words = tag(verb, 0)
    assert words and words[0].pos1 == "動詞", verb  # the lexicon names plain verbs
    return words[0]


def _relemma(tokens: list[Token], i: int, before: list[Token]) -> Token:
    """なさる / いたす after a noun or を -> する; いらっしゃる, 召し上がる, おっしゃる -> the plain verb."""
    tok = tokens[i]
    if tok.pos1 != "動詞":
        return tok
    prev = before[-1] if before else None
    if tok.lemma in _POLITE_LIGHT and prev is not None and (prev.pos1 == "名詞" or prev.surface == "を"):
        return replace(tok, lemma="為る")
    if tok.lemma == "いらっしゃる":
        aux = prev is not None and prev.pos1 == "助詞" and prev.surface in ("て", "で")
        return _renamed(tok, "居る" if aux else "来る")
    if tok.lemma == "召し上がる":
        return _renamed(tok, "飲む" if _object_noun(before) in DRINKS else "食べる")
    if tok.lemma in HONORIFIC_VERBS:
        return _renamed(tok, HONORIFIC_VERBS[tok.lemma])
    return tok


def _renamed(tok: Token, verb: str) -> Token:
    plain_verb = _dictionary_form(verb)
    return replace(tok, lemma=plain_verb.lemma, orth=plain_verb.orth, kana=plain_verb.kana, honorific=True)


def _object_noun(before: list[Token]) -> str:
    """The noun marked を nearest before (お茶を召し上がる: 茶), '' when there is none in the clause."""
    for k in range(len(before) - 1, 0, -1):
        t = before[k]
        if t.pos2 == "句点":
            break
        if t.surface == "を" and t.pos1 == "助詞":
            noun = before[k - 1]
            return noun.lemma if noun.pos1 == "名詞" else ""
    return ""
