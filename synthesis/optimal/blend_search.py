"""The blend-interval search of paper 000 §4.3, eqs. (10)–(15), vectorised over all candidate pairs.

For one blend interval with ranges ``t0 ∈ S``, ``t1 ∈ S`` (:mod:`synthesis.optimal.blend_ranges`)::

    min  w_t Q_t(t0, t1) + w_p Q_p(t0, t1) + w_v Q_v(t0, t1)                     (10)
    Q_t = |(t_p,end - t_p,begin) - (t1 - t0)|     blends using a foot-moving interval P   (11)
    Q_t = t1 - t0                                 pose–pose blends                        (12)
    Q_p = D(t0, t1)                               eq. (13), :mod:`synthesis.optimal.posedist`      (13)
    V(t) = approach speed at an end point, from D one frame (ε) on               (14)
    Q_v = |V(t0) - D/(t1 - t0)| + |V(t1) - D/(t1 - t0)|                          (15)

``D(t0, t1)`` is the distance between the *start* pose (the first source at
``t0``) and the *end* pose (the second source at ``t1``), over the joints of
the part searched. ``V`` follows the paper's description of eq. (14) (the
difference of distances, so it is signed): at the start
``V(t0) = (D(t0, t1) - D(t0 + ε, t1)) / ε`` — how fast the first motion
approaches the end pose — and at the end ``V(t1) = (D(t0, t1) - D(t0, t1 - ε)) / ε``
— how fast the second motion leaves the start pose; ``ε`` is one frame.
Units: seconds, metres and m/s, so the weights below convert them.

**Motion–motion blends** (the lower body of a transition): both motions play
through the blend, so its start "pose" is the pair ``A(t0)``/``B(t0)`` and its
end the pair ``A(t1)``/``B(t1)``. Comparing ``A(t0)`` with ``B(t1)`` literally
would measure the gait's own change over the blend (the legs swap in one
step: ``D`` grows to ~0.3 m whatever the two motions are), which drives every
gait transition to the shortest blend. For these :func:`evaluate_motions`
uses, per end, the distance between the two motions being mixed (Kovar's
criterion, the paper's [3]) and the difference of their speeds (eq. (14) as
written, ``V(t) = D(t, t + ε) / ε``)::

    Q_p = (D(A(t0), B(t0)) + D(A(t1), B(t1))) / 2
    Q_v = |V_A(t0) - V_B(t0)| + |V_A(t1) - V_B(t1)|

``Q_t`` stays eq. (11), so the blend lasts about one step.

**All pairs at once**: the features of every candidate start frame (and the
frame after it) and every candidate end frame (and the one before) are
computed once, one distance matrix gives ``D``, ``D(t0 + ε, t1)`` and
``D(t0, t1 - ε)`` as shifted views, and eq. (10) is evaluated on the whole
``(N0, N1)`` grid; the minimum is the global one (ties: the earliest start,
then the earliest end). No per-pair Python loop.

**Weights** (§4.3 last paragraph): one user weight ``W`` from 0 (time first)
to 1 (smoothness first) blends two preset sets linearly (:func:`preset`):

=============== ====== ====== ======
set             w_t    w_p    w_v
=============== ====== ====== ======
time first      1.0    1.0    0.05
smooth first    0.1    1.0    0.5
=============== ====== ====== ======

Per unit: 1 s of blend time (or of mismatch with the step) weighs as much as
1 m of mean joint distance. Time first: a pose change of ``D`` at rest is best
blended over about ``sqrt(2 * 0.05 * D / 1.0)`` s (0.17 s for 30 cm);
smoothness first over ``sqrt(2 * 0.5 * D / 0.1)`` s (1.7 s); the default
``W = 0.5`` about 0.5 s — the range animators use. ``w_p`` is the same in both
sets: which poses to join is not a question of taste.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .posedist import distance_matrix


@dataclass(frozen=True)
class Weights:
    """``w_t`` (per second), ``w_p`` (per metre), ``w_v`` (per m/s) of eq. (10)."""

    time: float
    pose: float
    velocity: float


TIME_FIRST = Weights(1.0, 1.0, 0.05)
SMOOTH_FIRST = Weights(0.1, 1.0, 0.5)


def preset(W: float) -> Weights:
    """The weights for the user's ``W`` in [0, 1]: ``(1 - W) * TIME_FIRST + W * SMOOTH_FIRST``."""
    W = float(W)
    if not 0.0 <= W <= 1.0:
        raise ValueError(f"smoothness must be between 0 (time first) and 1 (smoothness first), got {W}")
    a, b = TIME_FIRST, SMOOTH_FIRST
    return Weights(*((1 - W) * x + W * y for x, y in ((a.time, b.time), (a.pose, b.pose),
                                                         (a.velocity, b.velocity))))


