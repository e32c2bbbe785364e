"""The join post-pass every joining engine of ours runs on a laid track (optimal and constraint).

An engine lays whole-body clips and blends them at joins; this pass then makes
every join hold up the way ``docs/timetable.md`` §3 measures it, against the join's
own two source clips (as recorded, at the track's rate):

1. **Velocity carried over** at the join's seams (every end of its blend
   intervals): the outgoing velocity of every joint's local rotation and of the
   hips is carried into what follows and decayed by inertialization
   (:func:`synthesis.join.inertialize.inertialize_at`, Bollo's quintic) over
   :data:`SEAM_DECAY` s; where a blend ends on the first frame of the next
   clip's core (or too near the region's end to decay after it), the blend
   takes the difference instead, decaying backwards
   (:func:`~synthesis.join.inertialize.inertialize_before`), and the core is not touched.
2. **The clips' own accelerations.** The join's region (blend, foot locks and
   releases, :data:`PAD` s either side; from up to :data:`BRAKE` s before the
   blend when the first clip loops) is **retimed** (:func:`warp_frames`): played
   over up to 1.9 times its frames, the rate 1 at both ends and dipping where the
   hips' speed changes fastest — a run that must stop takes its last strides
   slower, braking over its own steps instead of halting in a frame; a flight it
   would slow into hanging in the air keeps its own time (:func:`flights`) — and its
   local rotations and hips' path are **low-passed** (a Gaussian over frames,
   quaternions unrolled and renormalised, faded in and out with the quintic
   ``smooth`` profile). The smallest stretch of :data:`STRETCHES` and width of
   :data:`SIGMAS` that bring the region's joint jerk p99 (m/s³) and hips'
   horizontal acceleration (m/s², :func:`core.metrics.quality`) within the two
   sources' are kept; the time added is reported (``post.added_s``) and the
   elements after the join start that much later. At that stretch a wider
   smoothing is taken instead when it is still within the sources' figures and
   nearer the figures of the frames the join replaces (``Region.near``: the first
   clip after its core, the second before it, :func:`synthesis.assemble.join_side`;
   "nearer": the larger of the two ratios, jerk and root pop, is smaller):
   a kick's accelerations in its core are no licence for the join beside it.
   The candidates are :mod:`synthesis.join.smoothing`'s: the feet of a width are re-planted (step 3) only when
   its exact hips' pop and a floor of its jerk leave it a chance of being chosen (:mod:`synthesis.join.pruning`),
   several widths of a stretch in one IK solve; the choice is the one trying all makes.
3. **Feet stay put.** Wherever a foot is in contact in the engine's output, or
   held still by its locks (toes and heels: the ankle's position *and* world
   orientation are kept, so the toe stays), the leg is solved by IK back onto
   that foot (:func:`synthesis.join.legsolve.solve_leg`); the correction fades out
   over the air phase around it.
4. **Nothing below the floor** (y = 0) and no shuffle: in the region a foot whose
   ankle or toe would go below it is lifted by IK by the deficit
   (:func:`lift_off_floor`), and a foot moving fast with its toe under 5.5 cm (above the floor, and
   above the motion's lowest foot point where GMD reads it) is lifted clear (:func:`lift_skimming_feet`);
   after an adaptation, whose fitted legs
   reach through the next clip's core, up to the next join.

5. **Weight over the feet**: where the finished region stands a slow body on its feet with its centre of
   mass beside them (``core.balance``), its hips are moved over them, the legs solved back onto the feet
   (:func:`synthesis.join.overfeet.over_feet`; the shift is scaled down to keep the hips' acceleration
   within the sources'; the report's ``post.weight_shift_cm``).
6. **The hips' path of least acceleration**: the hips' horizontal path over the region bent, by at most a
   few centimetres, into the path that accelerates least and keeps a slow body over its feet, the legs
   solved back onto the feet (:func:`synthesis.join.hipspath.least_acceleration`: a departure from eq. (8)
   of paper 000, written there; ``post.hips_bent_cm``). Where the feet a connection released after its
   blend land inside the next clip's core (the engine's frames there, not the clip's) and the body stands
   beside them on one of those frames, this step reaches to where they have landed (``Region.r1``): a
   dance ending on tiptoe, its last step landing 0.2 s into the bow, stood the body 6-8 cm outside its feet.

**Cores** are kept: the region stops at the next clip's core (except where the
engine's own adaptation returns inside it, or step 6 above) and starts after the first clip's
(a looped first clip is all core, and its braking strides become the join's).

All vectorised over frames and joints; deterministic.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d, maximum_filter1d, uniform_filter1d

from text2anim.core.balance import balance_heights
from text2anim.core.bodyparts import body_map
from text2anim.core.cancel import checkpoint
from text2anim.core.contacts import contacts_within, runs
from text2anim.core.easing import smootherstep_area
from text2anim.core.floor import ON_FLOOR
from text2anim.core.hang import slowed_into_hanging
from text2anim.core.kept import Kept, digest
from text2anim.core.metrics import gmd_floor, quality
from text2anim.core.motion import Motion, concatenate

from .blend import neighbours, sample, sample_path
from .hipspath import least_acceleration
from .inertialize import inertialize_at, inertialize_before
from .legsolve import LegGoal, solve_legs
from .overfeet import over_feet
from .pruning import Tried, least, may_keep, may_keep_by_pop, replaces
from .smoothing import Deferred, Smoothed, Stretch, low_pass_all, plant_all
from .spliced import Spliced

SEAM_DECAY = 0.3  # s: a seam's velocity jump decays over this (Bollo's t1)
PAD = 0.25  # s: the filtered pose fades in and out over this on each side of a region
SIGMAS = (0.0, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.5, 8.0)  # frames at 30 fps (scaled with the frame rate)
SLACK = 1.0  # the region may reach the sources' own figure times this
#: m/s²: the hips may always accelerate this much (half the low end of captured walking, docs/timetable.md §3): clips
#: smoother than capture (the built-in library's: 1 m/s²) would otherwise have every join slowed down
POP_FLOOR = 2.0
FLOOR = 0.0  # m
STILL = 0.15  # m/s: an ankle slower than this in the engine's output is held where it is


@dataclass(frozen=True)
class Region:
    """One join to finish: blend window ``[w0, w1)`` and region end ``r1`` (track frames), and the
    join's two source clips (their figures are the limits)."""

    w0: int
    w1: int
    r1: int
    sources: tuple
    keep: tuple[int, int] = (0, 1 << 30)  # track frames the pass may touch: after A's core, before B's
    brake_from: int | None = None  # a looped first clip: the pass may slow its steps from this frame
    seams: tuple[int, ...] = ()  # more frames where the engine switches blends (ends of its intervals)
    into_core: bool = False  # the engine's own blends reach into the next core (an adaptation's return)
    near: tuple = ()  # the parts of the sources the join replaces (their figures are the preferred limits)


