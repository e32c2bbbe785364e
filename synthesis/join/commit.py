"""A decided, written join committed to the track being laid: the one step every engine and baseline ends with.

The engines decide a join each their own way (paper 003's Connection / Transition, optimal blending's
intervals, the baselines' fixed crossfades) and write its frames; :func:`commit` then records it the same
way for all: the new track, the element as placed, the cores of looped clips (all core but the frames a join
uses), the earliest frame the next blend may start, any delay, and the join to be measured. Frames are the
track's; seconds only in the report.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from text2anim.core.motion import Motion

from ..result import JoinReport
from .footlock import Lock
from .laid import Frames, LaidJoin
from .laying import TrackState
from .placed import Placed


def commit(state: TrackState, placed: Placed, out: Motion | Sequence[Motion], report: JoinReport, window: Frames,
           region: Frames, rewrites_from: int, floor: int, delay: float = 0.0) -> Placed:
    """Commit the join of ``state``'s last element and ``placed`` (the next one, as placed) to ``state``.

    Args:
        placed: the next element as the join placed it (moved, and its offset, phase and stop as joined).
        out: the track with the join written (it ends with ``placed``'s last frame), or its pieces end to
            end (:meth:`TrackState.lay`).
        report: the join's report (metrics are added when the track is measured).
        window: the frames measured as the join's blend; ``region``: the blend and the feet released after it.
        rewrites_from: the first track frame the join rewrites (a looped first clip's core ends there).
        floor: the earliest frame the next join may blend from.
        delay: seconds the join moved ``placed`` later than scheduled (0: kept its time).

    Returns ``placed`` as committed (a looped clip's core without the frames the join uses).
    """
    k = len(state.placed) - 1
    prev = state.placed[k]
    if placed.cyclic:  # a looped clip is all core: the join (blend, feet released) is taken out of it
        placed = replace(placed, core=(max(placed.core[0], region[1] - placed.offset), placed.core[1]))
    if prev.cyclic:  # and the loop it leaves ends its core where the join starts rewriting it
        state.placed[k] = replace(prev, core=(prev.core[0], min(prev.core[1], rewrites_from - prev.offset)))
    state.lay([out] if isinstance(out, Motion) else out)
    state.floor = floor
    if delay:
        state.delays.append((placed.element.id, delay))
    state.placed.append(placed)
    state.joins.append(LaidJoin(report, window, region, k, k + 1))
    return placed


def skip(state: TrackState, inc: Placed, reason: str) -> None:
    """The next element not executed (a warning says why); the track stays as it was."""
    state.skipped[inc.element.id] = reason
    state.warnings.append(reason)
    prev = state.placed[-1]
    rep = JoinReport(prev.element.id, inc.element.id, inc.joined_by, "not_executed", (), None, {}, (reason,))
    state.joins.append(LaidJoin(rep, first=len(state.placed) - 1))


def lock_report(locks: list[Lock], fps: float) -> list[dict]:
    """The foot locks of a join as its report lists them (``foot_locks``: side, begin, end, release end, s)."""
    return [{"side": lk.side, "begin": lk.begin / fps, "end": lk.end / fps, "release_end": lk.release_end / fps}
            for lk in locks]
