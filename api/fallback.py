"""Verbs the motion database lacks: one error naming all of them, or the nearest motion by meaning.

``text2anim.nlp.meaning`` compares verbs by their chiVe word vectors.  Strict
(the default): :func:`unknown_error` names every missing verb as the user wrote
it (登る, not UniDic's lemma 上る) with the database verbs nearest in meaning.
``--fallback nearest``: :func:`substitute` replaces each missing verb by the
nearest database verb when it is a real neighbour (cosine at least
``meaning.MIN_SIMILARITY`` and among the verb's ``meaning.MAX_RANK`` nearest
vectors in the whole table) and records what it did, so the output and the report can say so.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from text2anim.motiondb import MotionDB, UnknownVerbError
from text2anim.nlp import meaning
from text2anim.nlp.types import Analysis, MotionSpec


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
    """Several motions (or one) whose verbs no clip has; the message names every one.

    ``missing``: ``(written verb, [(nearest database verb, cosine), ...], stand-in or None)``
    per missing verb, where the stand-in is what ``--fallback nearest`` would play.
    """

    def __init__(self, missing: list[tuple[str, list[tuple[str, float]], str | None]], hint: bool = True):
        self.missing = tuple(missing)
        self.verb = missing[0][0]
        self.suggestions = tuple((v, "") for v, _ in missing[0][1])
        parts = []
        for written, near, standin in missing:
            text = f"nearest by meaning: {', '.join(v for v, _ in near)}" if near else "nothing near in meaning"
            if hint:
                text += f"; --fallback nearest would play {standin}" if standin else "; no stand-in near enough"
            parts.append(f"{written} ({text})")
        noun = "verb" if len(missing) == 1 else "verbs"
        msg = f"no clip in the motion database for the {noun} " + ", ".join(parts)
        if not hint:
            msg += (f"; none is near enough in meaning to stand in (cosine >= {meaning.MIN_SIMILARITY} "
                    f"and among the verb's {meaning.MAX_RANK} nearest words)")
        else:
            msg += "; --skip-unknown drops such motions, `text2anim db verbs` lists the verbs there are"
        Exception.__init__(self, msg)


def _written(spec: MotionSpec) -> str:
    return spec.written or spec.verb


def database_verbs(db: MotionDB) -> list[str]:
    """Every verb the database retrieves clips by, in its own order."""
    return [v.lemma for v in db.verbs()]


def stand_in(verb: str, verbs: list[str]) -> tuple[str, float] | None:
    """The database verb ``--fallback nearest`` plays for ``verb``: the nearest by meaning,
    if it is a real neighbour (module docstring); else None."""
    near = meaning.nearest(verb, verbs, n=1, floor=meaning.MIN_SIMILARITY, within=meaning.MAX_RANK)
    return near[0] if near else None


def unknown_error(analysis: Analysis, unknown: dict[int, UnknownVerbError], db: MotionDB,
                  hint: bool = True) -> UnknownVerbsError:
    """The error for the motions ``unknown``: every missing verb once, as written, with its
    three nearest database verbs by meaning and the stand-in the fallback would play."""
    verbs = database_verbs(db)
    missing: dict[str, tuple] = {}
    for spec in analysis.motions:
        if spec.id in unknown and _written(spec) not in missing:
            standin = stand_in(spec.verb, verbs)
            missing[_written(spec)] = (meaning.nearest(spec.verb, verbs, n=3), standin[0] if standin else None)
    return UnknownVerbsError([(w, near, st) for w, (near, st) in missing.items()], hint=hint)


def substitute(analysis: Analysis, unknown: dict[int, UnknownVerbError],
               db: MotionDB) -> tuple[Analysis, tuple[Substitution, ...]]:
    """``analysis`` with each unknown verb replaced by the nearest database verb by meaning.

    Raises :class:`UnknownVerbsError` naming the verbs that have nothing near
    enough (see the module docstring): no unrelated motion is played.
    """
    verbs = database_verbs(db)
    subs: list[Substitution] = []
    specs = []
    far: dict[int, UnknownVerbError] = {}
    for spec in analysis.motions:
        if spec.id not in unknown:
            specs.append(spec)
            continue
        near = stand_in(spec.verb, verbs)
        if near is None:
            far[spec.id] = unknown[spec.id]
            continue
        used, score = near
        subs.append(Substitution(spec.id, _written(spec), used, score))
        specs.append(replace(spec, verb=used, reading=""))
    if far:
        raise unknown_error(analysis, far, db, hint=False)
    return replace(analysis, motions=tuple(specs)), tuple(subs)
