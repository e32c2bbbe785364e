"""The hips' path of least acceleration: a join's hips bent, by a few centimetres, out of their jolts.

A join moves the hips from where the first clip leaves them to where the second has them; the engine's
blends and its adaptation's return (eq. (8): the hips follow the mean of the feet's offsets back over one
step) can concentrate that travel into a fraction of a second — a 40-90 cm change of stance returned over
a 0.3-0.5 s step is a jolt of 6-11 m/s², where a crossfade's long slide reads 1-3. Step 6 of the join
post-pass (:mod:`synthesis.join.joinpass`) replaces the hips' horizontal path ``h`` ``(n, 2)`` over a
finished join region by the path ``x`` found by two linear programmes (PIQP's interior point method,
:func:`_minimum`; deterministic), over the accelerations ``a[t] = (x[t-1] - 2 x[t] + x[t+1]) fps²``, the two frames
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

import functools
import importlib
from dataclasses import dataclass
from types import ModuleType

import numpy as np
from scipy import sparse

from text2anim.core.balance import SLOW, Stance, stance
from text2anim.core.kept import Kept, digest
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
_DIRS[np.abs(_DIRS) < 1e-12] = 0.0  # exact zeros along the axes
#: the paths of the last regions solved, by the value of their programme's inputs (:func:`least_acceleration`): a
#: warm process meets the same joins again (the studio re-animates the whole text at every pause in typing)
KEPT_PATHS: Kept[np.ndarray | None] = Kept(256)


_Entries = tuple[np.ndarray, np.ndarray, np.ndarray]  # (rows, columns, values) of a sparse matrix's entries


def _second_difference(n: int, fps: float) -> _Entries:
    """The entries of the ``(n + 2, n)`` matrix of the second differences (times ``fps²``) at frames ``-1 .. n``
    of ``n`` free frames (the frames beside them fixed: their part is :func:`_fixed_part`)."""
    j = np.arange(n)
    return np.concatenate([j, j + 1, j + 2]), np.tile(j, 3), np.repeat([1.0, -2.0, 1.0], n) * fps ** 2


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

    rows: sparse.coo_matrix
    gap: np.ndarray
    frame: np.ndarray


def support_of(st: Stance) -> Support:
    """The :class:`Support` of a stance, on the frames slower than :data:`NEAR_SLOW` times the figure's (none for a
    foot of no size, or where a foot down has no place)."""
    n = len(st.com)
    frames = np.flatnonzero(st.standing(NEAR_SLOW * SLOW))
    points, down = st.corners[frames], st.down[frames]
    placed = (np.isfinite(points).all(axis=-1) | ~down).all(axis=1)
    if not st.radius > 0.0:
        placed[:] = False
    normals, offsets, edge = _widened_hull(np.nan_to_num(points), down, st.radius)  # (F, E, 2), (F, E), (F, E)
    edge &= placed[:, None]
    at, _k = np.nonzero(edge)
    nrm, frame = normals[edge], frames[at]
    gap = nrm[:, 0] * st.com[frame, 0] + nrm[:, 1] * st.com[frame, 1] + offsets[edge]
    r = np.arange(len(nrm))
    rows = sparse.coo_matrix((np.concatenate([nrm[:, 0], nrm[:, 1]]), (np.concatenate([r, r]),
                              np.concatenate([frame, n + frame]))), shape=(len(nrm), 2 * n))
    return Support(rows, gap, frame)


def _widened_hull(points: np.ndarray, down: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The edges of the convex hull of each frame's ``down`` ``(F, K)`` points ``(F, K, 2)`` widened by a regular
    octagon of circumradius ``radius`` (its corners at multiples of 45°), as ``normal · p + offset <= 0`` inside:
    ``(normals (F, E, 2), offsets (F, E), is_edge (F, E))`` over ``E = 8 + K (K - 1)`` candidates. A sum of two
    convex polygons has the edge directions of both: the octagon's eight, and those of the points' hull (a pair
    of points with every other on its inner side); its offset is the sum of the two supports. Equal to qhull's
    facets of the widened points (to 1e-13 over the golden sentences' 1,151 standing frames), at once for all
    frames: a hull a frame cost 50 µs."""
    F, K, _ = points.shape
    angle = np.pi / 8 + np.arange(8) * np.pi / 4
    first, second = np.array([(i, j) for i in range(K) for j in range(K) if i != j], dtype=int).reshape(-1, 2).T
    side = points[:, second] - points[:, first]  # (F, P, 2)
    length = np.linalg.norm(side, axis=-1)
    outward = np.stack([side[..., 1], -side[..., 0]], axis=-1) / np.where(length > 0.0, length, 1.0)[..., None]
    normals = np.concatenate([np.broadcast_to(np.stack([np.cos(angle), np.sin(angle)], axis=1), (F, 8, 2)), outward],
                             axis=1)  # (F, E, 2)
    nx, nz = normals[..., 0], normals[..., 1]  # (F, E)
    product = nx[..., None] * points[:, None, :, 0] + nz[..., None] * points[:, None, :, 1]  # (F, E, K)
    beyond = product[:, 8:] - np.take_along_axis(product[:, 8:], first[None, :, None], axis=-1)  # (F, P, K)
    hull_edge = down[:, first] & down[:, second] & (length > 1e-12) & (
        np.where(down[:, None, :], beyond, -np.inf).max(axis=-1) <= 1e-12 * np.maximum(1.0, length))
    corners = radius * np.stack([np.cos(np.arange(8) * np.pi / 4), np.sin(np.arange(8) * np.pi / 4)], axis=1)
    support = np.where(down[:, None, :], product, -np.inf).max(axis=-1) + (normals @ corners.T).max(axis=-1)
    edge = np.concatenate([np.repeat(down.any(axis=1, keepdims=True), 8, axis=1), hull_edge], axis=1)
    same = nx[..., None] * nx[:, None] + nz[..., None] * nz[:, None] > 1.0 - 1e-12  # one direction: one edge
    edge &= ~(same & edge[:, None, :] & np.tri(len(angle) + len(first), k=-1, dtype=bool)).any(axis=-1)
    return normals, -support, edge


