"""What every whole-body joiner shares after laying its clips: compositions, measurement, the Result.

Every joiner (paper 003's :mod:`synthesis.constraint.engine`, the optimal engine
:mod:`synthesis.optimal`, the baselines :mod:`synthesis.baselines`) lays the
whole-body elements of a track its own way; then :func:`assemble`:

1. the partial elements are composed onto the track
   (:func:`synthesis.join.composition.compose`, sway transfer and all);
2. every join is measured with the same figures (``docs/timetable.md`` §3:
   skating ratio and foot skate in the blend and its region, largest and RMS
   jerk against the source clips', core fidelity per element);
3. a :class:`synthesis.result.Result` is returned, so every method can be
   saved, viewed, reported and compared the same way, every actor's motion
   finished: swinging feet clear of the floor, no frozen pose (:func:`synthesis.finish.finish`).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from text2anim.core.contacts import detect_contacts, foot_tracks, horizontal_speed
from text2anim.core.metrics import jerk, skating_ratio
from text2anim.core.motion import Motion

from .finish import finish
from .join.composition import compose
from .join.laid import Laid, LaidJoin, LaidPart
from .join.measure import core_fidelity, max_slide, part_fidelity, skating_frames, window_metrics
from .join.placed import Placed, mirrored_if_needed, on_skeleton
from .join.timing import ease_hold, prepare
from .played import placed_paths
from .result import BlendInterval, ElementReport, JoinReport, Placement, Result
from .tracks import Element, Track


def shifted(parts: list[Element], delays: list) -> list[Element]:
    """Partial elements moved with the whole-body element they are laid on when a joiner moved it in time:
    ``delays`` lists ``(element id, seconds)``."""
    moved: dict = {}
    for eid, sec in delays:  # an element may be moved more than once (a join's room, then the post-pass)
        moved[eid] = moved.get(eid, 0.0) + sec
    return [replace(e, start=e.start + moved[e.prev], end=e.end + moved[e.prev]) if e.prev in moved else e
            for e in parts]


def finish_whole(tr: Motion, placed: list[Placed], elements) -> Motion:
    """The track cut after the last whole-body element and held (eased) to the last scheduled end."""
    last = placed[-1]
    tr = tr[:max(1, last.offset + last.stop)]
    n_end = max([int(round(e.end * tr.fps)) for e in elements] + [tr.n_frames])
    return ease_hold(tr, n_end)


def compose_parts(laid: Laid, parts: list[Element], whole: list[Element], fps: float, sway: bool) -> list[LaidPart]:
    """Compose the partial elements onto ``laid.motion`` (in place); returns the compositions."""
    tr = laid.motion
    comps = []
    for e in parts:
        prep = prepare(e, fps)
        laid.warnings.extend(prep.warnings)
        prep, _, note = on_skeleton(prep, tr.skeleton, e)
        if note:
            laid.warnings.append(note)
        part = e.body_part or e.clip.body_part or "upper"
        donor = mirrored_if_needed(e.clip.body_part, part, prep.motion)
        start = int(round(e.start * fps))
        end = start + donor.n_frames
        if end + 1 > tr.n_frames:
            tr = ease_hold(tr, end + 1)
        comp = compose(tr, start, end, donor, prep.core, part, sway=sway)
        tr = comp.motion
        t = comp.timing
        intervals = (BlendInterval(part, "motion-motion", t.ta0 / fps, (t.ta0 + t.blend_in) / fps),
                     BlendInterval(part, "motion-motion", (t.ta1 - t.blend_out) / fps, t.ta1 / fps))
        info = {"switch_s": [t.ta0 / fps, t.ta1 / fps], "clip_s": [t.tb0 / fps, t.tb1 / fps],
                "stretch": t.stretch, "sway_joints": len(comp.sway_joints), "sway_max_deg": comp.sway_deg}
        base_id = e.prev if e.prev is not None and e.prev not in laid.skipped else whole[0].id
        rep = JoinReport(base_id, e.id, "composition", "composition", intervals,
                         {"start": t.cost_start, "end": t.cost_end}, info, ())
        laid.joins.append(LaidJoin(rep, (t.ta0, t.ta0 + t.blend_in), (t.ta0, t.ta1),
                                   extra=((t.ta1 - t.blend_out, t.ta1),)))
        comps.append(LaidPart(e, comp, donor, prep.core))
    laid.motion = tr
    return comps


def measure(track: Track, laid: Laid, comps: list[LaidPart], fps: float
            ) -> tuple[list[JoinReport], dict[int, ElementReport]]:
    """Per-join reports with their metrics and per-element figures (the engine's, see the module doc)."""
    tr = laid.motion
    contacts = detect_contacts(tr)
    ftracks = foot_tracks(tr)
    skating = skating_frames(tr)
    composed_at = [(c.composed.timing.ta0, c.composed.timing.ta1) for c in comps]
    elements: dict[int, ElementReport] = {}
    for p in laid.placed:  # a repeated element's repetitions: from the first one's start to the last one's end
        key = p.element.id
        f = core_fidelity(tr, p)
        c0, c1 = p.offset + p.core[0], p.offset + p.core[1]
        rigid = p.rigid
        assert rigid is not None  # every element on a laid track is placed
        el = elements.get(key) or ElementReport(
            track.actor, start=(p.offset + p.lead) / fps, core=(c0 / fps, c1 / fps),
            placement=Placement(rigid.yaw, rigid.offset[0], rigid.offset[1]))
        assert el.core is not None
        el = replace(el, end=(p.offset + p.stop) / fps, core=(el.core[0], c1 / fps),
                     core_fidelity_cm=max(el.core_fidelity_cm or 0.0, f))
        if any(a < c1 and b > c0 for a, b in composed_at):
            from text2anim.core.bodyparts import body_map

            legs = list(body_map(tr.skeleton).joints("lower"))
            el = replace(el, core_fidelity_untouched_cm=core_fidelity(tr, p, legs))
        elements[key] = el
    for eid, why in laid.skipped.items():
        elements[eid] = ElementReport(track.actor, reason=why)
    for c in comps:
        t = c.composed.timing
        elements[c.element.id] = ElementReport(track.actor, start=t.ta0 / fps, end=t.ta1 / fps, part=c.composed.part,
                                               part_fidelity_cm=part_fidelity(tr, c.composed, c.donor, c.core))
    by_id = {p.element.id: p for p in laid.placed}
    reports = []
    for lj in laid.joins:
        rep = lj.report
        if lj.window is None or lj.region is None:
            reports.append(rep)
            continue
        window, region = lj.window, lj.region
        m = window_metrics(tr, window[0], window[1], contacts, ftracks, skating)
        for a, b in lj.extra:
            m2 = window_metrics(tr, a, b, contacts, ftracks, skating)
            m["jerk_max"] = max(m["jerk_max"], m2["jerk_max"])
            m["jerk_rms"] = float(np.hypot(m["jerk_rms"], m2["jerk_rms"]) / np.sqrt(2))
            m["skating_ratio"] = max(m["skating_ratio"], m2["skating_ratio"])
            m["max_slide_cm_s"] = max(m["max_slide_cm_s"], m2["max_slide_cm_s"])
        reg = window_metrics(tr, region[0], region[1], contacts, ftracks, skating)
        m["region"] = {k: reg[k] for k in ("frames", "skating_ratio", "max_slide_cm_s", "foot_skate")}
        srcs: list[Placed | None] = [laid.placed[i] for i in (lj.first, lj.second) if i is not None]
        srcs = srcs or [by_id.get(rep.first)]
        src_m = [p.motion for p in srcs if p is not None]
        if rep.method == "composition":
            src_m = [c.donor for c in comps if c.element.id == rep.second] + src_m
        src_j = [jerk(x) for x in src_m]
        m["source_max_slide_cm_s"] = max((max_slide(x) for x in src_m), default=0.0)
        m["source_skating_ratio"] = max((skating_ratio(x) for x in src_m), default=0.0)
        m["source_jerk_max"] = max((j.max for j in src_j), default=0.0)
        m["source_jerk_rms"] = max((j.rms for j in src_j), default=0.0)
        a_el, b_el = elements.get(rep.first), elements.get(rep.second)
        m["core_fidelity_cm"] = {str(rep.first): a_el.core_fidelity_cm if a_el is not None else None,
                                 str(rep.second): b_el.fidelity_cm if b_el is not None else None}
        reports.append(replace(rep, metrics={**rep.metrics, **m}))
    return reports, elements


NEAR_CORE = 0.1  # s of a clip's core its join side keeps (the 3-frame average and differences reach that far)


def join_side(clip, side: str, whole: bool = False) -> Motion:
    """The frames of a source ``clip`` a join replaces, as recorded: after its core when the join leaves
    it (``side="out"``), before its core when the join enters it (``"in"``), each with :data:`NEAR_CORE` s
    of the core. A looped clip (every step is core), a part under 0.2 s, or ``whole``: the whole clip.

    The join post-pass prefers the smoothing that brings a join within these parts' figures (at the time
    its whole clips' figures asked for): a kick's or a landing's accelerations inside its core are no
    licence for the join next to it to move as hard.
    """
    m = clip.motion
    if whole or clip.cyclic:
        return m
    c0, c1 = clip.core

    def make() -> Motion:
        part = m.between(max(0.0, c1 - NEAR_CORE), m.duration + 1.0) if side == "out" \
            else m.between(0.0, c0 + NEAR_CORE)
        return part if part.duration >= 0.2 else m
    # kept with the clip's motion: the same part, and the figures the post-pass measures of it (kept in its
    # cache), join after join of a long text
    return m.cache.get(("join_side", side, float(c0), float(c1)), make)


def finish_joins(laid: Laid) -> None:
    """Run the join post-pass (:mod:`synthesis.join.joinpass`) on ``laid.motion`` in place; each join's
    report gets what the pass did (``post``). Where the pass gave a join more time (a region retimed
    over more frames), the next element and every later one move later by as much: their placement,
    the later joins' frames, and ``laid.delays`` (the partial elements laid on them follow)."""
    from .join.joinpass import Region, finish_track

    fps = laid.motion.fps  # the post-pass retimes frames, never the rate
    idx, regions = [], []
    for k, lj in enumerate(laid.joins):
        if lj.window is None or lj.region is None or lj.first is None or lj.second is None:
            continue
        rep, first, second = lj.report, laid.placed[lj.first], laid.placed[lj.second]
        (w0, w1), r1 = lj.window, lj.region[1]
        keep = (first.offset + first.core[1], second.offset + second.core[0])  # cores are kept (§4.2.5)
        idx.append(k)
        brake = first.offset + first.lead if first.cyclic else None  # a loop may take braking steps
        seams = tuple(sorted({int(round(t * fps)) for i in rep.intervals for t in (i.begin, i.end)}))
        into_core = rep.blend.startswith("motion_adaptation")
        sources = (first.element.clip.motion, second.element.clip.motion)  # as recorded: no loop seams, no holds
        near = (join_side(first.element.clip, "out"), join_side(second.element.clip, "in", whole=into_core))
        regions.append(Region(int(w0), int(w1), int(r1), sources, keep, brake, seams, into_core, near))
    laid.motion, infos, warps = finish_track(laid.motion, regions)
    for k, info, (lo, hi, n_new, src) in zip(idx, infos, warps):
        lj = laid.joins[k]
        assert lj.first is not None and lj.second is not None  # only carried-out joins of two placed elements
        first = laid.placed[lj.first]
        delta = n_new - (hi - lo)
        laid.joins[k] = replace(lj, report=replace(lj.report, metrics={**lj.report.metrics, "post": info}))
        if delta <= 0:
            continue

        def moved(f: int) -> int:
            if f < lo:
                return f
            if f >= hi:
                return f + delta
            return lo + int(np.searchsorted(src, f - lo))

        if first.cyclic:  # a loop's steps slowed for braking belong to the join, not to its core
            laid.placed[lj.first] = replace(first, core=(first.core[0],
                                                         max(first.core[0], min(first.core[1], lo - first.offset))))
        laid.placed[lj.second:] = [p.moved(delta) for p in laid.placed[lj.second:]]
        laid.delays.extend((p.element.id, delta / fps) for p in laid.placed[lj.second:] if p.repetition == 0)
        for j in range(k, len(laid.joins)):
            lj = laid.joins[j]
            r = lj.report
            r = replace(r, intervals=tuple(replace(i, begin=moved(round(i.begin * fps)) / fps,
                                                   end=moved(round(i.end * fps)) / fps) for i in r.intervals))
            if "foot_locks" in r.metrics:
                locks = [{**lk, **{key: moved(round(lk[key] * fps)) / fps for key in ("begin", "end", "release_end")}}
                         for lk in r.metrics["foot_locks"]]
                r = replace(r, metrics={**r.metrics, "foot_locks": locks})
            laid.joins[j] = replace(lj, report=r, window=_moved_span(lj.window, moved),
                                    region=_moved_span(lj.region, moved),
                                    extra=tuple((moved(x), moved(y)) for x, y in lj.extra))


def _moved_span(span, moved):
    """``span`` ``(begin, end)`` with both ends mapped by ``moved``; ``None`` stays ``None``."""
    return None if span is None else (moved(span[0]), moved(span[1]))


#: m/s at a person's size: a track whose hips end slower than this ends at rest, and is held
END_MOVING = 0.1


def same_length(motions: dict) -> dict:
    """Every actor's motion made as long as the longest: a join the post-pass gave more time lengthens its
    actor's track, and the others wait for it.

    A track that ends at rest (its hips slower than :data:`END_MOVING` over its last 0.2 s) holds its last
    pose (:func:`ease_hold`; the finish step makes a held pose play the idle and breathe,
    :mod:`synthesis.alive`): its motion keeps its own time. Slowing it instead played a whole short track
    up to half speed, stood a body on one foot through a slowed step and moved every frame away from the
    times the report gives its joins and elements. A track that ends moving (a walk or a run still going
    when the scene ends) cannot stop dead: its last 2 s (at least 4x the difference) play that much slower
    (:func:`synthesis.join.joinpass.retime`); a track too short for that is held.
    """
    from text2anim.core.size import human_scale

    from .join.joinpass import retime

    n = max((m.n_frames for m in motions.values()), default=0)
    out = {}
    for actor, m in motions.items():
        delta = n - m.n_frames
        k = min(m.n_frames, max(4 * delta + 2, int(round(2 * m.fps))))
        if delta <= 0:
            out[actor] = m
        elif k > delta + 1 and _end_speed(m) * human_scale(m) > END_MOVING:
            out[actor] = retime(m, m.n_frames - k, m.n_frames, k + delta)
        else:
            out[actor] = ease_hold(m, n)
    return out


def _end_speed(m: Motion) -> float:
    """The hips' mean horizontal speed (m/s) over the last 0.2 s of ``m``."""
    tail = m.root_positions[-max(2, int(round(0.2 * m.fps)) + 1):]
    return float(horizontal_speed(tail, m.fps).mean()) if len(tail) > 1 else 0.0


def assemble(tracks, fps: float, lay, sway: bool = True, post: bool = False, finished: bool = True) -> Result:
    """Lay every track with ``lay(track, whole_elements) -> Laid``, compose its partial elements, measure.

    Each track is laid at its own origin and heading (the scene stage's staging, :mod:`text2anim.scene`). ``post``
    runs the join post-pass (:func:`finish_joins`) before the compositions are laid. ``finished=False``
    leaves the motions before :func:`synthesis.finish.finish` (for a caller that finishes them itself).
    """
    motions, reports, elements, warnings, placed = {}, [], {}, [], {}
    for track in tracks:
        whole = [e for e in track.elements if e.method != "composition"]
        parts = sorted((e for e in track.elements if e.method == "composition"), key=lambda e: (e.start, e.id))
        if not whole:
            raise ValueError(f"actor {track.actor!r} has no whole-body motion to lay compositions onto")
        laid = lay(track, whole)
        laid.motion = finish_whole(laid.motion, laid.placed, track.elements)
        if post:
            finish_joins(laid)
        comps = compose_parts(laid, shifted(parts, laid.delays), whole, fps, sway)
        reps, els = measure(track, laid, comps, fps)
        reports.extend(reps)
        elements.update(els)
        warnings.extend(laid.warnings)
        motions[track.actor] = laid.motion
        placed[track.actor] = laid.placed
    final = same_length(motions) if post else motions
    if finished:
        idles = {t.actor: t.idle for t in tracks}
        final = {actor: finish(m, feet=post, idle=idles[actor]) for actor, m in final.items()}
    paths = {actor: placed_paths(placed[actor], m.n_frames) for actor, m in final.items()}
    return Result(final, reports, fps, elements, tuple(warnings), paths)