def _limits(sources, fps: float) -> tuple[float, float]:
    """The largest jerk p99 (m/s³) and root pop (m/s²) of the source clips, at ``fps`` (:func:`core.metrics.quality`)."""
    qs = [source_figures(m, fps) for m in sources if m is not None and m.n_frames >= 6]
    return max([q[0] for q in qs] or [0.0]), max([q[1] for q in qs] or [0.0])


def source_figures(m: Motion, fps: float) -> tuple[float, float]:
    """``(jerk p99, root pop)`` of a source clip at ``fps`` (:func:`core.metrics.quality`), kept in the clip's
    cache: the same library clips (the database hands out the same motions) are the sources of join after
    join, animation after animation."""
    def make() -> tuple[float, float]:
        q = quality(m, fps)
        return q.jerk_p99, q.root_pop
    return m.cache.get(("source_figures", float(fps)), make)


def lift_off_floor(motion: Motion, lo: int, hi: int, floor: float = FLOOR) -> Motion:
    """``motion`` with every foot whose ankle or toe goes below ``floor`` over ``[lo, hi)`` lifted by IK by
    the deficit (widened by 2 frames each side and smoothed, so the lift eases in and out)."""
    feet = body_map(motion.skeleton).feet
    out = motion
    a, b = max(0, lo), min(motion.n_frames, hi)
    if b <= a:
        return motion
    for side, joints in feet.items():
        p = out[a:b].positions  # kinematics is per frame: the window's only, not the whole track's
        deficit = np.zeros(out.n_frames)
        deficit[a:b] = np.maximum(0.0, floor - p[:, list(joints), 1].min(axis=1))
        if not (deficit > 5e-4).any():
            continue
        out = _raise_ankle(out, side, joints[0], deficit)
    return out