@dataclass(frozen=True)
class Found:
    """The chosen interval ``[t0, t1]`` (frames) and its terms: ``Q_t`` s, ``Q_p`` = ``D`` m, ``Q_v`` m/s,
    the end-point speeds ``V0``, ``V1`` (m/s, signed), and ``cost`` (eq. (10))."""

    t0: int
    t1: int
    Qt: float
    Qp: float
    Qv: float
    V0: float
    V1: float
    cost: float
    weights: Weights

    @property
    def D(self) -> float:
        return self.Qp

    def terms(self) -> dict:
        """The weighted terms of eq. (10) (the report's ``cost``)."""
        w = self.weights
        return {"time": w.time * self.Qt, "pose": w.pose * self.Qp, "velocity": w.velocity * self.Qv}


@dataclass(frozen=True)
class Grid:
    """Every candidate pair's terms: ``t0`` ``(N0,)``, ``t1`` ``(N1,)`` frames; ``D``, ``V0``, ``V1``,
    ``Qt``, ``Qv``, ``cost`` ``(N0, N1)``; ``cost`` is ``inf`` where ``t1 - t0 < min_len``."""

    t0: np.ndarray
    t1: np.ndarray
    D: np.ndarray
    V0: np.ndarray
    V1: np.ndarray
    Qt: np.ndarray
    Qv: np.ndarray
    cost: np.ndarray


def evaluate(f_from: np.ndarray, f_to: np.ndarray, t0: tuple[int, int], t1: tuple[int, int], fps: float,
             weights: Weights, p_len: int | None = None, min_len: int = 1) -> Grid:
    """eq. (10) on the whole grid of ``t0`` in ``[t0[0], t0[1]]`` and ``t1`` in ``[t1[0], t1[1]]``.

    Args:
        f_from: :func:`~synthesis.optimal.posedist.features` of the first source at frames ``t0[0] .. t0[1] + 1``,
            ``(N0 + 1, K, 3)`` (one frame past the range: ε of eq. (14)).
        f_to: features of the second source at frames ``t1[0] - 1 .. t1[1]``, ``(N1 + 1, K, 3)``.
        fps: frames per second (ε = 1 / fps).
        p_len: frames of the foot-moving interval for eq. (11); ``None`` for eq. (12).
        min_len: shortest blend, frames.
    """
    a = np.arange(t0[0], t0[1] + 1)
    b = np.arange(t1[0], t1[1] + 1)
    if len(f_from) != len(a) + 1 or len(f_to) != len(b) + 1:
        raise ValueError(f"features for {len(f_from)}/{len(f_to)} frames, ranges of {len(a)}/{len(b)}")
    full = distance_matrix(f_from, f_to)  # rows t0 .. t0_hi + 1, columns t1_lo - 1 .. t1
    D = full[:-1, 1:]  # eq. (13) D(t0, t1)
    V0 = (D - full[1:, 1:]) * fps  # eq. (14) at the start: D(t0, t1) - D(t0 + ε, t1)
    V1 = (D - full[:-1, :-1]) * fps  # eq. (14) at the end: D(t0, t1) - D(t0, t1 - ε)
    frames = b[None, :] - a[:, None]
    T = np.maximum(frames, 1) / fps
    mean = D / T
    Qv = np.abs(V0 - mean) + np.abs(V1 - mean)  # eq. (15)
    Qt = np.abs(p_len / fps - T) if p_len is not None else T  # eq. (11) / (12)
    cost = weights.time * Qt + weights.pose * D + weights.velocity * Qv  # eq. (10)
    cost = np.where(frames >= min_len, cost, np.inf)
    return Grid(a, b, D, V0, V1, Qt, Qv, cost)


