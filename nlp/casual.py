"""Casual writing: laughter marks and the commonest typos, read before chunking.

- A trailing laughter mark (w, ww, 笑, 草 right after a predicate, at the end of
  a line or before punctuation) ends the sentence like 。, so ダンスするw keeps
  its verb.
- わ (or the small ゎ of chat) typed for the topic particle は (太郎わ走る): わ after a noun and before more
  of the sentence can only be は (the sentence-final わ ends a predicate; UniDic
  tags it a sentence-final particle, or the counter 把 after 太郎).
- お typed for を (ボールお蹴る): UniDic tags it the honorific prefix; after a
  noun and right before a verb that is not a polite お + 連用形 form, it is を.
- The IME's homophone of a library verb (手を降る for 手を振る) is read as that verb
  where the written one gives no plausible motion (:func:`recover_homophone`).

Every token read differently is said in ``notes`` (stderr and ``--explain``).
"""
from __future__ import annotations

from dataclasses import replace

from .lexicon import ANIMALS, HOMOPHONE_TYPOS
from .pred import Pred
from .types import Token

#: Words that mark laughter at the end of a casual sentence.
LAUGHTER = frozenset(["笑", "草"])

#: Polite request / light verbs after お + 連用形 (お待ちください): お stays the prefix.
_POLITE_NEXT = frozenset(["下さる", "為る", "為さる", "頂く", "願う"])

#: Characters without which a line has nothing to repair (a fast test on the line's text).
_TRIGGERS = frozenset("わゎお笑草wW")


def may_apply(line: str) -> bool:
    """Could :func:`repair` change anything in ``line``?"""
    return not _TRIGGERS.isdisjoint(line)


def is_laughter(surface: str) -> bool:
    """w, www, W (after NFKC) or 笑 / 草."""
    return surface in LAUGHTER or (surface.isascii() and surface.isalpha() and set(surface.lower()) == {"w"})


def repair(tokens: list[Token], notes: list[str]) -> list[Token]:
    """The tokens of one line with laughter marks made punctuation and わ/お typos made は/を."""
    out = list(tokens)
    for i, tok in enumerate(out):
        prev = out[i - 1] if i else None
        nxt = out[i + 1] if i + 1 < len(out) else None
        if prev is None:
            continue
        if is_laughter(tok.surface) and _ends_predicate(prev) and (nxt is None or _mark_or_laugh(nxt)
                                                                    or nxt.start > tok.end):  # ｗ　まじうける
            out[i] = replace(tok, pos1="補助記号", pos2="句点", pos3="*", lemma=tok.surface, orth=tok.surface)
        elif (tok.surface in ("わ", "ゎ") and tok.pos1 in ("助詞", "接尾辞") and _name_end(out, i - 1) and nxt is not None
              and nxt.pos1 not in ("補助記号", "助詞", "助動詞")):
            out[i] = replace(tok, surface="は", pos1="助詞", pos2="係助詞", pos3="*", lemma="は", orth="は")
            if _numeral(prev) and i >= 2 and out[i - 2] is not None and out[i - 2].pos2 == "固有名詞":
                # 健 + 一 is the name 健一, as UniDic reads it before は
                name = out[i - 2]
                out[i - 1] = replace(name, surface=name.surface + prev.surface, orth=name.orth + prev.orth,
                                     lemma=name.surface + prev.surface, kana=name.kana + prev.kana,
                                     kana_form=name.kana_form + prev.kana_form, end=prev.end)
                out[i - 2] = None  # type: ignore[call-overload]
                prev = out[i - 1]
            notes.append(f"read {prev.surface}{tok.surface} as {prev.surface}は (topic particle)")
        elif (tok.surface == "お" and tok.pos1 == "接頭辞" and _noun(prev) and nxt is not None
              and nxt.pos1 == "動詞" and not _polite(out, i + 1)):
            out[i] = replace(tok, surface="を", pos1="助詞", pos2="格助詞", pos3="*", lemma="を", orth="を")
            notes.append(f"read {prev.surface}お{nxt.surface} as {prev.surface}を{nxt.surface} (object particle)")
    return [t for t in out if t is not None]


def _ends_predicate(tok: Token) -> bool:
    """A predicate's last token, or the bracket closing a stage direction: (手を振る)ｗ."""
    return tok.pos1 in ("動詞", "助動詞", "助詞") or is_laughter(tok.surface) or tok.surface == ")"


def _mark_or_laugh(tok: Token) -> bool:
    return tok.pos1 == "補助記号" or is_laughter(tok.surface)


def _noun(tok: Token) -> bool:
    return tok.pos1 in ("名詞", "代名詞") and not tok.is_number


def _name_end(tokens: list[Token], j: int) -> bool:
    """``tokens[j]`` ends a noun: a noun, or a name's numeral (健一: UniDic reads 健 + the number 一)."""
    tok = tokens[j]
    return _noun(tok) or (_numeral(tok) and j > 0 and tokens[j - 1] is not None and tokens[j - 1].pos2 == "固有名詞")


def _numeral(tok: Token) -> bool:
    return tok.is_number or tok.pos2 == "数詞"


def _polite(tokens: list[Token], v: int) -> bool:
    """お待ちください / お辞儀する: the お is the honorific prefix of a 連用形 or noun."""
    verb = tokens[v]
    after = tokens[v + 1] if v + 1 < len(tokens) else None
    return verb.cform.startswith("連用形") and after is not None and after.lemma in _POLITE_NEXT


def recover_homophone(pred: Pred) -> None:
    """手を降る -> 手を振る: an IME homophone of a library verb, read as that verb where the
    written one gives no plausible motion (``lexicon.HOMOPHONE_TYPOS``); said in ``note``."""
    typo = HOMOPHONE_TYPOS.get(pred.written)
    if typo is None or not pred.motion:
        return
    meant, when = typo
    has_object = pred.object is not None or pred.body_part is not None
    if (when == "object" and not has_object) or (when == "no object" and has_object) or (
            when == "human" and pred.actor in ANIMALS):
        return
    pred.note = f"read {pred.written} as {meant} (a homophone the IME may have chosen: {pred.written} is no motion here)"
    pred.verb = pred.written = meant
