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

:func:`keep_clearance` gives a swinging foot back the height the capture gave it:
the built-in character's foot is longer than a CMU subject's (its ball 13 cm in
front of the ankle and 5.5 cm under it, against 11 and 2.5), so the world rotations
carried over put a pointed foot's ball lower than the capture did (the kick's
stepping foot 0.4-3.7 cm up at 2-3 m/s where the capture's was 2.4-3.8): GMD's
figure counts that as skating (kick 0.15 -> 0.25, walk 0.21 -> 0.30).

Feet and hands kept above the floor and swinging feet clear of it are
:mod:`core.clearance` (the engines apply the swing rule to joined motion too).

Shapes: positions ``(T, J, 3)`` metres; offsets ``(T, 2)`` (x, z).
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.clearance import lift
from text2anim.core.contacts import FootContacts, detect_contacts, horizontal_speed
from text2anim.core.easing import smoothstep
from text2anim.core.floor import lowest_foot_heights
from text2anim.core.metrics import SKATE_SPEED
from text2anim.core.ik import leg_ik, set_world_rotation
from text2anim.core.motion import Motion

#: Frames over which the pinning offset eases in before a contact and out after it.
RAMP = 3


def pin_offsets(joint: np.ndarray, speed: np.ndarray, intervals: list[tuple[int, int]]) -> np.ndarray:
    """Horizontal offsets ``(T, 2)`` that hold ``joint`` ``(T, 3)`` still over each interval (``speed`` ``(T,)``).

    Inside ``[a, b)`` the offset moves the joint to its position at the interval's slowest frame;
    over :data:`RAMP` frames before and after, the first and last offsets fade in and out.
    """
    T = len(joint)
    off = np.zeros((T, 2))
    weight = np.zeros(T)
    inside = np.zeros(T, dtype=bool)
    fade = smoothstep(np.arange(1, RAMP + 1) / (RAMP + 1))  # rising towards the contact
    for a, b in intervals:
        k = a + int(np.argmin(speed[a:b]))
        d = joint[k, [0, 2]] - joint[a:b][:, [0, 2]]
        off[a:b], weight[a:b], inside[a:b] = d, 1.0, True
        for i, w in enumerate(fade):  # before a: frames a-RAMP .. a-1; after b: b .. b+RAMP-1
            for t, dd, ww in ((a - RAMP + i, d[0], w), (b + RAMP - 1 - i, d[-1], w)):
                if 0 <= t < T and not inside[t] and ww > weight[t]:
                    off[t], weight[t] = dd * ww, ww
    return off


def lock_feet(motion: Motion, contacts: FootContacts | None = None) -> Motion:
    """``motion`` with each planted foot held still (see the module docstring); ``contacts``: where the
    feet are planted when not as detected on ``motion`` itself (a clip whose hips were moved after)."""
    contacts = contacts if contacts is not None else detect_contacts(motion)
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


def keep_clearance(motion: Motion, capture: Motion) -> Motion:
    """``motion`` (the capture retargeted, frame for frame) with each swinging foot (not in contact, faster
    than GMD's 0.5 m/s, the other foot planted) lifted where its ball is lower above the motion's lowest
    foot point than the capture's ball was above the capture's (the heights GMD's figure reads; leg IK,
    eased, the foot's world rotation kept: :func:`core.clearance.lift`); planted feet, a run's flight
    (lifting the lower foot there would lengthen it) and everything above the knees are left as they are."""
    contacts = detect_contacts(motion)
    mine, theirs = body_map(motion.skeleton).feet, body_map(capture.skeleton).feet
    rise = lowest_foot_heights(motion).min() - lowest_foot_heights(capture).min()  # m: the floors GMD reads
    pos = motion.positions
    limbs, deficits = [], []
    for side, (ankle, toe) in mine.items():
        other = contacts.of("right" if side == "left" else "left")
        swinging = ~contacts.of(side) & other & (horizontal_speed(pos[:, [toe]], motion.fps)[:, 0] > SKATE_SPEED)
        deficit = capture.positions[:, theirs[side][1], 1] + rise - pos[:, toe, 1]  # (T,) m
        limbs.append((leg_ik, side, ankle))
        deficits.append(np.where(swinging, np.maximum(0.0, deficit), 0.0))
    return lift(motion, limbs, deficits)
