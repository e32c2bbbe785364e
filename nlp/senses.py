"""What a verb means as a bodily action: its WordNet verb senses, through JMdict.

``verb_senses.json.gz`` beside this module (``tools/lexicon/derive_senses.py``; licences in
``verb_senses.LICENSE.txt``) maps about 39 000 Japanese verbs and サ変 nouns to the WordNet
3.1 verb synsets their JMdict English glosses name (ぶらつく: "to stroll about; to saunter"
-> stroll.v.01), and keeps WordNet's hierarchy of those synsets (stroll is a kind of walk).
A synset is written as its 8-digit WordNet offset (``"01908923"`` is walk.v.01).

``senses(verb)`` is what a stand-in is judged by: a clip can stand in for a verb it does
not list only when the clip's own action is one of the verb's senses or what that sense
is a kind of (``relation``), see ``api/fallback.py``.
"""
from __future__ import annotations

import gzip
import json
from functools import lru_cache
from pathlib import Path

DATA = Path(__file__).with_name("verb_senses.json.gz")

#: WordNet lexicographer files of senses a body can act out or show (pondering, reading: the
#: cognition a clip shows). A verb's senses in the others (stative, emotion, possession,
#: social, weather) are no action of a body: 背負う's "be burdened with" is stative, and never
#: makes a clip a stand-in.
BODILY = frozenset(["motion", "contact", "body", "consumption", "communication", "competition",
                    "perception", "creation", "change", "cognition"])


@lru_cache(maxsize=1)
def _table() -> tuple[dict[str, list[list[str]]], dict[str, tuple[str, str, tuple[str, ...]]]]:
    data = json.loads(gzip.decompress(DATA.read_bytes()))
    synsets = {o: (lex, lemma, tuple(hyper)) for o, (lex, lemma, hyper) in data["synsets"].items()}
    return data["words"], synsets


def known(offset: str) -> bool:
    """Is ``offset`` a WordNet verb synset of the table?"""
    return offset in _table()[1]


def name(offset: str) -> str:
    """A synset for people: its first lemma and file, ``walk (verb.motion)``."""
    lex, lemma, _ = _table()[1][offset]
    return f"{lemma.replace('_', ' ')} (verb.{lex})"


@lru_cache(maxsize=4096)
def senses(verb: str) -> tuple[str, ...]:
    """The bodily WordNet senses of ``verb``'s first JMdict verb sense, in gloss order.

    ``verb`` is looked up as ``meaning.forms`` spells it (as written, without する, its head
    verb), first spelling found; a word's later JMdict senses are left out (跳ねる "to close
    (a show)" is its third). Empty when the verb is not in the table or has no bodily sense.
    """
    from .meaning import forms

    words, synsets = _table()
    for w in forms(verb):
        if w in words and words[w]:
            return tuple(o for o in words[w][0] if synsets[o][0] in BODILY)
    return ()


def hypernyms(offset: str) -> tuple[str, ...]:
    """The synsets ``offset`` is directly a kind of (stroll -> walk)."""
    return _table()[1][offset][2]


def relation(sense: str, action: str) -> int | None:
    """How a verb's ``sense`` relates to a clip's ``action``: 0 the same synset, 1 the sense is
    a kind of the action (a direct hypernym that is not itself a root of WordNet's verbs:
    "move", "change" and "act" are no action of a clip), else None."""
    if sense == action:
        return 0
    if action in hypernyms(sense) and hypernyms(action):
        return 1
    return None


#: Second verbs of a compound verb (V1連用形 + V2) that leave V1's action as it is and add a path,
#: a direction, a strength or an aspect: 駆け寄る runs (up to), 走り回る runs (around), 握り締める
#: grips (tightly). Not 上げる/下ろす/出す, which change what is done (抱き上げる lifts, it does not
#: hug), nor 込む, which often does (踏み込む steps in, it does not stamp), nor a second action (泣き叫ぶ).
MANNER_V2 = frozenset(["寄る", "抜ける", "回る", "締める", "付ける", "掛かる", "かかる", "続ける",
                       "始める", "直す", "まくる", "捲る", "通す", "切る", "留める", "集める", "のめす",
                       "巡らす", "入る", "付く"])


def _words(text: str) -> list[tuple[str, str, str, str]]:
    """``(surface, pos1, cForm, orthBase)`` of each word of ``text`` (copied out: the tagger's
    nodes are only valid until its next call)."""
    from .tagging import tagger

    return [(w.surface, w.feature.pos1 or "", w.feature.cForm or "", w.feature.orthBase or w.surface)
            for w in tagger()(text)]


@lru_cache(maxsize=4096)
def compound_head(verb: str) -> tuple[str, str] | None:
    """``(V1, V2)`` dictionary forms when ``verb`` is a compound verb V1 + V2 whose V2 keeps V1's
    action (:data:`MANNER_V2`): 駆け寄る -> (駆ける, 寄る); else None (one verb, a phrase, or a V2
    that changes the action)."""
    if not 3 <= len(verb) <= 12 or _words(verb)[-1][1] != "動詞":
        return None
    for i in range(1, len(verb) - 1):
        first = _words(verb[:i] + "ます")  # 投げ alone is read as a noun; 投げます is the verb
        second = _words(verb[i:])
        if len(first) != 2 or len(second) != 1 or first[0][0] != verb[:i]:
            continue
        (_, pos1, form1, base1), (surface2, pos2, form2, base2) = first[0], second[0]
        if (pos1 == "動詞" and form1.startswith("連用形") and pos2 == "動詞" and form2.startswith("終止形")
                and (surface2 in MANNER_V2 or base2 in MANNER_V2)):
            return base1, base2
    return None