def _raise_ankle(motion: Motion, side: str, ankle: int, short: np.ndarray) -> Motion:
    """``motion`` with ``side``'s ankle raised by ``short`` ``(T,)`` (m), widened by 2 frames each side and
    smoothed so the lift eases in and out, by leg IK with the ankle's world rotation kept."""
    d = gaussian_filter1d(maximum_filter1d(short, 5, mode="nearest"), 1.0, mode="nearest")
    d = np.maximum(d, short)
    goals = []
    for a, b in runs(d > 1e-5):
        a, b = int(a), int(b)
        pose = motion[a:b].pose
        target = pose.positions[:, ankle] + np.stack([np.zeros(b - a), d[a:b], np.zeros(b - a)], 1)
        goals.append(LegGoal(side, a, b, target, pose.quaternions(ankle)))  # its world rotation kept
    # the runs as rows of one solve (each run's arithmetic is what it is alone: the same bits, one IK's fixed cost)
    return solve_legs(motion, goals)


SKIM_HEIGHT = 0.055  # m: a foot moving faster than SWING_SPEED keeps its toe this high (GMD counts < 5 cm)
SWING_SPEED = 0.5  # m/s, the GMD skating speed
#: m under core.floor.ON_FLOOR a lifted toe stays: higher, the foot no longer touches (core.balance, core.hang)
TOUCH_MARGIN = 0.005


def lift_skimming_feet(motion: Motion, lo: int, hi: int, lowest: float | None = None) -> Motion:
    """``motion`` with every foot that skims the floor over ``[lo, hi)`` lifted: where its toe is lower than
    :data:`SKIM_HEIGHT` while it moves faster than :data:`SWING_SPEED` (5-frame mean) — a shuffle a
    blend of two foot placements makes, counted as skating — the ankle is raised by IK (world orientation
    kept, so the toe rises as much), by the shortfall widened by 2 frames and smoothed.

    GMD's figure reads toes above the motion's lowest foot point (:func:`core.metrics.gmd_floor`), not
    above y = 0: a crouch whose toe goes 1.7 cm down counts a toe up to 6.7 cm as on the floor. Where the
    other foot is on the floor, the toe is kept :data:`SKIM_HEIGHT` above that point too (below
    :data:`core.floor.ON_FLOOR`, so the lifted foot still touches: a spin's pivoting feet stay its support);
    where it is not, only above y = 0 (lifted higher, a landing foot kept a run's flight in the air longer).
    ``lowest`` (m): that point, default ``motion``'s own (a window's: its track's, :func:`finish_track`)."""
    feet = body_map(motion.skeleton).feet
    out = motion
    fps = motion.fps
    floor = gmd_floor(motion) if lowest is None else lowest
    skim = min(SKIM_HEIGHT + max(0.0, floor), ON_FLOOR - TOUCH_MARGIN)
    for side, (ankle, toe) in feet.items():
        p = out.positions
        other = feet["right" if side == "left" else "left"]
        height = np.where(p[:, list(other), 1].min(axis=1) < ON_FLOOR, skim, SKIM_HEIGHT)
        xz = p[:, toe][:, [0, 2]]
        v = np.zeros(len(p))
        v[1:] = np.linalg.norm(np.diff(xz, axis=0), axis=1) * fps
        fast = (v > SWING_SPEED) & (uniform_filter1d(v, 5, mode="nearest") > SWING_SPEED)
        short = np.where(fast, np.maximum(0.0, height - p[:, toe, 1]), 0.0)
        short[:lo] = 0.0
        short[hi:] = 0.0
        if not (short > 1e-3).any():
            continue
        out = _raise_ankle(out, side, ankle, short)
    return out


#: stretch factors tried for a join's region (its new length over its old); below 2 the rate stays positive
STRETCHES = (1.0, 1.4, 1.7, 1.9)
BRAKE = 0.6  # s: how far before its blend a looped first clip may be slowed (its braking steps)


def warp_frames(n: int, n_new: int, seam: int | None = None, air: np.ndarray | None = None) -> np.ndarray:
    """``(n_new,)`` source positions (frames, in ``[0, n)``) of a region of ``n`` frames played over ``n_new``.

    The playback rate is 1 at both ends (the velocity carried in and out is the motion's own) and dips
    smoothly to ``1 - c`` where the region's frame ``seam`` plays (default: its middle), with
    ``c = 2 (n_new - n) / n_new``: rising and falling by the quintic ``smoothstep``, so the rate is C2.
    Slowed there, the motion's own changes of speed (a run that stops: the hips from 3 m/s to standing)
    are spread over more time — the clip's own steps, time-warped — instead of happening in a frame.

    ``air`` ``(n,)`` bool: frames of a flight the warp must not slow (:func:`flights`). A body in the air
    falls as gravity takes it, so those frames keep their own time: the time the warp would add to them
    goes to the frames on the floor, in proportion to what each already gets (the edges eased over
    :data:`AIR_EASE` frames; :func:`_off_the_air`).
    """
    if n_new <= n:
        return np.arange(n, dtype=np.float64)
    seam = n // 2 if seam is None else int(np.clip(seam, 1, n - 1))
    c = 2.0 * (n_new - n) / n_new
    ts = seam / (1.0 - c / 2.0)  # the new time at which the seam plays
    tau = np.arange(n_new, dtype=np.float64)
    before = ts * smootherstep_area(np.clip(tau / ts, 0.0, 1.0))
    after = (n_new - ts) * (0.5 - smootherstep_area(np.clip((n_new - tau) / (n_new - ts), 0.0, 1.0)))
    area = np.where(tau <= ts, before, ts / 2.0 + after)
    warp = np.clip(tau - c * area, 0.0, n - 1e-9)
    if air is None or not np.asarray(air).any():
        return warp
    return _off_the_air(warp, n, np.asarray(air, dtype=bool))


