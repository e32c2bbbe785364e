"""Quality metrics of ``docs/timetable.md`` §3, on world joint positions (metres, seconds).

The figures the literature compares (:class:`Quality`, all taken after
resampling to :data:`COMPARE_FPS` = 30 fps by :func:`quality`, because
acceleration and jerk grow with the frame rate):

- **foot-skating ratio** by the GMD benchmark's rule (:func:`skating_pairs`): a
  frame pair counts when EITHER toe is below 5 cm on both frames and slides
  faster than 0.5 m/s, also on a 5-frame average; with two floors:

  - ``skating_ratio``, floor-true: heights above the floor ``y = 0``, where a
    planted toe joint stands 3.8 cm up (:data:`core.floor.FOOT_CLEARANCE`), so a
    toe counts as on the floor up to 1.2 cm above where it plants;
  - ``skating_gmd``, GMD's own floor: heights above the motion's lowest foot
    point (:func:`gmd_floor`), as GMD reads HumanML3D, whose processing puts
    each motion's lowest joint at 0: a toe counts up to 5 cm above where it
    plants. This is the figure that carries GMD's name;
- **root pop**: the largest horizontal acceleration of the hips (m/s²) after
  a 3-frame moving average of their horizontal position;
- **joint jerk p99**: the 99th percentile of the jerk magnitude (m/s³) of
  every joint on every frame;
- **floor penetration**: how far the lowest joint or end site (a toe tip, a
  fingertip) goes below y = 0 (cm);
- **frozen frames**: the fraction of frame pairs on which every joint moves
  slower than 0.5 cm/s;
- **floating foot**: how high above the floor a foot stands on air (cm: a still foot
  on a leg hanging straight down, :mod:`core.floating`).

And the per-file figures of ``text2anim metrics`` at the file's own rate:

- foot skate: per foot, mean horizontal speed (cm/s) of its lowest joint over
  its contact frames (see :mod:`core.contacts`), and the distance it
  slides while in contact (cm);
- upper / lower body speed (Fig. 5 of the optimal-blending paper): lower is
  the mean world speed of left foot, right foot and hips; upper the mean of
  both hands, chest and head. Speeds are absolute world speeds (m/s), the
  root's own travel included;
- jerk: the third time derivative of joint positions (m/s³), its largest
  magnitude and its RMS over joints and frames of a frame range.

Thresholds (used by ``benchmarks/bench_quality.py``, ``text2anim compare`` and
the report): a join against its source clips, :func:`against_sources`; motion
made from the built-in library, :data:`BUILTIN_LIMITS` and :func:`against_limits`.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from scipy.ndimage import uniform_filter1d

from .bodyparts import body_map
from .contacts import detect_contacts, foot_tracks
from .floating import floating_heights
from .floor import lowest_foot_heights, lowest_points
from .motion import Motion

# --------------------------------------------------------------------------- the literature's figures
SKATE_HEIGHT = 0.05  # m above the floor (y = 0): GMD's thresh_height
SKATE_SPEED = 0.5  # m/s, horizontal: GMD's thresh_vel
SKATE_WINDOW = 5  # frames: GMD's avg_window (a centred moving average, zero beyond the ends)
COMPARE_FPS = 30.0  # the common rate of every figure that compares motions (docs/timetable.md §3)
ROOT_POP_WINDOW = 3  # frames of the moving average of the hips' horizontal position
FROZEN_SPEED = 0.005  # m/s: a frame pair on which every joint is slower than this is frozen
JERK_PERCENTILE = 99.0

#: GMD's skating ratio (:func:`skating_ratio_gmd`, 30 fps) of the shared capture, whole takes
#: (``benchmarks/bench_floor.py`` prints the spread: 70 takes, median 0.020, 90th percentile 0.143,
#: largest 0.256, a turn on the spot): what real capture reaches, so what our motion may.
CAPTURE_GMD_LIMIT = 0.26
#: Thresholds for motion made from the built-in library (issue 11): root pop (m/s²), joint jerk p99
#: (m/s³), skating ratio (floor-true, and GMD's floor from capture), floor penetration (cm), floating foot
#: (cm: the built-in clips float at most 6, :mod:`core.floating`); the frozen-frame fraction is held to
#: :data:`MAX_FROZEN`.
BUILTIN_LIMITS = {"root_pop": 15.0, "jerk_p99": 2300.0, "skating_ratio": 0.02, "floor_penetration_cm": 1.0,
                  "floating_cm": 10.0, "skating_gmd": CAPTURE_GMD_LIMIT}
#: What every clip of the built-in library is held to on its own (issue 24), at 30 fps.
CLIP_LIMITS = {"skating_ratio": 0.03, "floor_penetration_cm": 1.0, "floating_cm": 10.0,
               "skating_gmd": CAPTURE_GMD_LIMIT}
MAX_PENETRATION_CM = 1.0  # a join may put no joint deeper than this below the floor
MAX_FROZEN = 0.05  # nor hold more than this fraction of frozen frame pairs
SKATING_MARGIN = 0.01  # a join may skate this much more than the more skating of its two sources
SOURCE_FACTOR = 1.2  # and pop / jerk up to this factor above the larger of its sources'
FLOAT_MARGIN_CM = 2.0  # a join may float a foot this much higher than the more floating of its sources
CRITERIA = ("skating", "root_pop", "jerk", "penetration", "frozen", "floating")


def toe_joints(motion: Motion) -> list[int]:
    """Indices of the left and right toe joints (the ankle on a skeleton without toes)."""
    feet = body_map(motion.skeleton).feet
    return [feet["left"][1], feet["right"][1]]


def skating_pairs(motion: Motion, floor: float = 0.0) -> np.ndarray:
    """Per frame pair ``(t, t+1)``, whether a foot skates, as the GMD benchmark's code decides, ``(T-1,)`` bool.

    ``calculate_skating_ratio`` of korrawe/guided-motion-diffusion,
    ``data_loaders/humanml/utils/metrics.py`` (commit 7bc73c0): the feet are
    the toe joints (HumanML3D joints 10 and 11, the balls of the feet; here
    the skeleton's toe joints); the horizontal (XZ) speed between frames t and
    t+1 is the distance times the frame rate (GMD hard-codes its data's
    20 fps; here ``motion.fps``); its 5-frame moving average is
    ``uniform_filter1d(size=5, mode="constant", origin=0)``, centred, with
    zeros beyond both ends; a foot is in contact when its height above
    ``floor`` (m) is below 5 cm on both t and t+1; it skates when in contact
    AND its speed > 0.5 m/s AND the averaged speed > 0.5 m/s; a pair counts
    when EITHER foot skates (``np.logical_or``, whatever the comment above it says).
    """
    if motion.n_frames < 2:
        return np.zeros(0, dtype=bool)
    return toe_skating_pairs(motion.positions[:, toe_joints(motion)], motion.fps, floor)


def toe_skating_pairs(toes: np.ndarray, fps: float, floor: float = 0.0) -> np.ndarray:
    """:func:`skating_pairs` from the toes' world positions ``(T, 2, 3)`` (``T >= 2``) at ``fps``."""
    speed = np.linalg.norm(np.diff(toes[..., [0, 2]], axis=0), axis=-1) * fps  # (T-1, 2)
    avg = uniform_filter1d(speed, size=SKATE_WINDOW, axis=0, mode="constant", origin=0)
    low = toes[..., 1] - floor < SKATE_HEIGHT  # (T, 2)
    skating = low[:-1] & low[1:] & (speed > SKATE_SPEED) & (avg > SKATE_SPEED)
    return np.logical_or(skating[:, 0], skating[:, 1])


def skating_by_frame(motion: Motion, floor: float = 0.0) -> np.ndarray:
    """:func:`skating_pairs` per frame, ``(T,)`` bool: frame t skates when the pair (t, t+1) does (the last never).

    For code that counts skating over a frame range ``[a, b)``: ``skating_by_frame(m)[a:b].mean()``.
    """
    out = np.zeros(motion.n_frames, dtype=bool)
    out[:max(0, motion.n_frames - 1)] = skating_pairs(motion, floor)
    return out


def skating_ratio(motion: Motion, floor: float = 0.0) -> float:
    """GMD foot-skating ratio at the motion's own rate: skating pairs / all frame pairs (:func:`skating_pairs`)."""
    pairs = skating_pairs(motion, floor)
    return float(pairs.mean()) if len(pairs) else 0.0


def gmd_floor(motion: Motion) -> float:
    """GMD's floor (m): the motion's lowest foot point, the lowest ankle or toe joint over all frames.

    HumanML3D's processing (``motion_process.py``, "Put on Floor") moves each motion so its lowest
    joint is at 0, and GMD reads toe heights above that; its joints are SMPL's, whose lowest is a foot
    joint, and have no end sites, so neither do we here.
    """
    return float(lowest_foot_heights(motion).min()) if motion.n_frames else 0.0


def skating_ratio_gmd(motion: Motion) -> float:
    """GMD's skating ratio as GMD measures it: :func:`skating_ratio` above :func:`gmd_floor`."""
    return skating_ratio(motion, gmd_floor(motion))


@dataclass(frozen=True)
class Series:
    """Per-frame quality figures of one motion at ``fps``; NaN where a frame has no value.

    ``skating``, ``skating_gmd``, ``frozen``: ``(T,)`` 1.0/0.0 for the frame pair (t, t+1), NaN on the last
    frame (``skating`` above the floor given, ``skating_gmd`` above :func:`gmd_floor`);
    ``root_acc``: ``(T,)`` hips' horizontal acceleration (m/s²) centred on frame t, NaN on the 2 frames
    at each end; ``jerk``: ``(T, J)`` jerk magnitude (m/s³) of frames t-1 .. t+2, NaN on frame 0 and the
    last two; ``lowest``: ``(T,)`` height (m) of the lowest joint or end site; ``floating``: ``(T,)`` height (m) a foot
    stands on air by (:func:`core.floating.floating_heights`).
    """

    fps: float
    skating: np.ndarray
    frozen: np.ndarray
    root_acc: np.ndarray
    jerk: np.ndarray
    lowest: np.ndarray
    floating: np.ndarray
    skating_gmd: np.ndarray


def _padded(values: np.ndarray, before: int, n: int) -> np.ndarray:
    out = np.full((n,) + values.shape[1:], np.nan)
    out[before:before + len(values)] = values
    return out


def hips_acceleration(root_positions: np.ndarray, fps: float) -> np.ndarray:
    """Hips' horizontal acceleration magnitude (m/s²) of root positions ``(T, 3)`` at ``fps``, after a
    3-frame moving average of their XZ position.

    Second differences of the averaged positions times fps²; only frames whose average needs no
    padding are used, ``(T-4,)`` for frames 2 .. T-3.
    """
    w = ROOT_POP_WINDOW
    if len(root_positions) < w + 2:
        return np.zeros(0)
    xz = root_positions[:, [0, 2]]  # the root joint's world positions (no kinematics needed)
    n = len(xz) - w + 1
    # (T-w+1, 2): the window's mean as ``sliding_window_view(xz, w, axis=0).mean(axis=-1)`` takes it (summed in
    # order, then divided: the same bits) without the view's set-up, which cost half of this function's time
    # (the join post-pass asks it for every candidate's hips' path, ~20 a join)
    total = xz[:n].copy()
    for k in range(1, w):
        total += xz[k:k + n]
    avg = total / w
    return np.linalg.norm(np.diff(avg, n=2, axis=0), axis=-1) * fps ** 2


def root_acceleration(motion: Motion) -> np.ndarray:
    """:func:`hips_acceleration` of a motion at its own rate, ``(T-4,)`` m/s²."""
    return hips_acceleration(motion.root_positions, motion.fps)


def peak_hips_acceleration(root_positions: np.ndarray, fps: float) -> float:
    """The largest :func:`hips_acceleration` of root positions ``(T, 3)`` at ``fps`` (0 if too short), m/s²."""
    acc = hips_acceleration(root_positions, fps)
    return float(acc.max()) if acc.size else 0.0


def root_pop(motion: Motion) -> float:
    """:class:`Quality` ``root_pop`` of a whole motion at its own rate (``quality(motion, None).root_pop``)
    from its root positions alone, m/s²."""
    return peak_hips_acceleration(motion.root_positions, motion.fps)


def joint_jerk(positions: np.ndarray, fps: float) -> np.ndarray:
    """Jerk magnitude of every joint, ``(T-3, J)`` m/s³, of world positions ``(T, J, 3)`` at ``fps``."""
    if len(positions) < 4:
        return np.zeros((0, positions.shape[1]))
    return np.linalg.norm(np.diff(positions, n=3, axis=0), axis=-1) * fps ** 3


def jerk_p99(jerk: np.ndarray) -> float:
    """:class:`Quality` ``jerk_p99`` of per-frame joint jerks (any shape, NaN left out; 0 if none), m/s³."""
    return _nanreduce(lambda v: np.percentile(v, JERK_PERCENTILE), jerk.ravel())


def frozen_pairs(motion: Motion, factor: float = 1.0) -> np.ndarray:
    """``(T-1,)`` bool: frame pairs (t, t+1) on which every joint moves slower than :data:`FROZEN_SPEED`
    (times ``factor``)."""
    if motion.n_frames < 2:
        return np.zeros(0, dtype=bool)
    speed = np.linalg.norm(np.diff(motion.positions, axis=0), axis=-1).max(axis=1) * motion.fps
    return speed < FROZEN_SPEED * factor


def series(motion: Motion, floor: float = 0.0) -> Series:
    """The per-frame figures of :class:`Series` (positions after FK, at the motion's own rate)."""
    n, fps = motion.n_frames, motion.fps
    pos = motion.positions
    frozen = frozen_pairs(motion).astype(float)
    jerk_tj = joint_jerk(pos, fps)
    gmd = skating_pairs(motion, gmd_floor(motion))
    return Series(fps, _padded(skating_pairs(motion, floor).astype(float), 0, n), _padded(frozen, 0, n),
                  _padded(root_acceleration(motion), (ROOT_POP_WINDOW - 1) // 2 + 1, n),
                  _padded(jerk_tj, 1, n), lowest_points(motion) - floor if n else np.zeros(0),
                  floating_heights(motion, floor), _padded(gmd.astype(float), 0, n))


@dataclass(frozen=True)
class Quality:
    """The figures the literature compares, at ``fps`` over ``frames`` frames (see the module docstring)."""

    fps: float
    frames: int
    skating_ratio: float
    root_pop: float  # m/s²
    jerk_p99: float  # m/s³
    floor_penetration_cm: float
    frozen_fraction: float
    floating_cm: float = 0.0
    skating_gmd: float = 0.0  # GMD's own floor (the module docstring)

    def to_dict(self) -> dict:
        return asdict(self)


def _nanreduce(fn, values: np.ndarray) -> float:
    v = values[~np.isnan(values)]
    return float(fn(v)) if v.size else 0.0


def summarise(s: Series, start: int = 0, stop: int | None = None) -> Quality:
    """The :class:`Quality` of frames ``[start, stop)`` of a :class:`Series` (a pair counts by its first frame)."""
    n = len(s.lowest)
    start, stop = max(0, start), n if stop is None else min(n, stop)
    last_pair = min(stop, n - 1)  # the pair (t, t+1) needs t+1 inside the motion
    sk, fr = s.skating[start:last_pair], s.frozen[start:last_pair]
    low = s.lowest[start:stop]
    return Quality(s.fps, max(0, stop - start), _nanreduce(np.mean, sk), _nanreduce(np.max, s.root_acc[start:stop]),
                   jerk_p99(s.jerk[start:stop]),
                   max(0.0, -float(low.min()) * 100) if low.size else 0.0, _nanreduce(np.mean, fr),
                   float(s.floating[start:stop].max()) * 100 if low.size else 0.0,
                   _nanreduce(np.mean, s.skating_gmd[start:last_pair]))


def at_rate(motion: Motion, fps: float | None = COMPARE_FPS) -> Motion:
    """``motion`` resampled to ``fps`` (unchanged when ``fps`` is None or already its rate); kept in the
    motion's cache, so the figures read from one output (the whole motion's, each join's, what it played
    as placed, balance and glides) resample it once."""
    if fps is None or motion.fps == fps:
        return motion
    return motion.cache.get(("at_rate", float(fps)), lambda: motion.resample(fps))


def window_frames(fps: float, window: tuple[float, float]) -> tuple[int, int]:
    """Frames ``[a, b)`` whose times lie in ``[t0, t1)`` seconds at ``fps``."""
    t0, t1 = window
    return int(np.ceil(t0 * fps - 1e-9)), int(np.ceil(t1 * fps - 1e-9))


def quality(motion: Motion, fps: float | None = COMPARE_FPS, window: tuple[float, float] | None = None,
            floor: float = 0.0) -> Quality:
    """The six figures of ``motion`` after resampling to ``fps`` (None: its own rate).

    ``window`` = ``(t0, t1)`` seconds limits them to the frames in ``[t0, t1)``; the figures are
    taken on the whole motion first, so a window's edges see the motion around them (a GMD
    average near a window edge is not padded with zeros).
    """
    m = at_rate(motion, fps)
    s = series(m, floor)
    if window is None:
        return summarise(s)
    return summarise(s, *window_frames(m.fps, window))


def against_sources(out: Quality, sources: list[Quality]) -> dict[str, bool]:
    """Whether ``out`` (a join's output) meets each criterion of issue 11 against its source clips.

    skating ≤ the sources' larger + 0.01; root pop and jerk p99 ≤ 1.2 × the sources' larger;
    floor penetration ≤ 1 cm; frozen frames ≤ 5 %; a floating foot ≤ the sources' larger + 2 cm.
    Compare figures taken at one rate (30 fps).
    """
    worst = {k: max([getattr(q, k) for q in sources] or [0.0])
             for k in ("skating_ratio", "root_pop", "jerk_p99", "floating_cm")}
    return {"skating": out.skating_ratio <= worst["skating_ratio"] + SKATING_MARGIN + 1e-12,
            "root_pop": out.root_pop <= SOURCE_FACTOR * worst["root_pop"] + 1e-9,
            "jerk": out.jerk_p99 <= SOURCE_FACTOR * worst["jerk_p99"] + 1e-9,
            "penetration": out.floor_penetration_cm <= MAX_PENETRATION_CM,
            "frozen": out.frozen_fraction <= MAX_FROZEN,
            "floating": out.floating_cm <= worst["floating_cm"] + FLOAT_MARGIN_CM + 1e-9}


def against_limits(out: Quality, limits: dict = BUILTIN_LIMITS) -> dict[str, bool]:
    """Whether ``out`` meets the fixed thresholds of :data:`BUILTIN_LIMITS` (and :data:`MAX_FROZEN`)."""
    return {"skating": out.skating_ratio <= limits["skating_ratio"],
            "root_pop": out.root_pop <= limits["root_pop"],
            "jerk": out.jerk_p99 <= limits["jerk_p99"],
            "penetration": out.floor_penetration_cm <= limits["floor_penetration_cm"],
            "frozen": out.frozen_fraction <= MAX_FROZEN,
            "floating": out.floating_cm <= limits["floating_cm"]}


@dataclass(frozen=True)
class FootSkate:
    """Skate of one foot: mean speed in contact (cm/s), slide distance in contact (cm), contact frames."""

    mean_speed_cm_s: float
    slide_cm: float
    contact_frames: int


def foot_skate(motion: Motion) -> dict[str, FootSkate]:
    """Per foot (``left``/``right``), its skate over the contact frames of :func:`core.contacts.detect_contacts`."""
    contacts = detect_contacts(motion)
    out = {}
    for side, tr in foot_tracks(motion).items():
        c = contacts.of(side)
        n = int(c.sum())
        mean = float(tr.speed[c].mean() * 100) if n else 0.0
        slide = float(tr.speed[c].sum() / motion.fps * 100) if n else 0.0
        out[side] = FootSkate(mean, slide, n)
    return out


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
    j = joint_jerk(seg, motion.fps)
    return Jerk(float(j.max()), float(np.sqrt(np.mean(j ** 2))))


@dataclass(frozen=True)
class Metrics:
    """The whole-clip figures of ``text2anim metrics``: at the file's rate, and ``quality`` at 30 fps."""

    frames: int
    fps: float
    duration: float
    foot_skate: dict[str, FootSkate]
    skating_ratio: float
    jerk: Jerk
    mean_upper_speed: float
    mean_lower_speed: float
    quality: Quality

    def to_dict(self) -> dict:
        return asdict(self)


def compute_metrics(motion: Motion) -> Metrics:
    """Every figure of ``text2anim metrics`` for one motion."""
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
        quality=quality(motion),
    )
