"""The cast: every person the text names is in the scene, even one who never acts (花子に手を振る)."""
from __future__ import annotations

from dataclasses import replace

from text2anim.nlp.types import Analysis, MotionSpec

#: What a person does who is only looked at, spoken to or approached: they wait (a captured idle).
IDLE_VERB = "待つ"
IDLE_READING = "マツ"


def cast(analysis: Analysis) -> Analysis:
    """``analysis`` with one idle motion (:data:`IDLE_VERB`) for each person who is the target of a motion
    but performs none, placed after the text's motions (the span of the first motion naming them)."""
    actors = {m.actor for m in analysis.motions}
    extra: list[MotionSpec] = []
    next_id = max((m.id for m in analysis.motions), default=0) + 1
    for m in analysis.motions:
        name = m.target
        if name is None or name in actors or not m.target_person:
            continue
        extra.append(MotionSpec(next_id, name, IDLE_VERB, span=m.span, reading=IDLE_READING, written=IDLE_VERB))
        actors.add(name)
        next_id += 1
    return replace(analysis, motions=analysis.motions + tuple(extra)) if extra else analysis

