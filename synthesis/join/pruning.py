"""Which candidates of the join post-pass's search (:func:`synthesis.join.joinpass.finish_region`) need their feet
re-planted, decided exactly: the search's choice is the one re-planting every candidate makes.

A candidate (:class:`synthesis.join.smoothing.Smoothed`) has a score, ``max(jerk p99 / limit, root pop / limit)``
against the whole source clips' figures, and a nearness, the same against the figures of the parts the join
replaces. Its root pop is exact before its feet are re-planted and its jerk p99 has a floor
(:func:`synthesis.join.smoothing.jerk_floor`), so both have lower bounds: :func:`may_keep` skips a candidate that
cannot be within the limits and then kept (:func:`replaces`, the rule), and :func:`least`, the fallback when
no candidate is within, finds the least score from the bounds.
"""
from __future__ import annotations

import heapq

from .smoothing import Smoothed, plant_all

#: a candidate tried: (score or nearness, width, stretch, candidate, jerk p99, root pop, region end)
Tried = tuple[float, float, float, Smoothed, float, float, int]


def score_floor(cand: Smoothed, lims: tuple[float, float, float, float], near: bool = False) -> float:
    """A lower bound of ``cand``'s score (of its nearness with ``near``) from its exact pop and the floor of
    its jerk p99 (:class:`synthesis.join.smoothing.Smoothed`): the score is ``max(jerk / lim, pop / lim)``. The pop
    alone is a bound already (known before the rotations are low-passed): use :func:`pop_bound` first."""
    k = 2 if near else 0
    return max(cand.jk_floor / lims[k], cand.pop / lims[k + 1])


def pop_bound(cand: Smoothed, lims: tuple[float, float, float, float], near: bool = False) -> float:
    """The pop's part of ``cand``'s score (nearness with ``near``): a bound from the hips' path alone."""
    return cand.pop / lims[3 if near else 1]


def replaces(near: float, jk: float, pop: float, kept: Tried | None) -> bool:
    """The rule: a candidate within the whole clips' figures, of nearness ``near`` (to the figures of the parts
    the join replaces; ``jk``, ``pop`` its figures) is kept instead of ``kept`` (the first within is kept) when
    it is nearer: the larger of its two ratios smaller. It must stay monotone (lower figures never make a
    candidate less eligible): :func:`may_keep` applies it to lower bounds."""
    return kept is None or near < kept[0] - 1e-9


def may_keep(cand: Smoothed, lims: tuple[float, float, float, float], kept: Tried | None) -> bool:
    """Whether ``cand`` may be within the limits and then be kept (:func:`synthesis.join.joinpass.finish_region`), from its bounds:
    a candidate that cannot is not re-planted (exact: the choice is the one re-planting every candidate
    makes; one that can only be the fallback, the least score, waits for :func:`least`). The cheap bound
    (the pop alone, :func:`may_keep_by_pop`) is asked first."""
    if not may_keep_by_pop(cand, lims, kept):
        return False
    return score_floor(cand, lims) <= 1.0 and replaces(score_floor(cand, lims, near=True), cand.jk_floor, cand.pop, kept)


def may_keep_by_pop(cand: Smoothed, lims: tuple[float, float, float, float], kept: Tried | None) -> bool:
    """:func:`may_keep` from the pop's bound alone (the hips' path: no rotations low-passed yet)."""
    return pop_bound(cand, lims) <= 1.0 and replaces(pop_bound(cand, lims, near=True), 0.0, cand.pop, kept)


def least(tried: list[tuple[float, float, Smoothed, int]], lims: tuple[float, float, float, float]) -> Tried:
    """The fallback when no candidate is within the limits: the first of least score of every ``(width,
    stretch, candidate, region end)`` tried, as a scan in order takes it (a later one replaces the least so
    far when lower by more than 1e-9), re-planting as few candidates as that needs, exactly:

    1. the least score ``m``: candidates in order of their bounds, re-planted while a bound is below the
       least found (those of one stretch together);
    2. a threshold ``t >= m + g`` with no known score in ``(t - g, t]`` and every candidate not yet re-planted
       bounded above ``t`` (re-planting those at or below it); ``g`` = 2e-9 and what rounding at ``t``'s size
       may take from it;
    3. the scan, the candidates not re-planted taken as scoring more than ``t``: a candidate at or below
       ``t - g`` replaces any of them and none of them replaces it, so the scan's choice (at or below
       ``m + 1e-9``) is the one every exact score gives.
    """
    cands = [c for _s, _t, c, _h in tried]

    def score(c: Smoothed) -> float:
        jk, pop = c.plant()
        return max(jk / lims[0], pop / lims[1])

    # the candidates not yet re-planted by their cheapest bound so far: the pop's part, then the floor
    heap = [(pop_bound(c, lims), i) for i, c in enumerate(cands) if c.jk is None]
    heapq.heapify(heap)
    least = min((score(c) for c in cands if c.jk is not None), default=float("inf"))

    def settle(limit: float, strict: bool) -> None:
        """Bound, and re-plant, every candidate whose bounds are below ``limit`` (at or below unless
        ``strict``; ``least`` follows what is re-planted); re-planted alongside: the others of its stretch
        bounded below ``limit`` so far."""
        nonlocal least
        while heap and (heap[0][0] < min(limit, least) if strict else heap[0][0] <= limit):
            bound, i = heapq.heappop(heap)
            c = cands[i]
            if c.jk is not None:
                continue
            floor = score_floor(c, lims)
            if c.jk is None and bound == pop_bound(c, lims) and bound < floor:  # the floor is higher: wait for it
                heapq.heappush(heap, (floor, i))
                continue
            cap = min(limit, least) if strict else limit
            plant_all([c] + [d for d in cands if d.stretch is c.stretch and d.jk is None and d.measured
                             and score_floor(d, lims) <= cap])
            least = min(least, min(score(d) for d in cands if d.stretch is c.stretch and d.jk is not None))

    def gap(t: float) -> float:  # 2e-9 and what rounding at the scores' size may take from it
        return 2e-9 + 1e-12 * abs(t)

    settle(float("inf"), strict=True)  # 1.
    top = least + gap(least)
    while True:  # 2.
        settle(top, strict=False)
        band = [score(c) for c in cands if c.jk is not None and top - gap(top) < score(c) <= top]
        if not band:
            break
        top = max(band) + gap(max(band))
    best: Tried | None = None  # 3.
    for sigma, stretch, cand, h2 in tried:
        s = score(cand) if cand.jk is not None else float("inf")
        if best is None or s < best[0] - 1e-9:
            best = (s, sigma, stretch, cand, cand.jk or 0.0, cand.pop, h2)
    assert best is not None and best[3].jk is not None  # the least is re-planted
    return best