#: frames over which the rate returns to 1 either side of a body's flight
AIR_EASE = 2.0


def _times(warp: np.ndarray, n: int) -> np.ndarray:
    """``(n + 1,)``: the new time (frames) at which each of ``n`` source frames starts, and the last ends, under
    ``warp`` (the source positions of the new frames)."""
    return np.interp(np.arange(n + 1), np.r_[warp, n], np.arange(len(warp) + 1))


def flights(region: Motion, n_new: int, seam: int | None) -> np.ndarray:
    """``(n,)`` bool: the frames of the flights of ``region`` (its ``n`` frames) that :func:`warp_frames` over
    ``n_new`` would slow into hanging in the air (:func:`core.hang.slowed_into_hanging`): a standing pose
    blended into a run's flight, played slowly, holds the body up for a second."""
    return slowed_into_hanging(region, _times(warp_frames(region.n_frames, n_new, seam), region.n_frames))


def _off_the_air(warp: np.ndarray, n: int, air: np.ndarray) -> np.ndarray:
    """``warp`` (source positions of the new frames) with the time it adds to the ``air`` frames ``(n,)`` moved
    onto the others (:func:`warp_frames`); the warp as it is when every frame is in the air."""
    n_new = len(warp)
    t_at = _times(warp, n)  # the new time each source frame starts
    extra = np.maximum(np.diff(t_at) - 1.0, 0.0)  # (n,) the time added to each source frame
    free = np.clip(1.0 - gaussian_filter1d(air.astype(np.float64), AIR_EASE, mode="nearest") * 2.0, 0.0, 1.0)
    free[air] = 0.0
    kept = extra * free
    if not kept.sum() > 1e-9:
        return warp
    dt = 1.0 + kept * (extra.sum() / kept.sum())
    knots = np.r_[0.0, np.cumsum(dt)]
    return np.clip(np.interp(np.arange(n_new, dtype=np.float64), knots, np.arange(n + 1.0)), 0.0, n - 1e-9)


def retime(motion: Motion, lo: int, hi: int, n_new: int, seam: int | None = None) -> Motion:
    """``motion`` with frames ``[lo, hi)`` played over ``n_new`` frames by :func:`warp_frames` (later frames follow)."""
    if n_new <= hi - lo:
        return motion
    return replay(motion, lo, hi, warp_frames(hi - lo, n_new, seam))


def replay(motion: Motion, lo: int, hi: int, src: np.ndarray, origin: int = 0) -> Motion:
    """``motion`` with frames ``[lo, hi)`` replaced by its frames ``lo + src`` (``src`` ``(n_new,)``: a
    :func:`warp_frames`; later frames follow). ``origin``: ``motion`` is a window of a track from that frame on
    (the fractions sampled are the track's, :func:`synthesis.join.blend.sample`)."""
    return _with_middle(motion, lo, hi, sample(motion, (origin + lo) + src, origin))


def _with_middle(motion: Motion, lo: int, hi: int, mid: Motion) -> Motion:
    """``motion`` with its frames ``[lo, hi)`` replaced by ``mid``'s (any number)."""
    return concatenate([p for p in (motion[:lo], mid, motion[hi:]) if p.n_frames])