def search(f_from: np.ndarray, f_to: np.ndarray, t0: tuple[int, int], t1: tuple[int, int], fps: float,
           weights: Weights, p_len: int | None = None, min_len: int = 1) -> Found:
    """The global minimum of eq. (10) over the ranges (see :func:`evaluate` for the arguments).

    Raises ``ValueError`` when no pair is at least ``min_len`` frames apart.
    """
    return best(evaluate(f_from, f_to, t0, t1, fps, weights, p_len, min_len), weights, min_len)


def _rowwise(fa: np.ndarray, fb: np.ndarray) -> np.ndarray:
    """eq. (13) frame by frame: ``(N,)`` distances between ``fa[k]`` and ``fb[k]``."""
    return np.linalg.norm(fa - fb, axis=-1).mean(axis=-1)


def evaluate_motions(fa0: np.ndarray, fb0: np.ndarray, fa1: np.ndarray, fb1: np.ndarray, t0: tuple[int, int],
                     t1: tuple[int, int], fps: float, weights: Weights, p_len: int | None = None,
                     min_len: int = 1) -> Grid:
    """eq. (10) for a motion–motion blend on the whole grid (see the module docstring).

    ``fa0``/``fb0``: features of the first / second motion at frames ``t0[0] .. t0[1] + 1``;
    ``fa1``/``fb1``: at ``t1[0] .. t1[1] + 1`` (one frame more for ε). ``V0``/``V1`` of the result are the
    literal eq. (15) speeds' counterpart here: the first motion's speed at ``t0`` and the second's at ``t1``.
    """
    a = np.arange(t0[0], t0[1] + 1)
    b = np.arange(t1[0], t1[1] + 1)
    if not (len(fa0) == len(fb0) == len(a) + 1 and len(fa1) == len(fb1) == len(b) + 1):
        raise ValueError("features must cover each range and one frame more")
    d0 = _rowwise(fa0[:-1], fb0[:-1])  # D(A(t0), B(t0))
    d1 = _rowwise(fa1[:-1], fb1[:-1])  # D(A(t1), B(t1))
    va0, vb0 = _rowwise(fa0[:-1], fa0[1:]) * fps, _rowwise(fb0[:-1], fb0[1:]) * fps  # eq. (14)
    va1, vb1 = _rowwise(fa1[:-1], fa1[1:]) * fps, _rowwise(fb1[:-1], fb1[1:]) * fps
    D = 0.5 * (d0[:, None] + d1[None, :])
    Qv = np.abs(va0 - vb0)[:, None] + np.abs(va1 - vb1)[None, :]
    frames = b[None, :] - a[:, None]
    T = np.maximum(frames, 1) / fps
    Qt = np.abs(p_len / fps - T) if p_len is not None else T
    cost = weights.time * Qt + weights.pose * D + weights.velocity * Qv
    cost = np.where(frames >= min_len, cost, np.inf)
    shape = cost.shape
    return Grid(a, b, D, np.broadcast_to(va0[:, None], shape), np.broadcast_to(vb1[None, :], shape), Qt, Qv, cost)


def best(g: Grid, weights: Weights, min_len: int = 1) -> Found:
    """The global minimum of a :class:`Grid` (ties: the earliest start, then the earliest end)."""
    if not np.isfinite(g.cost).any():
        raise ValueError(f"no blend of {min_len} frames fits t0 in [{g.t0[0]}, {g.t0[-1]}], "
                         f"t1 in [{g.t1[0]}, {g.t1[-1]}]")
    i, j = np.unravel_index(int(np.argmin(g.cost)), g.cost.shape)
    return Found(int(g.t0[i]), int(g.t1[j]), float(g.Qt[i, j]), float(g.D[i, j]), float(g.Qv[i, j]),
                 float(g.V0[i, j]), float(g.V1[i, j]), float(g.cost[i, j]), weights)