def _acceleration(h: np.ndarray, before: np.ndarray, after: np.ndarray,
                  fps: float) -> tuple[_Entries, np.ndarray]:
    """``(U, a0)``: ``U @ d + a0`` are the accelerations (m/s²) along each direction ``u_k`` (``u_k · a[t]``, row
    ``k (n + 2) + t`` for ``t`` in ``-1 .. n``) of the path ``h + d`` (``h`` ``(n, 2)``, its moves ``d`` stacked
    ``[x (n), z (n)]``): the entries of the ``(4 (n + 2), 2 n)`` matrix ``U`` (none for an axis a direction is
    square to) and ``(4 (n + 2),)``, ``a0`` the given path's own."""
    n = len(h)
    r, c, v = _second_difference(n, fps)
    a = sparse.csr_matrix((v, (r, c)), shape=(n + 2, n)) @ h + _fixed_part(before, after, n) * fps ** 2  # (n + 2, 2)
    blocks = [(r + k * (n + 2), c + axis * n, v * u[axis]) for k, u in enumerate(_DIRS) for axis in (0, 1) if u[axis]]
    return _joined(blocks), (a @ _DIRS.T).T.ravel()


def _limits(band: np.ndarray, sup: Support, reach: np.ndarray,
            room: float) -> tuple[_Entries, np.ndarray, np.ndarray]:
    """``(rows, lower, upper)``: ``lower <= rows @ d <= upper`` (``rows`` as its entries) holds the moves ``d``
    within the octagon's diagonals (its sides along the axes are the moves' bounds) and the balance (no edge's
    distance grows beyond ``max(gap, room)``): only the edges a move within the octagon can take that far, the
    rest hold anyway (``reach``: :func:`_reach`)."""
    n = len(band)
    t = np.arange(n)
    diagonals = [(t + i * n, t + axis * n, np.full(n, u[axis])) for i, u in enumerate(_DIRS[1::2]) for axis in (0, 1)]
    wide = np.concatenate([band, band])
    room_left = np.maximum(0.0, room - sup.gap)
    held = reach > room_left
    return (_joined(diagonals + [_at(_edges(sup, held), 2 * n, 0)]),
            np.concatenate([-wide, np.full(held.sum(), -np.inf)]), np.concatenate([wide, room_left[held]]))


def _edges(sup: Support, keep: np.ndarray) -> _Entries:
    """The entries of ``sup.rows[keep]`` (``keep`` ``(R,)`` bool)."""
    c = sup.rows
    kept = keep[c.row]
    return (np.cumsum(keep) - 1)[c.row[kept]], c.col[kept], c.data[kept]


