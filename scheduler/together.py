"""Co-actors of one motion perform it together, for the same time.

太郎と花子が踊る, and 太郎は花子と一緒に踊る (docs/language.md §9), give each actor a motion of the same
words of the text: the analysis copies the motion for every co-actor, with the same span and verb.
The picker gives each a variant of its own (:mod:`variants`: another capture, or the same mirrored),
and the variants of a looping clip differ in length (the captured dances: 6.0 and 3.2 s), so 花子
stopped dancing after 3.2 s while 太郎 danced on.  Now the first of them placed fixes the time every
other one plays (:func:`plan.plan`): a looping clip loops for it; any other clip is a capture about as
long (within ``picker.TOGETHER_SLACK``), held at its last pose or trimmed to that time, or else the
first one's own clip mirrored (:class:`picker.Picker`).
"""
from __future__ import annotations

from text2anim.nlp.types import Analysis


def together(analysis: Analysis) -> dict[int, tuple[int, ...]]:
    """Motion id -> the ids of the other motions performed together with it: the same verb on the same
    span of the text (not empty: a bridge the scheduler adds has none), or linked to it in parallel (太郎も
    一緒に踊った, 同時に), another actor."""
    groups: dict[tuple[str, tuple[int, int]], list[int]] = {}
    for m in analysis.motions:
        if m.span[1] > m.span[0]:
            groups.setdefault((m.verb, m.span), []).append(m.id)
    by_id = {m.id: m for m in analysis.motions}
    linked = [[a.id, b.id] for c in analysis.constraints  # 花子は踊り始めた。太郎も一緒に踊った: in parallel, one verb
              if c.relation == "parallel" and (a := by_id.get(c.first)) is not None
              and (b := by_id.get(c.second)) is not None and a.verb == b.verb]
    out: dict[int, tuple[int, ...]] = {}
    for ids in [*groups.values(), *linked]:
        if len({by_id[i].actor for i in ids}) < 2:
            continue
        for i in ids:
            out[i] = tuple(j for j in ids if j != i and by_id[j].actor != by_id[i].actor)
    return out


__all__ = ["together"]
