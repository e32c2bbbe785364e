"""Floating feet: a foot that stands on air (docs/timetable.md §3, the sixth criterion).

A body placed above the floor, or a leg whose IK target it cannot reach, leaves a foot hanging
where it should stand: the leg is straight and points down, the foot does not move, and yet it is
not on the floor. Per frame and foot, a foot *stands* when its leg hangs straight down (the ankle
below the hip joint by at least :data:`STRAIGHT` of the leg's length) and the ankle moves slower
than :data:`SLOW`; over a run of at least :data:`RUN` seconds of standing, the foot *floats* by the
lowest height its lowest point (ankle, toe joint or heel, :func:`heel_heights`) reaches in the run. A
planted foot reaches the floor; a raised leg (a kick's chamber, a knee raise) is bent, so it does not
stand. A foot on its heel, toes raised, stands on its heel: its lowest joint, the ankle, stands 5-6 cm
up there (CMU 05_03, a dance: 5.2 cm on its own floor) where a planted ball stands 3.8, and read by the
ankle such a foot floated by 2 cm more than it does.

Calibration (30 fps, floor at y = 0): the built-in clips float at most 6 cm (the built-in body's
toe joints sit a few cm above its soles); the shared CMU captures at most 14 cm (13_10, a reach on
tiptoe), except those that climb steps or a ladder (60-90 cm: they do stand above the floor).
The run-into-walk join that lifted the walk 44 cm read 44 cm here.
"""
from __future__ import annotations

import numpy as np

from .bodyparts import BodyMapError, body_map
from .contacts import runs
from .motion import Motion

#: Ankle speed (m/s) below which a foot is still.
SLOW = 0.15
#: Seconds a foot must stand still, its leg straight down, for its height to count.
RUN = 0.3
#: Hip-to-ankle vertical drop, as a fraction of the leg's length (thigh + shin at rest), of a leg that
#: hangs straight down.
STRAIGHT = 0.9


def floating_heights(motion: Motion, floor: float = 0.0) -> np.ndarray:
    """``(T,)`` metres: on each frame, the larger height a standing foot floats by (module docstring),
    0 where neither foot stands on air; zeros for a skeleton whose legs cannot be found."""
    T = motion.n_frames
    out = np.zeros(T)
    skel = motion.skeleton
    try:
        feet = body_map(skel).feet
    except BodyMapError:
        return out
    if T < 2:
        return out
    pos, rest = motion.positions, skel.rest_positions()
    n = max(2, int(round(RUN * motion.fps)))
    for ankle, toe in feet.values():
        knee = int(skel.parents[ankle])
        hip = int(skel.parents[knee]) if knee >= 0 else -1
        if hip < 0:
            continue
        leg = np.linalg.norm(rest[knee] - rest[hip]) + np.linalg.norm(rest[ankle] - rest[knee])
        speed = np.linalg.norm(np.diff(pos[:, ankle], axis=0), axis=-1) * motion.fps  # (T-1,)
        speed = np.r_[speed[0], speed]  # frame t: the step that reaches it (frame 0: the first step)
        stands = (pos[:, hip, 1] - pos[:, ankle, 1] >= STRAIGHT * leg) & (speed < SLOW)
        low = np.minimum(pos[:, [ankle, toe], 1].min(axis=1), heel_heights(motion, ankle, toe)) - floor
        for a, b in runs(stands):
            if b - a >= n:
                out[a:b] = np.maximum(out[a:b], max(0.0, float(low[a:b].min())))
    return out


def heel_heights(motion: Motion, ankle: int, toe: int) -> np.ndarray:
    """``(T,)`` metres: the height of the heel's stand-in, a point carried by the ankle that in the rest pose
    lies under it, level with the toe joint (a flat foot's heel stands as high as its ball). A foot on its
    heel, toes raised, stands there: its lowest joint is the ankle, 3-5 cm higher (module docstring)."""
    rest = motion.skeleton.rest_positions()
    drop = max(0.0, float(rest[ankle, 1] - rest[toe, 1]))
    # the rest pose's world rotations are the identity: the point is (0, -drop, 0) in the ankle's frame
    return motion.positions[:, ankle, 1] - drop * motion.pose.rotations[:, ankle, 1, 1]


def floating_cm(motion: Motion, floor: float = 0.0) -> float:
    """The most any foot floats over ``motion`` (cm): :func:`floating_heights`' largest value."""
    h = floating_heights(motion, floor)
    return float(h.max()) * 100 if h.size else 0.0
