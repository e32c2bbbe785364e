"""The public entry of the nlp stage: ``analyze(text) -> Analysis``."""
from __future__ import annotations

from .bunsetsu import Phrase, chunk, split_sentences
from .constraints import build_constraints
from .dependency import link_heads
from .errors import NLPError
from .motions import annotate
from .tokens import OffsetMap, normalize, tokenize
from .types import Analysis, Bunsetsu, MotionSpec

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
    phrases = chunk(split_sentences(tokenize(norm)))
    preds, cues = annotate(phrases)
    motions = [p for p in preds if p.motion]
    if not motions:
        raise NLPError(f"no motion found in the text {_quote(text)} "
                       "(write an action verb, e.g. 歩く or ジャンプする)")
    for n, pred in enumerate(motions, 1):
        pred.id = n
    link_heads(phrases)
    constraints = build_constraints(phrases, cues)
    specs = tuple(
        MotionSpec(p.id, p.actor, p.verb, p.object, p.body_part, p.repeat, p.speed,
                   p.duration, offsets.span(p.start, p.end),
                   hold=p.ending == "mama", reading=p.reading)
        for p in motions
    )
    return Analysis(text, specs, tuple(constraints), _bunsetsu(text, offsets, phrases))


def _bunsetsu(text: str, offsets: OffsetMap, phrases: list[Phrase]) -> tuple[Bunsetsu, ...]:
    out = []
    for ph in phrases:
        a, b = offsets.span(ph.start, ph.end)
        out.append(Bunsetsu(ph.index, text[a:b], (a, b), ph.sentence, ph.role, ph.head, ph.why))
    return tuple(out)


def _quote(text: str, limit: int = 40) -> str:
    flat = " ".join(text.split())
    return f"'{flat[:limit]}…'" if len(flat) > limit else f"'{flat}'"
