"""The join post-pass every joining engine of ours runs on a laid track (optimal and constraint).

An engine lays whole-body clips and blends them at joins; this pass then makes
every join hold up the way ``timetable.md`` §3 measures it, against the join's
own two source clips:

1. **Velocity carried over** at the join's seams (the first and last frame of
   its blend window): the outgoing velocity of every joint's rotation and of the
   hips is carried into what follows and decayed by inertialization
   (:func:`synthesis.inertialize.inertialize_at`, Bollo's quintic) over
   :data:`SEAM_DECAY` s.
2. **Accelerations of the clips themselves.** Over the join's region (blend,
   foot locks and releases, padded by :data:`PAD` s) the local rotations and the
   hips' path are low-passed (a Gaussian over frames, quaternions unrolled and
   renormalised) by the smallest width of :data:`SIGMAS` that brings the region's
   joint jerk (p99, m/s³) and hips' horizontal acceleration (m/s², after a
   3-frame average) within those of the two source clips; the filtered pose is
   faded in and out over the padding with the quintic ``smooth`` profile, so
   the pass adds no step of its own. A run that must stop thus takes as long
   to brake as the clips' own strides allow, not one frame.
3. **Feet stay put.** Wherever a foot is in contact in the engine's output
   (its locks already hold it; toes and heels: the ankle's position *and*
   world orientation are kept, so the toe stays), the filtered leg is solved by
   IK back onto that foot (:func:`synthesis.footlock.solve_leg`); the
   correction fades out over the air phase around the contact.
4. **Nothing below the floor** (y = 0) and no shuffle: in the region a foot
   whose ankle or toe would go below it is lifted by IK by the deficit
   (:func:`lift_off_floor`), and a foot moving fast with its toe under 5.5 cm
   is lifted clear (:func:`clear_swings`). Cores are never touched (the
   region stops at the first clip's core end and the next one's core start).

All vectorised over frames and joints; deterministic.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d, maximum_filter1d, uniform_filter1d
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import detect_contacts, runs
from text2anim.core.ik import set_world_rotation
from text2anim.core.motion import Motion, unroll_quaternions

from .blend import ease, lerp, slerp
from .footlock import solve_leg
from .inertialize import inertialize_at

SEAM_DECAY = 0.3  # s: a seam's velocity jump decays over this (Bollo's t1)
PAD = 0.25  # s: the filtered pose fades in and out over this on each side of a region
SIGMAS = (0.0, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0)  # frames at 30 fps (scaled with the frame rate)
SLACK = 1.0  # the region may reach the sources' own figure times this
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


def jerk_p99(positions: np.ndarray, fps: float) -> float:
    """99th percentile over frames and joints of the jerk magnitude (m/s³) of ``(T, J, 3)`` positions."""
    if len(positions) < 4:
        return 0.0
    return float(np.percentile(np.linalg.norm(np.diff(positions, 3, axis=0), axis=-1) * fps ** 3, 99))


def root_pop(hips: np.ndarray, fps: float) -> float:
    """Largest horizontal acceleration (m/s²) of hips ``(T, 3)`` after a 3-frame moving average."""
    if len(hips) < 3:
        return 0.0
    xz = uniform_filter1d(hips[:, [0, 2]], 3, axis=0, mode="nearest")
    return float(np.linalg.norm(np.diff(xz, 2, axis=0), axis=1).max() * fps ** 2)


def _limits(sources, fps: float) -> tuple[float, float]:
    """The largest jerk p99 and root pop of the source clips (resampled to ``fps`` if they are not)."""
    jk, pop = 0.0, 0.0
    for m in sources:
        if m is None or m.n_frames < 4:
            continue
        if abs(m.fps - fps) > 1e-6:
            m = m.resample(fps)
        jk = max(jk, jerk_p99(m.positions, fps))
        pop = max(pop, root_pop(m.positions[:, 0], fps))
    return jk, pop


def _fade(n: int, pad: int) -> np.ndarray:
    """``(n,)``: 0 → 1 over the first ``pad`` frames, 1, 1 → 0 over the last ``pad`` (quintic, C2)."""
    e = np.ones(n)
    if pad > 0:
        up = ease(np.linspace(0.0, 1.0, pad + 1)[:-1], "smooth")
        e[:pad] = up
        e[n - pad:] = up[::-1]
    return e


def low_pass(motion: Motion, lo: int, hi: int, sigma: float, pad: int) -> Motion:
    """``motion`` with local rotations and root position Gaussian-filtered (``sigma`` frames) over
    ``[lo, hi)``, faded in and out over ``pad`` frames at each end."""
    if sigma <= 0 or hi - lo < 2 * pad + 1:
        return motion
    q = unroll_quaternions(motion.rotations[lo:hi])
    qs = gaussian_filter1d(q, sigma, axis=0, mode="nearest")
    qs /= np.linalg.norm(qs, axis=-1, keepdims=True)
    e = _fade(hi - lo, pad)
    rots = motion.rotations.copy()
    rots[lo:hi] = slerp(q, qs, e[:, None])
    root = motion.root_positions.copy()
    root[lo:hi] = lerp(root[lo:hi], gaussian_filter1d(root[lo:hi], sigma, axis=0, mode="nearest"), e)
    return motion.replace(root_positions=root, rotations=rots)


def _soft(mask: np.ndarray, fps: float) -> np.ndarray:
    """A contact mask as a weight: 1 on contact frames, falling smoothly to 0 over about 0.1 s around them."""
    w = np.clip(2.0 * gaussian_filter1d(mask.astype(np.float64), 0.05 * fps, mode="nearest"), 0.0, 1.0)
    w[mask] = 1.0
    return w


def keep_feet(motion: Motion, ref: Motion, lo: int, hi: int, contacts) -> Motion:
    """``motion`` with its legs solved over ``[lo, hi)`` so that every foot in contact in ``ref``
    (``contacts``) has ``ref``'s ankle position and world orientation; the correction fades out around."""
    if hi - lo < 2:
        return motion
    feet = body_map(motion.skeleton).feet
    out = motion
    ref_p = ref.positions
    for side, (ankle, _toe) in feet.items():
        still = np.zeros(ref.n_frames, dtype=bool)  # a foot the engine holds still counts too (its locks)
        still[1:] = np.linalg.norm(np.diff(ref_p[:, ankle][:, [0, 2]], axis=0), axis=1) * ref.fps < STILL
        c = _soft(contacts.of(side) | still, motion.fps)[lo:hi]
        if not c.any():
            continue
        sub = out[lo:hi]
        now = sub.pose
        want = ref.pose
        target = lerp(now.positions[:, ankle], want.positions[lo:hi, ankle], c)
        r_now = now.quaternions()[:, ankle]
        r_want = Rotation.from_matrix(want.rotations[lo:hi, ankle]).as_quat()
        solved = set_world_rotation(solve_leg(sub, side, target), ankle, slerp(r_now, r_want, c))
        rots = out.rotations.copy()
        rots[lo:hi] = solved.rotations
        out = out.replace(rotations=rots)
    return out


