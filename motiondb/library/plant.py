"""Exact foot plants for keyframed clips, by two-bone leg IK.

Keyframed legs only roughly agree with the root's travel: a stance foot
drifts. Given when each foot is planted (:class:`FramePlant`, frames), this
module makes the plants exact and keeps the swings smooth:

- **Where.** A plant's position and heading are those of the keyed foot
  at its ``anchor`` frame (ball of the foot = toe joint, yaw of the foot).
- **Vertical lock** (``start``..``stop``): the foot is on the ground with
  the plant's yaw. It may land on the heel, toes ``strike`` degrees up, and
  roll flat by ``flat``; it is flat until ``heel_off``, then rolls onto the
  ball (heel rising to ``toe_off`` degrees at ``stop``) while the toes stay
  flat on the ground. The height comes from the sole: its lowest point
  (heel or ball) touches the ground.
- **Horizontal lock**: the ball does not move horizontally over the vertical
  lock *and* over any neighbouring frame the contact detector
  (:func:`core.contacts.detect_contacts`) would call a contact (low and
  slow), and the frames either side of those (its speed is a central
  difference): so the detector's contact intervals are exactly frames where
  the foot stands still (the foot first lifts, then swings). The locks grow
  by iteration until the detector agrees.
- **Between plants** the foot follows its keyed path plus a correction (lock
  minus keyed) blended by a smoothstep from one lock's value to the next's.
  Near lift-off and touchdown the ball is kept at least
  :data:`~.plant_foot.SWING_CLEARANCE` above its planted height (a smooth hump), so a
  step clears the ground instead of shuffling. A short swing (at most
  :data:`~.plant_gaps.SHORT_SWING_SECONDS`: a turn's step, a skip's hop) has no room
  for two humps: its height is one smooth lift across the gap, bounded by a jerk
  budget (:func:`~.plant_gaps.swing_heights`), and its keyed path is re-timed evenly
  along its length, leaving and landing at :data:`~.plant_foot.MIN_STEP_SPEED`
  (:meth:`~.plant_gaps.Gaps.retime`).
  Horizontally, the keyed swing (from the end of one vertical lock to the
  start of the next) is replayed over the real gap, eased in and out by a
  time-warp (its speed ramps from zero at a lock over :data:`~.plant_gaps.RAMP_FRAMES`
  frames, so the swing keeps its keyed shape but leaves and lands without a
  horizontal velocity jump). Vertically the ramp is shorter
  (:data:`~.plant_foot.V_RAMP_FRAMES`): feet push off and touch down briskly.
  Foot orientation corrections are slerped the same way. The heel and ball
  are kept above the ground.
- **Reach**: where a locked foot would need more than :data:`MAX_REACH` of
  the leg's length (a knee snapping straight, or a plant out of reach), the
  root is lowered just enough, by a smooth envelope (a maximum filter then a
  Gaussian of the same support, so it is never less than needed).
  Swing targets beyond that are pulled in smoothly towards
  :data:`SOFT_REACH` (soft IK), so a knee never snaps straight.
- **IK**: :func:`core.ik.leg_ik` puts the ankle where the ball target
  and foot orientation require, the knee bending towards a pole in front of
  the keyed knee; then the ankle (and toe) world rotations are set.

:func:`plant_feet` returns the planted motion and a :class:`PlantReport`
(largest lock error, frames added to locks), which the tests check. One foot's
targets are :mod:`.plant_foot`'s, the gaps between its locks :mod:`.plant_gaps`'.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d, maximum_filter1d
from scipy.spatial.transform import Rotation

from text2anim.core.contacts import detect_contacts, runs
from text2anim.core.ik import leg_ik
from text2anim.core.motion import Motion

from .keyframes import FramePlant
from .plant_foot import Foot
from text2anim.core.easing import smoothstep

from .plant_gaps import distance_to, nearest_index

__all__ = ["FramePlant", "PlantReport", "plant_feet"]

SIDES = ("left", "right")

#: Frames over which the toes ease from flat-on-the-ground back to their keyed bend.
TOE_BLEND_FRAMES = 5
#: Largest hip-to-ankle distance of a locked foot, as a fraction of the leg's length.
MAX_REACH = 0.993
#: Any farther ankle target is pulled in smoothly towards this fraction (soft IK: the knee
#: straightens gradually instead of snapping).
SOFT_REACH = 0.9995
#: Smoothing (frames) of the root drop that keeps locked feet within reach.
DROP_SIGMA = 3.0


@dataclass(frozen=True)
class PlantReport:
    """``max_error``: metres, largest distance of a locked ball from its lock (3-D on vertical
    locks, horizontal on the rest); ``extended``: frames the horizontal locks grew by;
    ``iterations``: passes until the detector agreed; ``stray_contacts``: detector contact
    frames left outside any lock (should be 0)."""

    max_error: float
    extended: int
    iterations: int
    stray_contacts: int


def _set_world(motion: Motion, joints_rots: list[tuple[int, Rotation]]) -> Motion:
    """Set several joints' world rotations ``(T)`` from one forward-kinematics pass.

    The joints must not be ancestors of one another.
    """
    pose = motion.pose
    rots = motion.rotations.copy()
    for j, world in joints_rots:
        parent = Rotation.from_matrix(pose.rotations[:, motion.skeleton.parents[j]])
        rots[:, j] = (parent.inv() * world).as_quat()
    return motion.replace(rotations=rots)


def _leg_length(motion: Motion, foot: "Foot") -> float:
    skel = motion.skeleton
    return float(np.linalg.norm(skel.offsets[foot.knee]) + np.linalg.norm(skel.offsets[foot.ankle]))


def _soft_reach(target: np.ndarray, hip: np.ndarray, length: float, a: float, b: float) -> np.ndarray:
    """Ankle targets pulled towards ``hip`` beyond ``a * length`` so they never pass ``b * length``
    (identity below ``a``, then an exponential approach; C1)."""
    v = target - hip
    d = np.linalg.norm(v, axis=1)
    lo, hi = a * length, b * length
    over = d > lo
    if not over.any():
        return target
    soft = np.where(over, lo + (hi - lo) * (1 - np.exp(-(d - lo) / (hi - lo))), d)
    return hip + v * (soft / np.maximum(d, 1e-12))[:, None]


def _root_drop(motion: Motion, feet: dict, ankle_targets: dict, max_reach: float) -> np.ndarray:
    """Smooth root drop ``(T,)`` (metres, >= 0) keeping locked ankles within ``max_reach`` of their legs."""
    pos = motion.positions
    T = motion.n_frames
    need = np.zeros(T)
    for side, target in ankle_targets.items():
        foot = feet[side]
        r = max_reach * _leg_length(motion, foot)
        v = target - pos[:, foot.hip]
        vy = v[:, 1]
        n2 = np.sum(v * v, axis=1)
        disc = vy ** 2 - n2 + r ** 2
        drop = np.where(disc >= 0, -vy - np.sqrt(np.maximum(disc, 0.0)), -vy)
        drop = np.where(n2 > r ** 2, np.maximum(drop, 0.0), 0.0)
        locked = foot.owner >= 0
        need = np.maximum(need, np.where(locked, drop, 0.0))
    if not need.any():
        return need
    half = int(np.ceil(2 * DROP_SIGMA))
    env = maximum_filter1d(need, size=2 * half + 1, mode="nearest")
    return gaussian_filter1d(env, DROP_SIGMA, mode="nearest", truncate=2.0)


def plant_feet(motion: Motion, plants: list[FramePlant], *, toe_height: float, sole: np.ndarray,
               ground: float = 0.0, max_iterations: int = 12,
               max_reach: float = MAX_REACH, report_frames: slice = slice(None)) -> tuple[Motion, PlantReport]:
    """Make ``plants`` exact on ``motion`` (see the module docstring).

    ``sole``: ``(S, 3)`` points of the sole in the ankle's frame (heel, ball) kept above
    ``ground``; ``toe_height``: toe joint above the ground when the ball is down;
    ``report_frames``: the frames the report is about (a cyclic clip's kept cycles).
    """
    T = motion.n_frames
    feet = {s: Foot(motion, s, [p for p in plants if p.side == s], toe_height, ground) for s in SIDES}
    keyed = motion
    extended = 0
    iterations = 0
    result = motion
    drop = np.zeros(T)
    for iterations in range(1, max_iterations + 1):
        solved = {}
        ankle_targets = {}
        for side, foot in feet.items():
            if not (foot.owner >= 0).any():
                continue
            target, Q, toe_flat = foot.targets(sole)
            ankle_targets[side] = target - Q.apply(np.tile(foot.toe_local, (T, 1)))
            solved[side] = (target, Q, toe_flat)
            foot.last_target = target
        if not solved:
            break
        drop = _root_drop(keyed, feet, ankle_targets, max_reach)
        root = keyed.root_positions.copy()
        root[:, 1] -= drop
        result = keyed.replace(root_positions=root)
        hips = result.positions
        for side in solved:
            foot = feet[side]
            pole = foot.knee_pos + 0.5 * foot.thigh_fwd - drop[:, None] * np.array([0.0, 1.0, 0.0])
            target = _soft_reach(ankle_targets[side], hips[:, foot.hip], _leg_length(result, foot),
                                 max_reach, SOFT_REACH)
            result = leg_ik(result, side, target, pole=pole)
        result = _set_world(result, [(feet[s].ankle, solved[s][1]) for s in solved])
        # Toes: flat on the ground on vertical locks, easing back to their keyed bend after.
        pose = result.pose
        rots = result.rotations.copy()
        for side in solved:
            foot = feet[side]
            v = foot.vlock & ~foot.keep_mask
            if not v.any():
                continue
            ankle_world = Rotation.from_matrix(pose.rotations[:, foot.ankle])
            flat_local = (ankle_world.inv() * solved[side][2]).as_quat()
            keyed_local = keyed.rotations[:, foot.toe]
            w = smoothstep(distance_to(v, T) / TOE_BLEND_FRAMES)
            near = nearest_index(v, T)
            r0 = Rotation.from_quat(flat_local[near])
            r1 = Rotation.from_quat(keyed_local)
            q = (r0 * Rotation.from_rotvec((r0.inv() * r1).as_rotvec() * w[:, None])).as_quat()
            rots[:, foot.toe] = q
        result = result.replace(rotations=rots)

        contacts = detect_contacts(result)
        changed = False
        for side, foot in feet.items():
            if not (foot.owner >= 0).any():
                continue
            # Every contact frame and both its neighbours (the detector's speed is a central
            # difference) must stand still: grow the adjacent lock over any that do not.
            c = contacts.of(side)
            need = c.copy()
            need[1:] |= c[:-1]
            need[:-1] |= c[1:]
            stray = need & (foot.owner < 0)
            for a, b in runs(stray):
                a, b = int(a), int(b)
                if a > 0 and foot.owner[a - 1] >= 0:
                    foot.owner[a:b] = foot.owner[a - 1]
                elif b < T and foot.owner[b] >= 0:
                    foot.owner[a:b] = foot.owner[b]
                else:
                    continue
                extended += b - a
                changed = True
        if not changed:
            break

    # Report (on the frames asked for; the detector sees the part the caller keeps).
    region = np.zeros(T, dtype=bool)
    region[report_frames] = True
    pos = result.positions
    contacts = detect_contacts(result[report_frames])
    err = 0.0
    stray_total = 0
    for side, foot in feet.items():
        c = contacts.of(side)
        if not (foot.owner >= 0).any():
            stray_total += int(c.sum())
            continue
        ball = pos[:, foot.toe]
        h = (foot.owner >= 0) & region
        v = foot.vlock & region
        horiz = np.linalg.norm(ball[h][:, [0, 2]] - foot.P[foot.owner[h]], axis=1)
        assert foot.last_target is not None  # every planted foot was solved
        vert = np.abs(ball[v, 1] - foot.last_target[v, 1])
        err = max(err, float(horiz.max(initial=0.0)), float(vert.max(initial=0.0)))
        stray_total += int((c & ~(foot.owner >= 0)[report_frames]).sum())
    return result, PlantReport(err, extended, iterations, stray_total)
