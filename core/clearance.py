"""Limbs kept above the floor, and swinging feet clear of it, by IK.

:func:`clear_floor` first bends the toes of a foot whose tip dips below ``y = 0`` while its ball is
about still (slower than GMD's 0.5 m/s: planted, pivoting, a dancer's pointed toe set down;
:func:`bend_toes`), then lifts a foot whose ankle, ball or toe tip still dips below it (marker noise at a
hard landing, a swinging foot's tip: lifted, it clears the floor as a swing does) by as much, eased in and
out over :data:`FLOOR_RAMP_SECONDS` (:func:`envelope`; two-bone leg IK,
:func:`core.ik.leg_ik`, the foot's world rotation kept), and a hand whose wrist, finger joints or fingertips
do (picking up from the floor: the finger joint 1.4 cm under it; a fall landing
on the hands: the fingertips 4-5 cm into it) by arm IK, the hand's world
rotation kept. The ends of the chains are the skeleton's end sites (BVH
``End Site``): a tip under the floor is as visible as a joint.

:func:`clear_swings` keeps a swinging foot off the floor: on frames where a
foot is not in contact and its ball moves faster than the contact detector's
speed (:data:`core.contacts.SPEED_THRESHOLD`), the ball is kept at least
:data:`SWING_CLEARANCE` above its planted height (:data:`core.floor.FOOT_CLEARANCE`),
lifted the same way. Capture brushes the floor there (a dancer's sliding
foot, a kick's follow-through, a thrower's trailing foot: the ball 2.3-3.3 cm
above the floor, under its own planted height, at 0.5-1.2 m/s), and a join can
carry a swinging foot that low (a root offset decaying into the next clip
while a foot lock is released): a foot sliding on the floor, i.e. skating.
The built-in library's build and every engine's last step apply it.

:func:`bend_toes` brings a toe tip that dips under the floor, its ball above it, up to the floor by
bending the toe joint, as a shoe's toe bends at the ball: the ball and the rest of the body stay where
they are, so a planted foot's contacts and the heights GMD's figure reads (joints) do not move. Capture
retargeted onto a longer foot puts the tips 1-5 cm under the floor its feet stand on (08_02_walk 4.1 cm
at toe-off, 14_29's stance 4.0); ``db import`` applies it.

:func:`keep_clearance` gives a retargeted capture's swinging feet back the height the capture gave
them. The built-in character's foot is longer than a CMU subject's (its ball 13 cm in front of the
ankle and 5.5 cm under it, against 11 and 2.5), so the world rotations carried over put a pointed
foot's ball lower than the capture did (the kick's stepping foot 0.4-3.7 cm up at 2-3 m/s where the
capture's was 2.4-3.8): GMD's figure counts that as skating (kick 0.15 -> 0.25, walk 0.21 -> 0.30).
The library's build and ``db import`` apply it after retargeting.

Shapes: positions ``(T, J, 3)`` metres; deficits and lifts ``(T,)`` metres.
"""
from __future__ import annotations

import numpy as np
from scipy.ndimage import distance_transform_edt, gaussian_filter1d, maximum_filter1d

from .bodyparts import body_map
from .contacts import SPEED_THRESHOLD, detect_contacts, horizontal_speed
from .easing import smoothstep
from .floor import FOOT_CLEARANCE, chain_lowest, lowest_foot_heights
from .ik import arm_ik, leg_ik, set_world_rotation
from .metrics import SKATE_SPEED
from .motion import Motion
from .quat import multiply
from .rotkernels import from_rotvec

#: Frames over which a lift eases in before the frames that need it and out after them.
RAMP = 3
#: How far a swinging foot's ball stays above its planted height (m): the minimum toe clearance
#: of human gait, 1-2 cm between the shoe's tip and the floor (Winter 1992: 1.29 +- 0.45 cm).
SWING_CLEARANCE = 0.015
#: Seconds over which :func:`clear_floor` eases a lift in and out (:func:`envelope`): a hand that lands
#: on the floor is lifted by up to 5 cm (its fingertips), which over :data:`RAMP` frames would stop it
#: dead (the fall's forearm: joint jerk 9,200 m/s³).
FLOOR_RAMP_SECONDS = 0.2
#: Seconds over which :func:`keep_clearance` eases a lift in after a foot leaves the floor and out before
#: it lands: the frames of a contact are never lifted.
CLEARANCE_EASE_SECONDS = 0.1


def lift_offsets(deficit: np.ndarray, ramp: int = RAMP) -> np.ndarray:
    """``deficit`` ``(T,)`` (metres below the floor, 0 where above) spread over ``ramp`` frames
    either side: the largest of the neighbours' deficits, each scaled by a smoothstep of its distance."""
    T = len(deficit)
    out = deficit.copy()
    for k in range(1, ramp + 1):
        w = smoothstep(np.array(1.0 - k / (ramp + 1)))
        out[k:] = np.maximum(out[k:], w * deficit[:T - k])
        out[:T - k] = np.maximum(out[:T - k], w * deficit[k:])
    return out


def lift(motion: Motion, limbs: list, deficits: list[np.ndarray], ramp: int = RAMP) -> Motion:
    """``motion`` with each limb's end joint raised by its ``(T,)`` deficit (m), eased over ``ramp`` frames
    (:func:`lift_offsets`) and solved by the limb's IK (``limbs``: ``(ik, side, end joint)``), the end's
    world rotation kept."""
    pos = motion.positions
    out = motion
    for (ik, side, end), deficit in zip(limbs, deficits):
        if not deficit.any():
            continue
        lift = lift_offsets(deficit, ramp)
        target = pos[:, end].copy()
        target[:, 1] += lift
        mask = lift > 0
        out = ik(out, side, target, mask=mask)
        # the end's world rotation alone (rows convert independently: the same bits as all joints' at once)
        out = set_world_rotation(out, end, motion.pose.quaternions(end), mask=mask)
    return out


