"""Foot–ground contact labels and foot-moving intervals.

A foot is its ankle and toe joints. On each frame it is in contact when

- its lowest joint is within :data:`HEIGHT_THRESHOLD` (5 cm) of that foot's
  floor level, and
- that joint's horizontal speed is below :data:`SPEED_THRESHOLD` (0.4 m/s).

The floor level of a foot is its planted height: the 5th percentile of its
lowest joint's height over the clip, clamped to ``[0, 0.10]`` m (joint
centres sit a few centimetres above the ground: the CMU toes at 1-4 cm). A
file whose feet are nowhere near y = 0 (a capture volume with its floor at
0.93 m, or more than 10 cm below 0) is read from its own lower foot: ``[b, b + 0.10]`` with ``b``
the lower of the two feet's levels.
Labels are then cleaned by hysteresis: gaps and runs shorter than
:data:`MIN_PHASE` seconds are absorbed into their neighbours, so a one-frame
flicker is never a step.

The speed here is a central difference over frames, in m/s.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .bodyparts import body_map
from .motion import Motion

HEIGHT_THRESHOLD = 0.05  # m above the foot's floor level
SPEED_THRESHOLD = 0.4  # m/s, horizontal
MIN_PHASE = 0.05  # s; shorter contact runs or gaps are flicker
FLOOR_PERCENTILE = 5.0
MAX_FLOOR = 0.10  # m


def runs(mask: np.ndarray) -> np.ndarray:
    """``(N, 2)`` array of ``[start, stop)`` frame ranges where ``mask`` is true."""
    m = np.concatenate([[False], np.asarray(mask, dtype=bool), [False]])
    d = np.diff(m.astype(np.int8))
    return np.stack([np.flatnonzero(d == 1), np.flatnonzero(d == -1)], axis=1)


def _drop_short(mask: np.ndarray, value: bool, min_len: int, keep_edges: bool) -> np.ndarray:
    """``mask`` with its runs of ``value`` shorter than ``min_len`` frames flipped (those touching either
    end kept when ``keep_edges``); runs are found once, on ``mask`` as given."""
    r = runs(mask if value else ~mask)
    drop = r[:, 1] - r[:, 0] < min_len
    if keep_edges:
        drop &= (r[:, 0] != 0) & (r[:, 1] != len(mask))
    out = mask.copy()
    if drop.any():  # runs are disjoint: +1 where a dropped run starts, -1 where it stops, summed
        edges = np.zeros(len(mask) + 1, dtype=np.int64)
        edges[r[drop, 0]] += 1
        edges[r[drop, 1]] -= 1
        out[np.cumsum(edges[:-1]) > 0] = not value
    return out


def hysteresis(mask: np.ndarray, min_len: int) -> np.ndarray:
    """Fill interior gaps shorter than ``min_len`` frames, then drop shorter runs."""
    if min_len <= 1 or len(mask) == 0:
        return np.asarray(mask, dtype=bool).copy()
    filled = _drop_short(np.asarray(mask, dtype=bool), False, min_len, keep_edges=True)
    return _drop_short(filled, True, min_len, keep_edges=False)


def horizontal_speed(positions: np.ndarray, fps: float) -> np.ndarray:
    """Horizontal (XZ) speed in m/s of ``(T, ..., 3)`` positions, ``(T, ...)``."""
    if len(positions) < 2:
        return np.zeros(positions.shape[:-1])
    vel = np.gradient(positions[..., [0, 2]], axis=0) * fps
    return np.linalg.norm(vel, axis=-1)


@dataclass(frozen=True)
class FootTrack:
    """Per-frame data of one foot: ``height`` above its floor (m), ``speed`` (m/s), ``joint`` lowest joint index, all ``(T,)``."""

    height: np.ndarray
    speed: np.ndarray
    joint: np.ndarray


def _lowest(motion: Motion) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    """``(sides, joints, positions, lowest)``: each foot's ankle and toe ``(2 * feet,)``, their world positions
    ``(T, feet, 2, 3)`` and which of the two is lower on each frame ``(T, feet)``."""
    bm = body_map(motion.skeleton)
    sides = list(bm.feet)
    joints = np.array([j for side in sides for j in bm.feet[side]])  # (2 * feet,) ankle, toe per foot
    pos = motion.positions[:, joints].reshape(motion.n_frames, len(sides), 2, 3)  # (T, feet, 2, 3)
    return sides, joints, pos, np.argmin(pos[..., 1], axis=2)


def lowest_heights(motion: Motion) -> np.ndarray:
    """``(T, feet)`` m: the world height of each foot's lowest joint (feet in ``body_map`` order), what
    :func:`floor_levels` reads. Per frame: a track's is its pieces' end to end."""
    _sides, _joints, pos, lowest = _lowest(motion)
    return pos[np.arange(motion.n_frames)[:, None], np.arange(pos.shape[1])[None, :], lowest, 1]


def floor_levels(heights: np.ndarray) -> np.ndarray:
    """``(feet,)`` m: each foot's floor level (module docstring) from its :func:`lowest_heights` ``(T, feet)``."""
    level = np.percentile(heights, FLOOR_PERCENTILE, axis=0)  # (feet,)
    # a file whose floor is not near y = 0 (PyMO's walk stands at 0.93 m): levels from its own lowest foot
    base = float(level.min()) if abs(level.min()) > MAX_FLOOR else 0.0
    return np.clip(level, base, base + MAX_FLOOR)


