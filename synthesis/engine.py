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
from dataclasses import dataclass, field, replace

import numpy as np

from .align import Rigid, place_at
from .blend import sample
from .composition import Composed
from text2anim.core.contacts import FootContacts, detect_contacts, foot_tracks
from text2anim.core.metrics import SKATING_MARGIN, jerk, skating_by_frame
from text2anim.core.motion import Motion
from .plan import BlendInterval, Element, JoinReport, Track
from .timing import Prepared, ease_lead, prepare
from .transition import Join, Side, apply_join, connection, transition

ACTOR_SPACING = 1.5  # m between actors placed by default


def default_origins(n: int, spacing: float = ACTOR_SPACING) -> list[tuple[float, float]]:
    """``n`` ground positions (x, z) in a row along X, ``spacing`` metres apart, centred on the origin.

    Every actor faces +Z (heading 0) from there, side by side.
    """
    return [((i - (n - 1) / 2.0) * spacing, 0.0) for i in range(n)]


def spread_actors(tracks: Sequence[Track], spacing: float = ACTOR_SPACING) -> tuple[Track, ...]:
    """The tracks with default origins when several actors would otherwise start on the same spot.

    Tracks keep their own ``origin`` unless two or more share one; then all
    of them are put on :func:`default_origins` (order as given).
    """
    tracks = tuple(tracks)
    if len(tracks) < 2:
        return tracks
    spots = {(round(t.origin[0], 3), round(t.origin[1], 3)) for t in tracks}
    if len(spots) == len(tracks):
        return tracks
    return tuple(replace(t, origin=o) for t, o in zip(tracks, default_origins(len(tracks), spacing)))


@dataclass
class Placed:
    """An element (or one repetition of it) as laid on its track.

    ``motion`` is its prepared clip moved by ``rigid``; its frame 0 is at
    track frame ``offset``; ``core`` is ``[c0, c1)`` in its own frames.
    """

    element: Element
    motion: Motion
    offset: int
    core: tuple[int, int]
    contacts: FootContacts
    cyclic: bool
    rigid: Rigid
    repetition: int = 0
    lead: int = 0
    stop: int | None = None

    def side(self) -> Side:
        return Side(self.motion, self.offset, self.core, self.contacts, self.cyclic, self.lead, self.stop)


@dataclass(frozen=True)
class Result:
    """What :func:`synthesize` returns.

    Attributes:
        motions: one motion per actor (key: the track's ``actor``), at ``fps``, starting at track time 0.
        joins: one :class:`~synthesis.plan.JoinReport` per join (connections, transitions,
            repetitions, compositions), in track and time order.
        elements: per element id: ``actor``, ``start``/``end`` as played (s), ``core`` (s on the
            track), ``core_fidelity_cm`` (and ``core_fidelity_untouched_cm`` when a
            composition changed part of it), ``placement`` (yaw, x, z).
        warnings: what could not be honoured.
    """

    motions: dict
    joins: list
    fps: float
    elements: dict = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    def report(self) -> dict:
        """The ``joins`` part of the synthesis report (``timetable.md`` §2) as plain JSON-ready data."""
        return {"joins": [join_to_dict(j) for j in self.joins]}


def join_to_dict(j: JoinReport) -> dict:
    d = {"first": j.first, "second": j.second, "method": j.method, "blend": j.blend,
         "intervals": [{"part": i.part, "kind": i.kind, "begin": round(i.begin, 3), "end": round(i.end, 3)}
                       for i in j.intervals]}
    if j.cost is not None:
        d["cost"] = j.cost
    d["metrics"] = j.metrics
    if j.warnings:
        d["warnings"] = list(j.warnings)
    return d


# ------------------------------------------------------------------------------------------ metrics
def _foot_skate_window(track: Motion, contacts: FootContacts, tracks: dict, w0: int, w1: int) -> dict:
    out = {}
    for side, tr in tracks.items():
        c = contacts.of(side)[w0:w1]
        sp = tr.speed[w0:w1][c]
        out[side] = {"mean_cm_s": float(sp.mean() * 100) if len(sp) else 0.0,
                     "max_cm_s": float(sp.max() * 100) if len(sp) else 0.0,
                     "slide_cm": float(sp.sum() / track.fps * 100) if len(sp) else 0.0,
                     "contact_frames": int(c.sum())}
    return out


def skating_frames(motion: Motion) -> np.ndarray:
    """Per frame, whether a foot skates: the GMD rule of :func:`core.metrics.skating_by_frame` (either toe
    below 5 cm on frames t and t+1, faster than 0.5 m/s and so over its centred 5-frame average), ``(T,)``
    bool at the motion's own rate; the figure a join is judged by, as the benchmark judges the output."""
    return skating_by_frame(motion)


def skating_exceeds(ratio: float, sources: float) -> bool:
    """Whether a join's skating ``ratio`` is beyond issue 11's bound: its sources' larger + 0.01
    (:func:`core.metrics.against_sources`)."""
    return ratio > sources + SKATING_MARGIN + 1e-12


def max_slide(motion: Motion) -> float:
    """Largest horizontal speed (cm/s) of a foot while it is in contact, over a whole motion."""
    c = detect_contacts(motion)
    return max((float(tr.speed[c.of(s)].max() * 100) if c.of(s).any() else 0.0)
               for s, tr in foot_tracks(motion).items())


def window_metrics(track: Motion, w0: int, w1: int, contacts: FootContacts, ftracks: dict,
                    skating: np.ndarray) -> dict:
    w0, w1 = max(0, w0), min(track.n_frames, w1)
    fs = _foot_skate_window(track, contacts, ftracks, w0, w1)
    jk = jerk(track, w0, w1)
    return {"frames": [w0, w1],
            "skating_ratio": float(skating[w0:w1].mean()) if w1 > w0 else 0.0,
            "foot_skate": fs,
            "max_slide_cm_s": max(v["max_cm_s"] for v in fs.values()),
            "jerk_max": jk.max, "jerk_rms": jk.rms}