def clear_floor(motion: Motion) -> Motion:
    """``motion`` with no ankle, toe, wrist or finger joint, nor a tip of one, below ``y = 0`` (docstring)."""
    motion = bend_toes(motion, SKATE_SPEED)  # a ball on or about the floor bends its toes; a swing is lifted
    bm = body_map(motion.skeleton)
    limbs = [(leg_ik, side, ankle) for side, (ankle, _) in bm.feet.items()]
    limbs += [(arm_ik, side, wrist) for side, wrist in bm.hands.items()]
    n = max(RAMP, int(round(FLOOR_RAMP_SECONDS * motion.fps)))
    return lift(motion, limbs, [envelope(np.maximum(0.0, -chain_lowest(motion, end)), n) for *_, end in limbs], 0)


def bend_toes(motion: Motion, slower_than: float | None = None) -> Motion:
    """``motion`` with each foot's toe tips (end sites of its toe joint) kept above ``y = 0`` by bending the toe
    joint up about the horizontal axis across its tip, eased as :func:`clear_floor` eases a lift (docstring);
    with ``slower_than`` (m/s), only on frames where the ball moves slower than that."""
    sites = motion.skeleton.end_sites
    tips = motion.end_site_positions()  # (T, E, 3)
    pos = motion.positions
    n = max(RAMP, int(round(FLOOR_RAMP_SECONDS * motion.fps)))
    out = motion
    for ankle, toe in body_map(motion.skeleton).feet.values():
        mine = [k for k, (j, _) in enumerate(sites) if j == toe != ankle]
        if not mine:
            continue
        ends = tips[:, mine]  # (T, S, 3)
        low = ends[np.arange(len(ends)), ends[..., 1].argmin(axis=1)]  # (T, 3) each frame's lowest tip
        dip = np.maximum(0.0, -low[:, 1])
        if slower_than is not None:
            dip[horizontal_speed(pos[:, toe], motion.fps) >= slower_than] = 0.0
        rise = envelope(dip, n)  # (T,) m
        v = low - pos[:, toe]  # (T, 3) ball to tip
        length, flat = np.linalg.norm(v, axis=1), np.linalg.norm(v[:, [0, 2]], axis=1)
        bend = (rise > 0) & (flat > 1e-6)
        if not bend.any():
            continue
        up = np.minimum(v[:, 1] + rise, length)  # the tip's new height above the ball
        bent = v[:, [0, 2]] * (np.sqrt(np.maximum(length ** 2 - up ** 2, 0.0)) / np.maximum(flat, 1e-12))[:, None]
        new = np.column_stack([bent[:, 0], up, bent[:, 1]])
        axis = np.cross(v, new)
        sin = np.linalg.norm(axis, axis=1)
        angle = np.arctan2(sin, np.einsum("ij,ij->i", v, new))
        turn = from_rotvec(axis * (angle / np.maximum(sin, 1e-12))[:, None])  # (T, 4) in world axes
        world = motion.pose.quaternions()[:, toe]  # only for a foot that bends: most motions have none
        out = set_world_rotation(out, toe, multiply(turn, world), mask=bend)
    return out


def envelope(deficit: np.ndarray, n: int) -> np.ndarray:
    """A smooth ``(T,)`` lift never below ``deficit``: its maximum over ``n`` frames either side, then a
    Gaussian of the same support, so a limb coming down to the floor slows before it instead of
    stopping on it."""
    if not deficit.any():
        return deficit
    return gaussian_filter1d(maximum_filter1d(deficit, 2 * n + 1, mode="nearest"), n / 2.0, mode="nearest",
                             truncate=2.0)


def clear_swings(motion: Motion) -> Motion:
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


def keep_clearance(motion: Motion, capture: Motion) -> Motion:
    """``motion`` (the capture retargeted, frame for frame) with each swinging foot (not in contact, faster
    than GMD's 0.5 m/s, the other foot planted) lifted where its ball is lower above the motion's lowest
    foot point than the capture's ball was above the capture's (the heights GMD's figure reads; leg IK,
    the foot's world rotation kept: :func:`lift`), eased in and out over :data:`CLEARANCE_EASE_SECONDS`
    off the floor; planted feet, a run's flight (lifting the lower foot there would lengthen it) and
    everything above the knees are left as they are."""
    mine_on, theirs_on = detect_contacts(motion), detect_contacts(capture)  # where either plants a foot: no lift
    mine, theirs = body_map(motion.skeleton).feet, body_map(capture.skeleton).feet
    rise = lowest_foot_heights(motion).min() - lowest_foot_heights(capture).min()  # m: the floors GMD reads
    pos = motion.positions
    n = max(1.0, CLEARANCE_EASE_SECONDS * motion.fps)
    limbs, deficits = [], []
    for side, (ankle, toe) in mine.items():
        free = ~mine_on.of(side) & ~theirs_on.of(side)
        other = mine_on.of("right" if side == "left" else "left")
        swinging = free & other & (horizontal_speed(pos[:, toe], motion.fps) > SKATE_SPEED)
        deficit = capture.positions[:, theirs[side][1], 1] + rise - pos[:, toe, 1]  # (T,) m
        away = distance_transform_edt(free) if not free.all() else np.full(len(free), n)  # frames off the floor
        ease = smoothstep(np.minimum(away / n, 1.0))  # 0 on a contact
        limbs.append((leg_ik, side, ankle))
        deficits.append(lift_offsets(np.where(swinging, np.maximum(0.0, deficit), 0.0)) * ease)
    return lift(motion, limbs, deficits, 0)
