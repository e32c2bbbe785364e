"""Verbs the motion database lacks: one error naming all of them, or a stand-in that does the same.

Strict (the default): :func:`unknown_error` names every missing verb as the user wrote it
(登る, not UniDic's lemma 上る) with the database verbs nearest in meaning, and the stand-in
``--fallback nearest`` would play or why there is none. ``--fallback nearest``:
:func:`substitute` animates each missing verb with a clip that does the same thing, and
records what it did and why, so the output and the report can say so.

A clip stands in for a verb it does not list only when two independent resources agree:

1. **what it does** (``text2anim.nlp.senses``, WordNet through JMdict): one of the verb's
   bodily senses is the clip's action (its description's ``actions``; for a clip without
   them, the first sense of its primary verb) or directly a kind of it (ぶらつく "stroll" is a
   kind of walk), and a verb that travels (a kind of WordNet's travel/go/move) gets a clip
   whose hips travel;
2. **what it is near** (``text2anim.nlp.meaning``, chiVe vectors): one of the clip's verbs is
   among the :data:`STANDIN_RANK` words nearest the verb in the whole vector table, at a
   cosine of at least :data:`STANDIN_FLOOR`.

The lexicon keeps a neighbour that only shares a context out (泳ぐ is near 潜る, but swimming is
no ducking under a bar); the vectors keep a wrong English reading out (写生する's gloss
"draw" is WordNet's pull). With neither, the verb is refused with what was looked for.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Sequence

from text2anim.motiondb import ClipInfo, MotionDB, UnknownVerbError
from text2anim.motiondb.seed import BUILTIN_SOURCE
from text2anim.nlp import meaning, senses
from text2anim.nlp.types import Analysis, MotionSpec

from . import phrase_sense

#: One of a stand-in clip's verbs must be among this many vectors nearest the asked verb ...
STANDIN_RANK = 30
#: ... and at least this near (cosine).
STANDIN_FLOOR = 0.30
#: ... unless the clip does the very action of one of the verb's first SAME_SENSES senses (not a kind
#: of it): then the cosine alone must reach STANDIN_FLOOR. A rarer word (囁く, 退場する) has few clip
#: verbs among its nearest words even where it names the clip's action; a kind of an action (a lick
#: is a kind of stroke) and a later sense still need the stricter agreement.
SAME_SENSES = 2
#: WordNet's travel.v.01 (travel, go, move, locomote): a verb that is a kind of it travels.
TRAVEL = "01839438"


@dataclass(frozen=True)
class StandIn:
    """Clip ``clip`` (animated as its verb ``verb``) stands in, for ``reason`` (in words: ``stroll is
    a kind of walk``, ``both mean throw``, ``投げ込む is a way of 投げる``); ``score`` the cosine of the vectors."""

    verb: str
    clip: str
    reason: str
    score: float


@dataclass(frozen=True)
class Substitution:
    """Motion ``id`` asked for ``written`` (no clip); ``used`` was animated instead (cosine ``score``),
    ``reason`` says why it does the same (:class:`StandIn`)."""

    id: int
    written: str
    used: str
    score: float
    reason: str = ""

    def to_dict(self) -> dict:
        return {"id": self.id, "asked": self.written, "animated_as": self.used, "similarity": self.score,
                "because": self.reason}

    def __str__(self) -> str:
        return f"{self.written} → {self.used} ({self.reason}; cosine {self.score:.2f})"


class UnknownVerbsError(UnknownVerbError):
    """Several motions (or one) whose verbs no clip has; the message names every one.

    ``missing``: ``(written verb, [(nearest database verb, cosine), ...], stand-in or None, why)``
    per missing verb, where the stand-in is what ``--fallback nearest`` would play and ``why``
    says why it does the same (or why nothing may stand in).
    """

    def __init__(self, missing: list[tuple[str, list[tuple[str, float]], str | None, str]], hint: bool = True):
        self.missing = tuple(missing)
        self.verb = missing[0][0]
        self.suggestions = tuple((v, "") for v, _ in missing[0][1])
        parts = []
        for written, near, standin, why in missing:
            text = f"nearest by meaning: {', '.join(v for v, _ in near)}" if near else "nothing near in meaning"
            if standin and hint:
                text += f"; --fallback nearest would play {standin}: {why}"
            elif not standin:
                text += f"; no stand-in: {why}"
            parts.append(f"{written} ({text})")
        noun = "verb" if len(missing) == 1 else "verbs"
        msg = f"no clip in the motion database for the {noun} " + ", ".join(parts)
        if hint:
            msg += "; --skip-unknown drops such motions, `text2anim db verbs` lists the verbs there are"
        else:
            msg += "; nothing was animated in place of a verb no clip does"
        Exception.__init__(self, msg)

    def __str__(self) -> str:
        return self.args[0]

    def __reduce__(self):  # pickled as its message and fields (its own constructor takes the missing verbs)
        return _restored, (type(self), self.args, self.__dict__)


def _restored(cls: type[UnknownVerbsError], args: tuple, fields: dict) -> UnknownVerbsError:
    """An :class:`UnknownVerbsError` unpickled: its message and fields as they were."""
    err = cls.__new__(cls)
    Exception.__init__(err, *args)
    err.__dict__.update(fields)
    return err


def _written(spec: MotionSpec) -> str:
    return phrase_sense.asked(spec)


def _stand_in(spec: MotionSpec, clips: Sequence[ClipInfo]) -> tuple[StandIn | None, str]:
    """:func:`find_stand_in` for ``spec``: a phrase about the actor's body (目を閉じる) is looked for
    as a whole, among the clips that act on that part of the body (``phrase_sense.does_body``)."""
    if phrase_sense.body_phrase(spec) is None:
        # the verb as written when the dictionary knows it so (泣きじゃくる; its lemma 泣き噦る is not)
        written = spec.written if spec.written and senses.senses(spec.written) else spec.verb
        return find_stand_in(written, clips)
    return find_stand_in(spec.phrase, [c for c in clips if phrase_sense.does_body(spec, c)
                                       and phrase_sense.same_sense(spec, c)])


def database_verbs(db: MotionDB) -> list[str]:
    """Every verb the database retrieves clips by, in its own order."""
    return [v.lemma for v in db.verbs()]


def clip_actions(clip: ClipInfo) -> tuple[str, ...]:
    """What ``clip`` does: its description's actions; for an imported clip without them, the first
    sense of its primary verb (a built-in clip without actions stands in for nothing)."""
    if clip.description.actions or clip.source.startswith(BUILTIN_SOURCE):
        return clip.description.actions
    return senses.senses(clip.verb)[:1]


def _travels(sense: str, depth: int = 6) -> bool:
    """Is ``sense`` a kind of travelling (WordNet's travel.v.01 within ``depth`` hypernym steps)?"""
    level = {sense}
    for _ in range(depth):
        if TRAVEL in level:
            return True
        level = {h for s in level for h in senses.hypernyms(s)}
    return TRAVEL in level


def find_stand_in(verb: str, clips: Sequence[ClipInfo]) -> tuple[StandIn | None, str]:
    """The clip that stands in for ``verb`` (module docstring), or None with what was looked for.

    Of several, the one matching the verb's earliest sense, then the same sense before a
    kind of it, then the nearest by the vectors, then the first clip given. A compound verb
    whose second verb keeps the first one's action (``senses.compound_head``: 走り回る) that
    WordNet cannot place is played as its first verb, when the vectors agree.
    """
    wanted = senses.senses(verb)
    if not wanted:
        return _compound(verb, clips, "what it means as a bodily action is not in the lexicon (JMdict, WordNet)")
    found: list[tuple[tuple, StandIn]] = []
    lexical: dict[str, None] = {}  # senses some clip does, in order
    first = _first_verb(verb, clips)
    for order, clip in enumerate(clips):
        for action in clip_actions(clip):
            for rank, sense in enumerate(wanted):
                how = senses.relation(sense, action)
                if how is None or (_travels(sense) and not clip.description.locomotion):
                    continue
                lexical[sense] = None
                near = meaning.nearest(verb, clip.verbs, n=1, floor=STANDIN_FLOOR, within=STANDIN_RANK)
                loose = not near and how == 0 and rank < SAME_SENSES and first in (None, *clip.verbs)
                if loose:  # the very action of one of its first senses: the vectors need only agree
                    near = meaning.nearest(verb, clip.verbs, n=1, floor=STANDIN_FLOOR)
                if near:
                    asked, does = _lemmas([sense]), _lemmas([action])
                    reason = f"{asked} is a kind of {does}" if how else f"both mean {does}"
                    found.append(((loose, rank, how, -near[0][1], order),
                                  StandIn(clip.verb, clip.name, reason, near[0][1])))
    if found:
        return min(found, key=lambda f: f[0])[1], ""
    if lexical:
        return _compound(verb, clips, f"the clips that do {_lemmas(lexical)} are not near it in meaning (word vectors)")
    return _compound(verb, clips, f"no clip does {_lemmas(wanted)} or what it is a kind of")


def _first_verb(verb: str, clips: Sequence[ClipInfo]) -> str | None:
    """The first verb of ``verb`` when it is a compound of two actions that clips list (泣き叫ぶ: 泣く
    and 叫ぶ): its main action, which a clip matched by the cosine alone must list too (a shout is
    not 泣き叫ぶ's crying); None otherwise (立ち去る: no clip lists 去る; 怒鳴りつける: 付ける only
    adds a manner, ``senses.MANNER_V2``)."""
    parts = senses.compound_parts(verb)
    listed = {v for c in clips for v in c.verbs}
    if (parts is None or parts[0] not in listed or not {parts[1], parts[2]} & listed
            or {parts[1], parts[2]} & senses.MANNER_V2):
        return None
    return parts[0]


def _compound(verb: str, clips: Sequence[ClipInfo], why: str) -> tuple[StandIn | None, str]:
    """The first clip that lists and does ``verb``'s first verb (one of that verb's senses is the clip's
    action or a kind of it), when ``verb`` is such a compound and that verb is among its nearest
    words (module docstring); else None and ``why``."""
    parts = senses.compound_head(verb)
    if parts is None:
        return None, why
    head, tail = parts
    near = meaning.nearest(verb, [head], n=1, floor=STANDIN_FLOOR, within=STANDIN_RANK)
    meant = senses.senses(head)  # the clip must do what the first verb means: 叩く's clip claps, and
    clip = next((c for c in clips if head in c.verbs and any(  # 叩きのめす (beat up) is no clapping
        senses.relation(m, a) is not None for m in meant for a in clip_actions(c))), None)
    if not near or clip is None:
        return None, why + f"; nor does its first verb {head} stand in" + ("" if clip else f" (no clip does {head})")
    return StandIn(head, clip.name, f"{verb} is {head} + {tail}, a way of {head}", near[0][1]), ""


def _lemmas(offsets) -> str:
    return ", ".join(dict.fromkeys(senses.name(o).split(" (")[0] for o in offsets))


def unknown_error(analysis: Analysis, unknown: dict[int, UnknownVerbError], db: MotionDB,
                  hint: bool = True) -> UnknownVerbsError:
    """The error for the motions ``unknown``: every missing verb once, as written, with its
    three nearest database verbs by meaning and the stand-in the fallback would play (or why none)."""
    verbs = database_verbs(db)
    clips = db.clips()
    missing: dict[str, tuple] = {}
    for spec in analysis.motions:
        if spec.id in unknown and _written(spec) not in missing:
            standin, why = _stand_in(spec, clips)
            missing[_written(spec)] = (meaning.nearest(spec.verb, verbs, n=3),
                                       standin.verb if standin else None, standin.reason if standin else why)
    return UnknownVerbsError([(w, near, st, why) for w, (near, st, why) in missing.items()], hint=hint)


def substitute(analysis: Analysis, unknown: dict[int, UnknownVerbError],
               db: MotionDB) -> tuple[Analysis, tuple[Substitution, ...]]:
    """``analysis`` with each unknown verb animated by a clip that does the same (module docstring).

    Raises :class:`UnknownVerbsError` naming the verbs nothing may stand in for: no
    unrelated motion is played.
    """
    clips = db.clips()
    subs: list[Substitution] = []
    specs = []
    far: dict[int, UnknownVerbError] = {}
    for spec in analysis.motions:
        if spec.id not in unknown:
            specs.append(spec)
            continue
        standin, _ = _stand_in(spec, clips)
        if standin is None:
            far[spec.id] = unknown[spec.id]
            continue
        subs.append(Substitution(spec.id, _written(spec), standin.verb, standin.score, standin.reason))
        specs.append(replace(spec, verb=standin.verb, reading=""))
    if far:
        raise unknown_error(analysis, far, db, hint=False)
    return replace(analysis, motions=tuple(specs)), tuple(subs)