def replay_both(seamed: Motion, motion: Motion, lo: int, hi: int, src: np.ndarray,
                origin: int = 0) -> tuple[Motion, Motion]:
    """``(replay(seamed, ...), replay(motion, ...))`` (:func:`replay`) of two motions of one length that differ in
    some frames only (the seams' inertialization): a new frame sampled between two frames the same in both is the
    same bits in both (sampling is per frame and joint), so ``motion``'s are sampled only where they are not."""
    base = replay(seamed, lo, hi, src, origin)
    if seamed is motion:
        return base, base
    T = motion.n_frames

    def bits(x: np.ndarray) -> np.ndarray:  # compared as bits: -0.0 is not 0.0 here
        return x.view(np.int64).reshape(T, -1)

    same = (bits(seamed.root_positions) == bits(motion.root_positions)).all(axis=1) & \
        (bits(seamed.rotations) == bits(motion.rotations)).all(axis=1)
    if (seamed.translations is None) != (motion.translations is None):
        same[:] = False
    elif seamed.translations is not None and motion.translations is not None:
        same &= (bits(seamed.translations) == bits(motion.translations)).all(axis=1)
    i0, i1, _ = neighbours((origin + lo) + src, T, origin)  # the frames blend.sample reads
    differ = ~(same[i0] & same[i1])
    if differ.all():
        return base, replay(motion, lo, hi, src, origin)
    mid = base[lo:lo + len(src)]
    root, rots = mid.root_positions.copy(), mid.rotations.copy()
    trans = None if mid.translations is None else mid.translations.copy()
    if differ.any():
        own = sample(motion, (origin + lo) + src[differ], origin)
        root[differ], rots[differ] = own.root_positions, own.rotations
        if trans is not None:
            trans[differ] = own.translations
    return base, _with_middle(motion, lo, hi, Motion(motion.skeleton, motion.fps, root, rots, trans))


def _planted(ref: Motion, contacts) -> dict:
    """Per side, ``(T,)``: the foot is in contact or held still by the engine (its ankle slower than :data:`STILL`)."""
    out = {}
    p = ref.positions
    for side, (ankle, _toe) in body_map(ref.skeleton).feet.items():
        still = np.zeros(ref.n_frames, dtype=bool)
        still[1:] = np.linalg.norm(np.diff(p[:, ankle][:, [0, 2]], axis=0), axis=1) * ref.fps < STILL
        out[side] = contacts.of(side)[:ref.n_frames] | still
    return out


def _hardest(m: Motion, lo: int, hi: int) -> int:
    """The frame of ``[lo, hi)`` (relative to ``lo``) where the hips' horizontal speed changes fastest:
    where a retiming slows the motion most (:func:`warp_frames`' ``seam``)."""
    xz = m.root_positions[max(0, lo - 1):hi + 1, [0, 2]]
    if len(xz) < 4:
        return (hi - lo) // 2
    speed = np.linalg.norm(np.diff(xz, axis=0), axis=1)
    acc = np.abs(np.diff(uniform_filter1d(speed, 3, mode="nearest")))
    return int(np.clip(np.argmax(acc) + (1 if lo > 0 else 0), 1, hi - lo - 1))


#: Which widths are re-planted together (one IK solve for several costs less than one each: ~0.4 against ~1.1 ms a
#: width of 30 frames, the solve's fixed cost), measured over the 32-motion text's 93 joins: a width is re-planted
#: alone until one of its stretch has failed the limits, then with every later width of the stretch that may count
#: (after a failure the stretch's later widths are mostly tried anyway); re-planting the next two beside each
#: (the rule before) planted 464 widths where the scan needed 375, and cost 12 % more
AHEAD = "after a failure"


#: the last joins finished (:func:`finish_region`), by the value of everything the pass reads (:func:`_finished_key`):
#: a warm process finishes the same joins again (the studio re-animates the whole text at every pause in typing,
#: and only the joins the edit reached differ); each keeps the window's arrays (~0.2 MB), no kinematics, up to
#: 32 MB of them (the 32-motion text's 93 joins: 20 MB; a bound by count dropped each join of a long text before
#: the text came back to it)
def _finished_bytes(kept: tuple) -> int:
    """Bytes of a kept finished join's arrays (frames and the retiming's source frames)."""
    return sum(a.nbytes for a in (*kept[:3], kept[4][3]) if a is not None)


KEPT_FINISHED: Kept[tuple] = Kept(4096, 32 * 2 ** 20, _finished_bytes)


