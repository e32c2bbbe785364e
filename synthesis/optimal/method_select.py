"""Which of the four synthesis methods of paper 000 joins two motions (§4.1, §4.2.5).

From the foot–ground constraints of the two clips around their cores, on the
track (frames), the first applicable of, in the paper's priority order:

1. ``motion_transition`` (動作遷移): both clips move **the same foot at the
   same time** — a foot-moving interval ``P0`` of the first motion after its
   core and one ``P1`` of the second, of the same foot, overlapping by at
   least :data:`SAME_TIME` of the longer, ``P1`` beginning before the second
   core (a step that *is* the core, like the kick itself, cannot be blended);
2. ``motion_connection`` (動作接続): the first motion moves a foot after its
   core (``P0``), lifting before the second motion's core begins (whether that
   leaves enough room for the blend is the caller's to settle: the engine may
   delay the second motion a little);
3. ``motion_adaptation_step`` (動作適応, 足の移動を含む): the first motion keeps
   its feet where they are; the second moves a foot (``P1``) late enough to
   leave room for the first blend — over that step the adapted lower body
   returns to the second motion's own;
4. ``motion_adaptation`` (足の移動を含まない): neither; the second motion's
   lower body stays adapted to the first motion's feet to its end.

Several foot-moving intervals: the one **nearest the core** (§4.2.5) — for the
first motion the earliest after its core, for the second the one closest to
its core interval (ties: the earlier).

Every foot-moving interval used is *complete* (the foot lifts after the clip's
first frame and lands before its last), so both key frames are real.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np

from ..join.gait import Step

#: The methods of §4.1 (a join report's ``blend``).
Blend = Literal["motion_transition", "motion_connection", "motion_adaptation_step", "motion_adaptation"]
BLENDS: tuple[Blend, ...] = get_args(Blend)

#: Overlap (fraction of the longer interval) for two steps to be "at the same time" (a 3-frame shuffle
#: inside a 16-frame step is not the same step).
SAME_TIME = 0.5


@dataclass(frozen=True)
class Choice:
    """The method chosen, the foot-moving intervals it uses, and the support foot (the foot that
    stays down through the step: the next motion is placed through it), ``None`` when free."""

    method: str
    p0: Step | None = None
    p1: Step | None = None
    support: str | None = None


def _other(side: str) -> str:
    return "left" if side == "right" else "right"


def _distance_to(step: Step, lo: int, hi: int) -> int:
    """Frames between a step and the interval ``[lo, hi)`` (0 when they overlap)."""
    return max(0, lo - step.end, step.begin - hi)


def select(a_steps: list[Step], b_steps: list[Step], c0_end: int, c1: tuple[int, int], *,
           floor: int = 0, b_first: int = 0, min_frames: int = 3) -> Choice:
    """§4.2.5: the method for two motions, from their steps on the track.

    Args:
        a_steps: the first motion's :func:`steps` on the track.
        b_steps: the second's.
        c0_end: first track frame after the first core.
        c1: ``[begin, end)`` of the second core on the track.
        floor: no blend may begin before this frame (a previous join, or eq. (17)'s current time).
        b_first: the track frame the second motion starts.
        min_frames: the shortest blend, frames.
    """
    c1_begin, c1_end = c1
    lo = max(c0_end, floor)
    p0s = [s for s in a_steps if s.begin >= lo and s.begin < c1_begin]  # room is the caller's (it may delay)
    p0 = min(p0s, key=lambda s: (s.begin, s.side)) if p0s else None
    if p0 is not None:
        same = [s for s in b_steps if s.side == p0.side and s.begin < c1_begin
                and p0.overlap(s) >= SAME_TIME * max(p0.frames, s.frames)]
        if same:
            p1 = max(same, key=lambda s: (s.end, p0.overlap(s)))
            return Choice("motion_transition", p0, p1, _other(p0.side))
        return Choice("motion_connection", p0, None, _other(p0.side))
    first = max(lo, b_first) + min_frames
    p1s = [s for s in b_steps if s.begin >= first and s.end - min_frames > max(first, s.begin)]
    if p1s:
        p1 = min(p1s, key=lambda s: (_distance_to(s, c1_begin, c1_end), s.begin))
        return Choice("motion_adaptation_step", None, p1, _other(p1.side))
    return Choice("motion_adaptation")


def cyclic_core_end(a_steps: list[Step], start: int, end: int, core: tuple[int, int]) -> int:
    """A looped clip is all core except its last step: the core ends where the last step beginning
    before the scheduled ``end`` (and after ``start``) lifts; that step is the one a join uses
    (the scheduler overlaps the next motion over it). No step: the core as it was."""
    last = [s.begin for s in a_steps if start < s.begin < end]
    return int(max(last)) if last and max(last) > core[0] else core[1]


def cyclic_core_begin(b_steps: list[Step], start: int, core: tuple[int, int]) -> int:
    """A looped clip joined into is all core except its first step: the core begins where the first
    step lifting at or after its scheduled ``start`` lands. No step: the core as it was."""
    first = [s.end for s in b_steps if s.begin >= start]
    return int(min(first)) if first and min(first) < core[1] else core[0]


def phase_for(p0: Step, b_steps_own: list[Step], offset: int, start: int) -> int | None:
    """For a looped second clip (with a margin cycle before its start): the clip offset that puts one of
    its steps of ``p0``'s foot at the same time as ``p0`` (a transition), nearest the scheduled
    ``offset`` and never later than ``start`` (so the clip still covers its start). ``None``: none."""
    best = None
    for s in b_steps_own:
        if s.side != p0.side:
            continue
        off = p0.begin - s.begin
        if off > start:
            continue
        if best is None or abs(off - offset) < abs(best - offset):
            best = off
    return best


def support_by_gap(a_feet: dict[str, np.ndarray], b_feet: dict[str, np.ndarray]) -> str:
    """For an adaptation without a step: the support foot is the one that, put on the first motion's
    same foot (headings matched by the caller), leaves the other foot the shorter way to go.

    ``a_feet``/``b_feet``: per side the foot's ground position (x, z) in each motion's heading frame.
    """
    gaps = {}
    for sup in ("left", "right"):
        oth = _other(sup)
        va = a_feet[oth] - a_feet[sup]
        vb = b_feet[oth] - b_feet[sup]
        gaps[sup] = float(np.linalg.norm(va - vb))
    return min(gaps, key=lambda s: (gaps[s], s))
