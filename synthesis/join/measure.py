"""What every engine measures at a join (``docs/timetable.md`` §3): foot skate, skating ratio, jerk, fidelity.

Windows are ``[w0, w1)`` track frames; speeds cm/s, distances cm.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.contacts import FootContacts, detect_contacts, foot_tracks
from text2anim.core.metrics import SKATING_MARGIN, jerk, skating_by_frame
from text2anim.core.motion import Motion

from .blend import sample
from .composition import Composed
from .placed import Placed


def _foot_skate_window(track: Motion, contacts: FootContacts, tracks: dict, w0: int, w1: int) -> dict:
    out = {}
    for side, tr in tracks.items():
        c = contacts.of(side)[w0:w1]
        sp = tr.speed[w0:w1][c]
        out[side] = {"mean_cm_s": float(sp.mean() * 100) if len(sp) else 0.0,
                     "max_cm_s": float(sp.max() * 100) if len(sp) else 0.0,
                     "slide_cm": float(sp.sum() / track.fps * 100) if len(sp) else 0.0,
                     "contact_frames": int(c.sum())}
    return out


def skating_frames(motion: Motion) -> np.ndarray:
    """Per frame, whether a foot skates: the GMD rule of :func:`core.metrics.skating_by_frame` (either toe
    below 5 cm on frames t and t+1, faster than 0.5 m/s and so over its centred 5-frame average), ``(T,)``
    bool at the motion's own rate; the figure a join is judged by, as the benchmark judges the output."""
    return skating_by_frame(motion)


def skating_exceeds(ratio: float, sources: float) -> bool:
    """Whether a join's skating ``ratio`` is beyond issue 11's bound: its sources' larger + 0.01
    (:func:`core.metrics.against_sources`)."""
    return ratio > sources + SKATING_MARGIN + 1e-12


def max_slide(motion: Motion) -> float:
    """Largest horizontal speed (cm/s) of a foot while it is in contact, over a whole motion."""
    c = detect_contacts(motion)
    return max((float(tr.speed[c.of(s)].max() * 100) if c.of(s).any() else 0.0)
               for s, tr in foot_tracks(motion).items())


def window_metrics(track: Motion, w0: int, w1: int, contacts: FootContacts, ftracks: dict,
                    skating: np.ndarray) -> dict:
    w0, w1 = max(0, w0), min(track.n_frames, w1)
    fs = _foot_skate_window(track, contacts, ftracks, w0, w1)
    jk = jerk(track, w0, w1)
    return {"frames": [w0, w1],
            "skating_ratio": float(skating[w0:w1].mean()) if w1 > w0 else 0.0,
            "foot_skate": fs,
            "max_slide_cm_s": max(v["max_cm_s"] for v in fs.values()),
            "jerk_max": jk.max, "jerk_rms": jk.rms}


def core_fidelity(track: Motion, placed: Placed, joints=None) -> float:
    """Largest joint position error (cm) in the element's core between the track and the placed clip."""
    c0, c1 = placed.core
    lo = max(placed.offset + c0, 0)
    hi = min(placed.offset + c1, track.n_frames, placed.offset + placed.motion.n_frames)
    if hi <= lo:
        return 0.0
    a = track[lo:hi].positions
    b = placed.motion[lo - placed.offset:hi - placed.offset].positions
    if joints is not None:
        a, b = a[:, joints], b[:, joints]
    return float(np.linalg.norm(a - b, axis=-1).max() * 100)


def hips_frame(points: np.ndarray, hips: np.ndarray, hips_rot: np.ndarray) -> np.ndarray:
    """World points ``(T, K, 3)`` in the hips' own frame (position ``(T, 3)``, rotation matrices ``(T, 3, 3)``)."""
    return np.einsum("tji,tkj->tki", hips_rot, points - hips[:, None, :])


def part_fidelity(track: Motion, comp: Composed, donor: Motion, core: tuple[int, int]) -> float:
    """Largest error (cm) of the switched part's joints relative to the hips (the hips' frame) against
    the partial clip, over the frames of its core that are fully switched (outside the blends)."""
    t = comp.timing
    n = t.ta1 - t.ta0
    k = np.arange(t.blend_in, n - t.blend_out)
    if len(k) == 0:
        return 0.0
    src = t.tb0 + k * (t.tb1 - t.tb0) / max(n, 1)
    keep = (src >= core[0]) & (src <= core[1] - 1)
    if not keep.any():
        return 0.0
    k, src = k[keep], src[keep]
    ref = sample(donor, src)
    out = track[t.ta0:t.ta1]
    joints = list(comp.joints)

    def rel(m: Motion, frames=None):
        pose = m.pose
        p = pose.positions if frames is None else pose.positions[frames]
        r = pose.rotations[:, 0] if frames is None else pose.rotations[frames, 0]
        return hips_frame(p[:, joints], p[:, 0], r)

    return float(np.linalg.norm(rel(out, k) - rel(ref), axis=-1).max() * 100)

