"""Text → animation: the whole pipeline, and what a user saves from it."""
from __future__ import annotations

import json
import os
from dataclasses import dataclass, replace
from pathlib import Path

from text2anim.motiondb import MotionDB
from text2anim.synthesis import plan as splan
from text2anim.core.atomic import OutputError, atomic_write_bytes

from . import postures
from .pipeline import Planned, plan_text

DEFAULT_ACTOR = "default"


#: A wait longer than this (s) between two motions is filled rather than frozen: a looping
#: motion (walk, run) first comes to a stop (止まる), then the idle clip (待つ) plays until the next
#: motion, so after 走る。3秒後に歩く the runner stops and stands, breathing, before walking.
IDLE_GAP = 0.5
IDLE_VERB = "待つ"
STOP_VERB = "止まる"


class _Clips:
    """Clips loaded from ``db`` once each, resampled to ``fps``."""

    def __init__(self, db: MotionDB, fps: float):
        self.db, self.fps, self.cache, self.infos = db, fps, {}, {}

    def get(self, info) -> splan.Clip:
        self.infos[info.name] = info
        if info.name not in self.cache:
            motion = self.db.load(info)
            if motion.fps != self.fps:
                motion = motion.resample(self.fps)
            self.cache[info.name] = splan.Clip(info.name, motion, tuple(info.core), info.cyclic, info.body_part)
        return self.cache[info.name]

    def by_verb(self, verb: str, character: str | None) -> splan.Clip | None:
        from text2anim.motiondb import UnknownVerbError

        try:
            hits = self.db.search(verb, prefer_character=character)
        except UnknownVerbError:
            return None
        return self.get(hits[0]) if hits else None

    def idle(self, posture: str, character: str | None) -> splan.Clip | None:
        """The idle clip for ``posture`` (a seated one after 座る), or None: the actor holds still."""
        if posture == "standing":
            return self.by_verb(IDLE_VERB, character)
        info = postures.matching(self.db, IDLE_VERB, posture, character=character)
        return self.get(info) if info is not None else None


def _fill_gap(clips: _Clips, prev: splan.Element, start: float, end: float, character: str | None,
              next_id: int) -> list[splan.Element]:
    """Elements that fill ``[start, end)`` after ``prev``: a stop for a looping motion, then idling."""
    out: list[splan.Element] = []
    stop = clips.by_verb(STOP_VERB, character) if prev.clip.cyclic else None
    if stop is not None:
        t1 = min(end, start + stop.motion.duration)
        if end - t1 <= IDLE_GAP:
            t1 = end
        out.append(splan.Element(next_id, stop, start, t1, "transition", prev.id))
        start = t1
    posture = getattr(clips.infos.get(prev.clip.name), "end_posture", "standing")
    idle = clips.idle(posture, character) if end - start > IDLE_GAP else None
    if idle is not None:
        out.append(splan.Element(next_id + len(out), idle, start, end, "connection",
                                 out[-1].id if out else prev.id))
    return out


