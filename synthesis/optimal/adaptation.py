"""Motion adaptation of paper 000 §4.1/§4.2.3: the next motion's lower body fitted to the previous feet.

"後の要素動作の下半身の姿勢を前の要素動作の両足の位置に合わせて変形させた動作":
the next motion with its lower body deformed so that its feet stand where the
previous motion left them. The next motion is first placed through its
support foot (:func:`synthesis.join.align.align_through_foot`), so that foot needs
no change; the other foot is ``d`` metres (horizontally) from where the
previous motion has it. :func:`adapt`:

- every foot target is the motion's own foot moved by its offset (0 for the
  support foot, ``d`` for the other), so a foot that is planted in the motion
  stays planted, where the previous motion had it;
- **the hips keep their place relative to both feet** (§4.1, last paragraph
  of the method list): they move by the mean of the two offsets, and sink
  where the legs could not otherwise reach a stance wider than the motion's
  own (:func:`_sink`; beyond the paper, which leaves an unreachable foot
  hanging above its place);
- both legs are solved by two-bone IK (:func:`core.ik.leg_ik`'s arithmetic, both legs as rows of one
  :func:`core.ik.solve_rows`) and each ankle keeps its world orientation (:func:`core.ik.set_world_rotation`'s),
  so the sole stays on the ground; the upper body is untouched (its joints are
  local to the hips).

The return to the motion's own lower body over the next step (eq. (8)) fades
the same deformation (``scale`` from 1 to 0), so the motion's own movement
plays through it and the support foot never moves. **Departure from eq. (8)**: the hips do not keep to
that fade. A change of stance of 40-90 cm returned over one step moved them 20-45 cm in 0.3-0.5 s (6-11
m/s², a jolt no capture has); the join post-pass bends their path by a few centimetres into the one of
least acceleration that keeps a slow body over its feet (:mod:`synthesis.join.hipspath`), so they shift
the weight before the step and spread the travel over the join, while the feet return as eq. (8) says.
:func:`pin_feet` puts feet
back exactly on reference positions where they should be planted — used when
§4.4.2 case (c) turns that return into a pose–pose blend of two leg solutions,
which would otherwise let a planted foot drift by a few millimetres per frame.
"""
from __future__ import annotations

import numpy as np
from scipy.ndimage import gaussian_filter1d, maximum_filter1d

from text2anim.core import rotkernels as rk
from text2anim.core.bodyparts import body_map
from text2anim.core.ik import leg_ik, set_world_rotation, solve_rows
from text2anim.core.kept import Kept, digest
from text2anim.core.motion import Motion
from text2anim.core.size import leg_length

from ..join.gait import SIDES
from ..join.legsolve import chain_length, leg_chain, put_legs


#: The last adaptations of the process, by the value of what :func:`adapt` reads: a warm process plans and renders
#: the same joins again (the studio re-animates the text at every pause in typing).
KEPT_ADAPTED: Kept[Motion] = Kept(16)


def adapt(motion: Motion, offsets: dict[str, np.ndarray], scale=None) -> Motion:
    """``motion`` with each foot moved by ``offsets[side]`` (metres, ``(3,)``; only x and z are used),
    the hips by their mean, legs re-solved by IK, ankles keeping their world rotation.

    ``scale`` ``(T,)`` in [0, 1] (default 1 everywhere) scales the offsets per frame: 1 is the adapted
    motion, 0 the motion's own; in between the deformation fades (eq. (8)'s return to the own pose, which
    leaves a support foot with no offset exactly where it is). An answer given before is taken from
    :data:`KEPT_ADAPTED`.
    """
    moves = tuple((s, np.asarray(v, dtype=np.float64).tobytes()) for s, v in sorted(offsets.items()))
    key = (_frames_digest(motion), moves, None if scale is None else digest(np.asarray(scale, dtype=np.float64)))
    known = KEPT_ADAPTED.known(key)
    if known is not None:
        return known
    out = _adapt(motion, offsets, scale)
    return out if out is motion else KEPT_ADAPTED.put(key, out)


def _frames_digest(motion: Motion) -> bytes:
    """A digest of everything of ``motion`` :func:`adapt` reads (its frames, rate and bones), kept with it."""
    def make() -> bytes:
        sk = motion.skeleton
        return digest(sk.names, sk.parents, sk.offsets, motion.fps, motion.root_positions, motion.rotations,
                      motion.translations)
    return motion.cache.get("adaptation.frames_digest", make)


def _adapt(motion: Motion, offsets: dict[str, np.ndarray], scale) -> Motion:
    feet = body_map(motion.skeleton).feet
    d = {s: np.array([float(v[0]), 0.0, float(v[2])]) for s, v in offsets.items()}
    if max(np.abs(x).max() for x in d.values()) < 1e-9:
        return motion
    k = np.ones(motion.n_frames) if scale is None else np.asarray(scale, dtype=np.float64).reshape(-1)
    shift = np.outer(k, 0.5 * (d["left"] + d["right"]))
    pose = motion.pose
    targets = {s: pose.positions[:, feet[s][0]] + np.outer(k, d[s]) for s in feet}
    shift[:, 1] = -_sink(motion, targets, shift)
    mask = (k > 1e-9) | (shift[:, 1] < -1e-9)  # the legs solved wherever the hips moved (a sink eases in and out)
    out = motion.replace(root_positions=motion.root_positions + shift)
    if not mask.any():
        return out
    frames = np.flatnonzero(mask)
    world = rk.as_quat(rk.from_matrix(pose.rotations[frames[:, None], [feet[s][0] for s in SIDES]]))  # (n * 2, 4)
    ankles = {s: world[i::len(SIDES)] for i, s in enumerate(SIDES)}  # each ankle keeps its world rotation
    return out.replace(rotations=_legs_to(out, frames, {s: targets[s][frames] for s in SIDES}, ankles))


