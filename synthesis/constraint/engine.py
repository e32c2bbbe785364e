"""The synthesis engine of paper 003 (§4): actor tracks of clips → one motion per actor, and a report.

For each :class:`~synthesis.tracks.Track`:

1. every element's clip is prepared (:mod:`synthesis.join.timing`: speed, loop,
   hold/trim; a non-cyclic clip repeated ``n`` times becomes ``n``
   repetitions joined by connections);
2. the whole-body elements are laid down in time order: the first placed at
   the track's origin and heading, each next one joined to the track so far
   by a Connection or Transition (:mod:`synthesis.constraint.connection`): placed through
   the support foot, blended by slerp, feet locked (:mod:`synthesis.join.footlock`);
3. the partial elements are composed onto the result
   (:mod:`synthesis.join.composition`): part switched, sway transferred;
4. every join is measured (``docs/timetable.md`` §3): foot skate and skating ratio
   in the blend, largest and RMS jerk in the blend against the source clips,
   and the core fidelity of each element.

Several tracks are independent; where each actor stands is the scene stage's
(:mod:`text2anim.scene`), given as each track's origin and heading.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from ..assemble import assemble
from ..join.apply import Join, apply_join
from ..join.commit import commit, lock_report
from ..join.laid import Laid
from ..join.laying import TrackState, lay_elements
from ..join.measure import hips_frame
from ..join.placed import Placed
from ..result import BlendInterval, JoinReport, Result
from ..tracks import Element, Track
from .connection import connection, transition

#: Names users import from here (they live in :mod:`synthesis.actors`, :mod:`synthesis.join.measure`,
#: :mod:`synthesis.result`).
__all__ = ["Result", "hips_frame", "synthesize"]


def _join(state: TrackState, inc: Placed, fps: float, lock: bool) -> None:
    """Join ``inc`` to the track so far by a Transition (it starts before the previous element ends)
    or a Connection (:mod:`synthesis.constraint.connection`), feet locked if ``lock``; updates ``state``."""
    e = inc.element
    prev = state.placed[-1]
    tr = state.laid()
    if e.method == "transition" and inc.first < prev.end:
        join: Join = transition(tr, prev, inc, fps, floor=state.floor)
    else:
        join = connection(tr, prev, inc, fps, floor=state.floor)
    m = join.rigid.apply(inc.motion)
    out, locks = apply_join(tr, m, inc.contacts, join, lock=lock)
    region_end = max([join.window[1]] + [lk.release_end for lk in locks])
    stop = inc.stop
    if inc.cyclic:  # a loop may have entered at another phase: it still ends when scheduled
        stop = int(np.clip(int(round(e.end * fps)) - join.offset, 1, m.n_frames))
    intervals = tuple(BlendInterval(part, kind, a / fps, b / fps) for part, kind, a, b in join.intervals)
    info = dict(join.info)
    if locks:
        info["foot_locks"] = lock_report(locks, fps)
    blend = "repeat" if inc.repetition > 0 else join.kind
    rep = JoinReport(prev.element.id, e.id, inc.joined_by, blend, intervals, None, info, tuple(join.warnings))
    placed = replace(inc, motion=m, offset=join.offset, stop=stop, rigid=join.rigid)
    commit(state, placed, out, rep, join.window, (join.window[0], region_end), join.retimed_from, join.window[1])


def lay_track(track: Track, whole: Sequence[Element], fps: float, lock: bool) -> Laid:
    """The whole-body elements of a track laid by paper 003's joins (:func:`synthesis.join.laying.lay_elements`)."""
    return lay_elements(track, whole, fps, lambda state, inc: _join(state, inc, fps, lock))


def synthesize(tracks: Sequence[Track], fps: float = 30.0, *, lock_feet: bool = True, sway: bool = True,
               finished: bool = True) -> Result:
    """Turn actor tracks into one motion per actor (paper 003 §4) and report every join.

    Args:
        tracks: one :class:`~synthesis.tracks.Track` per actor, each at its staged origin and heading.
        fps: the output frame rate.
        lock_feet: lock planted feet during blends (turn off only to measure what it does).
        sway: transfer the sway of composed clips (§4.4.3).
        finished: ``False`` leaves the motions before :func:`synthesis.finish.finish` (the caller finishes them).
    """
    return assemble(tracks, fps, lambda track, whole: lay_track(track, whole, fps, lock_feet), sway, post=lock_feet,
                    finished=finished)
