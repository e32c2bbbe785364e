"""What the scene reads of an actor's motion: where the body is and faces, where its hands and feet are,
and the frame a hand is lowest (picking a thing up, putting it down); the instants of contact are
:mod:`core.contact_instant`'s.

Every function takes a :class:`core.motion.Motion` (metres, Y up, heading 0 faces +Z) and frame indices
on its own clock; arrays are ``(T, 3)`` positions unless said otherwise.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.ground import headings
from text2anim.core.motion import Motion


#: s: the heading is averaged over this window (a gait's pelvis swings 5-10° each way per step).
HEADING_WINDOW = 0.6


def hips_path(motion: Motion) -> tuple[np.ndarray, np.ndarray]:
    """The hips over the floor ``(T, 3)`` (y = 0) and the body's heading ``(T,)`` rad, averaged over
    :data:`HEADING_WINDOW` (held at the ends, never extrapolated: an approach is measured at its last frame)."""
    return motion.cache.get("scene_path", lambda: _hips_path(motion))


def _hips_path(motion: Motion) -> tuple[np.ndarray, np.ndarray]:
    path = np.array(motion.root_positions, dtype=float)
    path[:, 1] = 0.0
    return path, np.asarray(headings(motion, HEADING_WINDOW))


def forward(heading: float) -> np.ndarray:
    """The unit floor vector a heading faces, ``(3,)``: ``(sin h, 0, cos h)``."""
    return np.array([np.sin(heading), 0.0, np.cos(heading)])


def heading_to(a: np.ndarray, b: np.ndarray) -> float:
    """The heading that faces from floor point ``a`` to ``b`` (rad)."""
    d = np.asarray(b, dtype=float) - np.asarray(a, dtype=float)
    return float(np.arctan2(d[0], d[2]))


def chest_heading(motion: Motion, f: int) -> float:
    """Where the chest faces at frame ``f`` (rad): the forward normal of the line across the shoulders (a
    throw's hips lag its chest)."""
    bm, parents = body_map(motion.skeleton), motion.skeleton.parents
    left, right = (motion.positions[f, parents[parents[bm.hands[s]]]] for s in ("left", "right"))
    across = left - right
    return float(np.arctan2(-across[2], across[0]))  # forward = left x up


def hand(motion: Motion, side: str) -> np.ndarray:
    """A hand's grip point ``(T, 3)``: the wrist carried 8 cm on along the forearm (the palm)."""
    bm = body_map(motion.skeleton)
    pos = motion.positions
    wrist = pos[:, bm.hands[side]]
    elbow = pos[:, motion.skeleton.parents[bm.hands[side]]]
    along = wrist - elbow
    along /= np.maximum(np.linalg.norm(along, axis=1, keepdims=True), 1e-6)
    return wrist + 0.08 * along


def hands(motion: Motion) -> np.ndarray:
    """The point between both hands' grips ``(T, 3)`` (a box or a book held in both)."""
    return 0.5 * (hand(motion, "left") + hand(motion, "right"))


def toe(motion: Motion, side: str) -> np.ndarray:
    """A foot's toe joint ``(T, 3)``."""
    return motion.positions[:, body_map(motion.skeleton).feet[side][1]]


def lowest(points: np.ndarray, lo: int, hi: int) -> int:
    """The frame in ``[lo, hi)`` where a point ``(T, 3)`` is lowest (a hand picking a thing up or putting it
    down)."""
    lo = int(np.clip(lo, 0, max(len(points) - 1, 0)))
    hi = int(np.clip(hi, lo + 1, len(points)))
    return lo + int(np.argmin(points[lo:hi, 1]))


def speed(points: np.ndarray, fps: float) -> np.ndarray:
    """Speed of a point ``(T, 3)`` -> ``(T,)`` m/s (central differences)."""
    if len(points) < 2:
        return np.zeros(len(points))
    return np.linalg.norm(np.gradient(points, 1.0 / fps, axis=0), axis=1)
