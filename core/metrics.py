"""Quality metrics of ``timetable.md`` §3, on world joint positions (metres, seconds).

- foot skate: per foot, mean horizontal speed (cm/s) of its lowest joint over
  its contact frames (see :mod:`core.contacts`), and the distance it
  slides while in contact (cm);
- foot-skating ratio, as in the GMD benchmark's code: the fraction of frames
  on which *both* feet skate, a foot skating when it is low (lowest joint
  < 5 cm above the foot's floor level) while its horizontal speed, averaged
  over 5 frames, exceeds 0.5 m/s. (Counting either foot would flag every
  genuine low swing of real gait: 20-45 % of the CMU walks);
- upper / lower body speed (Fig. 5 of the optimal-blending paper): lower is
  the mean world speed of left foot, right foot and hips; upper the mean of
  both hands, chest and head. Speeds are absolute world speeds (m/s), the
  root's own travel included;
- jerk: the third time derivative of joint positions (m/s³), its largest
  magnitude and its RMS over joints and frames of a frame range.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from scipy.ndimage import uniform_filter1d

from .bodyparts import body_map
from .contacts import detect_contacts, foot_tracks
from .motion import Motion

SKATE_HEIGHT = 0.05  # m
SKATE_SPEED = 0.5  # m/s
SKATE_WINDOW = 5  # frames


@dataclass(frozen=True)
class FootSkate:
    """Skate of one foot: mean speed in contact (cm/s), slide distance in contact (cm), contact frames."""

    mean_speed_cm_s: float
    slide_cm: float
    contact_frames: int


def foot_skate(motion: Motion) -> dict[str, FootSkate]:
    contacts = detect_contacts(motion)
    out = {}
    for side, tr in foot_tracks(motion).items():
        c = contacts.of(side)
        n = int(c.sum())
        mean = float(tr.speed[c].mean() * 100) if n else 0.0
        slide = float(tr.speed[c].sum() / motion.fps * 100) if n else 0.0
        out[side] = FootSkate(mean, slide, n)
    return out


def skating_ratio(motion: Motion) -> float:
    """Fraction of frames on which both feet are low and faster than 0.5 m/s (5-frame average)."""
    if motion.n_frames == 0:
        return 0.0
    skating = np.ones(motion.n_frames, dtype=bool)
    for tr in foot_tracks(motion).values():
        avg = uniform_filter1d(tr.speed, size=SKATE_WINDOW, mode="nearest")
        skating &= (tr.height < SKATE_HEIGHT) & (avg > SKATE_SPEED)
    return float(skating.mean())


@dataclass(frozen=True)
class SpeedCurves:
    """Fig. 5 curves: ``times`` (s), ``upper`` and ``lower`` body speed (m/s), each ``(T,)``."""

    times: np.ndarray
    upper: np.ndarray
    lower: np.ndarray


def _speed(positions: np.ndarray, fps: float) -> np.ndarray:
    if len(positions) < 2:
        return np.zeros(positions.shape[:-1])
    return np.linalg.norm(np.gradient(positions, axis=0) * fps, axis=-1)


def speed_curves(motion: Motion) -> SpeedCurves:
    bm = body_map(motion.skeleton)
    lower_j = [bm.feet["left"][0], bm.feet["right"][0], bm.hips]
    upper_j = [bm.hands["left"], bm.hands["right"], bm.chest, bm.head]
    pos = motion.positions
    return SpeedCurves(motion.times, _speed(pos[:, upper_j], motion.fps).mean(axis=1),
                       _speed(pos[:, lower_j], motion.fps).mean(axis=1))


@dataclass(frozen=True)
class Jerk:
    """Largest and RMS jerk magnitude (m/s³) over joints and frames."""

    max: float
    rms: float


def jerk(motion: Motion, start: int = 0, stop: int | None = None) -> Jerk:
    """Jerk of all joints over frames ``[start, stop)`` (third finite difference × fps³)."""
    pos = motion.positions
    stop = len(pos) if stop is None else stop
    lo, hi = max(0, start - 2), min(len(pos), stop + 1)
    seg = pos[lo:hi]
    if len(seg) < 4:
        return Jerk(0.0, 0.0)
    j = np.linalg.norm(np.diff(seg, n=3, axis=0), axis=-1) * motion.fps ** 3
    return Jerk(float(j.max()), float(np.sqrt(np.mean(j ** 2))))


@dataclass(frozen=True)
class Metrics:
    """The whole-clip figures of ``text2anim metrics``."""

    frames: int
    fps: float
    duration: float
    foot_skate: dict[str, FootSkate]
    skating_ratio: float
    jerk: Jerk
    mean_upper_speed: float
    mean_lower_speed: float

    def to_dict(self) -> dict:
        return asdict(self)


def compute_metrics(motion: Motion) -> Metrics:
    curves = speed_curves(motion)
    n = motion.n_frames
    return Metrics(
        frames=n,
        fps=motion.fps,
        duration=motion.duration,
        foot_skate=foot_skate(motion),
        skating_ratio=skating_ratio(motion),
        jerk=jerk(motion),
        mean_upper_speed=float(curves.upper.mean()) if n else 0.0,
        mean_lower_speed=float(curves.lower.mean()) if n else 0.0,
    )
