"""Placing whole actors so the relations hold: one rigid ground move per actor (:class:`core.ground.Rigid`).

Each actor's motion was synthesised on its own track from its default spot; moving all of it by a yaw and a
ground translation changes nothing of the motion itself (feet, joins, quality figures stay as they are) and
puts it where the text wants it. The relations are taken in time order: the first places its actor where
the default staging put them and the other relative to them; a later relation places whichever of its two
actors is still free, relative to the placed one; a relation between two actors already placed is only
measured (:class:`~scene.types.Met`). Actors no relation places keep their default spot, moved aside
(:data:`ASIDE`) while they would stand within :data:`CLEARANCE` of a placed actor.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from text2anim.core.ground import Rigid, match, wrap_angle
from text2anim.core.motion import Motion

from .bodies import forward, heading_to, hips_path
from .types import Met, Relation

#: m: actors closer than this (hips, any frame) stand inside each other.
CLEARANCE = 0.55
#: m: how far an unplaced actor is moved aside at a time while too close.
ASIDE = 1.5


def fit(motions: dict[str | None, Motion], rels: Sequence[Relation]) -> tuple[dict[str | None, Rigid], list[Met]]:
    """One :class:`Rigid` per actor of ``motions`` (identity for those no relation moves) and how well each
    relation holds after all moves."""
    rigids: dict[str | None, Rigid] = {}
    for rel in rels:
        a, b = rel.actor, rel.other
        if a in rigids and b in rigids:
            continue
        if a not in rigids and b not in rigids:
            rigids[a] = Rigid()
        if a in rigids:
            rigids[b] = _place_other(motions, rigids, rel)
        else:
            rigids[a] = _place_actor(motions, rigids, rel)
    for name in motions:
        if name not in rigids:
            rigids[name] = _aside(motions, rigids, name)
    return rigids, [measure(motions, rigids, rel) for rel in rels]


def _at(motion: Motion, rigid: Rigid, time: float) -> tuple[np.ndarray, float]:
    """The hips' floor point ``(3,)`` and heading of ``motion`` at ``time`` s after ``rigid``."""
    path, heading = hips_path(motion)
    f = int(np.clip(round(time * motion.fps), 0, len(path) - 1))
    return rigid.apply_points(path[f]), float(heading[f] + rigid.yaw)


def _move_to(motion: Motion, time: float, point: np.ndarray, heading: float) -> Rigid:
    """The move that puts ``motion``'s hips over ``point`` facing ``heading`` at ``time``."""
    p, h = _at(motion, Rigid(), time)
    return match(p, h, point, heading)


def _place_other(motions, rigids, rel: Relation) -> Rigid:
    """``rel.other`` placed relative to the placed ``rel.actor``."""
    p, h = _at(motions[rel.actor], rigids[rel.actor], rel.time)
    fwd, left = forward(h), forward(h + np.pi / 2)
    if rel.kind == "face":
        return _move_to(motions[rel.other], rel.time, p + rel.distance * fwd, h + np.pi)
    if rel.kind == "behind":  # the actor behind the other: the other ahead, facing the same way
        return _move_to(motions[rel.other], rel.time, p + rel.distance * fwd, h)
    if rel.kind == "beside":  # the actor on the other's left: the other on the actor's right
        return _move_to(motions[rel.other], rel.time, p - rel.distance * left, h)
    return _move_to(motions[rel.other], rel.time, p - rel.distance * fwd, h)  # away: the other behind, watching


def _place_actor(motions, rigids, rel: Relation) -> Rigid:
    """``rel.actor`` placed relative to the placed ``rel.other``."""
    p, h = _at(motions[rel.other], rigids[rel.other], rel.time)
    fwd, left = forward(h), forward(h + np.pi / 2)
    if rel.kind == "face":
        return _move_to(motions[rel.actor], rel.time, p + rel.distance * fwd, h + np.pi)
    if rel.kind == "behind":
        return _move_to(motions[rel.actor], rel.time, p - rel.distance * fwd, h)
    if rel.kind == "beside":
        return _move_to(motions[rel.actor], rel.time, p + rel.distance * left, h)
    return _move_to(motions[rel.actor], rel.time, p + rel.distance * fwd, h)


def measure(motions, rigids, rel: Relation) -> Met:
    """The hips' distance and the actor's heading error for ``rel`` as placed."""
    pa, ha = _at(motions[rel.actor], rigids[rel.actor], rel.time)
    pb, hb = _at(motions[rel.other], rigids[rel.other], rel.time)
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