def lift_off_floor(motion: Motion, lo: int, hi: int, floor: float = FLOOR) -> Motion:
    """``motion`` with every foot whose ankle or toe goes below ``floor`` over ``[lo, hi)`` lifted by IK by
    the deficit (widened by 2 frames each side and smoothed, so the lift eases in and out)."""
    feet = body_map(motion.skeleton).feet
    out = motion
    for side, joints in feet.items():
        p = out.positions
        deficit = np.maximum(0.0, floor - p[:, list(joints), 1].min(axis=1))
        deficit[:lo] = 0.0
        deficit[hi:] = 0.0
        if not (deficit > 5e-4).any():
            continue
        d = gaussian_filter1d(maximum_filter1d(deficit, 5, mode="nearest"), 1.0, mode="nearest")
        d = np.maximum(d, deficit)
        ankle = joints[0]
        for lo, hi in runs(d > 1e-5):
            lo, hi = int(lo), int(hi)
            sub = out[lo:hi]
            pose = sub.pose
            target = pose.positions[:, ankle] + np.stack([np.zeros(hi - lo), d[lo:hi], np.zeros(hi - lo)], 1)
            rot = pose.quaternions()[:, ankle]
            solved = set_world_rotation(solve_leg(sub, side, target), ankle, rot)
            rots = out.rotations.copy()
            rots[lo:hi] = solved.rotations
            out = out.replace(rotations=rots)
    return out


SWING_CLEARANCE = 0.055  # m: a foot moving faster than SWING_SPEED keeps its toe this high (GMD counts < 5 cm)
SWING_SPEED = 0.5  # m/s, the GMD skating speed


