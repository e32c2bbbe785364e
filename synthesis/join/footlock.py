"""Foot locking during blends (paper 003 §4.3.2, last paragraph).

While two motions are blended, a foot on the ground must stay where it is:
blending joint angles (and root positions) moves it otherwise. Each planted
foot gets a :class:`Lock` over the frames ``[begin, end)`` where it is down
in the motion that dominates the blend (and, past the blend, in the next
motion). The ankle is driven to a target by the analytic two-bone IK of
:mod:`core.ik` (hip and knee) and turned to a target orientation, so the toe stays too: every lock
and release of a join in one solve, every swing lift in another (:mod:`synthesis.join.legsolve`).

The target starts where the foot is on the lock's first frame and then moves
only as the foot moves *in the source motions that have it planted*
(:func:`planted_targets`): their foot velocities, weighted by their blend
weights, are integrated. A foot flat on the ground in both sources stays
exactly still; a foot rolling onto its toe in a source rolls the same way;
the sliding a blend of two different foot placements would cause is never
integrated. Past the blend only the next motion counts, so the foot does what
that clip does, displaced by whatever offset the lock had built up.

A foot that lands during the blend is carried to where the planted source
puts it over its approach (:func:`lock_feet`). At ``end`` the foot leaves
the ground in the next motion and is **released while it is in the air**: the leg's joint angles are blended from the locked
solution back to the motion's own by eq. (3) with the ratio of eq. (4) over
the air phase ``[end, release_end)``, so it lands where the next motion puts
it.

A lock holds only what the leg can reach (:func:`reachable_locks`): where the blend carries the hips on
faster than the planted sources' foot follows, the lock ends as the target leaves the leg's reach, and the
foot steps and is put down again under the body; it never hangs behind on a straight leg.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from text2anim.core import rotkernels as rk
from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import runs
from text2anim.core.easing import smootherstep
from text2anim.core.motion import Motion

from .blend import ease, ratio, slerp
from .legsolve import REACH, LegGoal, chain_length, leg_chain, quaternions, solve_goals, solve_leg

__all__ = ["Lock", "FootLocks", "planted_targets", "lock_feet", "reachable_locks", "lift_swings", "plan_locks", "REACH", "solve_leg"]


@dataclass(frozen=True)
class Lock:
    """One foot held on the ground: ``side``; frames ``[begin, end)`` locked, released over ``[end, release_end)``.
    ``at``: a foot put down again where a lock could not hold it (:func:`reachable_locks`): the ankle's
    world position (m), held still, turned as the foot's previous lock began; ``None``: the planted sources
    say where (:func:`planted_targets`)."""

    side: str
    begin: int
    end: int
    release_end: int
    at: tuple[float, float, float] | None = None


def planted_targets(start_pos: np.ndarray, start_rot: np.ndarray, positions: list[np.ndarray],
                    rotations: list[np.ndarray], weights: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Ankle targets of a lock: the start pose moved by the weighted motion of the planted sources.

    Args:
        start_pos: ``(3,)`` the ankle on the lock's first frame; ``start_rot`` its world rotation, a
            quaternion ``(4,)`` or ``(1, 4)``.
        positions: per source, the ankle's world positions ``(T, 3)`` over the lock.
        rotations: per source, the ankle's world rotations, quaternions ``(T, 4)``.
        weights: per source ``(T,)``: its blend weight where the foot is planted in it, else 0.

    Returns:
        ``(T, 3)`` positions and ``(T, 4)`` quaternions. Frame 0 is the start pose;
        frame ``t`` adds the weighted mean of the sources' steps ``t - 1 -> t``
        (velocity and body-frame angular velocity), summed.
    """
    steps_p, steps_r = _steps(positions, rotations)
    targets, turned = _integrate(start_pos, weights, steps_p, steps_r)
    start = np.reshape(start_rot, (-1, 4))  # a rotation already (not normalised again: scipy's bits)
    return targets, rk.as_quat(rk.compose(start, rk.from_rotvec(turned)))


def _steps(positions: list[np.ndarray], rotations: list[np.ndarray]) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Per source the ankle's steps ``t - 1 -> t`` (:func:`planted_targets`): ``(T - 1, 3)`` moves and
    ``(T - 1, 3)`` turns in its own frame (rotation vectors), all sources' turns in one conversion (per pair
    of frames the same arithmetic, so a lock's steps are the slice of the steps of a longer run)."""
    if len(rotations[0]) < 2:
        return [np.zeros((0, 3)) for _ in positions], [np.zeros((0, 3)) for _ in rotations]
    turns = rk.as_rotvec(rk.compose(rk.inverse(np.concatenate([r[:-1] for r in rotations])),
                                    np.concatenate([r[1:] for r in rotations])))
    return [np.diff(p, axis=0) for p in positions], np.split(turns, len(rotations))