def build_tracks(planned: Planned, db: MotionDB, fps: float) -> list[splan.Track]:
    """The synthesis tracks of a time table: clips loaded from ``db`` and resampled to ``fps``.

    A connection that waits more than :data:`IDLE_GAP` seconds gets filler
    elements (ids above the table's) in the gap: see :func:`_fill_gap`.
    """
    clips = _Clips(db, fps)
    table = planned.table
    next_id = max(e.id for e in table.elements) + 1
    tracks = []
    for actor in table.actors():
        elements: list[splan.Element] = []
        # In playing order (前に puts a later id first); a composition after its base.
        mine = sorted((e for e in table.elements if e.actor == actor),
                      key=lambda e: (e.start, e.method == "composition", e.id))
        for e in mine:
            info = planned.clips[e.id]
            prev, method = e.prev, e.method
            idle = clips.idle(info.start_posture, info.character) if method == "initial" and e.start > IDLE_GAP else None
            if idle is not None:  # an actor who comes in later stands idle until then
                elements.append(splan.Element(next_id, idle, 0.0, e.start, "initial"))
                prev, method, next_id = next_id, "connection", next_id + 1
            if e.method == "connection" and e.prev is not None:
                before = next(x for x in elements if x.id == e.prev)
                if e.start - before.end > IDLE_GAP:
                    fill = _fill_gap(clips, before, before.end, e.start, info.character, next_id)
                    elements.extend(fill)
                    if fill:
                        prev, next_id = fill[-1].id, next_id + len(fill)
            elements.append(splan.Element(e.id, clips.get(info), e.start, e.end, method, prev,
                                          e.speed, e.repeat, e.hold, e.body_part))
        tracks.append((actor, elements))
    # Actors who finish early stop and stand idle until the last one is done.
    end = max(e.end for e in table.elements)
    out = []
    for actor, elements in tracks:
        last = max((x for x in elements if x.method != "composition"), key=lambda x: x.end)
        if end - last.end > IDLE_GAP:
            character = planned.clips[last.id].character if last.id in planned.clips else None
            fill = _fill_gap(clips, last, last.end, end, character, next_id)
            if not fill and not last.clip.cyclic:  # no idle keeps this posture (seated, lying): hold the last pose
                elements[elements.index(last)] = replace(last, end=end)
            elements.extend(fill)
            next_id += len(fill)
        out.append(splan.Track(actor, tuple(elements)))
    return out


@dataclass(frozen=True, eq=False)
class Animation:
    """The result of :func:`animate`: time table, one motion per actor, the synthesis report.

    ``motions`` maps each actor's name (``"default"`` when the text names none)
    to its :class:`synthesis.Motion`, all on one clock starting at 0 s.
    """

    planned: Planned
    result: object  # synthesis.engine.Result
    fps: float
    blend: str = "optimal"
    smoothness: float = 0.5
    synthesis_tracks: tuple = ()  # the synthesis input (source clips per element), for the report's join figures

    @property
    def text(self) -> str:
        return self.planned.analysis.text

    @property
    def table(self):
        return self.planned.table

    @property
    def motions(self) -> dict:
        return {a or DEFAULT_ACTOR: m for a, m in self.result.motions.items()}

    @property
    def report(self) -> dict:
        """The synthesis report of timetable.md §2, with the time table and per-element figures.

        ``actors`` holds each actor's whole-motion figures; every join gets ``quality``: the figures of
        :mod:`text2anim.quality` on a window around it next to its two source clips', all at 30 fps.
        """
        from text2anim.core.metrics import foot_skate

        from .quality import actor_quality, join_quality, rounded

        whole = {}
        for (name, m), q in zip(self.motions.items(), actor_quality(self.motions).values()):
            whole[name] = {"frames": m.n_frames, "duration": round(m.duration, 3),
                           "skating_ratio": round(q.skating_ratio, 4), "quality": rounded(q),
                           "foot_skate_cm_s": {s: round(f.mean_speed_cm_s, 3) for s, f in foot_skate(m).items()}}
        joins = self.result.report()["joins"]
        for j, q in zip(joins, join_quality(self.result, self.synthesis_tracks)):
            if q is not None:
                j["quality"] = q
        return {
            "text": self.text,
            "fps": self.fps,
            "synthesis": {"blend": self.blend, "smoothness": self.smoothness},
            "time_table": self.table.to_dict()["elements"],
            "joins": joins,
            "elements": {str(k): v for k, v in self.result.elements.items()},
            "actors": whole,
            "skipped": list(self.planned.skipped),
            "warnings": list(self.result.warnings),
        }

    # ---------------------------------------------------------------- for the viewer
    def tracks(self):
        from text2anim.core.viewer.types import Track

        return [Track(name, m) for name, m in self.motions.items()]

    def spans(self):
        """Time-table elements and blend intervals as viewer spans."""
        from text2anim.core.viewer.types import Span

        out = []
        for e in self.table.elements:
            played = self.result.elements.get(e.id, {})
            start, end = played.get("start", e.start), played.get("end", e.end)
            part = f" [{e.body_part}]" if e.body_part else ""
            out.append(Span(e.actor or DEFAULT_ACTOR, f"{e.id} {e.verb} ({e.method}){part}", start, end, "element"))
        for j in self.result.joins:
            actor = self.result.elements.get(j.second, {}).get("actor") or DEFAULT_ACTOR
            for iv in j.intervals:
                if iv.end > iv.begin:
                    out.append(Span(actor, f"{j.first}→{j.second} {iv.kind}", iv.begin, iv.end, "blend", iv.part))
        return out

    # ------------------------------------------------------------------- saving
    def bvh_paths(self, path: str | os.PathLike) -> dict[str, Path]:
        """Where :meth:`save_bvh` writes: ``path`` itself for one actor, ``stem_ACTOR.bvh`` for several."""
        path = Path(path)
        names = list(self.motions)
        if len(names) == 1:
            return {names[0]: path}
        return {n: path.with_name(f"{path.stem}_{n}{path.suffix or '.bvh'}") for n in names}

    def save_bvh(self, path: str | os.PathLike) -> list[Path]:
        from text2anim.core.bvh import format_bvh

        files = {p: format_bvh(self.motions[n]).encode() for n, p in self.bvh_paths(path).items()}
        return _write_all(files)

    def save_html(self, path: str | os.PathLike) -> Path:
        from text2anim.core.viewer import render_html

        html = render_html(self.tracks(), self.spans(), title=self.text)
        return _write_all({Path(path): html.encode()})[0]

    def save_glb(self, path: str | os.PathLike) -> Path:
        from text2anim.core.gltf import glb_bytes

        return _write_all({Path(path): glb_bytes(self.tracks())})[0]

    def save_report(self, path: str | os.PathLike) -> Path:
        text = json.dumps(self.report, ensure_ascii=False, indent=2) + "\n"
        return _write_all({Path(path): text.encode()})[0]

    def save_plot(self, path: str | os.PathLike) -> Path:
        """Upper/lower-body speed curves (Fig. 5 of paper 000) with the blend intervals shaded."""
        from text2anim.core.plots import plot_speeds

        plot_speeds(self.motions, path, [s for s in self.spans() if s.kind == "blend"])
        return Path(path)


