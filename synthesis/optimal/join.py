"""One join carried out on a track being laid (:func:`join_next`: plan, render, report), and a whole
track laid so (:func:`lay_track`)."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from text2anim.core.kept import Kept, value_digest
from text2anim.core.metrics import root_pop, skating_ratio
from text2anim.core.motion import Motion

from ..join.commit import commit, lock_report, skip
from ..join.laid import Laid
from ..join.laying import TrackState, extended, laid_feet, lay_elements
from ..join.placed import Placed
from ..result import BlendInterval, JoinReport
from ..tracks import Element, Track
from .blend_search import Weights
from .planner import MIN_BLEND, plan_join, public_info
from .records import Plan, Skip
from .repair import carry_out


def report_of(prev: Placed, inc: Placed, plan: Plan, fps: float, locks) -> JoinReport:
    """The join's :class:`~synthesis.result.JoinReport` (docs/timetable.md §2)."""
    e = inc.element
    order = {"S0": 0, "S1": 1, "S3": 2}
    intervals = tuple(BlendInterval(iv.part, iv.kind, iv.t0 / fps, iv.t1 / fps)
                      for iv in sorted(plan.intervals.values(), key=lambda iv: order[iv.name]))
    info = public_info(plan.info)
    if inc.repetition > 0:
        info["repetition"] = inc.repetition
    if locks:
        info["foot_locks"] = lock_report(locks, fps)
    return JoinReport(prev.element.id, e.id, inc.joined_by, plan.choice.method, intervals, plan.cost(), info,
                      tuple(plan.warnings))


#: the last joins planned and rendered (:func:`join_next`), by the state's chain and the options: a warm process
#: lays the same joins again (the studio re-animates the whole text at every pause in typing, and a sentence typed
#: at the end leaves every join before it as it was). Each keeps its plan and rendering, copied out of the track
#: they were cut from; bounded by :data:`KEPT_BYTES`
KEPT_BYTES = 64 * 2 ** 20


def _weight(made: tuple) -> int:
    """Bytes of a kept join's frames (:func:`_kept`): its rendering's, and its plan's placed and adapted motions'
    (the clip itself is the database's and the preparations', :data:`synthesis.join.timing.PREPARED`)."""
    plan, rendered = made[0], made[3]
    motions = [rendered] + ([plan.placed, plan.adapted] if isinstance(plan, Plan) else [])
    return sum(m.rotations.nbytes + m.root_positions.nbytes for m in motions if m is not None)


KEPT_JOINS: Kept[tuple] = Kept(1024, KEPT_BYTES, _weight)


def join_next(state: TrackState, inc: Placed, fps: float, weights: Weights, lock: bool = True,
              min_blend: float = MIN_BLEND, allow_shift: bool = True) -> Plan | Skip:
    """Join ``inc`` to the track's last element (plan, render, report); a :class:`Skip` leaves the track as it was.
    A join made before from the same state and options (``state.chain``, :data:`KEPT_JOINS`) is that one's plan and
    rendering again, bit for bit."""
    key = value_digest("optimal", state.chain, fps, weights, lock, min_blend, allow_shift) if state.chain else None
    labels = (state.placed[-1].element.id, inc.element.id)
    made = None if key is None else _relabelled(KEPT_JOINS.known(key), labels, inc)
    tr = None
    if made is None:
        made, tr = _made(state, inc, fps, weights, lock, min_blend, allow_shift)
        if key is not None:
            KEPT_JOINS.put(key, (*_kept(made), labels))
    plan, inc, carry, rendered, c0, locks, window = made
    if isinstance(plan, Skip):
        skip(state, inc, plan.reason)
        return plan
    prev = state.placed[-1]
    if tr is None:
        tr = extended(state, inc.offset + inc.motion.n_frames)
    e = inc.element
    out = (tr[:c0], rendered)  # the track, laid as these two pieces (TrackState.lay)
    region_end = max([window[1]] + [lk.release_end for lk in locks])
    shown = replace(e, start=inc.first / fps, end=inc.end / fps) if (plan.shift or plan.phase or carry) else e
    state.warnings.extend(w for w in plan.warnings if w not in state.warnings)  # a repeated motion's joins say it once
    rep = report_of(prev, inc, plan, fps, locks)
    ivs = plan.intervals
    # S0/S1 blend the two motions: their jerk and skating are the join's; the return to the next motion's own
    # lower body (S3) plays that motion's own step, its figures are in the region's
    main = (min(ivs[n].t0 for n in ("S0", "S1")), max(ivs[n].t1 for n in ("S0", "S1")) + 1)
    placed = replace(inc, element=shown, motion=plan.placed, rigid=plan.rigid)
    # the delay is this element's only: later ones keep their scheduled times unless dropped otherwise
    commit(state, placed, out, rep, main, (window[0], region_end), window[0], window[1], (plan.shift + carry) / fps)
    state.feet = laid_feet(tr, c0, rendered)  # the next join's contacts are then found from the new frames alone
    return plan


