"""The public entry of the nlp stage: ``analyze(text) -> Analysis``."""
from __future__ import annotations

from dataclasses import replace

from .bunsetsu import Phrase, chunk, split_sentences
from .constraints import build_constraints
from .dependency import link_heads
from .errors import NLPError
from .lexicon import LOCOMOTION_VERBS
from .motions import annotate
from .targets import add_causers, add_counterparts, time_catches
from .tokens import OffsetMap, normalize, tokenize
from .types import Analysis, Constraint, MotionSpec

#: Longest text accepted, in characters (a few pages of a script).  Longer
#: texts are refused rather than producing an unreadable animation.
MAX_CHARS = 2000


def analyze(text: str) -> Analysis:
    """Find the motions of ``text`` and the temporal constraints between them.

    Raises ``NLPError`` for empty or blank text, text over ``MAX_CHARS``
    characters, and text with no motion.  Spans index into ``text`` itself.
    """
    if not isinstance(text, str):
        raise NLPError(f"text must be a string, not {type(text).__name__}")
    if not text.strip():
        raise NLPError("the text is empty")
    if len(text) > MAX_CHARS:
        raise NLPError(f"the text is too long: {len(text)} characters (the limit is {MAX_CHARS})")
    norm, offsets = normalize(text)
    if not norm.strip():
        raise NLPError("the text is empty (only control characters)")
    notes: list[str] = []
    phrases = chunk(split_sentences(tokenize(norm, notes)))
    preds, cues = annotate(phrases, notes)
    notes.extend(p.note for p in preds if p.note)
    motions = [p for p in preds if p.motion]
    if not motions:
        raise NLPError(f"no motion found in the text {_quote(text)}{_why_not(preds, norm)} "
                       "(write an action verb, e.g. 歩く or ジャンプする)")
    for n, pred in enumerate(motions, 1):
        pred.id = n
    link_heads(phrases)
    constraints = build_constraints(phrases, cues)
    specs = [
        MotionSpec(p.id, p.actor, p.verb, p.object, p.body_part, p.repeat, p.speed,
                   p.duration, offsets.span(p.start, p.end),
                   hold=p.ending == "mama", reading=p.reading, delay=p.delay,
                   written=p.written or p.verb, phrase=p.verb_phrase, manner=p.manner, style=p.style,
                   intensity=p.intensity, target=p.target,
                   target_role=p.target_role, target_side=p.target_side, target_person=p.target_person)
        for p in motions
    ]
    constraints = list(constraints)
    notes.extend(add_causers(specs, constraints, {p.id: p.causer for p in motions if p.causer}))
    _add_co_actors(specs, constraints, {p.id: p.co_actors for p in motions if p.co_actors})
    notes.extend(add_counterparts(specs, constraints))
    time_catches(specs, constraints)
    return Analysis(text, tuple(specs), tuple(constraints), _phrases(offsets, phrases), tuple(notes))


def _add_co_actors(specs: list[MotionSpec], constraints: list[Constraint], co: dict[int, tuple[str, ...]]) -> None:
    """太郎と花子が歩く: each co-actor gets a copy of the motions (ids after the text's own, same span); a
    copy directed at its co-actor is directed at the actor instead (太郎は花子と握手する: 花子's handshake is
    with 太郎; 花子の手を取って、一緒に踊る: she dances toward him); a copy of a walk or run directed at no one
    goes beside the actor (partner, side ``beside``: 二人は並んで歩いた walk side by side, and a later motion
    between them does not turn one round to meet the other head-on).

    Links among the copied motions are copied; a copy with no copied link starts
    with its original (parallel), so every actor's track is linked as the contract says.
    """
    names = list(dict.fromkeys(n for group in co.values() for n in group))
    by_id = {s.id: s for s in specs}
    next_id = len(specs) + 1
    for name in names:
        copies: dict[int, int] = {}
        for orig in sorted(i for i, group in co.items() if name in group):
            copies[orig] = next_id
            spec = by_id[orig]
            target = spec.actor if spec.target == name else spec.target  # never directed at oneself
            dup = replace(spec, id=next_id, actor=name, target=target)
            if spec.target is None and spec.verb in LOCOMOTION_VERBS and spec.actor is not None:
                # 二人は並んで歩いた, 太郎と花子が走る: side by side with the first, whatever places them later
                dup = replace(dup, target=spec.actor, target_role="partner", target_side="beside",
                              target_person=True)
            specs.append(dup)
            next_id += 1
        linked = set()
        for c in list(constraints):
            if c.first in copies and c.second in copies:
                constraints.append(replace(c, first=copies[c.first], second=copies[c.second]))
                linked.add(copies[c.second])
        for orig, copy in copies.items():
            if copy not in linked:
                constraints.append(Constraint(orig, copy, "parallel", None, None, "composition", "と"))


def _phrases(offsets: OffsetMap, phrases: list[Phrase]) -> tuple[tuple, ...]:
    """The rows :attr:`Analysis.bunsetsu` is made of (plain tuples: most analyses never read them)."""
    return tuple((ph.index, offsets.span(ph.start, ph.end), ph.sentence, ph.role, ph.head, ph.why, ph.persons)
                 for ph in phrases)


def _why_not(preds: list, norm: str) -> str:
    """': 泳げる is a potential form (...)' for each predicate that was not a motion, if any."""
    from .endings import NOT_MOTION

    said = [f"{norm[p.start:p.end]} is not one: {NOT_MOTION.get(p.reason, p.reason)}" for p in preds[:3]]
    return (": " + "; ".join(said)) if said else ""


def _quote(text: str, limit: int = 40) -> str:
    flat = " ".join(text.split())
    return f"'{flat[:limit]}…'" if len(flat) > limit else f"'{flat}'"
