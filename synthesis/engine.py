"""The synthesis engine of paper 003 (§4): actor tracks of clips → one motion per actor, and a report.

For each :class:`~synthesis.plan.Track`:

1. every element's clip is prepared (:mod:`synthesis.timing`: speed, loop,
   hold/trim; a non-cyclic clip repeated ``n`` times becomes ``n``
   repetitions joined by connections);
2. the whole-body elements are laid down in time order: the first placed at
   the track's origin and heading, each next one joined to the track so far
   by a Connection or Transition (:mod:`synthesis.transition`): placed through
   the support foot, blended by slerp, feet locked (:mod:`synthesis.footlock`);
3. the partial elements are composed onto the result
   (:mod:`synthesis.composition`): part switched, sway transferred;
4. every join is measured (``docs/timetable.md`` §3): foot skate and skating ratio
   in the blend, largest and RMS jerk in the blend against the source clips,
   and the core fidelity of each element.

Several tracks are independent; :func:`default_origins` spaces actors that
were given no place of their own (:func:`spread_actors`), so characters do not
start inside each other.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .actors import default_origins, spread_actors
from .assemble import assemble
from .laid import Laid, LaidJoin
from .measure import hips_frame
from .placed import Placed
from .plan import Element, Track
from .result import BlendInterval, JoinReport, Result
from .track import Incoming, TrackState, lay_elements
from .transition import Join, Side, apply_join, connection, transition

#: Names users import from here (they live in :mod:`synthesis.actors`, :mod:`synthesis.measure`,
#: :mod:`synthesis.result`).
__all__ = ["Result", "default_origins", "hips_frame", "spread_actors", "synthesize"]


def _join(state: TrackState, inc: Incoming, fps: float, lock: bool) -> None:
    """Join ``inc`` to the track so far by a Transition (it starts before the previous element ends)
    or a Connection (:mod:`synthesis.transition`), feet locked if ``lock``; updates ``state``."""
    e = inc.element
    prev = state.placed[-1]
    tr = state.laid()
    b_side = Side(inc.motion, inc.offset, inc.core, inc.contacts, inc.cyclic, inc.lead, inc.stop)
    if e.method == "transition" and inc.first < prev.offset + prev.stop:
        join: Join = transition(tr, prev.side(), b_side, fps, floor=state.floor)
    else:
        join = connection(tr, prev.side(), b_side, fps, floor=state.floor)
    state.floor = join.window[1]  # the next join starts after this one's blend
    m = join.rigid.apply(inc.motion)
    state.motion, locks = apply_join(tr, m, inc.contacts, join, lock=lock)
    core, stop = inc.core, inc.stop
    region_end = max([join.window[1]] + [lk.release_end for lk in locks])
    if inc.cyclic:  # a looped clip is all core: the join (blend, feet released) is taken out of it
        core = (max(core[0], region_end - join.offset), core[1])
    if prev.cyclic:
        prev.core = (prev.core[0], min(prev.core[1], join.retimed_from - prev.offset))
    if inc.cyclic:  # a loop may have entered at another phase: it still ends when scheduled
        stop = int(np.clip(int(round(e.end * fps)) - join.offset, 1, m.n_frames))
    p = Placed(e, m, join.offset, core, inc.contacts, inc.cyclic, join.rigid, inc.rep, inc.lead, stop)
    state.placed.append(p)
    method = "connection" if inc.rep > 0 else e.method
    blend = "repeat" if inc.rep > 0 else join.kind
    intervals = tuple(BlendInterval(part, kind, a / fps, b / fps) for part, kind, a, b in join.intervals)
    info = dict(join.info)
    if locks:
        info["foot_locks"] = [{"side": lk.side, "begin": lk.begin / fps, "end": lk.end / fps,
                               "release_end": lk.release_end / fps} for lk in locks]
    rep = JoinReport(prev.element.id, e.id, method, blend, intervals, None, info, tuple(join.warnings))
    state.joins.append(LaidJoin(rep, join.window, (join.window[0], region_end), prev, p))


def lay_track(track: Track, whole: Sequence[Element], fps: float, lock: bool) -> Laid:
    """The whole-body elements of a track laid by paper 003's joins (:func:`synthesis.track.lay_elements`)."""
    return lay_elements(track, whole, fps, lambda state, inc: _join(state, inc, fps, lock))


def synthesize(tracks: Sequence[Track], fps: float = 30.0, *, lock_feet: bool = True, sway: bool = True,
               spread: bool = True, finished: bool = True) -> Result:
    """Turn actor tracks into one motion per actor (paper 003 §4) and report every join.

    Args:
        tracks: one :class:`~synthesis.plan.Track` per actor.
        fps: the output frame rate.
        lock_feet: lock planted feet during blends (turn off only to measure what it does).
        sway: transfer the sway of composed clips (§4.4.3).
        spread: give actors sharing one origin the :func:`default_origins`.
        finished: ``False`` leaves the motions before :func:`synthesis.finish.finish` (the caller finishes them).
    """
    if spread:
        tracks = spread_actors(tracks)
    return assemble(tracks, fps, lambda track, whole: lay_track(track, whole, fps, lock_feet), sway, post=lock_feet,
                    finished=finished)