def _legs_to(motion: Motion, frames: np.ndarray, targets: dict[str, np.ndarray],
             ankles: dict[str, np.ndarray]) -> np.ndarray:
    """The local rotations ``(T, J, 4)`` of ``motion`` with, on ``frames`` ``(n,)``, each leg's ankle on
    ``targets[side]`` ``(n, 3)`` (world, metres; two-bone IK keeping the knee's bend plane) and turned to the
    world rotations ``ankles[side]`` ``(n, 4)``: :func:`core.ik.leg_ik` then :func:`core.ik.set_world_rotation`
    per leg, both legs as rows of one solve (per row the same arithmetic: the same bits; the legs' subtrees
    are apart, so neither solve reads what the other changed)."""
    chains = [leg_chain(motion, s) for s in SIDES]
    pose = motion.pose
    P, R = pose.positions[frames], pose.rotations[frames]
    hip, knee, ankle = (np.concatenate([np.full(len(frames), c[i]) for c in chains]) for i in range(3))
    rows = np.tile(np.arange(len(frames)), len(SIDES))
    Rp = R[rows, motion.skeleton.parents[hip]]
    poles = P[rows, knee]
    qa, qb = solve_rows(P[rows, hip], poles, P[rows, ankle], R[rows, hip], R[rows, knee], Rp,
                        np.concatenate([targets[s] for s in SIDES]), poles.copy())
    return put_legs(motion.rotations, np.concatenate([frames] * len(SIDES)), (hip, knee, ankle), qa, qb, Rp,
                    np.concatenate([ankles[s] for s in SIDES]))


#: fraction of a leg's length the adapted legs may stretch to (a straight leg has no bend left to give)
STRETCH = 0.98
#: leg lengths: the most the hips sink (a lunge's depth; further, a knee would reach the floor)
MAX_SINK = 0.15
#: s: the hips sink and rise over at least this (a Gaussian of this sigma over the frames that need it)
SINK_S = 0.1


def _sink(motion: Motion, targets: dict[str, np.ndarray], shift: np.ndarray) -> np.ndarray:
    """``(T,)`` metres the hips sink so both legs reach their adapted feet ``targets`` (per side ``(T, 3)``)
    from the hips moved by ``shift`` ``(T, 3)``: a stance wider than the motion's own is stood in lower, as
    a person does, instead of leaving a foot hanging above its place on a straightened leg. Held over
    :data:`SINK_S` either side and smoothed (the most any frame needs is kept), 0 where the legs reach."""
    pos = motion.pose.positions
    need = np.zeros(motion.n_frames)
    for side in targets:
        hip, _knee, ankle = chain = leg_chain(motion, side)
        reach = STRETCH * chain_length(motion, chain)

        def over(h: np.ndarray, t: np.ndarray) -> np.ndarray:  # how far the hip is above its highest place
            flat = np.hypot(*(t - h)[:, [0, 2]].T)  # a foot further away than the leg reaches: sinking cannot help
            top = np.sqrt(np.maximum(reach ** 2 - np.minimum(flat, reach) ** 2, 0.0))
            return np.where(flat < reach, h[:, 1] - (t[:, 1] + top), 0.0)
        # only what the adaptation adds: a leg the motion itself holds straight is not the adaptation's to bend
        need = np.maximum(need, over(pos[:, hip] + shift, targets[side]) - np.maximum(over(pos[:, hip], pos[:, ankle]), 0.0))
    need = np.clip(need, 0.0, MAX_SINK * leg_length(motion.skeleton))
    if not need.any():
        return need
    n = max(1, int(round(SINK_S * motion.fps)))
    held = maximum_filter1d(need, 2 * n + 1, mode="nearest")
    return np.maximum(gaussian_filter1d(held, n, mode="nearest"), need)


def pin_feet(motion: Motion, reference: Motion, masks: dict[str, np.ndarray]) -> Motion:
    """``motion`` with each foot put on ``reference``'s (ankle position and world rotation) on the frames
    where ``masks[side]`` ``(T,)`` is true; both motions on the same frames."""
    feet = body_map(motion.skeleton).feet
    ref = reference.pose
    out = motion
    for side, mask in masks.items():
        mask = np.asarray(mask, dtype=bool)
        if not mask.any():
            continue
        ankle = feet[side][0]
        out = leg_ik(out, side, ref.positions[:, ankle], mask=mask)
        out = set_world_rotation(out, ankle, rk.as_quat(rk.from_matrix(ref.rotations[:, ankle])), mask=mask)
    return out
