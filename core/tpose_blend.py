"""The converter's blend out of a dropped T-pose, held still.

Some exporters prepend a T-pose frame (``--drop-first`` drops it) and then blend out of it: every take
of cgspeed's CMU conversion (``cmu_everyday``) moves its fastest joint at 26-34 m/s over the next
frames, decaying and ringing (e.g. 32, 29, 20, 7.8, 0.9, 4.2 m/s at 120 fps) before the capture's own
speeds (a median of 0.2-2 m/s). No body moves a joint that fast from rest; the frames are an
interpolation between the T-pose and the first captured pose, and their legs swing through the floor
(an imported climb's toe tips 1.4-2.4 cm under it).

:func:`held_blend` finds those leading frames (the first faster than :data:`BLEND_START`, then
while the fastest joint moves faster than :data:`BLEND_FACTOR` times the take's median speed, at most :data:`MAX_BLEND_SECONDS`) and gives them
the first settled frame's pose: the frame count and every time in the file stay as they were (a clip's
core interval, given in the file's seconds, still means the same frames).

Shapes: positions ``(T, J, 3)`` metres; speeds ``(T - 1,)`` m/s.
"""
from __future__ import annotations

import numpy as np

from .motion import Motion

#: a leading frame belongs to the blend while the fastest joint moves faster than this many times the
#: take's median fastest-joint speed (the blends read 13-40 times; capture's own first frames 0.1-2.5)
BLEND_FACTOR = 4.0
#: m/s: a blend starts faster than this (no joint leaves rest that fast: a kick's foot peaks at 12-14 m/s
#: after a wind-up); a take whose first frames are slower has no blend, however still the rest of it is
BLEND_START = 15.0
#: seconds: the longest blend held (cgspeed's take 3-7 frames at 120 fps)
MAX_BLEND_SECONDS = 0.1


def blend_frames(motion: Motion) -> int:
    """How many leading frames of ``motion`` are a blend out of a T-pose (0 when none)."""
    if motion.n_frames < 3:
        return 0
    pos = motion.positions
    speed = np.linalg.norm(np.diff(pos, axis=0), axis=2).max(axis=1) * motion.fps  # (T - 1,) fastest joint
    if speed[0] <= BLEND_START:
        return 0
    fast = speed[:int(MAX_BLEND_SECONDS * motion.fps)] > BLEND_FACTOR * np.median(speed)
    return len(fast) if fast.all() else int(np.argmin(fast))


def held_blend(motion: Motion) -> tuple[Motion, int]:
    """``motion`` with its leading blend (:func:`blend_frames`) holding the first settled frame's pose, and
    how many frames were held."""
    k = blend_frames(motion)
    if k == 0:
        return motion, 0
    rot, root = motion.rotations.copy(), motion.root_positions.copy()
    rot[:k], root[:k] = rot[k], root[k]
    tr = None
    if motion.translations is not None:
        tr = motion.translations.copy()
        tr[:k] = tr[k]
    return motion.replace(rotations=rot, root_positions=root, translations=tr), k
