"""Weight functions of paper 000 §4.4: how a blend interval moves from one motion to the next.

A weight ``w(t)`` (0 = the first motion or pose, 1 = the second) over a blend
interval ``[t0, t1]``; frames are integers, ``w(t0) = 0`` and ``w(t1) = 1``.

§4.4.1 — pose–pose and motion–motion blends: a cubic **Hermite** curve in the
normalised time ``u = (t - t0) / (t1 - t0)`` through ``(0, 0)`` and ``(1, 1)``
(:class:`scipy.interpolate.CubicHermiteSpline`), whose end slopes come from
eq. (16)::

    w'(t) = V(t) / (D(t0, t1) / (t1 - t0))            (16)

the ratio of the pose's speed at the end point (``V``, eq. (14), signed: how
fast the pose there approaches the other end of the blend) to the mean speed
over the blend (``D / (t1 - t0)``). The slope is ``dw/du``, dimensionless. So
a blend leaves the first motion at the speed it had and arrives in the second
at its speed. Where the motion at an end point moves *against* the blend
(``V < 0``, Fig. 3(c)) it must stop first: that end's slope is 0.

Choices where the paper is silent (documented and tested):

- a slope larger than :data:`MAX_SLOPE` would make the curve overshoot 1 or
  dip below 0 (a cubic through (0,0) and (1,1) is monotone iff its slopes lie
  in the Fritsch–Carlson region; the circle ``m0² + m1² <= 9`` is the usual
  sufficient part of it): both slopes are scaled down together onto that
  circle, so the weight is always monotone;
- when the two end poses are the same (``D`` below :data:`SAME_POSE` m) the
  ratio is undefined: slope 1 (a straight line) at both ends.

§4.4.2 — motion–pose and pose–motion blends also look at the distance ``d``
between the pose side and every pose the moving side passes through in the
interval (:func:`shape_of`, :func:`plan_partial`). The paper words the three
cases for a **pose → motion** blend (the pose is held, the motion takes over;
``d(t) = D(pose, motion(t))``):

(a) ``d`` increases monotonically: the motion moves away from the pose as the
    blend does — Hermite weights from the end-point speeds;
(b) ``d`` has an interior maximum at ``tm``: that pose of the motion should be
    reproduced, so ``tm`` becomes the **end** of the weight curve (``w = 1``
    from ``tm`` on; the interval reported ends there);
(c) ``d`` decreases monotonically: the motion comes back towards the pose,
    and any weight would pass the final pose and return — the blend becomes
    pose–pose (the pose to the motion's pose at ``t1``).

A **motion → pose** blend is the same analysis in reversed time (the paper:
同様の場合分け), ``d(t) = D(motion(t), pose)``:

(a) ``d`` decreases (the motion approaches the pose): Hermite weights;
(b) an interior maximum at ``tm`` (the apex of a jump used for a connection,
    §6): that pose is reproduced, so ``tm`` becomes the **start** of the weight
    curve (``w = 0`` until ``tm``);
(c) ``d`` increases (the motion moves away from the pose): pose–pose from the
    motion's pose at ``t0`` (動作の始端点の姿勢) to the pose.

A change smaller than :data:`FLAT` m counts as flat, i.e. case (a); a maximum
must stand :data:`FLAT` above both ends and leave at least ``min_frames``
of blend, else the end values decide between (a) and (c).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Largest |slope| pair radius keeping the Hermite weight monotone (Fritsch–Carlson).
MAX_SLOPE = 3.0
#: m: end poses closer than this are "the same": straight-line weights.
SAME_POSE = 1e-3
#: m of mean joint distance: changes smaller than this are flat (§4.4.2).
FLAT = 0.01

CASES = ("increase", "maximum", "decrease")


def slope(V: float, D: float, T: float) -> float:
    """eq. (16) at one end: ``V / (D / T)``; 0 where the motion reverses (``V < 0``); 1 for equal poses.

    ``V`` m/s (signed approach speed, eq. (14)), ``D`` metres (eq. (13)), ``T`` seconds (``t1 - t0``).
    """
    if D < SAME_POSE or T <= 0:
        return 1.0
    return max(0.0, float(V) / (D / T))


def monotone_slopes(m0: float, m1: float) -> tuple[float, float]:
    """Both slopes scaled down together onto the circle of radius :data:`MAX_SLOPE` when outside it."""
    m0, m1 = max(0.0, float(m0)), max(0.0, float(m1))
    r = np.hypot(m0, m1)
    if r > MAX_SLOPE:
        m0, m1 = m0 * MAX_SLOPE / r, m1 * MAX_SLOPE / r
    return m0, m1


def hermite(u, m0: float, m1: float) -> np.ndarray:
    """The Hermite weight at normalised times ``u`` (clipped to [0, 1]) with end slopes ``m0``, ``m1``
    (already made monotone by the caller, see :func:`monotone_slopes`)."""
    u = np.clip(np.asarray(u, dtype=np.float64), 0.0, 1.0)
    # CubicHermiteSpline([0, 1], [0, 1], [m0, m1])(u), bit for bit (tests/synthesis/test_weights_hermite.py):
    # its power-basis coefficients on the one unit interval (c3 = y0 = 0, c2 = m0, c0 = m0 + m1 - 2 * slope,
    # c1 = slope - m0 - c0; every division is by 1) summed in PPoly's order, lowest power first. Written out
    # because importing scipy.interpolate costs a command ~0.08 s of CPU for this one cubic.
    m0, m1 = float(m0), float(m1)
    c0 = m0 + m1 - 2.0
    c1 = (1.0 - m0) - c0
    z = u * u
    return ((0.0 + m0 * u) + c1 * z) + c0 * (z * u)


def hermite_weights(n: int, m0: float, m1: float) -> np.ndarray:
    """Weights for the frames ``t0 .. t1`` of a blend ``n = t1 - t0`` frames long, ``(n + 1,)``:
    0 at ``t0``, 1 at ``t1``; slopes made monotone first."""
    if n <= 0:
        return np.ones(1)
    m0, m1 = monotone_slopes(m0, m1)
    return hermite(np.arange(n + 1) / n, m0, m1)


def linear_weights(n: int) -> np.ndarray:
    """``(n + 1,)`` weights rising linearly from 0 at ``t0`` to 1 at ``t1`` (the baselines' weight)."""
    if n <= 0:
        return np.ones(1)
    return np.arange(n + 1) / n


def shape_of(d: np.ndarray, min_frames: int = 2) -> tuple[str, int]:
    """The shape of a distance curve over a blend, ``d`` ``(n + 1,)`` metres: ``(case, index)``.

    ``"maximum"`` with the index of an interior maximum standing :data:`FLAT` above both ends and
    at least ``min_frames`` from either end; otherwise ``"increase"`` or ``"decrease"`` by the end
    values (a change under :data:`FLAT` counts as ``"flat"``), index -1.
    """
    d = np.asarray(d, dtype=np.float64)
    n = len(d) - 1
    if n >= 2:
        k = int(np.argmax(d))
        if min_frames <= k <= n - min_frames and d[k] > max(d[0], d[-1]) + FLAT:
            return "maximum", k
    change = d[-1] - d[0]
    if abs(change) < FLAT:
        return "flat", -1
    return ("increase" if change > 0 else "decrease"), -1


@dataclass(frozen=True)
class PartialPlan:
    """How a motion–pose / pose–motion blend is carried out (§4.4.2).

    ``kind`` the blend actually used (``pose-pose`` in case (c)); ``case`` ``a``/``b``/``c``;
    ``begin``/``end`` the frames (relative to the searched ``t0``) the weight curve runs over.
    """

    kind: str
    case: str
    begin: int
    end: int


def plan_partial(kind: str, d: np.ndarray, min_frames: int = 2) -> PartialPlan:
    """§4.4.2: case and effective weight interval of a ``motion-pose`` or ``pose-motion`` blend.

    ``d`` ``(n + 1,)``: the distance (eq. (13), m) from the pose side to each pose of the moving side at
    ``t0 .. t1``. See the module docstring for the cases.
    """
    n = len(d) - 1
    shape, k = shape_of(d, min_frames)
    if kind == "pose-motion":
        if shape == "maximum":
            return PartialPlan(kind, "b", 0, k)
        if shape == "decrease":
            return PartialPlan("pose-pose", "c", 0, n)
        return PartialPlan(kind, "a", 0, n)
    if kind == "motion-pose":
        if shape == "maximum":
            return PartialPlan(kind, "b", k, n)
        if shape == "increase":
            return PartialPlan("pose-pose", "c", 0, n)
        return PartialPlan(kind, "a", 0, n)
    raise ValueError(f"{kind!r} is not a motion-pose or pose-motion blend")
