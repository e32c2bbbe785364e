"""Facing continuity: an actor who leaves the person it was facing turns its back first.

花子に手を振って、立ち去る: the wave is addressed to 花子, so the scene stands him facing her; the leaving walks
away from her (role ``source``), so at its start she is behind him. A walk cannot start by turning round on
the spot, and without a turn the scene can meet only one of the two: he waved with his back to her, or walked
through her. :func:`turn_away` gives the clip a reader pictures in between (the built-in ``turn_away``: half a
turn on the spot), which :func:`arrangement.arrange` adds as a motion of its own, as it adds posture bridges.

Only metadata is read: the two motions' targets and roles (``nlp.types.MotionSpec``) and the clips' loops.
"""
from __future__ import annotations

from text2anim.nlp.lexicon import RECEIVING_VERBS
from text2anim.nlp.types import MotionSpec

from .clips import C, ClipSource

#: The verb of the clip that turns the back on whoever was in front.
TURN_VERB = "背を向ける"
#: Verbs of going somewhere, and of coming back from there (行ったり来たり, 行って戻る): the second turns round first.
GOING_VERBS = frozenset("行く 向かう 進む".split())
BACK_VERBS = frozenset("来る 戻る 引き返す".split())
#: Roles a motion faces its target person in (the scene stands them face to face).
FACING_ROLES = frozenset(("goal", "addressee", "patient", "recipient", "partner"))
#: Sides of the target that put the actor beside or behind them, not facing them.
SIDEWAYS = frozenset(("beside", "behind", "left", "right", "around", "under", "on", "near"))


def faces(spec: MotionSpec | None, person: str | None) -> bool:
    """Does ``spec`` leave its actor facing ``person`` (a goal reached, a gesture or touch addressed to them, a
    thing received from them)?"""
    return (spec is not None and person is not None and spec.target == person and spec.target_person
            and (spec.target_role in FACING_ROLES or (spec.target_role == "source" and spec.verb in RECEIVING_VERBS))
            and spec.target_side not in SIDEWAYS)


def came_to(motions, spec: MotionSpec) -> bool:
    """Did ``spec``'s target come up to its actor earlier in the text (熊が現れた: a goal of theirs that is the
    actor)? The scene then stands them face to face, as after a goal of the actor's own."""
    return any(m.id < spec.id and m.actor == spec.target and m.target == spec.actor and m.target_role == "goal"
               for m in motions)


def comes_back(prev: MotionSpec | None, spec: MotionSpec) -> bool:
    """Does ``spec`` come back the way its actor just went (廊下を行ったり来たりした, 公園まで行って戻った):
    a verb of coming back (:data:`BACK_VERBS`) with nowhere else named, right after a going of the same actor
    (:data:`GOING_VERBS`)?"""
    return (prev is not None and prev.actor == spec.actor and prev.verb in GOING_VERBS
            and spec.verb in BACK_VERBS and spec.target is None)


def turn_away(prev: MotionSpec | None, spec: MotionSpec, leaving: C, source: ClipSource[C], *,
              character: str | None = None, met: bool = False) -> list[C]:
    """``[the turning clip]`` when ``spec`` (played by ``leaving``) walks or runs away from the person ``prev``
    faced (花子に手を振って、立ち去る), or who came up to the actor (``met``: 熊が現れた。少年は逃げ出した), or
    comes back the way ``prev`` went (:func:`comes_back`); else ``[]`` (also when the database has no such clip)."""
    away = spec.target_role == "source" and spec.target_person and (met or faces(prev, spec.target))
    if not ((away or comes_back(prev, spec)) and leaving.cyclic and leaving.body_part is None):
        return []
    hits = [c for c in source.by_verb(TURN_VERB, prefer_character=character) if c.body_part is None and not c.cyclic]
    return hits[:1]
