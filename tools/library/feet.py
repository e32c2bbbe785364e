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

Feet and hands kept above the floor and swinging feet clear of it are
:mod:`core.clearance` (the engines apply the swing rule to joined motion too).

Shapes: positions ``(T, J, 3)`` metres; offsets ``(T, 2)`` (x, z).
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import FootContacts, detect_contacts, horizontal_speed
from text2anim.core.easing import smoothstep
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