def _reach(band: np.ndarray, sup: Support) -> np.ndarray:
    """``(R,)`` m: the furthest a move within the octagon of inradius ``band`` (its corners 1 / cos 22.5° out)
    takes the centre of mass across each edge of the support (with a hair's margin)."""
    c = sup.rows
    norm = np.sqrt(np.bincount(c.row, c.data * c.data, minlength=len(sup.gap)))
    return norm * band[sup.frame] / np.cos(np.pi / 8) * (1.0 + 1e-9) + 1e-12


def _joined(entries: list[_Entries]) -> _Entries:
    """The entries of several blocks as one."""
    r, c, v = (np.concatenate(x) for x in zip(*entries))
    return r, c, v


def _at(M: _Entries, row: int, col: int, sign: float = 1.0) -> _Entries:
    """The entries of ``M`` placed with its corner at ``(row, col)``, times ``sign``."""
    return M[0] + row, M[1] + col, sign * M[2]


def _ones(rows: np.ndarray, cols: np.ndarray | int, value: float) -> _Entries:
    """Entries ``value`` at ``(rows, cols)``."""
    return rows, np.broadcast_to(cols, rows.shape), np.full(len(rows), value)


def _matrix(entries: list[_Entries], shape: tuple[int, int]) -> sparse.csc_matrix:
    """The matrix of ``shape`` with these entries (none twice), assembled once from index arithmetic (scipy's
    sparse blocks, stacked, scaled and converted, cost 1.5 ms of a region's 5.8 outside the solver)."""
    r, c, v = _joined(entries)
    return sparse.csc_matrix((v, (r, c)), shape=shape)


@functools.cache
def _piqp() -> ModuleType | None:
    """PIQP's compiled module (imported at the first programme: the commands that synthesise nothing never pay
    for it): its AVX2 build where the CPU has AVX2, as the goldens' bytes are pinned there
    (:mod:`api.reproducible`; piqp itself takes its AVX-512 build where it can, whose paths differ by up to
    0.01 mm); else the build piqp chose. None without piqp."""
    try:
        import piqp
    except ImportError:
        return None
    try:
        return importlib.import_module("piqp.piqp_python_avx2") if piqp.instruction_set.avx2 else piqp
    except ImportError:  # a piqp that renamed its builds
        return piqp


def _minimum(cost: np.ndarray, rows: sparse.spmatrix, lower: np.ndarray, upper: np.ndarray, col_lower: np.ndarray,
             col_upper: np.ndarray, stage: np.ndarray) -> np.ndarray | None:
    """The ``x`` that minimises ``cost · x`` subject to ``lower <= rows @ x <= upper`` and ``col_lower <= x <=
    col_upper`` (``np.inf`` for no bound): PIQP's proximal interior point method, on one thread; to its tolerance
    (1e-8 relative), where optima tie the middle of the optimal ones rather than a vertex. ``stage`` ``(len(x),)``:
    the frame each variable belongs to (one after the last for one every frame shares): put in frame order, the
    variables make the KKT system banded (a row reaches three neighbouring frames), which PIQP's multistage solver
    factors as the block-tridiagonal system it finds, the shared variable its arrow — on the 32-motion and the
    varied text's 103 regions in about half the time of the general sparse LDLᵀ's (216 vs 393 ms), the solves
    12-15 % faster; 12-25 iterations, 2.4x faster than HiGHS's dual simplex. Both programmes always have a solution (the
    given path, or programme 1's, is one), so PIQP's test for infeasibility is off: it had called one of the
    32-motion text's 93 least-peak programmes infeasible after 8 iterations (its optimum, 5.171 m/s², found in 16
    without the test, as HiGHS finds it), and HiGHS's fallback cost that region ~95 ms. scipy's HiGHS where PIQP
    finds none or piqp is missing; None when that finds none either."""
    piqp = _piqp()
    if piqp is not None:
        n = len(cost)
        order = np.argsort(stage, kind="stable")
        solver = piqp.SparseSolver()
        solver.settings.verbose = False
        solver.settings.num_threads = 1
        solver.settings.kkt_solver = piqp.KKTSolver.sparse_multistage
        solver.settings.eps_primal_inf = solver.settings.eps_dual_inf = 1e-30  # never infeasible nor unbounded
        solver.setup(sparse.csc_matrix((n, n)), cost[order], None, None, sparse.csc_matrix(rows)[:, order], lower,
                     upper, col_lower[order], col_upper[order])
        if solver.solve() == piqp.PIQP_SOLVED:
            x = np.empty(n)
            x[order] = solver.result.x
            return x
    return _minimum_scipy(cost, rows, lower, upper, col_lower, col_upper)


