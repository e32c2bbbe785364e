"""Cleaning a captured clip's foot contacts: a planted foot stays where it was put.

Capture carries marker noise and a little sliding of planted feet (a few cm/s,
more at heel strike and toe-off), which retargeting keeps in proportion. For
every contact interval of each foot (:func:`core.contacts.detect_contacts`)
the ball of the foot (the toe joint)'s horizontal position is pinned to where
it is at the interval's slowest frame: the ankle is moved by the same horizontal offset
(two-bone leg IK, :func:`core.ik.leg_ik`) and the foot gets its world rotation
back, so heel and toe roll as captured while the foot does not slide. The
offset eases in and out over :data:`RAMP` frames on either side (smoothstep),
so a foot lifting off is not jerked. Nothing else changes.

:func:`clear_floor` then lifts a foot whose ankle or ball dips below ``y = 0``
(marker noise at a hard landing) by as much, eased over :data:`RAMP` frames
either side, the same way (leg IK, foot rotation kept), and a hand whose wrist
or finger joints do (picking up from the floor: the finger joint 1.4 cm under
it) by arm IK, the hand's world rotation kept.

:func:`lift_swings` keeps a swinging foot off the floor: on frames where a
foot is not in contact and its ball moves faster than the contact detector's
speed (:data:`core.contacts.SPEED_THRESHOLD`), the ball is kept at least
:data:`SWING_CLEARANCE` above its planted height (:data:`core.floor.FOOT_CLEARANCE`),
lifted by leg IK as :func:`clear_floor` does. Capture brushes the floor there
(a dancer's sliding foot, a kick's follow-through, a thrower's trailing foot:
the ball 2.3-3.3 cm above the floor, under its own planted height, at
0.5-1.2 m/s), which is a foot sliding on the floor, i.e. skating.

Shapes: positions ``(T, J, 3)`` metres; offsets ``(T, 2)`` (x, z).
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import SPEED_THRESHOLD, detect_contacts, horizontal_speed
from text2anim.core.floor import FOOT_CLEARANCE
from text2anim.core.ik import arm_ik, leg_ik, set_world_rotation
from text2anim.core.motion import Motion

#: Frames over which the pinning offset eases in before a contact and out after it.
RAMP = 3
#: How far a swinging foot's ball stays above its planted height (m): the minimum toe clearance
#: of human gait, 1-2 cm between the shoe's tip and the floor (Winter 1992: 1.29 +- 0.45 cm).
SWING_CLEARANCE = 0.015


def _smooth(u: np.ndarray) -> np.ndarray:
    return u * u * (3 - 2 * u)


def pin_offsets(joint: np.ndarray, speed: np.ndarray, intervals: list[tuple[int, int]]) -> np.ndarray:
    """Horizontal offsets ``(T, 2)`` that hold ``joint`` ``(T, 3)`` still over each interval (``speed`` ``(T,)``).

    Inside ``[a, b)`` the offset moves the joint to its position at the interval's slowest frame;
    over :data:`RAMP` frames before and after, the first and last offsets fade in and out.
    """
    T = len(joint)
    off = np.zeros((T, 2))
    weight = np.zeros(T)
    inside = np.zeros(T, dtype=bool)
    fade = _smooth(np.arange(1, RAMP + 1) / (RAMP + 1))  # rising towards the contact
    for a, b in intervals:
        k = a + int(np.argmin(speed[a:b]))
        d = joint[k, [0, 2]] - joint[a:b][:, [0, 2]]
        off[a:b], weight[a:b], inside[a:b] = d, 1.0, True
        for i, w in enumerate(fade):  # before a: frames a-RAMP .. a-1; after b: b .. b+RAMP-1
            for t, dd, ww in ((a - RAMP + i, d[0], w), (b + RAMP - 1 - i, d[-1], w)):
                if 0 <= t < T and not inside[t] and ww > weight[t]:
                    off[t], weight[t] = dd * ww, ww
    return off


def lock_feet(motion: Motion) -> Motion:
    """``motion`` with each planted foot held still (see the module docstring)."""
    contacts = detect_contacts(motion)
    bm = body_map(motion.skeleton)
    pos = motion.positions
    world = motion.pose.quaternions()
    out = motion
    for side, (ankle, toe) in bm.feet.items():
        speed = horizontal_speed(pos[:, [toe]], motion.fps)[:, 0]
        off = pin_offsets(pos[:, toe], speed, contacts.intervals(side))
        mask = np.any(off != 0.0, axis=1)
        if not mask.any():
            continue
        target = pos[:, ankle].copy()
        target[:, [0, 2]] += off
        out = leg_ik(out, side, target, mask=mask)
        out = set_world_rotation(out, ankle, world[:, ankle], mask=mask)
    return out


def lift_offsets(deficit: np.ndarray) -> np.ndarray:
    """``deficit`` ``(T,)`` (metres below the floor, 0 where above) spread over :data:`RAMP` frames
    either side: the largest of the neighbours' deficits, each scaled by a smoothstep of its distance."""
    T = len(deficit)
    out = deficit.copy()
    for k in range(1, RAMP + 1):
        w = _smooth(np.array(1.0 - k / (RAMP + 1)))
        out[k:] = np.maximum(out[k:], w * deficit[:T - k])
        out[:T - k] = np.maximum(out[:T - k], w * deficit[k:])
    return out


