"""The contact instant of a motion, read from the motion itself: the frame a hand meets another's hand
or a thing, a foot meets the ball, a hand lets the ball go.

Two actors' exchanges (a handshake, a hand-over, a catch, a kick to someone) are timed by these
frames, so they are found where the effector does it, never at a fixed time of the clip. The
effector is a hand, both hands (their mean) or a foot (:data:`EFFECTORS`); the kind says what to
look for (:data:`KINDS`):

- ``reach``: the effector arrives at its furthest point in front of the body (a grip, a slap of
  palms, the take of something handed over, a catch, arms closing in a hug). Its forward distance
  is measured along the hips' heading from the hips' ground point, frame by frame; the instant is
  the first frame within :data:`REACH_TOLERANCE` of the largest, then on while the effector still
  moves forward: where it stops (a hold's first frame; an offer pushed slowly on, its end).
- ``strike``: the effector's fastest frame (a kick meets the ball at full speed).
- ``release``: the frame the effector flies out from its limb's root fastest (the shoulder for a
  hand, the hip for a foot): the arm's whip at a throw's release. Not simply the fastest frame: a
  basketball shot's hands come down faster after the ball has gone.

Speeds are central differences of joint positions (metres, seconds). A ``window`` (seconds, the
clip's core as a rule) limits the search; the frame returned indexes the whole motion.
"""
from __future__ import annotations

from typing import Literal

import numpy as np
from scipy.spatial.transform import Rotation

from .bodyparts import body_map
from .motion import Motion

Effector = Literal["left_hand", "right_hand", "both_hands", "left_foot", "right_foot"]
Kind = Literal["reach", "strike", "release"]
EFFECTORS: tuple[str, ...] = ("left_hand", "right_hand", "both_hands", "left_foot", "right_foot")
KINDS: tuple[str, ...] = ("reach", "strike", "release")
#: m: a reach has arrived once the effector is this close to its furthest forward distance (the
#: idle sway of a held arm moves it about 1 cm).
REACH_TOLERANCE = 0.01


def _joints(motion: Motion, effector: str) -> list[int]:
    """The joint index of each effector's end: wrists for hands, ankles for feet."""
    bm = body_map(motion.skeleton)
    if effector == "both_hands":
        return [bm.hands["left"], bm.hands["right"]]
    side, part = effector.split("_")
    return [bm.hands[side]] if part == "hand" else [bm.feet[side][0]]


def _frames(motion: Motion, window: tuple[float, float] | None) -> tuple[int, int]:
    """``[first, last]`` frames of ``window`` (seconds), clamped to the motion; the whole motion by default."""
    last = motion.n_frames - 1
    if window is None:
        return 0, last
    a = int(np.clip(np.ceil(window[0] * motion.fps - 1e-6), 0, last))
    b = int(np.clip(np.floor(window[1] * motion.fps + 1e-6), a, last))
    return a, b


def _forward(motion: Motion, positions: np.ndarray) -> np.ndarray:
    """``(T,)`` metres: ``positions`` ``(T, 3)`` ahead of the hips' ground point along their heading."""
    fwd = Rotation.from_quat(motion.rotations[:, 0]).apply([0.0, 0.0, 1.0])
    fwd[:, 1] = 0.0
    fwd /= np.maximum(np.linalg.norm(fwd, axis=1, keepdims=True), 1e-9)
    rel = positions - motion.root_positions
    return np.einsum("ti,ti->t", rel, fwd)


def _reach(motion: Motion, joints: list[int], a: int, b: int) -> int:
    p = motion.positions[:, joints].mean(axis=1)
    ahead = _forward(motion, p)[a:b + 1]
    near = ahead >= ahead.max() - REACH_TOLERANCE
    k = int(np.argmax(near))
    while k + 1 < len(near) and near[k + 1] and ahead[k + 1] > ahead[k]:
        k += 1
    return a + k


def _strike(motion: Motion, joints: list[int], a: int, b: int) -> int:
    p = motion.positions[:, joints].mean(axis=1)
    speed = np.linalg.norm(np.gradient(p, axis=0), axis=1)
    return a + int(np.argmax(speed[a:b + 1]))


def _release(motion: Motion, joints: list[int], a: int, b: int) -> int:
    parents = motion.skeleton.parents
    pos = motion.positions
    outward = np.zeros(motion.n_frames)
    for j in joints:
        root = int(parents[parents[j]])  # wrist -> elbow -> shoulder; ankle -> knee -> hip
        out = pos[:, j] - pos[:, root]
        out /= np.maximum(np.linalg.norm(out, axis=1, keepdims=True), 1e-9)
        outward += np.einsum("ti,ti->t", np.gradient(pos[:, j], axis=0), out)
    return a + int(np.argmax(outward[a:b + 1]))


_FINDERS = {"reach": _reach, "strike": _strike, "release": _release}


def contact_instant(motion: Motion, effector: Effector | str, kind: Kind | str,
                    window: tuple[float, float] | None = None) -> int:
    """The frame of ``motion`` at which ``effector`` makes its contact of ``kind`` (module docstring).

    Args:
        motion: a clip or any motion of a body :func:`core.bodyparts.body_map` knows.
        effector: one of :data:`EFFECTORS`.
        kind: one of :data:`KINDS`.
        window: ``(start, end)`` seconds to search (the clip's core); ``None``: every frame.

    Returns:
        The frame index into ``motion`` (``window`` only narrows the search).

    Raises:
        ValueError: an unknown effector or kind, or an empty motion.
    """
    if effector not in EFFECTORS:
        raise ValueError(f"unknown effector {effector!r}; one of {', '.join(EFFECTORS)}")
    if kind not in KINDS:
        raise ValueError(f"unknown contact kind {kind!r}; one of {', '.join(KINDS)}")
    if motion.n_frames < 2:
        raise ValueError("a contact instant needs a motion of at least two frames")
    a, b = _frames(motion, window)
    return _FINDERS[kind](motion, _joints(motion, effector), a, b)


__all__ = ["EFFECTORS", "KINDS", "REACH_TOLERANCE", "Effector", "Kind", "contact_instant"]