def finish_region(motion: Motion, region: Region, contacts, origin: int = 0,
                  outside: float = np.inf) -> tuple[Motion, dict, tuple[int, int, int, np.ndarray]]:
    """One join finished (steps 1–6 of the module docstring). ``origin``: ``motion`` is the window of a track from
    that frame on (``region`` and ``contacts`` in the window's frames; :func:`finish_track`), ``outside`` (m) the
    lowest foot joint of the track outside the window (:meth:`Spliced.lowest_outside`).

    Returns the motion, what was done, and ``(lo, hi, n_new, src)``: the frames ``[lo, hi)`` now play
    over ``n_new``, new frame ``k`` showing source frame ``lo + src[k]`` (:func:`warp_frames`; later frames
    are ``n_new - (hi - lo)`` later). A join finished before, from the same values, is the frames it gave then
    (:data:`KEPT_FINISHED`; bit for bit the pass), their kinematics shared with ``motion`` where they are its.
    """
    key = _finished_key(motion, region, contacts, origin, outside)
    known = KEPT_FINISHED.known(key)
    if known is None:
        done, info, warp = _finish_region(motion, region, contacts, origin, outside)
        warp[3].setflags(write=False)  # kept: read-only, as the frames are
        KEPT_FINISHED.put(key, (done.root_positions, done.rotations, done.translations, info, warp))
        return done, dict(info), warp
    root, rotations, translations, info, warp = known
    done = Motion(motion.skeleton, motion.fps, root, rotations, translations)
    lo, added = warp[0], len(root) - motion.n_frames  # the frames before lo are the input's, those after the
    rows = np.arange(len(root))  # region the input's `added` later: shared where bit for bit so
    rows[lo:] -= added
    return done.share_pose(motion, np.where(rows < motion.n_frames, rows, -1)), dict(info), warp


def _finished_key(motion: Motion, region: Region, contacts, origin: int, outside: float) -> bytes:
    """A digest of everything :func:`finish_region` reads: the window's frames and skeleton, the region's frames,
    the sources' figures (its limits), the contacts, the track's lowest foot outside the window, and this
    module's settings."""
    sk, fps = motion.skeleton, motion.fps
    return digest(fps, motion.root_positions, motion.rotations, motion.translations, sk.offsets, sk.parents,
                  tuple(sk.names), region.w0, region.w1, region.r1, region.keep, region.brake_from, region.seams,
                  region.into_core, _limits(region.sources, fps), _limits(region.near, fps) if region.near else None,
                  contacts.fps, contacts.left, contacts.right, origin, outside, SIGMAS, STRETCHES, SLACK, PAD,
                  BRAKE, POP_FLOOR, SEAM_DECAY, STILL, AHEAD, FLOOR, SKIM_HEIGHT, SWING_SPEED, AIR_EASE,
                  TOUCH_MARGIN, ON_FLOOR)