def _write_all(files: dict[Path, bytes]) -> list[Path]:
    """Write every file atomically; if one fails, the ones this call wrote are removed again."""
    written: list[Path] = []
    try:
        for path, data in files.items():
            atomic_write_bytes(path, data)
            written.append(path)
    except BaseException:
        for p in written:
            p.unlink(missing_ok=True)
        raise
    return written


def animate(text: str, db=None, *, fps: float = 30.0, skip_unknown: bool = False,
            lock_feet: bool = True, sway: bool = True, blend: str = "optimal",
            smoothness: float = 0.5) -> Animation:
    """Analyse ``text``, schedule it, and synthesise one motion per actor.

    Args:
        db: a :class:`motiondb.MotionDB`, a database URL or SQLite path, or
            ``None`` for the default database (the built-in library on first use).
        fps: output frame rate.
        skip_unknown: drop motions whose verb the database lacks instead of failing.
        lock_feet, sway: the synthesis options of paper 003 (foot locking, sway transfer).
        blend: how consecutive motions are joined: ``optimal`` (paper 000, the default),
            ``constraint`` (paper 003), ``pose`` or ``crossfade`` (the common baselines);
            see :mod:`synthesis.engines`.
        smoothness: ``W`` of paper 000 §4.3 for ``optimal``: 0 joins as fast as it can, 1 as
            smoothly as it can.
    """
    from text2anim.synthesis.engines import check_method, synthesize_with

    if not fps > 0:
        raise OutputError(f"fps must be positive, not {fps}")
    check_method(blend)
    if not 0.0 <= float(smoothness) <= 1.0:
        raise OutputError(f"smoothness must be between 0 (time first) and 1 (smoothness first), not {smoothness}")
    opened = db if isinstance(db, MotionDB) else MotionDB.open(db)
    try:
        planned = plan_text(text, opened, fps=fps, skip_unknown=skip_unknown)
        tracks = build_tracks(planned, opened, fps)
    finally:
        if opened is not db:
            opened.close()
    result = synthesize_with(blend, tracks, fps, smoothness=smoothness, lock_feet=lock_feet, sway=sway)
    return Animation(planned, result, fps, blend, float(smoothness), tuple(tracks))


__all__ = ["Animation", "animate", "build_tracks"]
