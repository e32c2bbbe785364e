"""Placing whole actors so the relations hold: one rigid ground move per actor (:class:`core.ground.Rigid`).

Each actor's motion was synthesised on its own track from its default spot; moving all of it by a yaw and a
ground translation changes nothing of the motion itself (feet, joins, quality figures stay as they are) and
puts it where the text wants it. The relations that place a body (a goal, a source, a partner, a patient,
a recipient) are taken first, then those that only turn it (an addressee), each group in time order: the
first places its actor where the default staging put them and the other relative to them; a later relation
places whichever of its two actors is still free, relative to the placed one. An approach between two
actors already placed turns on its way: the walk is steered towards the other over its first half, about
the foot on the floor (:func:`core.steer.steer`); any other relation between placed actors is only
measured (:class:`~scene.types.Met`). So 太郎は花子に手を振った。それから花子に近づいた。 puts 花子 where
his walk ends, and his wave, earlier, is towards her there. Actors no relation places keep their default spot, moved aside
(:data:`ASIDE`) while they would stand within :data:`CLEARANCE` of a placed actor.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from text2anim.core.ground import Rigid, match, wrap_angle
from text2anim.core.motion import Motion
from text2anim.core.steer import steer

from .bodies import forward, hand, hands, heading_to, hips_path, toe
from .types import Kick, Met, Relation

#: m: actors closer than this (hips, any frame) stand inside each other.
CLEARANCE = 0.55
#: m: how far an unplaced actor is moved aside at a time while too close.
ASIDE = 1.5


#: Below this (deg) an approach between placed actors is not steered.
STEER_MIN_DEG = 8.0


def fit(motions: dict[str | None, Motion], rels: Sequence[Relation], kicks: Sequence[Kick] = ()
        ) -> tuple[dict[str | None, Motion], dict[str | None, Rigid], list[Met]]:
    """Each actor's motion (steered where an approach turns on its way, or a kick would strike where
    someone else stands: :func:`_clear_kick`), one :class:`Rigid` per actor (identity for those no relation
    moves) and how well each relation holds after all moves."""
    motions = dict(motions)
    rigids: dict[str | None, Rigid] = {}
    pairs = {frozenset((r.actor, r.other)) for r in rels if _together(r)}
    for rel in sorted(rels, key=lambda r: (r.role == "addressee", not _together(r), r.time, r.element)):
        a, b = rel.actor, rel.other
        if a in rigids and b in rigids:
            if rel.role == "goal" and rel.start is not None and frozenset((a, b)) not in pairs:
                motions[a] = _steered(motions, rigids, rel)  # (steering partners would part them again)
            continue
        if a not in rigids and b not in rigids:
            rigids[a] = Rigid()
        if a in rigids:
            if rel.role == "goal" and rel.start is not None:
                motions[a] = _around(motions, rigids, rel)
            rigids[b] = _hand_to_hand(motions, rigids, rel, b, _place_other(motions, rigids, rel))
        else:
            rigids[a] = _hand_to_hand(motions, rigids, rel, a, _place_actor(motions, rigids, rel))
    for name in motions:
        if name not in rigids:
            rigids[name] = _aside(motions, rigids, name)
    for kick in kicks:
        if kick.actor in motions:
            motions[kick.actor] = _clear_kick(motions, rigids, kick)
    return motions, rigids, [measure(motions, rigids, rel) for rel in rels]


def _together(rel: Relation) -> bool:
    """Partners side by side (太郎は花子と一緒に歩いた): placed first, so that what comes before (his approach)
    is steered to where they set off together rather than turning her to face him, and their walk apart."""
    return rel.role == "partner" and rel.kind == "beside"


def _clear_kick(motions, rigids, kick: Kick) -> Motion:
    """The kicker's motion with its kick steered (:data:`DETOURS`, from the frame it sets off) so that the
    thing it kicks lies no closer than :data:`CLEARANCE` to anyone else's hips while it waits to be kicked,
    and the kicker passes no one closer than that; unchanged when it is clear or no turn clears it. Placed
    facing someone who has just walked up to her, a kick with a run-up struck the ball at his feet."""
    m, rigid = motions[kick.actor], rigids[kick.actor]
    others = [o for o in motions if o != kick.actor]
    if not others or not 0 <= kick.hit < m.n_frames:
        return m
    paths = {o: rigids[o].apply_points(hips_path(motions[o])[0]) for o in others}
    f0 = setting_off(m, kick.start)

    def clear(motion: Motion) -> bool:
        ball = rigid.apply_points(toe(motion, kick.side)[kick.hit])
        mine = rigid.apply_points(hips_path(motion)[0])
        return all(_min_distance(path[:kick.hit + 1], np.broadcast_to(ball, (kick.hit + 1, 3))) >= CLEARANCE
                   and _min_distance(path[f0:], mine[f0:]) >= CLEARANCE for path in paths.values())

    if clear(m):
        return m
    for deg in DETOURS:
        turned = steer(m, f0, f0 + int(0.6 * m.fps), np.radians(deg))
        if clear(turned):
            return turned
    return m


#: deg: the turns tried, in order, to lead an approach around the people in its way.
DETOURS = (30.0, -30.0, 50.0, -50.0, 70.0, -70.0, 90.0, -90.0, 120.0, -120.0)


def _around(motions, rigids, rel: Relation) -> Motion:
    """The actor's motion with its approach steered (:data:`DETOURS`) so it passes no placed person closer than
    :data:`CLEARANCE` (the one it goes to is placed where it ends); unchanged when its way is clear or no
    turn clears it."""
    m = motions[rel.actor]
    others = [o for o in rigids if o not in (rel.actor, rel.other)]
    if not others:
        return m
    f1 = int(round(rel.time * m.fps)) + 1
    f0 = setting_off(m, int(round(float(rel.start or 0.0) * m.fps)))

    def clear(motion: Motion) -> bool:
        path = rigids[rel.actor].apply_points(hips_path(motion)[0][f0:f1])
        return all(_min_distance(path, rigids[o].apply_points(hips_path(motions[o])[0][f0:f1])) >= CLEARANCE
                   for o in others)

    if clear(m):
        return m
    half = max(int(round(0.5 * (f0 + f1))), f0 + int(0.6 * m.fps))
    for deg in DETOURS:
        turned = steer(m, f0, half, np.radians(deg))
        if clear(turned):
            return turned
    return m


def _steered(motions, rigids, rel: Relation) -> Motion:
    """The actor's motion with its approach (``rel.start`` to ``rel.time``) turned towards the other over its
    first half, so it heads for where the other stands when it arrives."""
    m = motions[rel.actor]
    start = float(rel.start or 0.0)
    p0, _ = _at(m, rigids[rel.actor], start)
    p1, _ = _at(m, rigids[rel.actor], rel.time)
    goal, _ = _at(motions[rel.other], rigids[rel.other], rel.time)
    turn = float(wrap_angle(heading_to(p0, goal) - heading_to(p0, p1)))
    if abs(np.degrees(turn)) < STEER_MIN_DEG or np.hypot(*(p1 - p0)[[0, 2]]) < 0.3:
        return m
    f0 = setting_off(m, int(round(start * m.fps)))
    f1 = int(round(0.5 * (f0 / m.fps + rel.time) * m.fps))
    return steer(m, f0, max(f1, f0 + int(0.6 * m.fps)), turn)


#: m/s: below this the hips stand still (an approach sets off after it).
STILL = 0.2


def arrival(m: Motion, t: float) -> float:
    """When an approach whose row ends at ``t`` s has arrived: the first frame from ``t`` on, at most 2 s later,
    at which the hips stand still (a run into a hug slows on through the hug's first steps), s."""
    path = hips_path(m)[0]
    speed = np.linalg.norm(np.diff(path[:, [0, 2]], axis=0), axis=1) * m.fps
    f = int(np.clip(round(t * m.fps), 0, len(speed)))
    still = np.nonzero(speed[f:f + int(2 * m.fps)] < STILL)[0]
    return (f + int(still[0])) / m.fps if len(still) else t


def setting_off(m: Motion, f: int) -> int:
    """The frame an approach whose row plays from ``f`` sets off: the last frame, at most a second before
    ``f``, at which the hips stood still (a join may have started the walk before its row)."""
    path = hips_path(m)[0]
    speed = np.linalg.norm(np.diff(path[:, [0, 2]], axis=0), axis=1) * m.fps
    lo = max(0, f - int(m.fps))
    still = np.nonzero(speed[lo:max(lo, min(f, len(speed)))] < STILL)[0]
    return lo + int(still[-1]) + 1 if len(still) else lo


def _at(motion: Motion, rigid: Rigid, time: float, span: tuple[float, float] | None = None) -> tuple[np.ndarray, float]:
    """The hips' floor point ``(3,)`` of ``motion`` at ``time`` s after ``rigid``, and its heading then (or
    its mean heading over ``span`` s: a throw's wind-up turns the body away and back)."""
    path, heading = hips_path(motion)
    f = int(np.clip(round(time * motion.fps), 0, len(path) - 1))
    h = float(heading[f])
    if span is not None:
        lo, hi = (int(np.clip(round(t * motion.fps), 0, len(path) - 1)) for t in span)
        h = float(np.arctan2(np.sin(heading[lo:hi + 1]).mean(), np.cos(heading[lo:hi + 1]).mean()))
    return rigid.apply_points(path[f]), h + rigid.yaw


def _hand_to_hand(motions, rigids, rel: Relation, free: str | None, rigid: Rigid) -> Rigid:
    """``rigid`` (the move of the actor ``free`` that the relation placed) slid over the floor so that, at the
    relation's time, its hand meets the placed one's (:attr:`Relation.hands`); ``rigid`` without hands."""
    if rel.hands is None:
        return rigid
    placed = rel.other if free == rel.actor else rel.actor
    mine, theirs = (rel.hands[0], rel.hands[1]) if free == rel.actor else (rel.hands[1], rel.hands[0])
    f = int(np.clip(round(rel.time * motions[free].fps), 0, motions[free].n_frames - 1))
    here = rigid.apply_points(_effector(motions[free], mine)[f])
    there = rigids[placed].apply_points(_effector(motions[placed], theirs)[f])
    return Rigid(rigid.yaw, (rigid.offset[0] + float(there[0] - here[0]), rigid.offset[1] + float(there[2] - here[2])))


def _effector(m: Motion, effector: str) -> np.ndarray:
    return hands(m) if effector == "both_hands" else hand(m, effector.split("_")[0])


def _actor_at(motions, rigids, rel: Relation) -> tuple[np.ndarray, float]:
    """The relation's placed actor's hips and facing at its time (its own ``facing`` where set)."""
    rigid = rigids[rel.actor]
    p, h = _at(motions[rel.actor], rigid, rel.time, rel.span)
    return p, (h if rel.facing is None else rel.facing + rigid.yaw)


def _move_to(motion: Motion, rel: Relation, point: np.ndarray, heading: float, own: float | None = None) -> Rigid:
    """The move that puts ``motion``'s hips over ``point`` at the relation's time, facing ``heading`` (over
    its span; ``own``: the facing to turn, where the motion's own heading is not it)."""
    p, h = _at(motion, Rigid(), rel.time, rel.span)
    return match(p, h if own is None else own, point, heading)


def _place_other(motions, rigids, rel: Relation) -> Rigid:
    """``rel.other`` placed relative to the placed ``rel.actor``."""
    p, h = _actor_at(motions, rigids, rel)
    fwd, left = forward(h), forward(h + np.pi / 2)
    other = motions[rel.other]
    if rel.kind == "face":
        return _move_to(other, rel, p + rel.distance * fwd, h + np.pi)
    if rel.kind == "behind":  # the actor behind the other: the other ahead, facing the same way
        return _move_to(other, rel, p + rel.distance * fwd, h)
    if rel.kind == "beside":  # the actor on the other's left: the other on the actor's right
        return _move_to(other, rel, p - rel.distance * left, h)
    return _move_to(other, rel, p - rel.distance * fwd, h)  # away: the other behind, watching


def _place_actor(motions, rigids, rel: Relation) -> Rigid:
    """``rel.actor`` placed relative to the placed ``rel.other``."""
    p, h = _at(motions[rel.other], rigids[rel.other], rel.time, rel.span)
    fwd, left = forward(h), forward(h + np.pi / 2)
    mine, own = motions[rel.actor], rel.facing
    if rel.kind == "face":
        return _move_to(mine, rel, p + rel.distance * fwd, h + np.pi, own)
    if rel.kind == "behind":
        return _move_to(mine, rel, p - rel.distance * fwd, h, own)
    if rel.kind == "beside":
        return _move_to(mine, rel, p + rel.distance * left, h, own)
    return _move_to(mine, rel, p + rel.distance * fwd, h, own)


def measure(motions, rigids, rel: Relation) -> Met:
    """The hips' distance and the actor's heading error for ``rel`` as placed."""
    pa, ha = _actor_at(motions, rigids, rel)
    pb, hb = _at(motions[rel.other], rigids[rel.other], rel.time, rel.span)
    if rel.kind == "face":
        want = heading_to(pa, pb)
    elif rel.kind == "away":
        want = heading_to(pb, pa)
    else:
        want = hb
    return Met(rel, float(np.hypot(*(pa - pb)[[0, 2]])), float(np.degrees(abs(wrap_angle(ha - want)))))


def _aside(motions, rigids, name) -> Rigid:
    """An unplaced actor's move: none, or sideways along +X until clear of every placed actor."""
    mine = hips_path(motions[name])[0]
    for k in range(12):
        rigid = Rigid(0.0, (k * ASIDE, 0.0))
        path = rigid.apply_points(mine)
        if all(_min_distance(path, rigids[o].apply_points(hips_path(motions[o])[0])) >= CLEARANCE
               for o in rigids):
            return rigid
    return Rigid()


def _min_distance(a: np.ndarray, b: np.ndarray) -> float:
    n = min(len(a), len(b))
    return float(np.min(np.hypot(a[:n, 0] - b[:n, 0], a[:n, 2] - b[:n, 2]))) if n else np.inf
