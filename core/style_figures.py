"""Figures of how a motion is done, to compare a styled motion with the neutral one (issue 40).

Each is measured over ``window`` = ``(t0, t1)`` seconds of the motion (default: all of it): the hips'
horizontal speed (m/s), the head's lean (m the top of the head is ahead of the hips, along where the
body faces: forward bent positive, leaning back negative), the cadence (steps per minute: 60 s over the median time between landings of
either foot), the step length (m: hips' speed
over steps per second), the head's height above the hips (m, the top of the head: its end site), a hand's
range (m: the diagonal of the box its path relative to the hips spans) and the hips' bounce (m: the
standard deviation of their height).
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from .body_axes import body_axes
from .bodyparts import body_map
from .contacts import detect_contacts
from .motion import Motion


@dataclass(frozen=True)
class StyleFigures:
    """The figures of one motion (units in the module docstring)."""

    hips_speed: float
    head_lean: float
    cadence: float
    step_length: float
    head_height: float
    hand_range: float
    bounce: float

    def to_dict(self) -> dict[str, float]:
        return {k: round(v, 3) for k, v in asdict(self).items()}


def style_figures(motion: Motion, window: tuple[float, float] | None = None, hand: str = "right") -> StyleFigures:
    """The :class:`StyleFigures` of ``motion`` over ``window`` seconds, ``hand``'s range."""
    a, b = (0, motion.n_frames) if window is None else (int(window[0] * motion.fps), int(window[1] * motion.fps))
    b = min(max(b, a + 2), motion.n_frames)
    seconds = (b - a) / motion.fps
    bm = body_map(motion.skeleton)
    root = motion.root_positions[a:b]
    speed = float(np.linalg.norm(np.diff(root[:, [0, 2]], axis=0), axis=1).sum()) / seconds
    contacts = detect_contacts(motion)
    landings = sorted(s for side in ("left", "right") for s, _ in contacts.intervals(side) if a <= s < b)
    frames = np.diff(landings)
    gaps = frames[frames > 0] / motion.fps  # s; both feet landing at once (a jump) is one landing
    cadence = 60.0 / float(np.median(gaps)) if len(gaps) else 0.0
    step = speed / (cadence / 60.0) if cadence > 0 else 0.0
    head = _head_top(motion, bm.head)[a:b]
    forward = body_axes(motion, bm)[1][a:b]
    lean = float(np.mean(np.sum((head - root) * forward, axis=1)))
    rel = motion.positions[a:b, bm.hands[hand]] - root
    return StyleFigures(speed, lean, cadence, step, float(np.mean(head[:, 1] - root[:, 1])),
                        float(np.linalg.norm(np.ptp(rel, axis=0))), float(np.std(root[:, 1])))


def _head_top(motion: Motion, head: int) -> np.ndarray:
    """The top of the head ``(T, 3)``: the head's end site, else the head joint."""
    sites = [i for i, (j, _) in enumerate(motion.skeleton.end_sites) if j == head]
    return motion.end_site_positions()[:, sites[0]] if sites else motion.positions[:, head]