def clear_swings(motion: Motion, lo: int, hi: int) -> Motion:
    """``motion`` with every foot that skims the floor over ``[lo, hi)`` lifted: where its toe is lower than
    :data:`SWING_CLEARANCE` while it moves faster than :data:`SWING_SPEED` (5-frame mean) — a shuffle a
    blend of two foot placements makes, counted as skating — the ankle is raised by IK (world orientation
    kept, so the toe rises as much), by the shortfall widened by 2 frames and smoothed."""
    feet = body_map(motion.skeleton).feet
    out = motion
    fps = motion.fps
    for side, (ankle, toe) in feet.items():
        p = out.positions
        xz = p[:, toe][:, [0, 2]]
        v = np.zeros(len(p))
        v[1:] = np.linalg.norm(np.diff(xz, axis=0), axis=1) * fps
        fast = (v > SWING_SPEED) & (uniform_filter1d(v, 5, mode="nearest") > SWING_SPEED)
        short = np.where(fast, np.maximum(0.0, SWING_CLEARANCE - p[:, toe, 1]), 0.0)
        short[:lo] = 0.0
        short[hi:] = 0.0
        if not (short > 1e-3).any():
            continue
        d = gaussian_filter1d(maximum_filter1d(short, 5, mode="nearest"), 1.0, mode="nearest")
        d = np.maximum(d, short)
        for a, b in runs(d > 1e-5):
            a, b = int(a), int(b)
            sub = out[a:b]
            pose = sub.pose
            target = pose.positions[:, ankle] + np.stack([np.zeros(b - a), d[a:b], np.zeros(b - a)], 1)
            solved = set_world_rotation(solve_leg(sub, side, target), ankle, pose.quaternions()[:, ankle])
            rots = out.rotations.copy()
            rots[a:b] = solved.rotations
            out = out.replace(rotations=rots)
    return out


def _figures(m: Motion, lo: int, hi: int) -> tuple[float, float]:
    a, b = max(0, lo - 3), min(m.n_frames, hi + 3)
    p = m[a:b].positions
    return jerk_p99(p, m.fps), root_pop(p[:, 0], m.fps)


def finish_region(motion: Motion, region: Region, contacts) -> tuple[Motion, dict]:
    """One join finished (steps 1–3 of the module docstring); returns the motion and what was done."""
    fps = motion.fps
    T = motion.n_frames
    pad = max(1, int(round(PAD * fps)))
    lo = max(0, region.w0 - pad, min(region.keep[0], region.w0))
    hi = min(T, max(region.r1, region.w1) + pad, max(region.keep[1], region.w1 + 1))
    out = motion
    for s in sorted({region.w0, region.w1}):
        if s < hi - 2:
            out = inertialize_at(out, s, min(SEAM_DECAY, (hi - 1 - s) / fps))
    pad = max(1, min(pad, (hi - lo) // 3))
    jk_lim, pop_lim = _limits(region.sources, fps)
    scale = fps / 30.0
    best = None
    for sigma in SIGMAS:
        cand = keep_feet(low_pass(out, lo, hi, sigma * scale, pad), motion, lo, hi, contacts)
        jk, pop = _figures(cand, lo, hi)
        score = max(jk / max(jk_lim * SLACK, 1e-9), pop / max(pop_lim * SLACK, 1e-9))
        if best is None or score < best[0] - 1e-9:
            best = (score, sigma, cand, jk, pop)
        if score <= 1.0:
            break
    score, sigma, cand, jk, pop = best
    cand = lift_off_floor(clear_swings(cand, lo, hi), lo, hi)
    info = {"smoothing_frames": sigma, "jerk_p99": round(jk, 1), "source_jerk_p99": round(jk_lim, 1),
            "root_pop": round(pop, 2), "source_root_pop": round(pop_lim, 2), "seam_decay_s": SEAM_DECAY}
    return cand, info


def finish_track(motion: Motion, regions: list[Region]) -> tuple[Motion, list[dict]]:
    """All joins of a track finished in time order (the clips' own floor is the import's: only the joins'
    regions are lifted off it)."""
    contacts = detect_contacts(motion)
    infos = []
    out = motion
    for r in regions:
        out, info = finish_region(out, r, contacts)
        infos.append(info)
    return out, infos