def _minimum_scipy(cost: np.ndarray, rows: sparse.spmatrix, lower: np.ndarray, upper: np.ndarray,
                   col_lower: np.ndarray, col_upper: np.ndarray) -> np.ndarray | None:
    """:func:`_minimum` through :func:`scipy.optimize.linprog` (HiGHS's dual simplex: a vertex among equal
    optima; its import alone is ~55 ms): each two-sided row as two one-sided ones."""
    from scipy.optimize import linprog

    a = sparse.csr_matrix(rows)
    up, down = np.isfinite(upper), np.isfinite(lower)
    res = linprog(cost, A_ub=sparse.vstack([a[up], -a[down]]), b_ub=np.concatenate([upper[up], -lower[down]]),
                  bounds=[(lo if np.isfinite(lo) else None, hi if np.isfinite(hi) else None)
                          for lo, hi in zip(col_lower, col_upper)], method="highs")
    return np.asarray(res.x) if res.status == 0 else None


def _least_peak(U: _Entries, a0: np.ndarray, limits: tuple[_Entries, np.ndarray, np.ndarray],
                band: np.ndarray) -> float | None:
    """Programme 1 of the module docstring: the least peak acceleration (m/s²) over the moves ``d`` ``(2 n,)``
    within ``band`` ``(n,)`` and ``limits`` (:func:`_limits`), ``U @ d + a0`` the accelerations
    (:func:`_acceleration`); None when there is none. Its variables are ``[d (2 n), A]``."""
    rows, lower, upper = limits
    q, w = len(a0), 2 * len(band)
    r = np.arange(q)
    wide = np.concatenate([band, band])
    stage = np.r_[np.tile(np.arange(len(band)), 2), len(band)]  # each column's frame; A's: one after the last
    x = _minimum(np.r_[np.zeros(w), 1.0],
                 _matrix([_at(U, 0, 0), _ones(r, w, -1.0), _at(U, q, 0, -1.0), _ones(q + r, w, -1.0),
                          _at(rows, 2 * q, 0)], (2 * q + len(lower), w + 1)),
                 np.concatenate([np.full(2 * q, -np.inf), lower]), np.concatenate([-a0, a0, upper]),
                 np.r_[-wide, 0.0], np.r_[wide, np.inf], stage)
    return None if x is None else float(x[-1])