def core_fidelity(track: Motion, placed: Placed, joints=None) -> float:
    """Largest joint position error (cm) in the element's core between the track and the placed clip."""
    c0, c1 = placed.core
    lo = max(placed.offset + c0, 0)
    hi = min(placed.offset + c1, track.n_frames, placed.offset + placed.motion.n_frames)
    if hi <= lo:
        return 0.0
    a = track[lo:hi].positions
    b = placed.motion[lo - placed.offset:hi - placed.offset].positions
    if joints is not None:
        a, b = a[:, joints], b[:, joints]
    return float(np.linalg.norm(a - b, axis=-1).max() * 100)


def hips_frame(points: np.ndarray, hips: np.ndarray, hips_rot: np.ndarray) -> np.ndarray:
    """World points ``(T, K, 3)`` in the hips' own frame (position ``(T, 3)``, rotation matrices ``(T, 3, 3)``)."""
    return np.einsum("tji,tkj->tki", hips_rot, points - hips[:, None, :])


def part_fidelity(track: Motion, comp: Composed, donor: Motion, core: tuple[int, int]) -> float:
    """Largest error (cm) of the switched part's joints relative to the hips (the hips' frame) against
    the partial clip, over the frames of its core that are fully switched (outside the blends)."""
    t = comp.timing
    n = t.ta1 - t.ta0
    k = np.arange(t.blend_in, n - t.blend_out)
    if len(k) == 0:
        return 0.0
    src = t.tb0 + k * (t.tb1 - t.tb0) / max(n, 1)
    keep = (src >= core[0]) & (src <= core[1] - 1)
    if not keep.any():
        return 0.0
    k, src = k[keep], src[keep]
    ref = sample(donor, src)
    out = track[t.ta0:t.ta1]
    joints = list(comp.joints)

    def rel(m: Motion, frames=None):
        pose = m.pose
        p = pose.positions if frames is None else pose.positions[frames]
        r = pose.rotations[:, 0] if frames is None else pose.rotations[frames, 0]
        return hips_frame(p[:, joints], p[:, 0], r)

    return float(np.linalg.norm(rel(out, k) - rel(ref), axis=-1).max() * 100)


# --------------------------------------------------------------------------------------------- engine
def expand_repeats(elements: Sequence[Element]) -> list[tuple[Element, int]]:
    """Whole-body elements in time order, a repeated non-cyclic one as its repetitions."""
    out = []
    for e in sorted(elements, key=lambda e: (e.start, e.id)):
        n = max(1, int(e.repeat))
        if e.clip.cyclic or n == 1:
            out.append((e, 0))
            continue
        step = (e.end - e.start) / n
        for k in range(n):
            sub = replace(e, start=e.start + k * step, end=e.start + (k + 1) * step, repeat=1,
                          method=e.method if k == 0 else "connection", prev=e.prev if k == 0 else e.id)
            out.append((sub, k))
    return out


def mirrored_if_needed(clip_part: str | None, want: str | None, motion: Motion) -> Motion:
    if not clip_part or not want:
        return motion
    sides = {"left": "right", "right": "left"}
    for s, o in sides.items():
        if clip_part.startswith(s + "_") and want == o + "_" + clip_part.split("_", 1)[1]:
            from text2anim.core.mirror import mirror

            return mirror(motion)
    return motion


def on_skeleton(prep: Prepared, skeleton, e: Element):
    """The prepared clip played on the track's skeleton (the first element's); a note when bone lengths differ."""
    sk = prep.motion.skeleton
    if skeleton is None:
        return prep, sk, None
    if not sk.same_hierarchy(skeleton):
        raise ValueError(f"element {e.id} ({e.clip.name}) uses another joint hierarchy than the actor's first clip")
    if sk is skeleton:
        return prep, skeleton, None
    diff = float(np.abs(sk.offsets - skeleton.offsets).max())
    note = None
    if diff > 0.005:
        note = (f"element {e.id} ({e.clip.name}) was recorded on other bone lengths (up to {100 * diff:.1f} cm "
                f"different); it is played on the actor's skeleton")
    return replace(prep, motion=prep.motion.replace(skeleton=skeleton)), skeleton, note


def _synthesize_track(track: Track, fps: float, lock: bool, sway: bool):
    warnings: list[str] = []
    whole = [e for e in track.elements if e.method != "composition"]
    parts = sorted((e for e in track.elements if e.method == "composition"), key=lambda e: (e.start, e.id))
    if not whole:
        raise ValueError(f"actor {track.actor!r} has no whole-body motion to lay compositions onto")
    placed: list[Placed] = []
    joins: list[tuple[JoinReport, tuple, Placed | None, Placed | None, list]] = []
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
        joins.append((rep_, (join.window, (join.window[0], region_end)), prev, p, []))
    from .assemble import Laid, compose_parts, finish_joins, finish_whole, shifted  # assemble builds on this module's pieces

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
    from .assemble import measure, same_length  # assemble builds on this module's pieces

    motions, reports, elements, warnings = {}, [], {}, []
    for track in tracks:
        laid, comps = _synthesize_track(track, fps, lock_feet, sway)
        warnings.extend(laid.warnings)
        reps, els = measure(track, laid, comps, fps)
        reports.extend(reps)
        elements.update(els)
        motions[track.actor] = laid.motion
    return Result(same_length(motions) if lock_feet else motions, reports, fps, elements, tuple(warnings))
