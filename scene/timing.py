"""Timing between people: the contact instants of two actors who act on each other meet.

When two people shake hands, high-five, hug or hand a thing over, each one's motion has an instant of
contact (the hand furthest out, read from the clip itself); the time table starts both motions together
(a parallel link: a partner's copy of the motion, or the counterpart of a hand-over, docs/language.md §8),
and their clips reach at different times. A throw and its catch meet the same way, the thrower's instant
being the release plus the thing's flight (:data:`FLIGHT_S`). :func:`sync_shifts` says how much later one of the two must start
so the instants meet; the pipeline plans the text again with those delays (:mod:`text2anim.edits`).
"""
from __future__ import annotations

from collections.abc import Callable, Sequence

from text2anim.nlp.types import Constraint
from text2anim.scheduler.types import Element

#: Verbs (lemmas) two people do together with a contact instant (a throw and a catch: through the air).
CONTACT_VERBS = frozenset(
    """握手する ハイタッチする 抱き合う 抱き締める 渡す 手渡す 差し出す 受け取る 貰う 乾杯する キスする
    投げる 放る 放り投げる 投げ渡す パスする 取る キャッチする 受け止める 捕まえる""".split()
)
#: s: a thrown thing's flight to the catcher (a 4 m throw at about 7 m/s, rising half a metre).
FLIGHT_S = 0.6
#: s: instants closer than this are together (a frame at 30 fps).
TOLERANCE = 1.0 / 30.0


def pairs(rows: Sequence[Element], constraints: Sequence[Constraint]) -> list[tuple[Element, Element]]:
    """The rows of two actors that must meet: a parallel link between different actors' contact verbs."""
    by_id = {r.id: r for r in rows}
    out = []
    for c in constraints:
        a, b = by_id.get(c.first), by_id.get(c.second)
        if (a is not None and b is not None and c.relation == "parallel" and a.actor != b.actor
                and a.verb in CONTACT_VERBS and b.verb in CONTACT_VERBS):
            out.append((a, b))
    return out


def sync_shifts(rows: Sequence[Element], constraints: Sequence[Constraint],
                instant: Callable[[Element], float | None]) -> dict[int, float]:
    """Row (motion) id -> seconds to move its start (the edits' ``shift``) so that each pair's contact
    instants (``instant``: the contact time of a row on the animation's clock, ``None`` when its clip has
    none) coincide. The pair is ``a`` and ``b``, ``b`` linked to ``a`` in parallel: when ``b`` reaches
    first it starts later; when ``a`` does, ``a`` starts later and ``b`` as much before it, where it was."""
    shifts: dict[int, float] = {}
    for a, b in pairs(rows, constraints):
        ta, tb = instant(a), instant(b)
        if ta is None or tb is None or abs(ta - tb) <= TOLERANCE:
            continue
        by = round(abs(ta - tb), 3)
        if ta > tb:
            shifts[b.id] = shifts.get(b.id, 0.0) + by
        else:
            shifts[a.id] = shifts.get(a.id, 0.0) + by
            shifts[b.id] = shifts.get(b.id, 0.0) - by
    return shifts
