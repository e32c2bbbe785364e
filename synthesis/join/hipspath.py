"""The hips' path of least acceleration: a join's hips bent, by a few centimetres, out of their jolts.

A join moves the hips from where the first clip leaves them to where the second has them; the engine's
blends and its adaptation's return (eq. (8): the hips follow the mean of the feet's offsets back over one
step) can concentrate that travel into a fraction of a second — a 40-90 cm change of stance returned over
a 0.3-0.5 s step is a jolt of 6-11 m/s², where a crossfade's long slide reads 1-3. Step 6 of the join
post-pass (:mod:`synthesis.join.joinpass`) replaces the hips' horizontal path ``h`` ``(n, 2)`` over a
finished join region by the path ``x`` found by two linear programmes (HiGHS's dual simplex through
``highspy``; deterministic), over the accelerations ``a[t] = (x[t-1] - 2 x[t] + x[t+1]) fps²``, the two frames
either side of the region fixed so that position and velocity carry on:

1. the least peak ``A``: minimise ``A`` subject to ``|u_k · a[t]| <= A`` (four directions ``u_k``: an
   octagon, its corners 8 % beyond ``A``), ``|u_k · (x[t] - h[t])| <= band[t]`` (the move within an
   octagon), and the balance bounds;
2. under ``max(A (1 + SLACK), LEVELS[0])``: minimise ``sum_t sum_k max(0, |a[t]| - LEVELS[k])`` (a convex,
   piecewise-linear price: a larger jolt costs more per m/s², and every frame's jolt is lowered, not
   only the peak's) ``+ OUTSIDE · sum_t outside[t] + NEAR · sum_t |x[t] - h[t]|``.

``band[t]`` is :data:`BAND` where the hips move at :data:`MOVING` or faster, 0 where slower than
:data:`STILL` (a body holding a pose stays where it stands), linear between. The floor ``LEVELS[0]`` (0.7 m/s²) leaves gentle paths
alone: held under a lower cap a path only accelerates at the cap and coasts through zero, the steady glide
the glide figure finds (``core.glide``). **Balance** (:class:`Support`): on frames where a foot is down
and the centre of mass moves slower than :data:`NEAR_SLOW` times the balance figure's speed, per edge of
the support area (the hull of the feet on the floor widened by the foot's radius, ``core.balance``), the
centre of mass — moved at most as far as the hips — goes no further out than :data:`BALANCE_ROOM` or than
it was, and each metre it stays outside costs :data:`OUTSIDE` (``outside[t]``), so the path also stands a
body over its feet where the join left it beside them. Both legs are then solved back onto where the
feet were (ankle position and world rotation, :func:`synthesis.join.legsolve.feet_kept`): no foot moves,
the upper body rides on the hips. Lengths and accelerations are at a person's size
(:func:`core.size.human_scale`).

This departs from eq. (8) of paper 000 (the hips following the mean of the feet's offsets over the return
step): the feet still return over that step; the hips take the few centimetres' freedom of the band to
spread their travel over the join's region, shifting the weight before the step as a person does.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from highspy import HighsLp, HighsModelStatus, MatrixFormat, kHighsInf
from highspy._core import _Highs  # the public Highs wraps it with callbacks that print HiGHS's banner on stdout
from scipy import sparse
from scipy.spatial import ConvexHull, QhullError

from text2anim.core.balance import SLOW, Stance, stance
from text2anim.core.motion import Motion
from text2anim.core.size import human_scale

from .legsolve import feet_kept

#: m at a person's size: how far the hips may be moved off the path the join gave them (along each of four
#: directions: an octagon, its corners 8 % further)
BAND = 0.08
#: the balance is kept on frames whose centre of mass is slower than this many times core.balance.SLOW: a
#: path bent to accelerate less may slow a body into the frames the balance figure judges
NEAR_SLOW = 2.0
#: m/s at a person's size: hips slower than this may be moved only a share of :data:`BAND` (from 0 at
#: :data:`STILL`, where a body holding a pose or breathing stays exactly where it stands)
MOVING = 0.1
STILL = 0.02
#: m/s² at a person's size: each frame's acceleration pays its excess over each of these, so a larger jolt
#: costs more per m/s² than a smaller one (a convex, piecewise-linear price) and no frame's jolt is left
#: because another frame's cannot be lowered (as a least-peak programme would)
LEVELS = (0.7, 1.5, 3.0, 6.0, 12.0)
#: the path under the least peak may reach this much beyond it (a little room buys a much closer path)
SLACK = 0.02
#: (m/s²) per m and frame: the price of a centre of mass outside the support area on a standing frame
OUTSIDE = 20.0
#: (m/s²) per m: the price of moving the hips off their path, small: among paths that accelerate alike, the nearest
NEAR = 0.1
#: m: paths moved less than this are left as they were
MIN_MOVE = 1e-3
#: m at a person's size: how far a slow body's centre of mass may be moved beyond the support area (half the
#: balance figure's limit, core.balance.LIMIT_CM)
BALANCE_ROOM = 0.03
#: the region's frames solved at most (a bound on the programme's size; longer regions are left as they are)
MAX_FRAMES = 900
_DIRS = np.array([[np.cos(a), np.sin(a)] for a in np.arange(4) * np.pi / 4])  # (4, 2) unit directions


def _second_difference(n: int) -> sparse.csr_matrix:
    """``(n + 2, n)``: the second differences at frames ``-1 .. n`` of ``n`` free frames (the frames beside
    them fixed: their part is :func:`_fixed_part`)."""
    return sparse.diags([1.0, -2.0, 1.0], [0, -1, -2], shape=(n + 2, n), format="csr")


def _fixed_part(before: np.ndarray, after: np.ndarray, n: int) -> np.ndarray:
    """``(n + 2, 2)``: what the fixed frames (two before, two after, each ``(2, 2)``) add to the second
    differences of :func:`_second_difference`."""
    c = np.zeros((n + 2, 2))
    c[0] += before[0] - 2.0 * before[1]
    c[1] += before[1]
    c[-2] += after[0]
    c[-1] += after[1] - 2.0 * after[0]
    return c


@dataclass(frozen=True)
class Support:
    """The balance of a region as linear functions of the hips' moves ``d`` (stacked ``[x (n), z (n)]``, m):
    per edge ``r`` of the support area on a standing frame (the hull of the feet on the floor widened by the
    foot's radius, :class:`core.balance.Stance`), ``rows[r] · d`` is how much further out that edge the move
    takes the centre of mass (moving at most as far as the hips), ``gap[r]`` how far out it is (negative
    inside), ``frame[r]`` the frame."""

    rows: sparse.csr_matrix
    gap: np.ndarray
    frame: np.ndarray


def support_of(st: Stance) -> Support:
    """The :class:`Support` of a stance, on the frames slower than :data:`NEAR_SLOW` times the figure's."""
    n = len(st.com)
    ring = st.radius * np.array([[np.cos(a), np.sin(a)] for a in np.arange(8) * np.pi / 4])  # (8, 2)
    normals, gaps, frames = [], [], []
    for i in np.flatnonzero(st.standing(NEAR_SLOW * SLOW)):
        pts = (st.corners[i][st.down[i]][:, None, :] + ring[None]).reshape(-1, 2)
        try:
            eq = ConvexHull(pts).equations  # (E, 3): normal · p + offset <= 0 inside
        except (QhullError, ValueError):  # a degenerate foot (no radius, no extent): nothing to hold it to
            continue
        normals.append(eq[:, :2])
        gaps.append(eq[:, :2] @ st.com[i] + eq[:, 2])
        frames.append(np.full(len(eq), i))
    if not normals:
        return Support(sparse.csr_matrix((0, 2 * n)), np.zeros(0), np.zeros(0, dtype=int))
    nrm, frame = np.concatenate(normals), np.concatenate(frames)
    r = np.arange(len(nrm))
    rows = sparse.csr_matrix((np.concatenate([nrm[:, 0], nrm[:, 1]]), (np.concatenate([r, r]),
                              np.concatenate([frame, n + frame]))), shape=(len(nrm), 2 * n))
    return Support(rows, np.concatenate(gaps), frame)


def _acceleration_rows(n: int, fps: float, before: np.ndarray, after: np.ndarray) -> tuple[sparse.csr_matrix, np.ndarray]:
    """``(rows, const)``: ``rows @ [x, z] + const`` are the accelerations (m/s²) of ``n`` free frames along each
    direction and sign (``±u_k · a[t]`` for ``t`` in ``-1 .. n``): ``(8 (n + 2), 2 n)`` and ``(8 (n + 2),)``."""
    D = _second_difference(n) * fps ** 2
    c = _fixed_part(before, after, n) * fps ** 2  # (n + 2, 2)
    rows = [sign * sparse.hstack([D * u[0], D * u[1]]) for u in _DIRS for sign in (1.0, -1.0)]
    return sparse.vstack(rows).tocsr(), np.concatenate([sign * (c @ u) for u in _DIRS for sign in (1.0, -1.0)])


def _octagon(h: np.ndarray, band: np.ndarray) -> tuple[sparse.csr_matrix, np.ndarray]:
    """``(rows, bounds)``: ``rows @ [x, z] <= bounds`` holds the move from ``h`` ``(n, 2)`` within the octagon's
    diagonals (its sides along the axes are the variables' bounds)."""
    eye = sparse.identity(len(h), format="csr")
    rows = [sign * sparse.hstack([u[0] * eye, u[1] * eye]) for u in _DIRS[1::2] for sign in (1.0, -1.0)]
    return sparse.vstack(rows).tocsr(), np.concatenate([band + sign * (h @ u) for u in _DIRS[1::2] for sign in (1.0, -1.0)])


def _minimum(cost: np.ndarray, rows: sparse.spmatrix, rhs: np.ndarray, lower: np.ndarray,
             upper: np.ndarray) -> np.ndarray | None:
    """The ``x`` that minimises ``cost · x`` subject to ``rows @ x <= rhs`` and ``lower <= x <= upper``
    (``np.inf`` for no bound), HiGHS's choice among equal optima (the model as :func:`scipy.optimize.linprog`
    passes it, without its import); None when there is none."""
    a = sparse.csc_matrix(rows)
    lp = HighsLp()
    lp.num_col_, lp.num_row_ = a.shape[1], a.shape[0]
    lp.col_cost_, lp.col_lower_, lp.col_upper_ = cost, lower, upper
    lp.row_lower_, lp.row_upper_ = np.full(a.shape[0], -kHighsInf), rhs
    lp.a_matrix_.format_ = MatrixFormat.kColwise
    lp.a_matrix_.start_, lp.a_matrix_.index_, lp.a_matrix_.value_ = a.indptr, a.indices, a.data
    solver = _Highs()
    solver.setOptionValue("output_flag", False)
    solver.passModel(lp)
    solver.run()
    if solver.getModelStatus() != HighsModelStatus.kOptimal:
        return None
    return np.asarray(solver.getSolution().col_value)


def _least_peak(acc: tuple, limits: tuple, box: tuple[np.ndarray, np.ndarray]) -> float | None:
    """Programme 1 of the module docstring: the least peak acceleration (m/s²) over the paths within ``box``
    (the variables' lower and upper bounds) and ``limits`` (``rows @ [x, z] <= bounds``); None when there is
    none."""
    rows, const = acc
    A, b = limits
    ones = sparse.csr_matrix(np.ones((rows.shape[0], 1)))
    x = _minimum(np.r_[np.zeros(rows.shape[1]), 1.0],
                 sparse.vstack([sparse.hstack([rows, -ones]), sparse.hstack([A, sparse.csr_matrix((A.shape[0], 1))])]),
                 np.concatenate([-const, b]), np.r_[box[0], 0.0], np.r_[box[1], np.inf])
    return None if x is None else float(x[-1])


def least_acceleration_path(h: np.ndarray, before: np.ndarray, after: np.ndarray, fps: float, band: np.ndarray,
                            support: Support | None = None, levels: np.ndarray = np.asarray(LEVELS),
                            room: float = BALANCE_ROOM) -> np.ndarray | None:
    """The path ``(n, 2)`` (m) within ``band`` ``(n,)`` (m, an octagon's inradius) of ``h`` ``(n, 2)`` whose
    horizontal accelerations pay least over ``levels`` (m/s², module docstring) under the least peak, with
    the body standing over its feet; ``before``/``after`` ``(2, 2)``: the two fixed frames either side. None
    when the programme finds none.

    Programme 2's variables are ``[x (n), z (n), p (n + 2), e (K (n + 2)), v (2 n), o (n)]``: ``p`` bounds each
    frame's acceleration (octagon), ``e`` its excess over each level, ``v`` the distance from ``h``, ``o`` how far
    the centre of mass is outside the support (``support``: no edge's distance may grow beyond
    ``max(gap, room)``; each metre outside costs :data:`OUTSIDE`)."""
    n, K = len(h), len(levels)
    m = n + 2  # accelerations at frames -1 .. n
    flat = np.concatenate([h[:, 0], h[:, 1]])
    sup = support if support is not None else Support(sparse.csr_matrix((0, 2 * n)), np.zeros(0), np.zeros(0, int))
    S, R = sup.rows, len(sup.gap)
    octa, octa_rhs = _octagon(h, band)
    limits = (sparse.vstack([S, octa]).tocsr(), np.concatenate([np.maximum(0.0, room - sup.gap) + S @ flat, octa_rhs]))
    wide = np.concatenate([band, band])
    box = (flat - wide, flat + wide)
    acc, const = _acceleration_rows(n, fps, before, after)
    least = _least_peak((acc, const), limits, box)
    if least is None:
        return None
    peak = max(least * (1.0 + SLACK) + 1e-6, levels[0])
    Z = sparse.csr_matrix
    width = 2 * n + m + K * m + 2 * n + n
    eye_m, eye_x = sparse.identity(m, format="csr"), sparse.identity(2 * n, format="csr")
    pick = Z((np.ones(R), (np.arange(R), sup.frame)), shape=(R, n))
    blocks = [sparse.hstack([acc, -sparse.vstack([eye_m] * 8), Z((8 * m, width - 2 * n - m))]),  # ±u·a <= p
              sparse.hstack([Z((K * m, 2 * n)), sparse.vstack([eye_m] * K), -sparse.identity(K * m),
                             Z((K * m, 3 * n))]),  # p - e_k <= level_k
              sparse.hstack([eye_x, Z((2 * n, m + K * m)), -eye_x, Z((2 * n, n))]),  # ±(x - h) <= v
              sparse.hstack([-eye_x, Z((2 * n, m + K * m)), -eye_x, Z((2 * n, n))]),
              sparse.hstack([limits[0], Z((limits[0].shape[0], width - 2 * n))]),  # the balance, the octagon
              sparse.hstack([S, Z((R, width - 3 * n)), -pick])]  # gap + move <= o
    rhs = [-const, np.repeat(levels, m), flat, -flat, limits[1], S @ flat - sup.gap]
    cost = np.concatenate([np.zeros(2 * n + m), np.ones(K * m), np.full(2 * n, NEAR), np.full(n, OUTSIDE)])
    lower = np.concatenate([box[0], np.zeros(width - 2 * n)])
    upper = np.concatenate([box[1], np.full(m, peak), np.full(width - 2 * n - m, np.inf)])
    x = _minimum(cost, sparse.vstack(blocks), np.concatenate(rhs), lower, upper)
    return None if x is None else np.stack([x[:n], x[n:2 * n]], axis=1)


def least_acceleration(motion: Motion, lo: int, hi: int) -> tuple[Motion, float]:
    """``motion`` with the hips' horizontal path over frames ``[lo, hi)`` replaced by the
    :func:`least_acceleration_path` within :data:`BAND` (at the body's size) that keeps a slow body over its
    feet (:func:`support_of`, :data:`BALANCE_ROOM`), the legs solved back onto the feet; and the largest
    move (m). The motion as it is when the region is too short, too long or already as smooth as the band
    allows."""
    T = motion.n_frames
    lo, hi = max(lo, 2), min(hi, T - 2)
    n = hi - lo
    if n < 3 or n > MAX_FRAMES:
        return motion, 0.0
    k = human_scale(motion)
    xz = motion.root_positions[:, [0, 2]]
    if not np.isfinite(xz[lo - 2:hi + 2]).all():
        return motion, 0.0
    st = stance(motion[lo:hi])
    support = None if st is None else support_of(st)
    speed = np.linalg.norm(np.gradient(xz[lo - 1:hi + 1], axis=0), axis=-1)[1:-1] * motion.fps * k
    band = BAND / k * np.clip((speed - STILL) / (MOVING - STILL), 0.0, 1.0)  # a still body stays where it stands
    path = least_acceleration_path(xz[lo:hi], xz[lo - 2:lo], xz[hi:hi + 2], motion.fps, band, support,
                                   np.asarray(LEVELS) / k, BALANCE_ROOM / k)
    if path is None:
        return motion, 0.0
    size = float(np.linalg.norm(path - xz[lo:hi], axis=1).max())
    if size < MIN_MOVE / k:
        return motion, 0.0
    root = motion.root_positions.copy()
    root[lo:hi, 0] = path[:, 0]
    root[lo:hi, 2] = path[:, 1]
    return feet_kept(motion, motion.replace(root_positions=root), lo, hi), size