def _subtree(parents: np.ndarray, root: int) -> list[int]:
    """``root`` and every joint below it."""
    out = [root]
    for j in range(root + 1, len(parents)):
        if parents[j] in out:
            out.append(j)
    return out


def _lift(motion: Motion, limbs: list, deficits: list[np.ndarray]) -> Motion:
    """``motion`` with each limb's end joint raised by its ``(T,)`` deficit (m), eased (:func:`lift_offsets`)
    and solved by the limb's IK (``limbs``: ``(ik, side, end joint)``), the end's world rotation kept."""
    pos = motion.positions
    world = motion.pose.quaternions()
    out = motion
    for (ik, side, end), deficit in zip(limbs, deficits):
        if not deficit.any():
            continue
        lift = lift_offsets(deficit)
        target = pos[:, end].copy()
        target[:, 1] += lift
        mask = lift > 0
        out = ik(out, side, target, mask=mask)
        out = set_world_rotation(out, end, world[:, end], mask=mask)
    return out


def clear_floor(motion: Motion) -> Motion:
    """``motion`` with no ankle, toe, wrist or finger joint below ``y = 0`` (see the module docstring)."""
    bm = body_map(motion.skeleton)
    y = motion.positions[..., 1]
    limbs = [(leg_ik, side, ankle, [ankle, toe]) for side, (ankle, toe) in bm.feet.items()]
    limbs += [(arm_ik, side, wrist, _subtree(motion.skeleton.parents, wrist)) for side, wrist in bm.hands.items()]
    deficits = [np.maximum(0.0, -y[:, joints].min(axis=1)) for *_, joints in limbs]
    return _lift(motion, [limb[:3] for limb in limbs], deficits)


def lift_swings(motion: Motion) -> Motion:
    """``motion`` with no swinging foot's ball under its planted height + :data:`SWING_CLEARANCE` (docstring)."""
    contacts = detect_contacts(motion)
    bm = body_map(motion.skeleton)
    pos = motion.positions
    limbs: list = []
    deficits: list[np.ndarray] = []
    for side, (ankle, toe) in bm.feet.items():
        swinging = ~contacts.of(side) & (horizontal_speed(pos[:, toe], motion.fps) > SPEED_THRESHOLD)
        low = np.maximum(0.0, FOOT_CLEARANCE + SWING_CLEARANCE - pos[:, toe, 1])
        limbs.append((leg_ik, side, ankle))
        deficits.append(np.where(swinging, low, 0.0))
    return _lift(motion, limbs, deficits)
