"""Limbs kept above the floor, and swinging feet clear of it, by IK.

:func:`clear_floor` lifts a foot whose ankle or ball dips below ``y = 0``
(marker noise at a hard landing) by as much, eased over :data:`RAMP` frames
either side (two-bone leg IK, :func:`core.ik.leg_ik`, the foot's world rotation
kept), and a hand whose wrist or finger joints do (picking up from the floor:
the finger joint 1.4 cm under it) by arm IK, the hand's world rotation kept.

:func:`lift_swings` keeps a swinging foot off the floor: on frames where a
foot is not in contact and its ball moves faster than the contact detector's
speed (:data:`core.contacts.SPEED_THRESHOLD`), the ball is kept at least
:data:`SWING_CLEARANCE` above its planted height (:data:`core.floor.FOOT_CLEARANCE`),
lifted the same way. Capture brushes the floor there (a dancer's sliding
foot, a kick's follow-through, a thrower's trailing foot: the ball 2.3-3.3 cm
above the floor, under its own planted height, at 0.5-1.2 m/s), and a join can
carry a swinging foot that low (a root offset decaying into the next clip
while a foot lock is released): a foot sliding on the floor, i.e. skating.
The built-in library's build and every engine's last step apply it.

Shapes: positions ``(T, J, 3)`` metres; deficits and lifts ``(T,)`` metres.
"""
from __future__ import annotations

import numpy as np

from .bodyparts import body_map
from .contacts import SPEED_THRESHOLD, detect_contacts, horizontal_speed
from .easing import smoothstep
from .floor import FOOT_CLEARANCE
from .ik import arm_ik, leg_ik, set_world_rotation
from .motion import Motion

#: Frames over which a lift eases in before the frames that need it and out after them.
RAMP = 3
#: How far a swinging foot's ball stays above its planted height (m): the minimum toe clearance
#: of human gait, 1-2 cm between the shoe's tip and the floor (Winter 1992: 1.29 +- 0.45 cm).
SWING_CLEARANCE = 0.015


def lift_offsets(deficit: np.ndarray) -> np.ndarray:
    """``deficit`` ``(T,)`` (metres below the floor, 0 where above) spread over :data:`RAMP` frames
    either side: the largest of the neighbours' deficits, each scaled by a smoothstep of its distance."""
    T = len(deficit)
    out = deficit.copy()
    for k in range(1, RAMP + 1):
        w = smoothstep(np.array(1.0 - k / (RAMP + 1)))
        out[k:] = np.maximum(out[k:], w * deficit[:T - k])
        out[:T - k] = np.maximum(out[:T - k], w * deficit[k:])
    return out


def lift(motion: Motion, limbs: list, deficits: list[np.ndarray]) -> Motion:
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
    limbs += [(arm_ik, side, wrist, [int(j) for j in motion.skeleton.subtree(wrist)]) for side, wrist in bm.hands.items()]
    deficits = [np.maximum(0.0, -y[:, joints].min(axis=1)) for *_, joints in limbs]
    return lift(motion, [limb[:3] for limb in limbs], deficits)


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
    return lift(motion, limbs, deficits)
