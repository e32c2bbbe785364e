"""Text → animation: the whole pipeline, and what a user saves from it."""
from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

from text2anim.motiondb import MotionDB
from text2anim.synthesis import plan as splan
from text2anim.core.atomic import Content, check_distinct, check_output_path, write_all

from . import limits, postures
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
        """The synthesis report of timetable.md §2, with the time table and per-element figures."""
        from text2anim.core.metrics import compute_metrics

        whole = {}
        for name, m in self.motions.items():
            met = compute_metrics(m)
            whole[name] = {"frames": met.frames, "duration": round(met.duration, 3),
                           "skating_ratio": met.skating_ratio,
                           "foot_skate_cm_s": {s: round(f.mean_speed_cm_s, 3) for s, f in met.foot_skate.items()}}
        return {
            "text": self.text,
            "fps": self.fps,
            "synthesis": {"blend": self.blend, "smoothness": self.smoothness},
            "time_table": self.table.to_dict()["elements"],
            **self.result.report(),
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
        path = check_output_path(path)
        names = list(self.motions)
        if len(names) == 1:
            return {names[0]: path}
        return {n: path.with_name(f"{path.stem}_{n}{path.suffix or '.bvh'}") for n in names}

    def outputs(self, *, bvh=None, html=None, glb=None, report=None, plot=None) -> dict[Path, Content]:
        """The files :meth:`save` writes, by path: their bytes (or, for the plot, a function that draws it)."""
        from text2anim.core.bvh import format_bvh

        files: dict[Path, Content] = {}

        def add(path, content) -> None:
            path = check_output_path(path)
            check_distinct([*files, path])
            files[path] = content

        if bvh is not None:
            for name, path in self.bvh_paths(bvh).items():
                add(path, format_bvh(self.motions[name]).encode())
        if html is not None:
            from text2anim.core.viewer import render_html

            add(html, render_html(self.tracks(), self.spans(), title=self.text).encode())
        if glb is not None:
            from text2anim.core.gltf import glb_bytes

            add(glb, glb_bytes(self.tracks()))
        if report is not None:
            add(report, (json.dumps(self.report, ensure_ascii=False, indent=2) + "\n").encode())
        if plot is not None:
            add(check_plot_path(plot), self._plot_writer(Path(plot).suffix))
        return files

    def save(self, *, bvh=None, html=None, glb=None, report=None, plot=None) -> list[Path]:
        """Write the chosen outputs all-or-nothing (:func:`core.atomic.write_all`); returns their paths.

        Two outputs on one path are refused before anything is written; if one
        file cannot be written, none is, and files that existed are left as they were.
        """
        return write_all(self.outputs(bvh=bvh, html=html, glb=glb, report=report, plot=plot))

    def save_bvh(self, path: str | os.PathLike) -> list[Path]:
        """One BVH file per actor (see :meth:`bvh_paths`), all-or-nothing."""
        return self.save(bvh=path)

    def save_html(self, path: str | os.PathLike) -> Path:
        return self.save(html=path)[0]

    def save_glb(self, path: str | os.PathLike) -> Path:
        return self.save(glb=path)[0]

    def save_report(self, path: str | os.PathLike) -> Path:
        return self.save(report=path)[0]

    def save_plot(self, path: str | os.PathLike) -> Path:
        """Upper/lower-body speed curves (Fig. 5 of paper 000) with the blend intervals shaded."""
        return self.save(plot=path)[0]

    def _plot_writer(self, suffix: str):
        """A function drawing the speed plot into the path it is given (format from ``suffix``)."""
        from text2anim.core.plots import plot_speeds

        spans = [s for s in self.spans() if s.kind == "blend"]

        def draw(tmp: Path) -> None:
            # plot_speeds picks the format from the name and writes atomically: draw into a
            # private folder under that suffix, then move the picture onto the temporary.
            with tempfile.TemporaryDirectory(dir=tmp.parent, prefix=".t2a-plot.") as d:
                out = Path(d) / f"plot{suffix}"
                plot_speeds(self.motions, out, spans)
                os.replace(out, tmp)

        return draw


def check_plot_path(path: str | os.PathLike) -> Path:
    """A path for the speed plot: writable (:func:`core.atomic.check_output_path`), its suffix a picture format."""
    from text2anim.core.plots import FORMATS, PlotError

    path = check_output_path(path)
    if path.suffix.lower().lstrip(".") not in FORMATS:
        raise PlotError(f"{path}: cannot tell the image format from the suffix; use one of "
                        + ", ".join("." + f for f in FORMATS))
    return path


def animate(text: str, *, db: MotionDB | str | os.PathLike | None = None, fps: float = 30.0,
            skip_unknown: bool = False, lock_feet: bool = True, sway: bool = True, blend: str = "optimal",
            smoothness: float = 0.5, max_seconds: float = limits.MAX_SECONDS) -> Animation:
    """Analyse ``text``, schedule it, and synthesise one motion per actor.

    Args:
        db: a :class:`motiondb.MotionDB`, a database URL or SQLite path, or
            ``None`` for the default database (the built-in library on first use).
        fps: output frame rate, 1 to 240 frames per second.
        skip_unknown: drop motions whose verb the database lacks instead of failing.
        lock_feet, sway: the synthesis options of paper 003 (foot locking, sway transfer).
        blend: how consecutive motions are joined: ``optimal`` (paper 000, the default),
            ``constraint`` (paper 003), ``pose`` or ``crossfade`` (the common baselines);
            see :mod:`synthesis.engines`.
        smoothness: ``W`` of paper 000 §4.3 for ``optimal``: 0 joins as fast as it can, 1 as
            smoothly as it can.
        max_seconds: the output budget (seconds of animation summed over the actors; see
            :mod:`text2anim.limits`).

    Raises:
        limits.InputTypeError: an argument of the wrong type (a ``TypeError``).
        limits.InputError, limits.LimitError: a value out of range or a text that asks for
            more than the limits allow (``ValueError``), checked before any work starts; and
            the stages' own errors (``ValueError`` too) for a text they cannot serve.
    """
    from text2anim.synthesis.engines import check_method, synthesize_with

    fps, max_seconds, smoothness = check_options(text, db, fps, max_seconds, smoothness,
                                                 skip_unknown=skip_unknown, lock_feet=lock_feet, sway=sway)
    if not isinstance(blend, str):
        raise limits.InputTypeError(f"blend must be a str, not {type(blend).__name__}")
    check_method(blend)
    opened = db if isinstance(db, MotionDB) else MotionDB.open(db)
    try:
        planned = plan_text(text, opened, fps=fps, skip_unknown=skip_unknown, max_seconds=max_seconds)
        tracks = build_tracks(planned, opened, fps)
    finally:
        if opened is not db:
            opened.close()
    result = synthesize_with(blend, tracks, fps, smoothness=smoothness, lock_feet=lock_feet, sway=sway)
    return Animation(planned, result, fps, blend, smoothness)


def check_options(text, db, fps, max_seconds, smoothness: float = 0.5, **flags) -> tuple[float, float, float]:
    """Type and range checks of the API's arguments; returns ``(fps, max_seconds, smoothness)`` as floats."""
    limits.check_text(text)
    if not (db is None or isinstance(db, (MotionDB, str, os.PathLike))):
        raise limits.InputTypeError(f"db must be a MotionDB, a database URL or path, or None, not {type(db).__name__}")
    for name, value in flags.items():
        limits.flag(name, value)
    smooth = limits.real("smoothness", smoothness)
    if not 0.0 <= smooth <= 1.0:
        raise limits.InputError(f"smoothness must be between 0 (time first) and 1 (smoothness first), not {smoothness!r}")
    return limits.check_fps(fps), limits.check_budget(max_seconds), smooth


__all__ = ["Animation", "animate", "build_tracks"]
