"""Facing continuity: an actor who leaves the person it was facing turns its back first.

花子に手を振って、立ち去る: the wave is addressed to 花子, so the scene stands him facing her; the leaving walks
away from her (role ``source``), so at its start she is behind him. A walk cannot start by turning round on
the spot, and without a turn the scene can meet only one of the two: he waved with his back to her, or walked
through her. :func:`turn_away` gives the clip a reader pictures in between (the built-in ``turn_away``: half a
turn on the spot), which :func:`arrangement.arrange` adds as a motion of its own, as it adds posture bridges.

Only metadata is read: the two motions' targets and roles (``nlp.types.MotionSpec``) and the clips' loops.
"""
from __future__ import annotations

from text2anim.nlp.types import MotionSpec

from .clips import C, ClipSource

#: The verb of the clip that turns the back on whoever was in front.
TURN_VERB = "背を向ける"
#: Roles a motion faces its target person in (the scene stands them face to face).
FACING_ROLES = frozenset(("goal", "addressee", "patient", "recipient", "partner"))
#: Sides of the target that put the actor beside or behind them, not facing them.
SIDEWAYS = frozenset(("beside", "behind", "left", "right", "around", "under", "on", "near"))


def faces(spec: MotionSpec | None, person: str | None) -> bool:
    """Does ``spec`` leave its actor facing ``person`` (a goal reached, a gesture or touch addressed to them)?"""
    return (spec is not None and person is not None and spec.target == person and spec.target_person
            and spec.target_role in FACING_ROLES and spec.target_side not in SIDEWAYS)


def turn_away(prev: MotionSpec | None, spec: MotionSpec, leaving: C, source: ClipSource[C], *,
              character: str | None = None) -> list[C]:
    """``[the turning clip]`` when ``spec`` (played by ``leaving``) walks or runs away from the person ``prev``
    faced (花子に手を振って、立ち去る); else ``[]`` (also when the database has no such clip)."""
    if not (spec.target_role == "source" and spec.target_person and leaving.cyclic and leaving.body_part is None
            and faces(prev, spec.target)):
        return []
    hits = [c for c in source.by_verb(TURN_VERB, prefer_character=character) if c.body_part is None and not c.cyclic]
    return hits[:1]
