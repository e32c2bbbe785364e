"""Hanging in the air: a body off the floor longer than its own fall allows (docs/timetable.md §3).

A person leaves the floor only by jumping or running, and comes down as gravity takes it: a flight of
``T`` seconds lifts the hips by about ``g T² / 8``. A join that blends a standing pose into a run's flight
pose, or plays a flight slowly, holds the body up with both feet off the floor and the hips level — a
levitation no other figure reads (the feet are not planted, so nothing floats, skates or sinks).

Per frame the body is **airborne** when its lowest joint is higher than :data:`AIR` above the floor (y = 0;
at a person's size: a planted foot's lowest joint stands 3.8 cm up, ``core.floor.FOOT_CLEARANCE``, and the
contact rule's 5 cm over it). For each run of airborne frames ``[a, b)`` the time a ballistic body spends
in the air is ``sqrt(2 rise / g) + sqrt(2 fall / g)``, ``rise`` the hips' climb from the last frame on the
floor to their highest, ``fall`` their drop from there to the first frame back on it; the run **hangs** for
its length less that time (less one frame: the run's edges are read to the frame). The figure is the
longest hang (s).

Calibrated on the shared capture (``benchmarks/bench_transitions.py``): the limit :data:`LIMIT_S`.
"""
from __future__ import annotations

import numpy as np

from .contacts import HEIGHT_THRESHOLD, runs
from .floor import ON_FLOOR
from .motion import Motion
from .size import human_scale

G = 9.81  # m/s²
#: m at a person's size: a body whose lowest joint is higher than this touches nothing
AIR = ON_FLOOR
#: s: the longest hang capture has (0.18 s, a walk, 08_02), rounded up; bodies held by a prop (a ladder, a
#: stool, a bar) left out (bench_transitions.py)
LIMIT_S = 0.2


def hang_times(motion: Motion, floor: float = 0.0) -> np.ndarray:
    """``(T,)`` s: on every frame of an airborne run, how much longer than a ballistic flight the run lasts
    (module docstring; 0 where the body touches the floor or falls as fast as gravity takes it)."""
    out = np.zeros(motion.n_frames)
    for a, b, hang in _hangs(motion, np.arange(motion.n_frames + 1.0), floor):
        out[a:b] = max(0.0, hang)
    return out


def _hangs(motion: Motion, times: np.ndarray, floor: float) -> list[tuple[int, int, float]]:
    """``(a, b, s)`` per airborne run ``[a, b)`` of ``motion``: how much longer than a ballistic flight it lasts
    played at the new times ``times`` ``(T + 1,)`` (frames, when each frame starts and the last ends)."""
    hips = motion.root_positions[:, 1] * human_scale(motion)
    return [(int(a), int(b), (times[b] - times[a] - 1) / motion.fps - ballistic_s(hips, int(a), int(b)))
            for a, b in runs(airborne(motion, floor))]


def ballistic_s(hips: np.ndarray, a: int, b: int) -> float:
    """s: how long a body thrown as the hips' heights ``hips`` ``(T,)`` (m, at a person's size) rise and fall
    over the airborne frames ``[a, b)`` stays in the air: ``sqrt(2 rise / g) + sqrt(2 fall / g)`` from the
    frames on the floor either side to the highest."""
    top = hips[a:b].max()
    rise = max(0.0, top - hips[max(a - 1, 0)])
    fall = max(0.0, top - hips[min(b, len(hips) - 1)])
    return float(np.sqrt(2.0 * rise / G) + np.sqrt(2.0 * fall / G))


def slowed_into_hanging(motion: Motion, times: np.ndarray, floor: float = 0.0) -> np.ndarray:
    """``(T,)`` bool: the frames of each airborne run of ``motion`` that, played at the new times ``times``
    ``(T + 1,)`` (frames, when each frame starts and the last ends), would hang longer than :data:`LIMIT_S`."""
    out = np.zeros(motion.n_frames, dtype=bool)
    for a, b, hang in _hangs(motion, times, floor):
        out[a:b] = hang > LIMIT_S
    return out


def hang_s(motion: Motion, frames: np.ndarray | None = None) -> float:
    """The longest hang (s) of ``motion``, over the bool mask ``frames`` ``(T,)`` when given (a run counts
    where it touches those frames)."""
    h = hang_times(motion)
    if frames is not None:
        h = np.where(frames, h, 0.0)
    return float(h.max()) if h.size else 0.0


def airborne(motion: Motion, floor: float = 0.0) -> np.ndarray:
    """``(T,)`` bool: frames where the body's lowest joint is higher than :data:`AIR` above ``floor`` (at a
    person's size): it touches nothing."""
    return (motion.positions[..., 1].min(axis=1) - floor) * human_scale(motion) > AIR


def off_its_floor(motion: Motion) -> np.ndarray:
    """``(T,)`` bool: frames where the body's lowest joint is more than the contact rule's height (at a
    person's size) above the lowest any frame of the motion reaches: airborne on the motion's own floor, for
    a clip not placed on y = 0 (a lying or seated body rests on its floor and is not in the air)."""
    low = motion.positions[..., 1].min(axis=1)
    return (low - low.min()) * human_scale(motion) > HEIGHT_THRESHOLD