def least_acceleration_path(h: np.ndarray, before: np.ndarray, after: np.ndarray, fps: float, band: np.ndarray,
                            support: Support | None = None, levels: np.ndarray = np.asarray(LEVELS),
                            room: float = BALANCE_ROOM) -> np.ndarray | None:
    """The path ``(n, 2)`` (m) within ``band`` ``(n,)`` (m, an octagon's inradius) of ``h`` ``(n, 2)`` whose
    horizontal accelerations pay least over ``levels`` (m/s², module docstring) under the least peak, with
    the body standing over its feet; ``before``/``after`` ``(2, 2)``: the two fixed frames either side. None
    when the programme finds none.

    Programme 2's variables are ``[d+ (2 n), d- (2 n), s (K' (n + 2)), o (F)]``: the path is ``h + d+ - d-``
    (each part within ``band``, priced :data:`NEAR` per m: their sum is the distance from ``h``); ``levels[0] +
    sum_k s_k[t]`` bounds frame ``t``'s acceleration along each direction, ``s_k`` at most the step to the next
    level (the last: to the cap) and priced ``k`` per m/s², so a jolt pays each level it exceeds (the price of
    the module docstring; the ``K'`` levels under the cap: those at or over it are never exceeded); ``o`` how far
    the centre of mass is outside the support on each of the ``F`` frames where a move can take it out
    (``support``: no edge's distance may grow beyond ``max(gap, room)``; each metre outside costs
    :data:`OUTSIDE`). When the given path already accelerates under ``levels[0]`` and stands inside its feet it
    costs nothing, every other path costs its distance: it is returned as it is, without a programme."""
    n = len(h)
    m = n + 2  # accelerations at frames -1 .. n
    sup = support if support is not None else Support(sparse.coo_matrix((0, 2 * n)), np.zeros(0), np.zeros(0, int))
    U, a0 = _acceleration(h, before, after, fps)
    given_peak = float(np.abs(a0).max())
    if given_peak <= levels[0] and not (sup.gap > 0.0).any():
        return h.copy()
    reach = _reach(band, sup)
    limits = _limits(band, sup, reach, room)
    # the given path is within every limit: its peak bounds the least, and under the floor the cap is the floor
    least = 0.0 if given_peak * (1.0 + SLACK) + 1e-6 <= levels[0] else _least_peak(U, a0, limits, band)
    if least is None:
        return None
    peak = max(least * (1.0 + SLACK) + 1e-6, levels[0])
    levels = levels[:1 + int(np.sum(levels[1:] < peak))]  # a level at or over the cap is never exceeded: no price
    K = len(levels)
    out = sup.gap + reach > 0.0  # the edges a move may take the centre of mass outside of
    frames, at = np.unique(sup.frame[out], return_inverse=True)
    F = len(frames)
    width = 4 * n + K * m + F
    rows, lims, q, t = limits[0], len(limits[1]), 4 * m, np.arange(4 * m)
    s = 4 * n  # the first column of s
    seg_r, seg_c = np.tile(t, K), s + (np.arange(K)[:, None] * m + t % m).ravel()
    edges, e = _edges(sup, out), 8 * m + lims  # the first row of gap + move <= o
    A = _matrix([_at(U, 0, 0), _at(U, 0, 2 * n, -1.0), _ones(seg_r, seg_c, -1.0),  # u·a <= levels[0] + sum s
                 _at(U, q, 0, -1.0), _at(U, q, 2 * n), _ones(q + seg_r, seg_c, -1.0),  # -u·a <= the same
                 _at(rows, 8 * m, 0), _at(rows, 8 * m, 2 * n, -1.0),  # octagon, balance
                 _at(edges, e, 0), _at(edges, e, 2 * n, -1.0), _ones(e + np.arange(len(at)), s + K * m + at, -1.0)],
                (e + len(at), width))
    lower = np.concatenate([np.full(8 * m, -np.inf), limits[1], np.full(len(at), -np.inf)])
    upper = np.concatenate([levels[0] - a0, levels[0] + a0, limits[2], -sup.gap[out]])
    cost = np.concatenate([np.full(4 * n, NEAR), np.repeat(np.arange(1.0, K + 1.0), m), np.full(F, OUTSIDE)])
    wide = np.concatenate([band, band])
    col_upper = np.concatenate([wide, wide, np.repeat(np.diff(np.r_[levels, peak]), m), np.full(F, np.inf)])
    stage = np.concatenate([np.tile(np.arange(n), 4), np.tile(np.arange(-1, n + 1), K), frames])  # each column's frame
    x = _minimum(cost, A, lower, upper, np.zeros(width), col_upper, stage)
    if x is None:
        return None
    d = np.clip(x[:2 * n] - x[2 * n:4 * n], -wide, wide)  # within the band exactly: a still frame's 0 stays 0
    return h + np.stack([d[:n], d[n:]], axis=1)


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
    path = _kept_path(xz[lo:hi], xz[lo - 2:lo], xz[hi:hi + 2], motion.fps, band, support, np.asarray(LEVELS) / k,
                      BALANCE_ROOM / k)
    if path is None:
        return motion, 0.0
    size = float(np.linalg.norm(path - xz[lo:hi], axis=1).max())
    if size < MIN_MOVE / k:
        return motion, 0.0
    root = motion.root_positions.copy()
    root[lo:hi, 0] = path[:, 0]
    root[lo:hi, 2] = path[:, 1]
    return feet_kept(motion, motion.replace(root_positions=root), lo, hi), size


def _kept_path(h: np.ndarray, before: np.ndarray, after: np.ndarray, fps: float, band: np.ndarray,
               support: Support | None, levels: np.ndarray, room: float) -> np.ndarray | None:
    """:func:`least_acceleration_path` of these arguments, kept (:data:`KEPT_PATHS`) by their values, the module's
    prices and the solver that answers (PIQP's build, or the fallback): the same path, bit for bit, the programmes
    solved once."""
    sup = () if support is None else (support.rows.row, support.rows.col, support.rows.data, support.rows.shape,
                                      support.gap, support.frame)
    solver = _piqp()
    key = digest(h, before, after, fps, band, *sup, levels, room, SLACK, OUTSIDE, NEAR, _DIRS,
                 None if solver is None else solver.__name__)
    path = KEPT_PATHS.get(key, lambda: least_acceleration_path(h, before, after, fps, band, support, levels, room))
    return None if path is None else path.copy()
