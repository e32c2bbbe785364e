"""The two common joiners paper 000 §6 compares against, for ``--blend pose`` and ``--blend crossfade``.

Both blend the whole body, both motions playing, with a **linear** weight
over a **fixed** :data:`BLEND` seconds, and — as the methods they stand for —
no foot locking (their sliding feet are what the comparison shows):

- ``pose`` — the pose-based method ([10] Wang & Bodenheimer, [3] Kovar et al.):
  the pair of frames whose poses are closest (Kovar's distance over all
  joints, :mod:`synthesis.optimal.posedist`) — a frame of the first motion after its
  core, one of the next motion before its core — is found by one vectorised
  distance matrix; the next motion is moved in time so the two frames
  coincide, and in space so its hips stand where the first motion's do,
  facing the same way (Kovar's alignment); the blend is centred there.
- ``crossfade`` — what a game engine does when the next motion is triggered:
  the next motion starts at its scheduled time, its hips put on the first
  motion's hips at that moment (root motion continues), and the two are
  crossfaded over :data:`BLEND` s from there (the first motion holding its
  last pose if it has ended).

Compositions are laid and every join measured as for the other engines
(:mod:`synthesis.assemble`).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from text2anim.core.contacts import detect_contacts
from text2anim.core.ground import match, root_headings
from text2anim.core.motion import Motion

from .assemble import assemble
from .join.apply import Join, apply_join
from .join.commit import commit
from .join.gait import steps
from .join.laid import Laid
from .join.laying import TrackState, extend, lay_elements
from .join.placed import Placed
from .optimal.method_select import cyclic_core_begin, cyclic_core_end
from .optimal.posedist import distance_matrix, features
from .optimal.weights import linear_weights
from .result import BlendInterval, JoinReport, Result
from .tracks import Track

BLEND = 0.5  # s, both baselines
BASELINES = ("pose", "crossfade")


def _cores(tr: Motion, prev: Placed, inc: Placed) -> tuple[int, int]:
    """First frame after the first core and first frame of the next core, on the track (looped clips as
    :mod:`synthesis.optimal` counts them)."""
    c0_end = prev.offset + prev.core[1]
    if prev.cyclic:
        a_steps = [s for s in steps(detect_contacts(tr)) if s.begin >= prev.offset]
        c0_end = cyclic_core_end(a_steps, prev.offset + prev.lead, prev.offset + prev.stop,
                                 (prev.offset + prev.core[0], c0_end))
    c1 = (inc.offset + inc.core[0], inc.offset + inc.core[1])
    if inc.cyclic:
        c1 = (cyclic_core_begin(steps(inc.contacts, inc.offset), inc.first, c1), c1[1])
    return c0_end, c1[0]


def closest_pair(tr: Motion, a_range: tuple[int, int], b: Motion, b_range: tuple[int, int]) -> tuple[int, int, float]:
    """``(i, j, D)``: the track frame ``i`` in ``a_range`` and the frame ``j`` of ``b`` in ``b_range`` (both
    ``[lo, hi]``) whose poses are closest over all joints (Kovar); ties: the earliest."""
    joints = list(range(tr.skeleton.n_joints))
    ia = np.arange(a_range[0], a_range[1] + 1)
    jb = np.arange(b_range[0], b_range[1] + 1)
    D = distance_matrix(features(tr, joints, ia), features(b, joints, jb))
    i, j = np.unravel_index(int(np.argmin(D)), D.shape)
    return int(ia[i]), int(jb[j]), float(D[i, j])


def _join(state: TrackState, inc: Placed, fps: float, method: str, blend_s: float) -> None:
    prev = state.placed[-1]
    n = max(2, int(round(blend_s * fps)))
    half = n // 2
    tr = extend(state.laid(), inc.offset + inc.motion.n_frames + n, state.floor)
    c0_end, c1_begin = _cores(tr, prev, inc)
    info: dict = {}
    if method == "pose":
        a_lo = max(c0_end, state.floor) + half
        last = tr.n_frames - 1  # the incoming clip may end before the previous one would have
        a_hi = min(last, max(a_lo, prev.offset + prev.stop - 1))
        a_lo = min(a_lo, a_hi)
        b_lo = inc.lead
        b_hi = max(b_lo, c1_begin - inc.offset - (n - half))
        i, j, d = closest_pair(tr, (a_lo, a_hi), inc.motion, (b_lo, b_hi))
        offset = i - j
        rigid = match(inc.motion.root_positions[j], float(root_headings(inc.motion)[j]), tr.root_positions[i],
                      float(root_headings(tr)[i]))
        w0 = i - half
        info = {"closest_s": [i / fps, (j - inc.lead) / fps], "pose_distance_m": d,
                "shift_s": (offset - inc.offset) / fps}
    else:
        offset = inc.offset
        w0 = max(inc.first, state.floor)
        k = w0 - offset
        rigid = match(inc.motion.root_positions[k], float(root_headings(inc.motion)[k]), tr.root_positions[w0],
                      float(root_headings(tr)[w0]))
    w1 = w0 + n + 1
    placed = rigid.apply(inc.motion)
    frames = np.arange(w0, w1)
    w = linear_weights(n)
    join = Join(method, rigid, offset, (w0, w1), frames.astype(np.float64), (frames - offset).astype(np.float64),
                w, {}, {})
    out, _ = apply_join(tr, placed, inc.contacts, join, lock=False)
    stop = int(np.clip(inc.end - offset, 1, inc.motion.n_frames)) if inc.cyclic else inc.stop
    rep = JoinReport(prev.element.id, inc.element.id, inc.joined_by, method,
                     (BlendInterval("whole", "motion-motion", w0 / fps, (w1 - 1) / fps),), None, info, ())
    p = replace(inc, motion=placed, offset=offset, stop=stop, rigid=rigid)
    commit(state, p, out, rep, (w0, w1), (w0, w1), w0, w1, (offset - inc.offset) / fps)


def lay_track(track: Track, whole, fps: float, method: str, blend_s: float = BLEND) -> Laid:
    """The whole-body elements of a track joined by ``method`` (``pose`` or ``crossfade``)."""
    if method not in BASELINES:
        raise ValueError(f"unknown baseline {method!r}; known: {', '.join(BASELINES)}")
    return lay_elements(track, whole, fps, lambda state, inc: _join(state, inc, fps, method, blend_s))


def synthesize_baseline(tracks: Sequence[Track], fps: float = 30.0, method: str = "crossfade", *,
                        sway: bool = True, blend_s: float = BLEND) -> Result:
    """Tracks → one motion per actor by the ``pose`` or ``crossfade`` baseline (see the module docstring)."""
    if method not in BASELINES:
        raise ValueError(f"unknown baseline {method!r}; known: {', '.join(BASELINES)}")
    return assemble(tracks, fps, lambda track, whole: lay_track(track, whole, fps, method, blend_s), sway)
