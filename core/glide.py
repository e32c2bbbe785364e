"""Glides: hips carried at a constant speed, as no person moves (docs/timetable.md §3).

Paper 003 ends on it: a connection that only interpolates joint angles and the root "moves at constant
speed as no human does". A person's hips speed up and slow down with every step (the push-off, the
landing: walking, the hips' horizontal acceleration swings through 1-3 m/s² twice a stride) and when they
start or stop. Per frame, the hips **glide** when they travel (horizontal speed at least :data:`TRAVEL`,
at a person's size) and their horizontal acceleration — read as the root pop reads it, after a 3-frame
average (:func:`core.metrics.hips_acceleration`) — is below :data:`STEADY`. The figure is the longest run
of gliding frames (s).

Calibrated on the shared capture (68 CMU takes at 30 fps, ``benchmarks/bench_transitions.py``): at most
0.17 s (hips pass through a steady instant between two pushes); the limit :data:`LIMIT_S` is 0.2 s.
"""
from __future__ import annotations

import numpy as np

from .contacts import runs
from .metrics import hips_acceleration
from .motion import Motion
from .size import human_scale

#: m/s at a person's size: slower hips do not travel (a sway, a shift of weight)
TRAVEL = 0.3
#: m/s²: hips accelerating less than this (after the 3-frame average) keep their speed
STEADY = 0.3
#: s: the longest glide capture has (0.17 s), rounded up
LIMIT_S = 0.2


def gliding(motion: Motion) -> np.ndarray:
    """``(T,)`` bool: frames where the hips travel at a steady speed (module docstring). Lengths are read at
    a person's size (a body's path scaled by 0.86 m / its leg length)."""
    return gliding_path(motion.root_positions * human_scale(motion), motion.fps)


def gliding_path(root_positions: np.ndarray, fps: float) -> np.ndarray:
    """:func:`gliding` of a hips path ``(T, 3)`` (m, at a person's size) at ``fps``: ``(T,)`` bool."""
    T = len(root_positions)
    out = np.zeros(T, dtype=bool)
    acc = hips_acceleration(root_positions, fps)  # (T - 4,) for frames 2 .. T - 3
    if not acc.size:
        return out
    speed = np.linalg.norm(np.gradient(root_positions[:, [0, 2]], axis=0), axis=-1) * fps
    out[2:2 + len(acc)] = (speed[2:2 + len(acc)] >= TRAVEL) & (acc < STEADY)
    return out


def longest_s(mask: np.ndarray, fps: float) -> float:
    """The longest run of True in ``mask`` ``(T,)``, seconds at ``fps``."""
    r = runs(mask)
    return int((r[:, 1] - r[:, 0]).max()) / fps if len(r) else 0.0


def glide_s(motion: Motion, frames: np.ndarray | None = None) -> float:
    """The longest run of gliding frames (s), over the motion or over the bool mask ``frames`` ``(T,)``
    (a run counts its frames inside the mask)."""
    g = gliding(motion)
    if frames is not None:
        g &= np.asarray(frames, dtype=bool)
    return longest_s(g, motion.fps)
