"""One join planned (no frames written): method, ranges, search, placement, adaptation and weights
(:func:`plan_join`, steps 1–5 of :mod:`synthesis.optimal`), with the room and core rules."""
from __future__ import annotations

import numpy as np

from text2anim.core.contacts import detect_contacts
from text2anim.core.motion import Motion

from ..join.align import align_through_foot, moved_by
from ..join.gait import foot_points_at, steps
from ..join.placed import Placed
from .adaptation import adapt
from .blend_ranges import Bounds, after, ranges
from .blend_search import Weights, best
from .curves import interval_weights
from .geometry import geometry
from .method_select import phase_for
from .placement import alignment
from .records import Interval, Plan, Skip
from .search import Features, grid, runners_up, search

MIN_BLEND = 0.2  # s: the shortest blend interval (shorter pose changes read as pops)
MIN_ROOM = 0.25  # s: the least room the lower-body range should leave
MAX_SHIFT = 0.5  # s: the most an element is delayed for room
CORE_TOLERANCE = 0.1  # s: cores overlapping by less than this are taken as touching (a frame of contact noise)
SAME_FEET_CM = 1.0
RUNNERS_UP = 5  # next-best lower-body intervals tried when the best one's join would skate  # cm: an adaptation moving no foot further needs no return step (S3)


