"""A body's size: its leg length, and measuring a body of any size as a human-sized one.

The figures of docs/timetable.md §3 hold lengths in metres that are a human body's (a foot
within 5 cm of the floor is low, 0.5 m/s is a slide): a 0.2 m character's feet are always
"low", a 20 m giant's never. :func:`at_human_size` scales such a body to :data:`HUMAN_LEG`
before it is measured, so that a character of any size is held to the same figures.
"""
from __future__ import annotations

import numpy as np

from .bodyparts import BodyMapError, body_map
from .motion import Motion
from .skeleton import Skeleton

#: Leg length (m) of the built-in 1.70 m body: hip joints above the lowest foot joint at rest.
HUMAN_LEG = 0.86
#: Leg lengths within this factor of :data:`HUMAN_LEG` are people (a child, a tall adult) and
#: are measured as they are; beyond it a body is measured scaled to :data:`HUMAN_LEG`.
HUMAN_RANGE = 1.5


def leg_length(skel: Skeleton) -> float:
    """Rest-pose height (metres) of the hip joints above the lowest foot joint.

    The hip joints are the knees' parents, the knees the ankles' parents (:func:`core.bodyparts.body_map`'s
    feet). Raises :class:`BodyMapError` without two such legs, or when the hips are not above the feet. Found
    once per skeleton (kept in ``skel.derived``: every new motion's airborne test and adaptation asks for it).
    """
    return skel.derived.get(("leg_length",), lambda: _leg_length(skel))


def _leg_length(skel: Skeleton) -> float:
    feet = body_map(skel).feet
    rest = skel.rest_positions()
    hips, soles = [], []
    for side in ("left", "right"):
        ankle, toe = feet[side]
        knee = int(skel.parents[ankle])
        hip = int(skel.parents[knee]) if knee >= 0 else -1
        if knee < 0 or hip < 0:
            raise BodyMapError(f"the {side} leg has no knee and hip above its ankle")
        hips.append(rest[hip, 1])
        soles += [rest[ankle, 1], rest[toe, 1]]
    length = float(np.mean(hips) - min(soles))
    if not length > 1e-6:
        raise BodyMapError("the skeleton's hips are not above its feet in the rest pose")
    return length


def human_scale(motion: Motion) -> float:
    """:data:`HUMAN_LEG` / the body's :func:`leg_length`: lengths times this are at a person's size (1 for
    a skeleton whose legs cannot be found)."""
    try:
        return HUMAN_LEG / leg_length(motion.skeleton)
    except BodyMapError:
        return 1.0


def at_human_size(motion: Motion) -> tuple[Motion, float]:
    """``(motion, k)``: ``motion`` scaled by ``k`` to a human leg length when its body is outside
    :data:`HUMAN_RANGE` of :data:`HUMAN_LEG` (``k`` = 1 and the motion as it is otherwise, or when
    its legs cannot be found)."""
    try:
        leg = leg_length(motion.skeleton)
    except BodyMapError:
        return motion, 1.0
    if 1.0 / HUMAN_RANGE <= leg / HUMAN_LEG <= HUMAN_RANGE:
        return motion, 1.0
    from .conventions import scaled  # scipy: not on the paths that only read a size (seeding a database)

    k = HUMAN_LEG / leg
    return scaled(motion, k), k
