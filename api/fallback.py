"""Verbs the motion database lacks: one error naming all of them, or the nearest motion by meaning.

``text2anim.nlp.meaning`` compares verbs by their chiVe word vectors.  Strict
(the default): :func:`unknown_error` names every missing verb as the user wrote
it (登る, not UniDic's lemma 上る) with the database verbs nearest in meaning.
``--fallback nearest``: :func:`substitute` replaces each missing verb by the
nearest database verb whose cosine is at least ``meaning.MIN_SIMILARITY`` and
records what it did, so the output and the report can say so.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from text2anim.motiondb import MotionDB, UnknownVerbError
from text2anim.nlp import meaning
from text2anim.nlp.types import Analysis, MotionSpec

#: ``--fallback`` values: ``strict`` refuses a missing verb, ``nearest`` stands in the nearest by meaning.
FALLBACKS = ("strict", "nearest")


@dataclass(frozen=True)
class Substitution:
    """Motion ``id`` asked for ``written`` (no clip); ``used`` was animated instead (cosine ``score``)."""

    id: int
    written: str
    used: str
    score: float

    def to_dict(self) -> dict:
        return {"id": self.id, "asked": self.written, "animated_as": self.used, "similarity": self.score}

    def __str__(self) -> str:
        return f"{self.written} → {self.used} (nearest by meaning, cosine {self.score:.2f})"


class UnknownVerbsError(UnknownVerbError):
    """Several motions (or one) whose verbs no clip has; the message names every one."""

    def __init__(self, missing: list[tuple[str, list[tuple[str, float]]]], hint: bool = True):
        self.missing = tuple(missing)
        self.verb = missing[0][0]
        self.suggestions = tuple((v, "") for v, _ in missing[0][1])
        parts = []
        for written, near in missing:
            parts.append(f"{written} (nearest by meaning: {', '.join(v for v, _ in near)})" if near
                         else f"{written} (nothing near in meaning)")
        noun = "verb" if len(missing) == 1 else "verbs"
        msg = f"no clip in the motion database for the {noun} " + "; ".join(parts)
        if not hint:
            msg += f"; none is near enough in meaning to stand in (cosine < {meaning.MIN_SIMILARITY})"
        else:
            msg += ("; --fallback nearest animates the nearest one, --skip-unknown drops the motion, "
                    "`text2anim db verbs` lists the verbs there are")
        Exception.__init__(self, msg)


def _written(spec: MotionSpec) -> str:
    return spec.written or spec.verb


def database_verbs(db: MotionDB) -> list[str]:
    """Every verb the database retrieves clips by, in its own order."""
    return [v.lemma for v in db.verbs()]


def unknown_error(analysis: Analysis, unknown: dict[int, UnknownVerbError], db: MotionDB,
                  hint: bool = True) -> UnknownVerbsError:
    """The error for the motions ``unknown``: every missing verb once, as written, with its
    three nearest database verbs by meaning."""
    verbs = database_verbs(db)
    missing: dict[str, list[tuple[str, float]]] = {}
    for spec in analysis.motions:
        if spec.id in unknown and _written(spec) not in missing:
            missing[_written(spec)] = meaning.nearest(spec.verb, verbs, n=3)
    return UnknownVerbsError(list(missing.items()), hint=hint)


def substitute(analysis: Analysis, unknown: dict[int, UnknownVerbError],
               db: MotionDB) -> tuple[Analysis, tuple[Substitution, ...]]:
    """``analysis`` with each unknown verb replaced by the nearest database verb by meaning.

    Raises :class:`UnknownVerbsError` naming the verbs that have nothing near
    enough (cosine below ``meaning.MIN_SIMILARITY``): no unrelated motion is played.
    """
    verbs = database_verbs(db)
    subs: list[Substitution] = []
    specs = []
    far: dict[int, UnknownVerbError] = {}
    for spec in analysis.motions:
        if spec.id not in unknown:
            specs.append(spec)
            continue
        near = meaning.nearest(spec.verb, verbs, n=1, floor=meaning.MIN_SIMILARITY)
        if not near:
            far[spec.id] = unknown[spec.id]
            continue
        used, score = near[0]
        subs.append(Substitution(spec.id, _written(spec), used, score))
        specs.append(replace(spec, verb=used, reading=""))
    if far:
        raise unknown_error(analysis, far, db, hint=False)
    return replace(analysis, motions=tuple(specs)), tuple(subs)
