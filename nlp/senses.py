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

#: WordNet lexicographer files of senses a body can act out. A verb's senses in the
#: others (stative, cognition, emotion, possession, social, weather) are no bodily action:
#: 考える's "think" is cognition, and never makes a clip a stand-in.
BODILY = frozenset(["motion", "contact", "body", "consumption", "communication", "competition",
                    "perception", "creation", "change"])


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
