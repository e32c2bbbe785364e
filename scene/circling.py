"""A walk round a thing or a person (木の周りを三周歩く, 花子の周りを走る): the walk steered into loops.

The synthesised walk goes straight; :func:`circle` turns it at an even rate, a whole turn per lap (三周:
twelve seconds of walking, three laps), in short steps each about the foot on the floor
(:func:`core.steer.steer`), so the feet stay planted and the hips' path closes into loops. It turns to the right (clockwise seen from above):
what it goes round is on the walker's right, where a ``beside`` relation puts the other person.
:func:`centre` is the middle of those loops and their radius, where the thing stands.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.motion import Motion
from text2anim.core.steer import steer

from .bodies import hips_path

#: s: the walk is turned in steps this long (each step's turn eases in and out: short steps keep the rate even).
STEP_S = 0.25


def circle(motion: Motion, f0: int, f1: int, laps: int) -> Motion:
    """``motion`` with frames ``[f0, f1)`` turned by ``laps`` whole turns to the right, at an even rate, and the
    frames after by the same (a whole number of turns: they go on the way the walk first went)."""
    steps = max(1, int(round((f1 - f0) / (STEP_S * motion.fps))))
    edges = np.linspace(f0, f1, steps + 1).round().astype(int)
    share = -2.0 * np.pi * max(1, laps) / steps
    for a, b in zip(edges[:-1], edges[1:]):
        if b > a:
            motion = steer(motion, int(a), int(b), share)
    return motion


def centre(motion: Motion, f0: int, f1: int) -> tuple[np.ndarray, float]:
    """The middle of the hips' loops over frames ``[f0, f1)`` (``(3,)`` m, on the floor) and their mean radius (m)."""
    path = hips_path(motion)[0][f0:f1]
    mid = path.mean(axis=0)
    return mid, float(np.mean(np.hypot(path[:, 0] - mid[0], path[:, 2] - mid[2])))