def _made(state: TrackState, inc: Placed, fps: float, weights: Weights, lock: bool, min_blend: float,
          allow_shift: bool) -> tuple[tuple, Motion]:
    """The join's plan and rendering, ``(plan or Skip, the incoming element as joined, frames it was carried
    by, rendered, c0, locks, window)`` (:func:`.repair.carry_out`'s last four; ``None`` for a Skip), and the
    track extended to the element as joined."""
    prev = state.placed[-1]
    tr = extended(state, inc.offset + inc.motion.n_frames)
    plan = plan_join(tr, prev, inc, fps, weights, state.floor, min_blend, allow_shift)
    carry = _carried_delay(state, prev, fps)
    if isinstance(plan, Skip) and carry:
        # the previous element was delayed for room and its core now covers this one's start: the element
        # scheduled after it follows it rather than being dropped (only then; others keep their times)
        inc = inc.moved(carry)
        tr = extended(state, inc.offset + inc.motion.n_frames)
        plan = plan_join(tr, prev, inc, fps, weights, state.floor, min_blend, allow_shift)
    else:
        carry = 0
    if isinstance(plan, Skip):
        return (plan, inc, carry, None, 0, [], (0, 0)), tr
    # the sources' figures at the track's rate (quality(m, None)'s skating ratio and root pop, without the rest)
    own = max(skating_ratio(prev.motion), skating_ratio(plan.inc.motion))
    own_pop = max(root_pop(prev.motion), root_pop(plan.inc.motion))
    plan, c0, rendered, locks, window = carry_out(tr, plan, lock, own, own_pop)
    return (plan, plan.inc, carry, rendered, c0, locks, window), tr


def _kept(made: tuple) -> tuple:
    """A made join as kept: its motions' frames alone (the rendering's copied out of the track's: a slice of the
    track would keep the whole track alive; the plan's placed and adapted motions without what was computed from
    them, their poses and contacts: 61 of the 91 MB the 32-motion text's joins held), the rest as it is."""
    plan, inc, carry, rendered, c0, locks, window = made
    if rendered is not None:
        rendered = Motion(rendered.skeleton, rendered.fps, rendered.root_positions.copy(), rendered.rotations.copy(),
                          None if rendered.translations is None else rendered.translations.copy())
    if isinstance(plan, Plan):
        plan = replace(plan, placed=_bare(plan.placed), adapted=None if plan.adapted is None else _bare(plan.adapted))
    return plan, inc, carry, rendered, c0, locks, window


def _bare(m: Motion) -> Motion:
    """``m``'s frames (read-only arrays, shared) as a motion of its own, its caches empty."""
    return Motion(m.skeleton, m.fps, m.root_positions, m.rotations, m.translations)


def _relabelled(kept: tuple | None, labels: tuple[int, int], inc: Placed) -> tuple | None:
    """A kept join (:data:`KEPT_JOINS`) for the element ``inc`` after the element labelled ``labels[0]``: as kept
    where it was made for the same labels; else with ``inc``'s element (the same but for its labels) where the plan
    names no element (no warning, not a skip); else ``None`` (made again). Its motions as motions of their own,
    their caches empty: what a track computes from them is not kept with the join (:data:`KEPT_BYTES` counts frames)."""
    if kept is None:
        return None
    plan, was, carry, rendered, c0, locks, window, made_for = kept
    if made_for != labels:
        if isinstance(plan, Skip) or plan.warnings:
            return None
        was = replace(was, element=inc.element)
        plan = replace(plan, inc=was)
    if isinstance(plan, Plan):
        plan = replace(plan, placed=_bare(plan.placed), adapted=None if plan.adapted is None else _bare(plan.adapted))
    return plan, was, carry, None if rendered is None else _bare(rendered), c0, locks, window


def _carried_delay(state: TrackState, prev: Placed, fps: float) -> int:
    """Frames the previous element was delayed by its own join (0 if it kept its scheduled time)."""
    return sum(int(round(d * fps)) for i, d in state.delays if i == prev.element.id)


def lay_track(track: Track, whole: Sequence[Element], fps: float, weights: Weights, lock: bool = True,
              min_blend: float = MIN_BLEND) -> Laid:
    """The whole-body elements of one track joined by optimal blending (see the module docstring)."""
    return lay_elements(track, whole, fps, lambda state, inc: join_next(state, inc, fps, weights, lock, min_blend))