def _finish_region(motion: Motion, region: Region, contacts, origin: int = 0,
                   outside: float = np.inf) -> tuple[Motion, dict, tuple[int, int, int, np.ndarray]]:
    """:func:`finish_region`, done."""
    fps = motion.fps
    T = motion.n_frames
    pad0 = max(1, int(round(PAD * fps)))
    lo = max(0, region.w0 - pad0, min(region.keep[0], region.w0))
    if region.brake_from is not None:
        lo = max(0, min(lo, max(region.brake_from, region.w0 - int(round(BRAKE * fps)))))
    # an adaptation returns to the next clip's own legs inside its core: the pass follows the engine there
    hi = min(T, max(region.r1, region.w1) + pad0,
             max(region.keep[1], region.w1 + 1, region.r1 if region.into_core else 0))
    seamed = motion
    for s in sorted({region.w0, region.w1, *(x for x in region.seams if lo < x < hi)}):
        after, before = (hi - 1 - s) / fps, (s - lo - 1) / fps
        if s < hi - 2 and after >= min(SEAM_DECAY, before):
            seamed = inertialize_at(seamed, s, min(SEAM_DECAY, after))
        elif s - lo > 2:  # the blend hands over to the next core (or the track ends) right here: the blend, not
            # what follows, takes the velocity difference (decaying backwards from the seam)
            seamed = inertialize_before(seamed, s, min(SEAM_DECAY, before))
    planted = _planted(motion, contacts)  # the engine output's kinematics over the window, known from here on
    # the frames the seams left alone are the engine output's: their kinematics too (the flights', a stretch's)
    seamed = seamed.share_pose(motion, np.arange(T)) if seamed is not motion else seamed
    jk_lim, pop_lim = _limits(region.sources, fps)
    pop_lim = max(pop_lim, POP_FLOOR)
    jk_near, pop_near = _limits(region.near, fps) if region.near else (jk_lim, pop_lim)
    jk_near, pop_near = min(jk_near, jk_lim), max(min(pop_near, pop_lim), POP_FLOOR)
    scale = fps / 30.0
    lims = (max(jk_lim * SLACK, 1e-9), max(pop_lim * SLACK, 1e-9), max(jk_near * SLACK, 1e-9),
            max(pop_near * SLACK, 1e-9))
    tried: list[tuple[float, float, Smoothed, int]] = []  # (width, stretch, candidate, region end), in order
    kept: Tried | None = None  # within the limits, nearest
    whi = max(min(hi, region.keep[1]), region.w0 + 2)  # retimed: [lo, whi), never the next core
    seam = _hardest(seamed, lo, whi)
    stretches: list[Stretch] = []
    played: dict[float, np.ndarray] = {}  # per stretch, the warp of [lo, whi) (flights kept at their time)
    span = seamed[lo:whi]  # one slice: its kinematics are computed once for every stretch's flights
    for stretch in STRETCHES:
        n_new = int(round((whi - lo) * stretch))
        air = flights(span, n_new, seam) if n_new > whi - lo else None  # unslowed, nothing hangs
        src = played[stretch] = warp_frames(whi - lo, n_new, seam, air)
        frames: Motion | Deferred = seamed
        if n_new > whi - lo:  # retimed when a width's rotations are asked: the hips' path is enough for the pops
            path = seamed.root_positions
            frames = Deferred(np.concatenate([path[:lo], sample_path(path, (origin + lo) + src, origin), path[whi:]]),
                              fps, functools.partial(replay_both, seamed, motion, lo, whi, src, origin))
        # rounded as the track's frames: a window's would round its halves the other way half the time
        idx = np.round(np.concatenate([np.arange(lo), (origin + lo) + src, np.arange(whi, T)])).astype(int)
        idx[lo:lo + len(src)] -= origin
        mask = {k: v[np.clip(idx, 0, T - 1)] for k, v in planted.items()}
        h2 = hi + max(n_new, whi - lo) - (whi - lo)
        pad = max(1, min(pad0, (h2 - lo) // 3))
        # the hips' filtered path fades in and out over at least 2.5 sigma: a path low-passed where it
        # accelerates lags the original, and a shorter fade would return it with a pop of its own
        widths = Stretch(frames, motion if frames is seamed else None, lo, h2, mask, [
            (sigma * scale, pad, max(pad, min(int(np.ceil(2.5 * sigma * scale)), (h2 - lo) // 3))) for sigma in SIGMAS])
        stretches.append(widths)
        failed = False  # a width of this stretch re-planted and not within the limits
        for i, sigma in enumerate(SIGMAS):
            cand = widths[i]
            tried.append((sigma, stretch, cand, h2))
            if not may_keep(cand, lims, kept):
                continue
            if cand.jk is None and failed:  # the rest of a stretch that failed once is mostly tried too: every
                # later width that may count is re-planted with this one, in one IK solve (:data:`AHEAD`)
                rest = [widths[j] for j in range(i + 1, len(SIGMAS))]
                low_pass_all([w for w in rest if may_keep_by_pop(w, lims, kept)])  # their rotations in one go
                plant_all([cand] + [w for w in rest if may_keep(w, lims, kept)])
            jk, pop = cand.plant()
            failed = failed or max(jk / lims[0], pop / lims[1]) > 1.0
            if max(jk / lims[0], pop / lims[1]) <= 1.0:  # within the whole clips' figures: no more time. A wider
                # smoothing is taken if it is still within them and nearer the figures of the parts the join
                # replaces (the larger ratio smaller: a root pop brought down to the replaced frames' may cost
                # jerk within the sources')
                near = max(jk / lims[2], pop / lims[3])
                if replaces(near, jk, pop, kept):
                    kept = (near, sigma, stretch, cand, jk, pop, h2)
                assert kept is not None  # the first within is always kept
                if kept[0] <= 1.0:
                    break
        if kept is not None:
            break
    _score, sigma, stretch, chosen, jk, pop, h2 = kept or least(tried, lims)
    candidate = chosen.motion()
    for st in stretches:
        st.release()
    # outside [lo, h2) the frames are the input's (those the seams left alone), inside it the chosen width's (its
    # feet re-planted): the kinematics of both is known
    finished = candidate.share_pose(_beside(motion, chosen.sub, lo, hi), np.arange(candidate.n_frames))
    done = lift_off_floor(lift_skimming_feet(finished, lo, h2, min(outside, gmd_floor(finished))), lo, h2)
    # the feet a connection released after its blend may land inside the next core (the engine's frames, not
    # the clip's): where the body stands beside them there, the hips' path is bent over them too
    he = _landing_end(done, h2, region.r1 + h2 - hi)
    done, shifted = over_feet(done, lo, h2, pop_lim * SLACK)
    done, bent = least_acceleration(done, lo, he)
    info = {"smoothing_frames": sigma, "stretch": stretch, "added_s": round((h2 - hi) / fps, 3),
            "weight_shift_cm": round(100 * shifted, 2), "hips_bent_cm": round(100 * bent, 2),
            "jerk_p99": round(jk, 1), "source_jerk_p99": round(jk_lim, 1), "root_pop": round(pop, 2),
            "source_root_pop": round(pop_lim, 2), "seam_decay_s": SEAM_DECAY}
    return done, info, (lo, whi, whi - lo + (h2 - hi), played[stretch])


def _beside(motion: Motion, sub: Motion, lo: int, hi: int) -> Motion:
    """``motion`` with its frames ``[lo, hi)`` replaced by ``sub``'s, its kinematics known (both motions' are: the
    window's and a width's, :class:`synthesis.join.smoothing.Smoothed`; joined, no kinematics run): what a
    candidate's frames may share theirs with."""
    both = concatenate([motion[:lo], sub, motion[hi:]])
    _ = both.pose
    return both


def _landing_end(motion: Motion, h2: int, r1: int) -> int:
    """``r1`` (clamped to the motion) when the body stands outside its feet (``core.balance``) on a frame of
    ``[h2, r1)``, where a connection's released feet land inside the next core; else ``h2``."""
    r1 = min(motion.n_frames, r1)
    if r1 - h2 < 2:
        return h2
    h = balance_heights(motion[h2:r1])
    return r1 if bool((np.nan_to_num(h) > 0.0).any()) else h2


#: s: how far beyond a join's frames (its blend window, region end and pads) :func:`finish_region` reads: the widest
#: low-pass reads 4 sigma beyond the region (``SIGMAS[-1]`` frames at 30 fps: 1.07 s), the rest a few frames (the
#: feet's contact weights 0.2 s, the contacts' hysteresis 0.1 s); half a second to spare
REACH = 4.0 * SIGMAS[-1] / 30.0 + 0.5


def _shifted(r: Region, by: int) -> Region:
    """``r`` with its frames ``by`` later."""
    return Region(r.w0 + by, r.w1 + by, r.r1 + by, r.sources, (r.keep[0] + by, r.keep[1] + by),
                  None if r.brake_from is None else r.brake_from + by, tuple(x + by for x in r.seams),
                  r.into_core, r.near)


def _window(r: Region, fps: float, T: int) -> tuple[int, int]:
    """The frames ``[a, b)`` of a track of ``T`` frames that :func:`finish_region` reads and writes for ``r``
    (:data:`REACH` beyond the region it may take): the join finished on them is the join finished on the
    whole track, bit for bit, and costs its window's work."""
    pad0 = max(1, int(round(PAD * fps)))
    reach = int(np.ceil(REACH * fps))
    before = max(pad0, int(round(BRAKE * fps)) if r.brake_from is not None else 0)
    return max(0, r.w0 - before - reach), min(T, max(r.r1, r.w1) + pad0 + reach)


def finish_track(motion: Motion, regions: list[Region]) -> tuple[Motion, list[dict], list[tuple[int, int, int, np.ndarray]]]:
    """All joins of a track finished in time order (the clips' own floor is the import's: only the joins'
    regions are lifted off it, and after an adaptation, which fits the next clip's legs to the previous
    feet through its core, everything up to the next join). Returns the motion, per join what was done, and per join the retiming
    ``(lo, hi, n_new, src)`` in the frames of the motion as it was *before* that join (earlier joins' added
    frames included).

    Each join is finished on its window of the track (:func:`_window`), with the foot contacts of the whole
    track (their floor levels the track's, :class:`synthesis.join.spliced.Spliced`): a long track's joins cost
    their windows' work, not the track's each."""
    infos, warps = [], []
    track = Spliced(motion)
    fps = motion.fps
    added = 0
    for k, r in enumerate(regions):
        r = _shifted(r, added)
        checkpoint()  # an abandoned animation stops before its next region
        a, b = _window(r, fps, track.n_frames)
        win = track.window(a, b)
        done, info, (lo, hi, n_new, src) = finish_region(win, _shifted(r, -a), contacts_within(win, track.floor()), a,
                                                         track.lowest_outside(a, b))
        track.put(a, b, done)
        infos.append(info)
        warps.append((lo + a, hi + a, n_new, src))
        added += n_new - (hi - lo)
        if r.into_core:  # an adaptation's fitted legs reach through the next clip's core, up to the next join
            end = min(regions[k + 1].w0 + added if k + 1 < len(regions) else track.n_frames, track.n_frames)
            if end > r.w0:
                a, b = max(0, r.w0 - int(np.ceil(REACH * fps))), min(track.n_frames, end + int(np.ceil(REACH * fps)))
                track.put(a, b, lift_off_floor(track.window(a, b), r.w0 - a, end - a))
    return track.motion(), infos, warps
