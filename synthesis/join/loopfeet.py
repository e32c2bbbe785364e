"""The legs of a looped cycle kept as captured (:func:`plant_cycle`).

:func:`synthesis.join.cycles.make_cyclic` closes a gait cycle by spreading the
mismatch of its two ends (local rotations, hips' height) over the cycle. A
captured cycle rarely closes exactly (a CMU run of one stride: the knee 29°
apart at its two landings, the hips 3 cm lower), and the spread correction
bends the stance leg of every frame, so its foot slides, and lowers the swing
foot, so it skims the floor: looped, the 127_07 run skated on 20 % of its
frames (GMD rule) where the captured stride skates on none.

:func:`plant_cycle` puts both legs back on the captured cycle by IK on every
frame: each ankle on its captured position and world orientation (so toe and
heel follow, and a foot rolls as captured), the hips and upper body keeping
the correction. Each foot's own seam mismatch (where the next cycle's first
frame has it against where the cycle's end is heading) is taken up while that
foot is in the air — its height only where the toe is well clear of the floor,
and not for a foot standing across the seam (the strides' floors differ) — so a
foot on the ground never slides, sinks or skims it, and the loop closes.

Shapes: positions ``(T, 3)`` metres, rotations ``(T, 4)`` quaternions (x, y, z, w).
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import detect_contacts, runs
from text2anim.core.ground import Rigid
from text2anim.core.ik import set_world_rotation
from text2anim.core.motion import Motion

from .footlock import solve_leg

LOW = 0.05  # m: a toe below this is low (GMD's contact height); feet change height only above it

def swing_ramp(planted: np.ndarray) -> np.ndarray:
    """``(T,)`` from 0 to 1 over a cycle, rising only on frames the foot is in the air (flat on contact frames),
    reaching 1 on the frame after the last; linear over the cycle when the foot is never down."""
    air = ~np.asarray(planted, dtype=bool)
    if not air.any() or air.all():
        return np.arange(len(air)) / len(air)
    return np.concatenate([[0.0], np.cumsum(air)[:-1]]) / air.sum()


def lift_ramp(planted: np.ndarray, toe_height: np.ndarray) -> np.ndarray:
    """``(T,)`` from 0 to 1, rising only over the foot's last time in the air before the seam and there in
    proportion to the toe's height above :data:`LOW` (m): a change of the foot's height is made where the foot
    is high, never where it skims the floor. :func:`swing_ramp` when the toe is never that high then."""
    air = ~np.asarray(planted, dtype=bool)
    if not air.any() or air.all():
        return swing_ramp(planted)
    last = runs(air)[-1]
    inc = np.zeros(len(air))
    inc[last[0]:last[1]] = np.maximum(toe_height[last[0]:last[1]] - LOW, 0.0)
    if inc.sum() <= 1e-9:
        return swing_ramp(planted)
    return np.concatenate([[0.0], np.cumsum(inc)[:-1]]) / inc.sum()


def ankle_goals(original: Motion, planted: np.ndarray, ankle: int, toe: int, move: Rigid) -> np.ndarray:
    """Where ``ankle`` should be on each frame ``(T, 3)``: as captured, plus the seam's mismatch of that ankle
    (the next cycle's first frame, moved by ``move``, against the frame after the last) taken up while the
    foot is in the air — along the ground by :func:`swing_ramp`, in height by :func:`lift_ramp` — so it never
    slides on the ground nor skims it, and the loop closes."""
    pos = original.pose.positions
    p = pos[:, ankle]
    if len(p) < 3:
        return p
    # the frame after the last: a planted foot stays; a foot in the air moves on (central estimate)
    after = p[-1] if planted[-1] else p[-1] + 0.5 * ((p[-1] - p[-2]) + (p[1] - p[0]))
    d = move.apply_points(p[0]) - after
    goal = p + np.outer(swing_ramp(planted), d * np.array([1.0, 0.0, 1.0]))
    if not planted[-1]:  # a foot on the ground at the seam keeps its captured height (a lower next stride
        # would sink it into the floor): the difference of the two strides' floors stays at the seam
        goal[:, 1] += lift_ramp(planted, pos[:, toe, 1]) * d[1]
    return goal


def plant_cycle(motion: Motion, original: Motion, move: Rigid) -> Motion:
    """``motion`` (a corrected cycle) with each foot back on ``original``'s (the captured cycle's) path by IK:
    the ankle's position (:func:`ankle_goals`) and world orientation, so toe and heel follow; ``move`` is the
    cycle's ground move (:func:`synthesis.join.cycles.cycle_move`)."""
    if motion.n_frames < 3:
        return motion
    contacts = detect_contacts(original)
    ref = original.pose
    out = motion
    for side, (ankle, toe) in body_map(motion.skeleton).feet.items():
        goal = ankle_goals(original, contacts.of(side)[:motion.n_frames], ankle, toe, move)
        out = set_world_rotation(solve_leg(out, side, goal), ankle, ref.quaternions()[:, ankle])
    return out
