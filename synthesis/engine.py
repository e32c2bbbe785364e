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
4. every join is measured (``timetable.md`` §3): foot skate and skating ratio
   in the blend, largest and RMS jerk in the blend against the source clips,
   and the core fidelity of each element.

Several tracks are independent; :func:`default_origins` spaces actors that
were given no place of their own (:func:`spread_actors`), so characters do not
start inside each other.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from text2anim.core.contacts import detect_contacts
from text2anim.core.motion import Motion

from .actors import default_origins, spread_actors
from .finish import finish
from .align import place_at
from .assemble import compose_parts, finish_joins, finish_whole, measure, same_length, shifted
from .measure import hips_frame
from .laid import Laid, LaidJoin
from .placed import Placed, expand_repeats, on_skeleton
from .plan import Track
from .result import BlendInterval, JoinReport, Result
from .timing import Prepared, ease_lead, prepare
from .transition import Join, Side, apply_join, connection, transition

#: Names users import from here (they live in :mod:`synthesis.actors`, :mod:`synthesis.measure`,
#: :mod:`synthesis.result`).
__all__ = ["Result", "default_origins", "hips_frame", "spread_actors", "synthesize"]

def _synthesize_track(track: Track, fps: float, lock: bool, sway: bool):
    warnings: list[str] = []
    whole = [e for e in track.elements if e.method != "composition"]
    parts = sorted((e for e in track.elements if e.method == "composition"), key=lambda e: (e.start, e.id))
    if not whole:
        raise ValueError(f"actor {track.actor!r} has no whole-body motion to lay compositions onto")
    placed: list[Placed] = []
    joins: list[LaidJoin] = []
    tr: Motion | None = None
    skeleton = None
    floor = 0
    for e, rep in expand_repeats(whole):
        prep: Prepared = prepare(e, fps, margin=e.clip.cyclic)
        warnings.extend(prep.warnings)
        prep, skeleton, note = on_skeleton(prep, skeleton, e)
        if note and rep == 0:
            warnings.append(note)
        contacts = detect_contacts(prep.motion)
        lead = prep.lead
        stop = prep.motion.n_frames - lead  # a looped clip has a cycle of margin at both ends
        start = int(round(e.start * fps))
        if tr is None:
            rigid = place_at(prep.motion, track.origin, track.heading, frame=lead)
            m = rigid.apply(prep.motion)
            tr = ease_lead(m[lead:], start)
            placed.append(Placed(e, m, start - lead, prep.core, contacts, e.clip.cyclic, rigid, rep, lead, stop))
            continue
        prev = placed[-1]
        b_side = Side(prep.motion, start - lead, prep.core, contacts, e.clip.cyclic, lead, stop)
        if e.method == "transition" and start < prev.offset + prev.stop:
            join: Join = transition(tr, prev.side(), b_side, fps, floor=floor)
        else:
            join = connection(tr, prev.side(), b_side, fps, floor=floor)
        floor = join.window[1]  # the next join starts after this one's blend
        m = join.rigid.apply(prep.motion)
        tr, locks = apply_join(tr, m, contacts, join, lock=lock)
        core = prep.core
        region_end = max([join.window[1]] + [lk.release_end for lk in locks])
        if e.clip.cyclic:  # a looped clip is all core: the join (blend, feet released) is taken out of it
            core = (max(core[0], region_end - join.offset), core[1])
        if prev.cyclic:
            prev.core = (prev.core[0], min(prev.core[1], join.retimed_from - prev.offset))
        if e.clip.cyclic:  # a loop may have entered at another phase: it still ends when scheduled
            stop = int(np.clip(int(round(e.end * fps)) - join.offset, 1, m.n_frames))
        p = Placed(e, m, join.offset, core, contacts, e.clip.cyclic, join.rigid, rep, lead, stop)
        placed.append(p)
        method = "connection" if rep > 0 else e.method
        blend = "repeat" if rep > 0 else join.kind
        intervals = tuple(BlendInterval(part, kind, a / fps, b / fps) for part, kind, a, b in join.intervals)
        info = dict(join.info)
        if locks:
            info["foot_locks"] = [{"side": lk.side, "begin": lk.begin / fps, "end": lk.end / fps,
                                   "release_end": lk.release_end / fps} for lk in locks]
        rep_ = JoinReport(prev.element.id, e.id, method, blend, intervals, None, info, tuple(join.warnings))
        joins.append(LaidJoin(rep_, join.window, (join.window[0], region_end), prev, p))
    # a looped clip's margin after its end is not played; the track holds to the last scheduled end
    laid = Laid(finish_whole(tr, placed, track.elements), placed, joins, warnings)
    if lock:
        finish_joins(laid)
    comps = compose_parts(laid, shifted(parts, laid.delays), whole, fps, sway)
    return laid, comps


def synthesize(tracks: Sequence[Track], fps: float = 30.0, *, lock_feet: bool = True, sway: bool = True,
               spread: bool = True) -> Result:
    """Turn actor tracks into one motion per actor (paper 003 §4) and report every join.

    Args:
        tracks: one :class:`~synthesis.plan.Track` per actor.
        fps: the output frame rate.
        lock_feet: lock planted feet during blends (turn off only to measure what it does).
        sway: transfer the sway of composed clips (§4.4.3).
        spread: give actors sharing one origin the :func:`default_origins`.
    """
    if spread:
        tracks = spread_actors(tracks)
    motions, reports, elements, warnings = {}, [], {}, []
    for track in tracks:
        laid, comps = _synthesize_track(track, fps, lock_feet, sway)
        warnings.extend(laid.warnings)
        reps, els = measure(track, laid, comps, fps)
        reports.extend(reps)
        elements.update(els)
        motions[track.actor] = laid.motion
    final = same_length(motions) if lock_feet else motions
    return Result({actor: finish(m, feet=lock_feet) for actor, m in final.items()}, reports, fps, elements, tuple(warnings))