def plan_join(tr: Motion, prev: Placed, inc: Placed, fps: float, weights: Weights, floor: int = 0,
              min_blend: float = MIN_BLEND, allow_shift: bool = True) -> Plan | Skip:
    """Method, ranges, search, placement and weights of one join (no frames written).

    Args:
        tr: the track so far, holding ``prev`` (extended, held, at least to the next element's last frame).
        prev: the previous element as laid.
        inc: the next element.
        weights: eq. (10)'s weights (:func:`synthesis.optimal.blend_search.preset`).
        floor: no blend starts before this track frame (the previous join's end; eq. (17)'s current time).
        allow_shift: delay the next element for room (see the module docstring).
    """
    L = max(2, int(round(min_blend * fps)))
    tr_contacts = detect_contacts(tr)
    warnings: list[str] = []
    choice, bounds, a_steps = geometry(tr_contacts, prev, inc, floor, L)
    phase = 0
    if inc.cyclic and choice.p0 is not None:  # a loop may enter at the phase whose step lifts with P0's
        off = phase_for(choice.p0, steps(inc.contacts), inc.offset, inc.first)
        if off is not None and inc.end - off <= inc.motion.n_frames and off != inc.offset:
            moved = inc.at_phase(off)
            c2, b2, _ = geometry(tr_contacts, prev, moved, floor, L)
            if c2.method == "motion_transition":
                phase, inc, choice, bounds = off - inc.offset, moved, c2, b2
    shift = 0
    late = bounds.c0_end - int(round(CORE_TOLERANCE * fps)) - bounds.c1[0]
    if 0 < late <= int(round(MAX_SHIFT * fps)) and prev.cyclic and allow_shift:
        # a loop whose core the join before used up (a short walk between two motions) walks on a little
        shift, inc = late, inc.moved(late)
        choice, bounds, _ = geometry(tr_contacts, prev, inc, floor, L)
    if bounds.c1[0] < bounds.c0_end - int(round(CORE_TOLERANCE * fps)):
        return Skip(f"element {inc.element.id} ({inc.element.clip.name}) is not executed: its core "
                    f"({bounds.c1[0] / fps:.2f} s) would begin before the core of element {prev.element.id} "
                    f"ends ({bounds.c0_end / fps:.2f} s); schedule it later to perform it (paper 000 §4.2.5)")
    rs = ranges(choice, bounds)
    if allow_shift:
        s0 = rs[0]
        need = max(L, int(round(MIN_ROOM * fps)), (s0.p_len or 0) if choice.method == "motion_connection" else 0)
        have = s0.t1[1] - s0.t0[0]
        more = min(need - have, int(round(MAX_SHIFT * fps)) - shift)
        if more > 0:
            shift += more
            inc = inc.moved(more)
            choice, bounds, _ = geometry(tr_contacts, prev, inc, floor, L)
            rs = ranges(choice, bounds)
    for k, r in enumerate(rs):
        if not r.feasible(L):
            rs[k] = r.relax(L)
    byname = {r.name: r for r in rs}
    feats = Features(tr, inc)
    grid0 = grid(byname["S0"], feats, fps, weights, L)  # evaluated once: its minimum, and its runners-up below
    found = {"S0": best(grid0, weights, L), "S1": search(byname["S1"], feats, fps, weights, L)}
    support, ta, tb = alignment(choice, found["S0"], tr, tr_contacts, inc)
    ta = int(np.clip(ta, 0, tr.n_frames - 1))
    tb_own = int(np.clip(tb - inc.offset, 0, inc.motion.n_frames - 1))
    rigid = align_through_foot(tr, ta, inc.motion, tb_own, support)
    placed = moved_by(inc.motion, rigid)
    adapted = None
    info: dict = {}
    if choice.method.startswith("motion_adaptation"):
        fa, fb = foot_points_at(tr, ta), foot_points_at(placed, tb_own)
        offsets = {s: fa[s] - fb[s] for s in ("left", "right")}
        if support is not None:
            offsets[support] = np.zeros(3)
        adapted = adapt(placed, offsets)
        info["adapt_offsets"] = offsets
        info["adapt_offset_cm"] = {s: round(100 * float(np.hypot(v[0], v[2])), 2) for s, v in offsets.items()}
        feats = Features(tr, inc, adapted)
        found["S0"] = search(byname["S0"], feats, fps, weights, L)  # S0 again, onto the adapted lower body
        if "S3" in byname and max(info["adapt_offset_cm"].values()) < SAME_FEET_CM:
            del byname["S3"]  # the feet already agree: nothing to return from (S2 runs to the end, eq. (9))
            info["return"] = "not needed: the feet already stand as the next motion has them"
        if "S3" in byname:
            byname["S3"] = after(byname["S3"], found["S0"].t1, L)
            if not byname["S3"].feasible(L):
                byname["S3"] = byname["S3"].relax(L)
            found["S3"] = search(byname["S3"], feats, fps, weights, L)
    intervals = {n: interval_weights(n, byname[n], f, feats, fps, L) for n, f in found.items()}
    into = {n: into_cores(iv, bounds) / fps for n, iv in intervals.items() if n != "S3" and iv.range.relaxed}
    if into:
        info["into_core_s"] = {intervals[n].part: round(s, 3) for n, s in into.items()}
    if max(into.values(), default=0.0) > CORE_TOLERANCE:
        parts = " and ".join(sorted({intervals[n].part for n, s in into.items() if s > CORE_TOLERANCE}))
        warnings.append(f"element {inc.element.id} ({inc.element.clip.name}) follows element {prev.element.id} "
                        f"too closely for the {parts} body to change between them: it shows the end of one and "
                        f"the start of the other at once, softer than recorded; give the second more time "
                        f"after the first to keep both whole")
    alternatives = []
    if adapted is None:  # the next-best lower-body intervals, tried in turn if the best one's join skates
        alternatives = [interval_weights("S0", byname["S0"], f, feats, fps, L)
                        for f in runners_up(grid0, weights, RUNNERS_UP)]
    info.update({
        "support": support, "align_frames_s": [ta / fps, tb / fps],
        "p0_s": None if choice.p0 is None else [choice.p0.begin / fps, choice.p0.end / fps, choice.p0.side],
        "p1_s": None if choice.p1 is None else [choice.p1.begin / fps, choice.p1.end / fps, choice.p1.side],
        "cores_s": [bounds.c0_end / fps, bounds.c1[0] / fps],
        "weight_cases": {n: iv.case for n, iv in intervals.items()},
        "slopes": {n: [round(iv.slopes[0], 3), round(iv.slopes[1], 3)] for n, iv in intervals.items()},
        "ranges_s": {n: {"eq": r.eq, "t0": [r.t0[0] / fps, r.t0[1] / fps], "t1": [r.t1[0] / fps, r.t1[1] / fps]}
                     for n, r in byname.items()},
        "shift_s": shift / fps, "phase_s": phase / fps,
        "weights": {"time": weights.time, "pose": weights.pose, "velocity": weights.velocity},
    })
    if adapted is not None:
        s2_end = intervals["S3"].t0 if "S3" in intervals else inc.end
        info["adapted_s"] = [intervals["S0"].t1 / fps, s2_end / fps]  # eq. (7) / (9): S2
    return Plan(inc, choice, intervals, rigid, support, placed, adapted, shift, phase, warnings, info, alternatives)


def into_cores(iv: Interval, bounds: Bounds) -> int:
    """Frames of blend interval ``iv`` inside the two cores of ``bounds`` (0 when it keeps out of them)."""
    return max(0, bounds.c0_end - iv.t0) + max(0, iv.t1 - bounds.c1[0])


def public_info(info: dict) -> dict:
    """The plan's notes as they go into the report (plain JSON values)."""
    return {k: v for k, v in info.items() if k != "adapt_offsets"}