def _integrate(start_pos: np.ndarray, weights: list[np.ndarray], steps_p: list[np.ndarray],
               steps_r: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """:func:`planted_targets` 's sums: ``(T, 3)`` positions and the ``(T, 3)`` rotation vector turned since
    frame 0, from the sources' :func:`_steps` over the lock weighted by their shares of ``weights``."""
    T = len(weights[0])
    w = np.stack(weights)  # (S, T)
    tot = w.sum(axis=0)
    share = np.divide(w, tot, out=np.zeros_like(w), where=tot > 1e-9)
    dp = np.zeros((T, 3))
    dr = np.zeros((T, 3))
    for s, (step_p, step_r) in enumerate(zip(steps_p, steps_r)):
        if T < 2:
            break
        dp[1:] += share[s, 1:, None] * step_p
        dr[1:] += share[s, 1:, None] * step_r
    return start_pos + np.cumsum(dp, axis=0), np.cumsum(dr, axis=0)


@dataclass(frozen=True)
class FootLocks:
    """One foot's locks in a join and its planted sources (:func:`lock_feet`): ``positions``,
    ``rotations`` per source its ankle's world positions ``(N, 3)`` and rotation matrices ``(N, 3, 3)``
    from the join's first frame; ``weights`` per source ``(N,)``: its blend weight where the foot is
    planted in it, else 0."""

    locks: list[Lock]
    positions: list[np.ndarray]
    rotations: list[np.ndarray]
    weights: list[np.ndarray]


def _lock_start(w: np.ndarray, positions: list[np.ndarray], i0: int) -> tuple[np.ndarray | None, int]:
    """Where a lock starting on frame ``i0`` holds the ankle: the planted sources' weighted mean (``w``
    ``(S, T)`` their weights, ``positions`` per source the ankle ``(T, 3)``), and the source with the
    largest share (whose rotation the lock starts with); ``(None, -1)`` where no source has it planted."""
    tot = w[:, i0].sum()
    if tot <= 1e-9:
        return None, -1
    share = w[:, i0] / tot
    return sum(share[k] * positions[k][i0] for k in range(len(positions))), int(np.argmax(share))


def _lock_goal(side: str, p: np.ndarray, r: np.ndarray, sources: list[np.ndarray], feet: FootLocks, first: int,
               profile: str, fps: float = 30.0, toe: np.ndarray | None = None):
    """The goal holding one foot over ``[first, stop)`` (see :func:`lock_feet`): ``p`` ``(T, 3)`` and ``r``
    ``(T, 4)`` its ankle's own world positions and rotations there, ``sources`` per source its ankle's world
    rotations as quaternions ``(T, 4)``; ``toe`` ``(3,)`` the toe joint's offset in the ankle's frame, the
    ball a turn handed to the next motion pivots about (:func:`_settle_into_next`). Also the last lock's
    offset and turn: ``(goal, d (3,), e (3,))``."""
    locks = sorted(feet.locks, key=lambda lk: lk.begin)
    positions = feet.positions
    stop = locks[-1].end
    T = len(p)
    d = np.zeros((T, 3))
    e = np.zeros((T, 3))
    w = np.stack([x[:T] for x in feet.weights])
    steps_p, steps_r = _steps([x[:T] for x in positions], sources)  # once for all the locks
    starts, turns, rows = [], [], []
    start_rot = r[:1]
    for lk in locks:  # planted_targets of each lock, its rotations converted below for all at once
        i0, i1 = lk.begin - first, lk.end - first
        if lk.at is not None:  # put down again: still, turned as the lock before it began
            d[i0:i1] = np.asarray(lk.at) - p[i0:i1]
            starts.append(np.repeat(start_rot, i1 - i0, axis=0))
            turns.append(np.zeros((i1 - i0, 3)))
            rows.append(np.arange(i0, i1))
            continue
        start, lead = _lock_start(w, positions, i0)
        if start is not None:
            start_rot = sources[lead][i0:i0 + 1]
        else:
            start, start_rot = p[i0], r[i0:i0 + 1]
        tp, turned = _integrate(start, [x[i0:i1] for x in w], [x[i0:i1 - 1] for x in steps_p],
                                [x[i0:i1 - 1] for x in steps_r])
        d[i0:i1] = tp - p[i0:i1]
        starts.append(np.repeat(start_rot, i1 - i0, axis=0))
        turns.append(turned)
        rows.append(np.arange(i0, i1))
    tr = rk.as_quat(rk.compose(np.concatenate(starts), rk.from_rotvec(np.concatenate(turns))))
    at = np.concatenate(rows)
    e[at] = rk.as_rotvec(rk.compose(rk.inverse(r[at]), rk.from_quat(tr)))
    held = e.copy()
    for lk in locks:
        if lk.at is None:
            _settle_into_next(d, e, w, lk.begin - first, lk.end - first, max(1, int(round(SETTLE_S * fps))))
    if toe is not None and not np.array_equal(held, e):  # turned about the ball, not the ankle: the ball stays
        ball = [rk.apply(rk.compose(r[at], rk.from_rotvec(x[at])), np.broadcast_to(toe, (len(at), 3)))
                for x in (held, e)]
        d[at, 0] += ball[0][:, 0] - ball[1][:, 0]
        d[at, 2] += ball[0][:, 2] - ball[1][:, 2]
    prev_end, prev_d, prev_e = 0, np.zeros(3), np.zeros(3)
    for lk in locks:  # the approaches: the offset eases from the previous state to the lock's
        i0 = lk.begin - first
        if i0 > prev_end:
            u = ease(ratio(i0 - prev_end), profile)[:, None]
            d[prev_end:i0] = prev_d + u * (d[i0] - prev_d)
            e[prev_end:i0] = prev_e + u * (e[i0] - prev_e)
        prev_end = lk.end - first
        prev_d, prev_e = d[prev_end - 1].copy(), e[prev_end - 1].copy()
    goal = LegGoal(side, first, stop, p + d, rk.as_quat(rk.compose(r, rk.from_rotvec(e))))
    return goal, prev_d, prev_e


#: s: the least time over which a lock hands its foot's height and turn to the next motion (a weight
#: that shifts in 0.1 s turned the foot as fast: joint jerk 1,162 against the sources' 902)
SETTLE_S = 0.3
#: m: a lock hands the foot over only where it holds the ankle this much below where the next motion has
#: it (the next motion stands on the ball and cannot reach a flat foot's ankle). Handed over everywhere,
#: a bow into a dance put the dancer's foot on its ball with the body still over the bow's stance: its
#: centre of mass 3 cm outside the feet (6.5 cm on a 20 m character), against 0.15 held.
HAND_OVER_BELOW = 0.01


def _settle_into_next(d: np.ndarray, e: np.ndarray, w: np.ndarray, i0: int, i1: int, n: int = 1) -> None:
    """Fade a lock's height and turn offsets (``d[:, 1]``, ``e``, in place over ``[i0, i1)``) as the next
    motion, the last of the sources ``w`` ``(S, T)``, takes over the planted weight, over ``n`` frames at
    least (a smootherstep), when the lock ends with that motion alone holding the foot (a lock a blend
    lets go of keeps its offsets: a shot into a run slid the turning ball for 0.6 s, GMD 0.06 -> 0.20)
    and holds the ankle :data:`HAND_OVER_BELOW` or more below that motion's own:
    the foot ends the lock as that motion stands on it (a punch's heel raised, its
    weight on the ball), still where the lock holds it on the ground. Held at the first motion's height and
    turn, the foot stood flat or toes-up where the next one is on its ball: its leg straight and its sole
    3-5 cm off the floor for the whole punch (CMU pair dance→punch, floating 6.8 cm; now 3.6, its sources')."""
    tot = w[:, i0:i1].sum(axis=0)
    share = np.divide(w[-1, i0:i1], tot, out=np.zeros(i1 - i0), where=tot > 1e-9)
    if share[0] >= 1.0 - 1e-9 or share[-1] < 1.0 - 1e-9:  # only a lock the next motion alone ends
        return
    if d[i1 - 1, 1] > -HAND_OVER_BELOW:  # a foot its own leg reaches down to stays as the lock holds it
        return
    g = np.clip((share - share[0]) / (1.0 - share[0]), 0.0, 1.0)
    g = np.maximum.accumulate(g)  # once the next motion holds the foot, it keeps it
    k = np.arange(len(g)) / n
    g = smootherstep(np.minimum(k + np.minimum.accumulate(g - k), k + 1.0 / n))  # at most 1/n a frame
    d[i0:i1, 1] *= 1.0 - g
    e[i0:i1] *= (1.0 - g)[:, None]


#: s: a foot a lock cannot hold any longer (its leg cannot reach the target) steps this long before it is
#: put down again: a walking stride's swing lasts 0.35-0.4 s, a run's 0.25-0.3 s
STEP_S = 0.4
#: m: how far beyond the leg's IK reach (:data:`REACH`) a target may be before the lock is cut: the
#: library's own joins reach up to 7 cm past it for a frame or two as a foot rolls off (the post pass plants
#: it again, and every criterion holds); a foot left behind by a travelling body misses by metres
HANG = 0.10


def _held_path(lk: Lock, first: int, w: np.ndarray, positions: list[np.ndarray], steps: list[np.ndarray],
               own: np.ndarray) -> np.ndarray:
    """``(n, 3)`` where a lock holds the ankle over its frames (:func:`_lock_goal` 's positions): from the
    planted sources' weighted place on its first frame (``own``, the motion's ankle ``(T, 3)``, where no
    source has it planted), moved as they move; a put-down lock's ``at``, still."""
    i0, i1 = lk.begin - first, lk.end - first
    if lk.at is not None:
        return np.repeat(np.asarray(lk.at, dtype=np.float64)[None], i1 - i0, axis=0)
    start, _ = _lock_start(w, positions, i0)
    return _integrate(own[i0] if start is None else start, [x[i0:i1] for x in w], [x[i0:i1 - 1] for x in steps],
                      [np.zeros((max(0, i1 - i0 - 1), 3))] * len(steps))[0]


def reachable_locks(motion: Motion, feet: dict[str, FootLocks], first: int) -> dict[str, FootLocks]:
    """The locks cut where the leg cannot reach what they hold, the foot stepping on instead.

    A lock holds a foot where the planted sources have it while the hips go where the blend takes them;
    when the blend carries the hips on faster than the sources' feet follow (a run braking into a walk
    through a frozen pose), the target leaves the leg's reach and IK would leave the foot hanging behind on a
    straight leg, in the air (50 cm up, for 1.7 s, before). On the first frame the hip is further than the
    leg's reach (:data:`REACH` + :data:`HANG`) from the target, the lock ends: the foot swings for
    :data:`STEP_S` (lifted by :func:`lift_swings`) and is put down where the motion itself has it then, at
    the height it stood at, held still (``Lock.at``) — and cut again if the hips outrun that too. A lock its
    leg reaches throughout is returned as it was.
    """
    hi = min(motion.n_frames, max(lk.end for f in feet.values() for lk in f.locks))
    pos = motion[first:hi].pose.positions  # the hips are final (a lock turns the legs' joints only)
    n_step = max(1, int(round(STEP_S * motion.fps)))
    out = {}
    for side, f in feet.items():
        hip, _knee, ankle = chain = leg_chain(motion, side)
        reach = REACH * chain_length(motion, chain) + HANG
        T = hi - first
        w = np.stack([x[:T] for x in f.weights])
        steps = [np.diff(x[:T], axis=0) for x in f.positions]
        kept: list[Lock] = []
        for lk in sorted(f.locks, key=lambda x: x.begin):
            cur = lk
            while True:
                held = _held_path(cur, first, w, f.positions, steps, pos[:, ankle])
                far = np.flatnonzero(np.linalg.norm(held - pos[cur.begin - first:cur.end - first, hip], axis=1) > reach)
                if not len(far):
                    kept.append(cur)
                    break
                cut, land = cur.begin + int(far[0]), cur.begin + int(far[0]) + n_step
                if land >= cur.end:  # no room to put it down again: released from here
                    if cut > cur.begin:
                        kept.append(Lock(side, cur.begin, cut, max(cur.release_end, cut), cur.at))
                    break
                if cut > cur.begin:
                    kept.append(Lock(side, cur.begin, cut, land, cur.at))
                x, _, z = pos[land - first, ankle]
                cur = Lock(side, land, cur.end, cur.release_end, (float(x), float(held[0, 1]), float(z)))
        out[side] = f if kept == sorted(f.locks, key=lambda x: x.begin) else FootLocks(kept, f.positions, f.rotations,
                                                                                        f.weights)
    return out


def lock_feet(motion: Motion, feet: dict[str, FootLocks], first: int, profile: str = "smooth") -> Motion:
    """Apply all the locks of both feet in one join, each foot then released (one IK solve for all).

    Per foot (its :class:`FootLocks`; no lock begins before ``first``, the frame the sources start at,
    the blend's first): each lock's target starts where the planted sources put the foot (their
    weighted mean) and follows their motion (:func:`planted_targets`); its height and turn pass to the next
    motion's own as that motion takes the weight (:func:`_settle_into_next`). Between ``first`` and the first
    lock, and between two locks, the foot's offset from its own path moves smoothly (the ``profile``)
    from the one before to the one after, so a foot that lands during the blend is carried to its lock
    without a jump. After the last lock the foot is **released** over ``[end, release_end)`` while it is
    in the air (eq. (3)): the lock's last offset and turn ride on the motion's own foot, solved by IK,
    and the leg's joint angles are blended from that solution to the motion's own,
    ``angle = (1 - ratio) * locked + ratio * own`` with the ratio of eq. (4), eased.
    """
    feet = {s: f for s, f in feet.items() if f.locks}
    if not feet:
        return motion
    n = motion.n_frames
    hi = max(max(lk.release_end for lk in f.locks) for f in feet.values())
    hi = min(n, max(hi, max(max(lk.end for lk in f.locks) for f in feet.values())))
    span = motion[first:hi]
    pose = span.pose
    # every ankle rotation the locks ask for as quaternions, in one conversion: per foot its own over the
    # locks and over the release, and each source's
    where = {}  # per foot: its ankle, the locks' frames from first, and the release [b, e)
    for side, f in feet.items():
        last = max(f.locks, key=lambda lk: lk.begin)
        where[side] = (leg_chain(motion, side)[2], max(lk.end for lk in f.locks) - first,
                       max(0, last.end), min(n, last.release_end))
    blocks = []
    for side, f in feet.items():
        ankle, T, b, e = where[side]
        blocks += [pose.rotations[:T, ankle], pose.rotations[b - first:max(b, e) - first, ankle]]
        blocks += [x[:T] for x in f.rotations]
    quats = quaternions(blocks)
    goals, releases = [], []
    for side, f in feet.items():
        ankle, T, b, e = where[side]
        r, r_own, *sources = quats[:2 + len(f.rotations)]
        quats = quats[2 + len(f.rotations):]
        goal, prev_d, prev_e = _lock_goal(side, pose.positions[:T, ankle], r, sources, f, first, profile, motion.fps,
                                          motion.skeleton.offsets[body_map(motion.skeleton).feet[side][1]])
        goals.append(goal)
        if e > b:  # the release: the lock's offset riding on the motion's own foot
            turn = rk.from_rotvec(prev_e)
            goals.append(LegGoal(side, b, e, pose.positions[b - first:e - first, ankle] + prev_d,
                                 rk.as_quat(rk.compose(r_own, turn))))
            releases.append((side, b, e))
    rots = solve_goals(span, first, goals)
    if releases:  # eq. (3) over the legs' joints of every release at once
        legs = [np.asarray(body_map(motion.skeleton).joints(f"{side}_leg")) for side, _, _ in releases]
        fr = [np.repeat(np.arange(b - first, e - first), len(j)) for (_, b, e), j in zip(releases, legs)]
        jt = [np.tile(j, e - b) for (_, b, e), j in zip(releases, legs)]
        w = [np.repeat(ease(ratio(e - b), profile), len(j)) for (_, b, e), j in zip(releases, legs)]  # eq. (4), eased
        fr_all, jt_all = np.concatenate(fr), np.concatenate(jt)
        rots[fr_all, jt_all] = slerp(rots[fr_all, jt_all], span.rotations[fr_all, jt_all], np.concatenate(w))
    return motion.with_rotations(first, rots)


CLEARANCE_SLOPE = 0.3  # m of height per m of horizontal distance from the nearer end of a swing
CLEARANCE_MAX = 0.08  # m
SWING_SPEED = 0.3  # m/s: only where the foot moves faster than this does its height matter
LIFT_JERK = 500.0  # m/s^3: the largest jerk a lift may add (short runs get lower arcs)


def _lift_goal(pose, lo: int, fps: float, side: str, feet: tuple[int, int], b: int, e: int,
               slope: float, top: float) -> LegGoal | None:
    """The goal lifting one swing ``[b, e)`` (see :func:`lift_swings`) from ``pose`` (frames from ``lo``)."""
    ankle, toe = feet
    pos = pose.positions[b - lo:e - lo]
    p = pos[:, ankle]
    low = np.minimum(p[:, 1], pos[:, toe, 1])  # the foot's lowest point
    step = np.linalg.norm(np.diff(p[:, [0, 2]], axis=0), axis=1)
    s_from = np.concatenate([[0.0], np.cumsum(step)])
    total = s_from[-1]
    speed = np.linalg.norm(np.gradient(p[:, [0, 2]], axis=0), axis=1) * fps
    moving = speed > SWING_SPEED
    if total < 0.05 or not moving.any():
        return None
    clearance = np.minimum(slope * np.minimum(s_from, total - s_from), top)
    floor = min(low[0], low[-1])
    need = float(np.max((floor + clearance - low)[moving]))
    m = len(p)
    # one smooth arc (not a clipped max, which would kink the leg's motion), no taller than a jerk of
    # LIFT_JERK allows over the run: the arc's third derivative at its ends is 384 * height / duration^3
    height = min(need, top, LIFT_JERK * ((m - 1) / fps) ** 3 / 384.0)
    if height < 1e-3:
        return None
    u = np.arange(m) / (m - 1)
    target = p.copy()
    target[:, 1] += height * 64.0 * (u * (1.0 - u)) ** 3
    return LegGoal(side, b, e, target, np.empty((0, 4)))  # its ankle's own rotations: lift_swings


def lift_swings(motion: Motion, swings: list[tuple[str, int, int]],
                slope: float = CLEARANCE_SLOPE, top: float = CLEARANCE_MAX) -> Motion:
    """Keep feet off the floor while a blend (or a release) carries them through the air: each
    ``(side, begin, end)`` of ``swings`` (the runs of one foot must not overlap), in one IK solve.

    A blend moves a foot between two places along the mix of its two source
    paths; where the two places differ, the weight's own change pushes the
    foot along, which can skim the floor (a shuffle the skating measure
    rightly counts). The foot should be at least ``slope`` × its horizontal
    distance from the nearer end of the run (capped at ``top``) above the
    lower of its two end heights — its lowest point, ankle or toe, counts —
    wherever it moves faster than :data:`SWING_SPEED`. Where it is not, the
    ankle is raised by IK (its world orientation kept) along one smooth arc
    in time, ``64 (u (1 - u))^3``, tall enough for the largest shortfall but
    adding no more jerk than :data:`LIFT_JERK`; zero, with zero slope and
    curvature, at both ends. Runs shorter than 3 frames are left alone.
    """
    n = motion.n_frames
    runs_ = [(side, max(0, b), min(n, e)) for side, b, e in swings]
    runs_ = [(side, b, e) for side, b, e in runs_ if e - b >= 3]
    if not runs_:
        return motion
    lo, hi = min(b for _, b, _ in runs_), max(e for _, _, e in runs_)
    span = motion[lo:hi]
    pose = span.pose
    bm = body_map(motion.skeleton)
    goals = [g for side, b, e in runs_
             if (g := _lift_goal(pose, lo, motion.fps, side, bm.feet[side], b, e, slope, top)) is not None]
    if not goals:
        return motion
    own = quaternions([pose.rotations[g.begin - lo:g.end - lo, bm.feet[g.side][0]] for g in goals])
    goals = [LegGoal(g.side, g.begin, g.end, g.targets, rk.as_quat(q)) for g, q in zip(goals, own)]
    return motion.with_rotations(lo, solve_goals(span, lo, goals))


def plan_locks(planted: dict[str, np.ndarray], window: tuple[int, int], limit: int) -> list[Lock]:
    """Locks for the feet planted during a blend.

    Args:
        planted: per side, ``(N,)`` bool over the frames of the motion: whether
            the foot should be on the ground (inside the blend: in the motion
            that dominates, i.e. has the larger weight; after it: in the next motion).
        window: ``[w0, w1)``, the blend's frames.
        limit: no lock or release reaches this frame.

    Every run of ``planted`` that overlaps the window is locked from where it
    starts (at the earliest ``w0``) to where the foot lifts (at the latest
    ``limit``) and released over the foot's next air phase (cut at ``limit``).
    """
    w0, w1 = window
    out = []
    for side, mask in planted.items():
        mask = np.asarray(mask, dtype=bool)
        air = {int(a): int(h) for a, h in runs(~mask)}
        for lo, hi in runs(mask):
            if hi <= w0 or lo >= w1:
                continue
            begin, end = max(int(lo), w0), min(int(hi), limit)
            release_end = min(air.get(int(hi), limit), limit) if end < limit else end
            out.append(Lock(side, begin, end, release_end))
    return out
