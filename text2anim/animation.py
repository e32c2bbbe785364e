"""Text → animation: the whole pipeline, and what a user saves from it."""
from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

from motiondb import MotionDB
from synthesis import plan as splan
from synthesis.atomic import OutputError, atomic_write_bytes

from .pipeline import Planned, plan_text

DEFAULT_ACTOR = "default"


def build_tracks(planned: Planned, db: MotionDB, fps: float) -> list[splan.Track]:
    """The synthesis tracks of a time table: clips loaded from ``db`` and resampled to ``fps``."""
    loaded: dict[str, splan.Clip] = {}
    tracks = []
    for actor in planned.table.actors():
        elements = []
        for e in (e for e in planned.table.elements if e.actor == actor):
            info = planned.clips[e.id]
            if info.name not in loaded:
                motion = db.load(info)
                if motion.fps != fps:
                    motion = motion.resample(fps)
                loaded[info.name] = splan.Clip(info.name, motion, tuple(info.core), info.cyclic, info.body_part)
            elements.append(splan.Element(e.id, loaded[info.name], e.start, e.end, e.method, e.prev,
                                          e.speed, e.repeat, e.hold, e.body_part))
        tracks.append(splan.Track(actor, tuple(elements)))
    return tracks


@dataclass(frozen=True, eq=False)
class Animation:
    """The result of :func:`animate`: time table, one motion per actor, the synthesis report.

    ``motions`` maps each actor's name (``"default"`` when the text names none)
    to its :class:`synthesis.Motion`, all on one clock starting at 0 s.
    """

    planned: Planned
    result: object  # synthesis.engine.Result
    fps: float

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
        from synthesis.metrics import compute_metrics

        whole = {}
        for name, m in self.motions.items():
            met = compute_metrics(m)
            whole[name] = {"frames": met.frames, "duration": round(met.duration, 3),
                           "skating_ratio": met.skating_ratio,
                           "foot_skate_cm_s": {s: round(f.mean_speed_cm_s, 3) for s, f in met.foot_skate.items()}}
        return {
            "text": self.text,
            "fps": self.fps,
            "time_table": self.table.to_dict()["elements"],
            **self.result.report(),
            "elements": {str(k): v for k, v in self.result.elements.items()},
            "actors": whole,
            "skipped": list(self.planned.skipped),
            "warnings": list(self.result.warnings),
        }

    # ---------------------------------------------------------------- for the viewer
    def tracks(self):
        from synthesis.viewer.types import Track

        return [Track(name, m) for name, m in self.motions.items()]

    def spans(self):
        """Time-table elements and blend intervals as viewer spans."""
        from synthesis.viewer.types import Span

        out = []
        for e in self.table.elements:
            played = self.result.elements.get(e.id, {})
            start, end = played.get("start", e.start), played.get("end", e.end)
            part = f" [{e.body_part}]" if e.body_part else ""
            out.append(Span(e.actor or DEFAULT_ACTOR, f"{e.id} {e.verb} ({e.method}){part}", start, end, "element"))
        actor_of = {e.id: e.actor or DEFAULT_ACTOR for e in self.table.elements}
        for j in self.result.joins:
            for iv in j.intervals:
                if iv.end > iv.begin:
                    out.append(Span(actor_of.get(j.second, DEFAULT_ACTOR), f"{j.first}→{j.second} {iv.kind}",
                                    iv.begin, iv.end, "blend", iv.part))
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
        from synthesis.bvh import format_bvh

        files = {p: format_bvh(self.motions[n]).encode() for n, p in self.bvh_paths(path).items()}
        return _write_all(files)

    def save_html(self, path: str | os.PathLike) -> Path:
        from synthesis.viewer import render_html

        html = render_html(self.tracks(), self.spans(), title=self.text)
        return _write_all({Path(path): html.encode()})[0]

    def save_glb(self, path: str | os.PathLike) -> Path:
        from synthesis.gltf import glb_bytes

        return _write_all({Path(path): glb_bytes(self.tracks())})[0]

    def save_report(self, path: str | os.PathLike) -> Path:
        text = json.dumps(self.report, ensure_ascii=False, indent=2) + "\n"
        return _write_all({Path(path): text.encode()})[0]

    def save_plot(self, path: str | os.PathLike) -> Path:
        """Upper/lower-body speed curves (Fig. 5 of paper 000) with the blend intervals shaded."""
        from synthesis.plots import plot_speeds

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
            lock_feet: bool = True, sway: bool = True) -> Animation:
    """Analyse ``text``, schedule it, and synthesise one motion per actor.

    Args:
        db: a :class:`motiondb.MotionDB`, a database URL or SQLite path, or
            ``None`` for the default database (the built-in library on first use).
        fps: output frame rate.
        skip_unknown: drop motions whose verb the database lacks instead of failing.
        lock_feet, sway: the synthesis options of paper 003 (foot locking, sway transfer).
    """
    from synthesis.engine import synthesize

    if not fps > 0:
        raise OutputError(f"fps must be positive, not {fps}")
    opened = db if isinstance(db, MotionDB) else MotionDB.open(db)
    try:
        planned = plan_text(text, opened, fps=fps, skip_unknown=skip_unknown)
        tracks = build_tracks(planned, opened, fps)
    finally:
        if opened is not db:
            opened.close()
    result = synthesize(tracks, fps, lock_feet=lock_feet, sway=sway)
    return Animation(planned, result, fps)


__all__ = ["Animation", "animate", "build_tracks"]
