"""One join carried out on a track being laid (:func:`join_next`: plan, render, report), and a whole
track laid so (:func:`lay_track`)."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from text2anim.core.metrics import root_pop, skating_ratio

from ..blend_search import Weights
from ..laid import Laid, LaidJoin
from ..placed import Placed
from ..plan import Element, Track
from ..result import BlendInterval, JoinReport
from ..track import Incoming, TrackState, extend, lay_elements
from .plan import MIN_BLEND, plan_join, public_info
from .records import Plan, Skip
from .repair import carry_out


def report_of(prev: Placed, inc: Incoming, plan: Plan, fps: float, locks) -> JoinReport:
    """The join's :class:`~synthesis.plan.JoinReport` (docs/timetable.md §2)."""
    e = inc.element
    method = "connection" if inc.rep > 0 else e.method
    order = {"S0": 0, "S1": 1, "S3": 2}
    intervals = tuple(BlendInterval(iv.part, iv.kind, iv.t0 / fps, iv.t1 / fps)
                      for iv in sorted(plan.intervals.values(), key=lambda iv: order[iv.name]))
    info = public_info(plan.info)
    if inc.rep > 0:
        info["repetition"] = inc.rep
    if locks:
        info["foot_locks"] = [{"side": lk.side, "begin": lk.begin / fps, "end": lk.end / fps,
                               "release_end": lk.release_end / fps} for lk in locks]
    return JoinReport(prev.element.id, e.id, method, plan.choice.method, intervals, plan.cost(), info,
                      tuple(plan.warnings))


def join_next(state: TrackState, inc: Incoming, fps: float, weights: Weights, lock: bool = True,
              min_blend: float = MIN_BLEND, allow_shift: bool = True) -> Plan | Skip:
    """Join ``inc`` to the track's last element (plan, render, report); a :class:`Skip` leaves the track as it was."""
    prev = state.placed[-1]
    tr = extend(state.laid(), inc.offset + inc.motion.n_frames, state.floor)
    plan = plan_join(tr, prev, inc, fps, weights, state.floor, min_blend, allow_shift)
    carry = _carried_delay(state, prev, fps)
    if isinstance(plan, Skip) and carry:
        # the previous element was delayed for room and its core now covers this one's start: the element
        # scheduled after it follows it rather than being dropped (only then; others keep their times)
        inc = inc.moved(carry)
        tr = extend(state.laid(), inc.offset + inc.motion.n_frames, state.floor)
        plan = plan_join(tr, prev, inc, fps, weights, state.floor, min_blend, allow_shift)
    else:
        carry = 0
    e = inc.element
    if isinstance(plan, Skip):
        state.skipped[e.id] = plan.reason
        state.warnings.append(plan.reason)
        rep = JoinReport(prev.element.id, e.id, "connection" if inc.rep > 0 else e.method, "not_executed", (),
                         None, {}, (plan.reason,))
        state.joins.append(LaidJoin(rep, first=prev))
        return plan
    inc = plan.inc
    # the sources' figures at the track's rate (quality(m, None)'s skating ratio and root pop, without the rest)
    own = max(skating_ratio(prev.motion), skating_ratio(inc.motion))
    own_pop = max(root_pop(prev.motion), root_pop(inc.motion))
    plan, out, locks, window = carry_out(tr, plan, lock, own, own_pop)
    region_end = max([window[1]] + [lk.release_end for lk in locks])
    state.motion = out
    state.floor = window[1]
    if plan.shift or carry:  # this element only: later ones keep their scheduled times unless dropped otherwise
        state.delays.append((e.id, (plan.shift + carry) / fps))
    core = inc.core
    if inc.cyclic:  # a looped clip is all core: the join is taken out of it
        core = (max(core[0], region_end - inc.offset), core[1])
    if prev.cyclic:
        prev.core = (prev.core[0], min(prev.core[1], window[0] - prev.offset))
    shown = replace(e, start=inc.first / fps, end=inc.end / fps) if (plan.shift or plan.phase or carry) else e
    p = Placed(shown, plan.placed, inc.offset, core, inc.contacts, inc.cyclic, plan.rigid, inc.rep, inc.lead,
               inc.stop)
    state.placed.append(p)
    state.warnings.extend(plan.warnings)
    rep = report_of(prev, inc, plan, fps, locks)
    ivs = plan.intervals
    main = (min(ivs[n].t0 for n in ("S0", "S1")), max(ivs[n].t1 for n in ("S0", "S1")) + 1)
    # S0/S1 blend the two motions: their jerk and skating are the join's; the return to the next motion's own
    # lower body (S3) plays that motion's own step, its figures are in the region's
    state.joins.append(LaidJoin(rep, main, (window[0], region_end), prev, p))
    return plan


def _carried_delay(state: TrackState, prev: Placed, fps: float) -> int:
    """Frames the previous element was delayed by its own join (0 if it kept its scheduled time)."""
    return sum(int(round(d * fps)) for i, d in state.delays if i == prev.element.id)


def lay_track(track: Track, whole: Sequence[Element], fps: float, weights: Weights, lock: bool = True,
              min_blend: float = MIN_BLEND) -> Laid:
    """The whole-body elements of one track joined by optimal blending (see the module docstring)."""
    return lay_elements(track, whole, fps, lambda state, inc: join_next(state, inc, fps, weights, lock, min_blend))
