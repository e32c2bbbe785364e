"""Contacts planted: a restyled clip's feet held on the floor where they stand, as the clip had them.

The modifiers move a standing foot (a thigh swung further, the hips carried further or lower); here each
contact of the clip as captured (:func:`core.contacts.detect_contacts`) is held again: the ankle stays where
it stands at the middle of the contact (at the captured ankle's height, frame by frame) and turns as the
captured foot did (eased as the target is), the leg solved by two-bone IK (:func:`core.ik.leg_ik`), its reach softened near full length
(:func:`core.retarget.soft_reach`: a knee snapping straight for a frame is a jerk). Over :data:`EASE` frames before a
contact and :data:`EASE_OUT` after it the target eases from the foot's free path to the held point, so no frame jumps. The foot
locking of the synthesis, later, does the same at the joins between clips.
"""
from __future__ import annotations

import numpy as np

from text2anim.core import quat
from text2anim.core.bodyparts import BodyMap
from text2anim.core.contacts import detect_contacts
from text2anim.core.easing import smoothstep
from text2anim.core.ik import leg_ik, set_world_rotation
from text2anim.core.motion import Motion
from text2anim.core.retarget import soft_reach

from ..join.cycles import loop

#: Frames over which a held foot's target eases into its contact, and out of it: a foot lifting off leaves
#: quickly (held longer, it lingers low and slow enough to read as touching the floor again).
EASE = 6
EASE_OUT = 3


def plant(styled: Motion, captured: Motion, bm: BodyMap, cyclic: bool = False) -> Motion:
    """``styled`` with the feet of ``captured``'s contacts held (both clips of the same frames). A looping clip
    is held as it plays, looped (a contact across its seam is one contact, held at one point)."""
    if cyclic and styled.n_frames >= 3:
        n = styled.n_frames
        held = _plant(loop(styled, 3 * n, -n), loop(captured, 3 * n, -n), bm)
        return styled.replace(rotations=held.rotations[n:2 * n])
    return _plant(styled, captured, bm)


def _plant(styled: Motion, captured: Motion, bm: BodyMap) -> Motion:
    contacts = detect_contacts(captured)
    out = styled
    for side in ("left", "right"):
        ankle = bm.feet[side][0]
        intervals = contacts.intervals(side)
        weight = held_weight(intervals, out.n_frames)
        mask = weight > 0
        if not mask.any():
            continue
        targets = _targets(out.positions[:, ankle], captured.positions[:, ankle], intervals)
        knee = int(out.skeleton.parents[ankle])
        hip = int(out.skeleton.parents[knee])
        rest = out.skeleton.rest_positions()
        length = float(np.linalg.norm(rest[knee] - rest[hip]) + np.linalg.norm(rest[ankle] - rest[knee]))
        out = leg_ik(out, side, soft_reach(out.positions[:, hip], targets, length), mask)
        turns = quat.slerp(out.pose.quaternions(ankle), captured.pose.quaternions(ankle), weight)
        out = set_world_rotation(out, ankle, turns, mask)
    return out


def _eases(intervals: list[tuple[int, int]], T: int) -> list[tuple[int, int, int, int]]:
    """Per contact ``(a, b)``: ``(lo, a, b, hi)``, its frames with the eases on either side, each ease at most
    :data:`EASE` frames and half the gap to the next contact (so two contacts' eases never overlap)."""
    out = []
    for k, (a, b) in enumerate(intervals):
        before = a - intervals[k - 1][1] if k else a
        after = intervals[k + 1][0] - b if k + 1 < len(intervals) else T - b
        out.append((a - min(EASE, before // 2), a, b, b + min(EASE_OUT, after // 2)))
    return out


def _ramp(frames: np.ndarray, lo: int, a: int, b: int, hi: int) -> np.ndarray:
    """1 on ``[a, b)``, easing to 0 over ``[lo, a)`` and ``[b, hi)``."""
    w = np.ones(len(frames))
    up, down = frames < a, frames >= b
    w[up] = smoothstep((frames[up] - lo + 1) / (a - lo + 1))
    w[down] = smoothstep((hi - frames[down]) / (hi - b + 1))
    return w


def held_weight(intervals: list[tuple[int, int]], T: int) -> np.ndarray:
    """How much a foot is held per frame ``(T,)``: 1 in its contacts, easing to 0 around them."""
    weight = np.zeros(T)
    for lo, a, b, hi in _eases(intervals, T):
        frames = np.arange(lo, hi)
        weight[lo:hi] = _ramp(frames, lo, a, b, hi)
    return weight


def _targets(free: np.ndarray, captured: np.ndarray, intervals: list[tuple[int, int]]) -> np.ndarray:
    """The ankle's targets ``(T, 3)``: its ``free`` path moved, in each contact, onto the point it stands on
    at the contact's middle (at the ``captured`` ankle's height), the move easing in and out around it."""
    out = free.copy()
    for lo, a, b, hi in _eases(intervals, len(free)):
        mid = (a + b - 1) // 2
        frames = np.arange(lo, hi)
        held = np.column_stack([np.full(len(frames), free[mid, 0]), captured[lo:hi, 1],
                                np.full(len(frames), free[mid, 2])])
        out[lo:hi] += _ramp(frames, lo, a, b, hi)[:, None] * (held - free[lo:hi])
    return out
