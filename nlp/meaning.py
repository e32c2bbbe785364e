"""Verbs compared by meaning: the cosine of their chiVe word vectors.

``verb_meaning.npz`` beside this module holds int8 vectors of about 16 000
Japanese verbs and サ変 nouns, derived from the chiVe vectors that the
``ja-ginza`` package ships (``tools/derive_meaning.py``; licence and notice in
``verb_meaning.LICENSE.txt``).  No hand-written synonym list is involved: two
verbs are near when they occur in similar contexts in a large web corpus.

``nearest(verb, candidates)`` ranks the candidates (the verbs a motion
database has) by cosine; the table is loaded on first use (~1 MB, a few ms).
"""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # numpy is imported on first use: a plan whose verbs are all known loads none
    import numpy as np

DATA = Path(__file__).with_name("verb_meaning.npz")

#: Cosine below which no library verb is "near" a verb: the fallback refuses
#: rather than animate an unrelated motion.  Set from benchmarks/bench_vocab.py,
#: where accepted fallbacks mostly score above it and unrelated ones below.
MIN_SIMILARITY = 0.45

#: A stand-in must also be a real neighbour: among the ``MAX_RANK`` vectors nearest the
#: verb in the whole table (about 7 300 distinct vectors).  Cosine alone is not
#: comparable across words (frequent words sit in dense neighbourhoods), so 食べる's
#: "nearest library verb" at 0.57 is still its 199th neighbour; the rank says so.
MAX_RANK = 10


@lru_cache(maxsize=1)
def _table() -> tuple[dict[str, int], np.ndarray]:
    import numpy as np

    with np.load(DATA, allow_pickle=False) as z:
        words, rows, q = z["words"], z["rows"], z["vectors"]
        vecs = q.astype(np.float32)
    vecs /= np.maximum(np.linalg.norm(vecs, axis=1, keepdims=True), 1e-6)
    return {str(w): int(r) for w, r in zip(words, rows)}, vecs


#: Light verbs: in ポーズをとる / 伸びをする the meaning is the noun's.
_LIGHT = frozenset(["取る", "為る"])


def forms(verb: str) -> list[str]:
    """Spellings to look ``verb`` up under: as given, without する (掃除する -> 掃除),
    then the dictionary forms of its head word: the verb after a case particle
    (手を振る -> 振る, 手に取る -> 取る; but ポーズをとる -> ポーズ), else the first verb or noun (うなずく -> 頷く,
    登る -> 上る, 走っていく -> 走る, 泣き出す -> 泣く)."""
    out = [verb]
    if verb.endswith("する") and len(verb) > 2:
        out.append(verb[:-2].removesuffix("を"))
    from .tagging import tagger  # the analyzer's own tagger (lazy, cached)

    words = list(tagger()(out[-1]))
    content = [i for i, w in enumerate(words) if w.feature.pos1 in ("動詞", "名詞")]
    if content:
        after_case = [i for i in content if i > 0 and words[i - 1].feature.pos2 == "格助詞"]
        light = after_case and words[after_case[-1] - 1].surface == "を" and (
            words[after_case[-1]].feature.lemma or "") in _LIGHT
        if after_case and not light:
            head = after_case[-1]
        elif words[content[0]].feature.pos1 == "動詞":
            head = content[0]
        else:  # a compound noun's head is its last noun (一回転 -> 回転)
            nouns = [i for i in content if words[i].feature.pos1 == "名詞"]
            head = next((i for i in reversed(nouns) if not words[i].feature.pos2 == "数詞"), content[0])
        f = words[head].feature
        out += [f.orthBase or "", (f.lemma or "").split("-")[0]]
    return list(dict.fromkeys(w for w in out if w))


@lru_cache(maxsize=4096)
def _phrase(verb: str) -> bool:
    """Is ``verb`` a phrase with a case particle (手を振る, 後ろに下がる) rather than one word?"""
    from .tagging import tagger

    return any(w.feature.pos2 == "格助詞" for w in tagger()(verb))


@lru_cache(maxsize=4096)
def vector(verb: str) -> np.ndarray | None:
    """The unit vector ``(D,)`` of ``verb`` (first spelling of ``forms`` in the table), or None; cached: a
    nearest-verb search asks it of every database verb, and each lookup runs the tagger (the table's own row)."""
    index, vecs = _table()
    for w in forms(verb):
        if w in index:
            return vecs[index[w]]
    return None


def nearest(verb: str, candidates: list[str] | tuple[str, ...], n: int = 3,
            floor: float | None = None, within: int | None = None) -> list[tuple[str, float]]:
    """The ``n`` candidates nearest ``verb`` by meaning, ``(candidate, cosine)`` best first.

    Candidates without a vector, and phrases (手を振る: the clip also has 振る), are
    left out; ties go to the shortest candidate,
    then the one that sorts first, so the answer is deterministic.  With ``floor`` only
    candidates at least that near are returned; with ``within`` only those among the
    ``within`` table vectors nearest ``verb``.  Empty if ``verb`` has no vector.
    """
    v = vector(verb)
    if v is None:
        return []
    if within is not None:
        import numpy as np

        ranked = np.sort(_table()[1] @ v)[::-1]
        floor = max(floor or -1.0, float(ranked[min(within, len(ranked)) - 1]) - 1e-6)
    scored = []
    for c in dict.fromkeys(candidates):
        if _phrase(c):
            continue  # 足を止める, ステップを踏む: the head verb alone (止める, 踏む) is not its meaning
        cv = vector(c)
        if cv is not None and c != verb:
            s = float(cv @ v)
            if floor is None or s >= floor:
                scored.append((c, round(s, 4)))
    scored.sort(key=lambda x: (-x[1], len(x[0]), x[0]))  # a tie (one vector): the plainest verb
    return scored[:n]


def bodily(verb: str, library: frozenset[str]) -> bool:
    """Is ``verb`` a bodily action: one of the ``library`` verbs, or one whose nearest library verb
    is near in meaning (at least :data:`MIN_SIMILARITY`)?"""
    return verb in library or bool(nearest(verb, sorted(library), n=1, floor=MIN_SIMILARITY))