def foot_tracks(motion: Motion, floor: np.ndarray | None = None) -> dict[str, FootTrack]:
    """Height above floor and horizontal speed of each foot's lowest joint (both feet in one pass: every
    quantity is per frame and joint, or per foot column). ``floor``: the feet's levels ``(feet,)``, default
    the motion's own (:func:`floor_levels`)."""
    sides, joints, pos, lowest = _lowest(motion)
    rows = np.arange(motion.n_frames)[:, None]
    cols = np.arange(len(sides))[None, :]
    y = pos[rows, cols, lowest, 1]
    if len(y):
        floor = floor_levels(y) if floor is None else floor
        speed = horizontal_speed(pos, motion.fps)[rows, cols, lowest]
    else:
        floor, speed = np.zeros(len(sides)), y
    which = joints.reshape(len(sides), 2)
    return {side: FootTrack(y[:, k] - floor[k], speed[:, k], which[k][lowest[:, k]]) for k, side in enumerate(sides)}


@dataclass(frozen=True)
class FootContacts:
    """Contact labels per foot, ``(T,)`` booleans, at ``fps``."""

    fps: float
    left: np.ndarray
    right: np.ndarray

    def of(self, side: str) -> np.ndarray:
        return {"left": self.left, "right": self.right}[side]

    def intervals(self, side: str) -> list[tuple[int, int]]:
        """Contact intervals of one foot as ``[start, stop)`` frames."""
        return [(int(a), int(b)) for a, b in runs(self.of(side))]

    def moving(self, side: str) -> list[tuple[int, int]]:
        """Foot-moving intervals (lift-off to landing) of one foot, ``[start, stop)`` frames."""
        return [(int(a), int(b)) for a, b in runs(~self.of(side))]

    def state(self) -> np.ndarray:
        """Per-frame contact state code: 0 none, 1 left, 2 right, 3 both, ``(T,)``."""
        return self.left.astype(np.int8) + 2 * self.right.astype(np.int8)

    def phases(self) -> list[tuple[int, int, str]]:
        """Runs of equal state as ``(start, stop, "both"|"left"|"right"|"none")``."""
        st = self.state()
        if len(st) == 0:
            return []
        cuts = np.flatnonzero(np.diff(st)) + 1
        starts = np.concatenate([[0], cuts])
        stops = np.concatenate([cuts, [len(st)]])
        names = ("none", "left", "right", "both")
        return [(int(a), int(b), names[st[a]]) for a, b in zip(starts, stops)]


def detect_contacts(motion: Motion) -> FootContacts:
    """Contact labels of both feet (see the module docstring for the rule); read-only arrays, found once
    per motion and kept in its cache (a join asks for the same clips' contacts many times)."""
    return motion.cache.get("contacts", lambda: _detect(motion))


def contacts_within(motion: Motion, floor: np.ndarray) -> FootContacts:
    """:func:`detect_contacts`' labels of ``motion`` with the feet's floor levels ``floor`` ``(feet,)`` given
    (:func:`floor_levels`): those of a longer track ``motion`` is a window of. The rest of the rule reads a few
    frames either side (the speed's difference, the hysteresis' :data:`MIN_PHASE` twice), so the labels are
    the track's bit for bit but within ``2 * MIN_PHASE`` s and a frame of a window's end inside the track."""
    return _detect(motion, floor)


def lowest_tracks(motion: Motion) -> tuple[np.ndarray, np.ndarray]:
    """``(heights, speeds)``, ``(T, feet)`` each (feet in ``body_map`` order): the world height (m) and the
    horizontal speed (m/s) of each foot's lowest joint, what the rule reads before the floor levels. Per frame,
    but a frame's speed reads its neighbours (a track's is its pieces' end to end except a frame either side of
    a seam: the first and last frames' speeds are one-sided differences)."""
    _sides, _joints, pos, lowest = _lowest(motion)
    rows = np.arange(motion.n_frames)[:, None]
    cols = np.arange(pos.shape[1])[None, :]
    y = pos[rows, cols, lowest, 1]
    return y, (horizontal_speed(pos, motion.fps)[rows, cols, lowest] if len(y) else y)


def contacts_of(heights: np.ndarray, speeds: np.ndarray, fps: float, floor: np.ndarray | None = None) -> FootContacts:
    """:func:`detect_contacts`' labels from a motion's :func:`lowest_tracks` (``(T, feet)`` each, the feet
    ``left`` then ``right``): a long track's kept and extended by its new frames' values instead of redone
    (:func:`synthesis.join.laying.extended`). ``floor``: the feet's levels ``(feet,)``, default the heights'
    own (:func:`floor_levels`)."""
    min_len = max(1, int(round(MIN_PHASE * fps)))
    if floor is None:
        floor = floor_levels(heights) if len(heights) else np.zeros(heights.shape[1])
    labels = []
    for k in range(heights.shape[1]):
        raw = (heights[:, k] - floor[k] < HEIGHT_THRESHOLD) & (speeds[:, k] < SPEED_THRESHOLD)
        labels.append(hysteresis(raw, min_len))
        labels[-1].setflags(write=False)
    return FootContacts(fps, *labels)


def _detect(motion: Motion, floor: np.ndarray | None = None) -> FootContacts:
    return contacts_of(*lowest_tracks(motion), motion.fps, floor)
