"""The glue between the stages: text → analysis → time table (clips from the database).

Each stage keeps to its own records; this module turns one stage's records
into the next one's (``ClipInfo`` → ``ClipTiming`` for the scheduler, and
later ``ClipInfo`` + frames → ``synthesis.plan.Clip``).
"""
from __future__ import annotations

from dataclasses import dataclass

from text2anim import nlp
from text2anim.motiondb import ClipInfo, MotionDB, UnknownVerbError
from text2anim.nlp.types import Analysis, MotionSpec
from text2anim.scheduler import ClipTiming, ScheduleError, TimeTable, plan, without
from text2anim.core.bodyparts import GROUPS

from . import limits, postures


@dataclass(frozen=True)
class Planned:
    """A text's analysis and time table, with the clip chosen for each element id."""

    analysis: Analysis
    table: TimeTable
    clips: dict[int, ClipInfo]
    skipped: tuple[str, ...] = ()


def foot_moving(info: ClipInfo) -> tuple[tuple[float, float], ...]:
    """Intervals (s) where one foot is off the ground: the gaps between each foot's contacts."""
    out = []
    for side in ("left", "right"):
        cursor = 0
        for a, b in info.contacts(side):
            if a > cursor:
                out.append((cursor / info.fps, a / info.fps))
            cursor = b
        if cursor < info.frames:
            out.append((cursor / info.fps, info.frames / info.fps))
    return tuple(sorted(out))


def timing(info: ClipInfo) -> ClipTiming:
    return ClipTiming(info.name, info.duration, tuple(info.core), info.cyclic, info.body_part,
                      foot_moving(info), info.character)


class _Finder:
    """Retrieves the best clip for each motion and remembers it."""

    def __init__(self, db: MotionDB):
        self.db = db
        self.chosen: dict[int, ClipInfo] = {}

    def search(self, spec: MotionSpec, prefer: str | None) -> list[ClipInfo]:
        part = spec.body_part if spec.body_part in GROUPS else None
        try:
            hits = self.db.search(spec.verb, object=spec.object, body_part=part, prefer_character=prefer)
        except UnknownVerbError:
            if not spec.reading or spec.reading == spec.verb:
                raise
            # A spelling the database lacks may share a reading with one it has; if not, the
            # error about the verb as written (with its suggestions) is the one to show.
            try:
                hits = self.db.search(spec.reading, object=spec.object, body_part=part, prefer_character=prefer)
            except UnknownVerbError:
                hits = None
            if hits is None:
                return self.db.search(spec.verb)  # raises UnknownVerbError for the written verb
        if not hits and part:
            hits = self.db.search(spec.verb, object=spec.object, prefer_character=prefer)
        return hits

    def __call__(self, spec: MotionSpec, prefer: str | None) -> ClipTiming:
        hits = self.search(spec, prefer)
        if not hits:
            raise ScheduleError(f"the motion database has {spec.verb} but no clip of it fits"
                                + (f" the {spec.body_part}" if spec.body_part else ""))
        self.chosen[spec.id] = hits[0]
        return timing(hits[0])


def unknown_motions(analysis: Analysis, db: MotionDB) -> dict[int, UnknownVerbError]:
    """Motions whose verb no clip in ``db`` has, by motion id."""
    finder = _Finder(db)
    out = {}
    for spec in analysis.motions:
        try:
            finder.search(spec, None)
        except UnknownVerbError as exc:
            out[spec.id] = exc
    return out


def plan_text(text: str, db: MotionDB, *, fps: float = 30.0, skip_unknown: bool = False,
              max_seconds: float = limits.MAX_SECONDS) -> Planned:
    """Analyse ``text`` and schedule its motions with clips from ``db``.

    Unknown verbs raise :class:`UnknownVerbError` (naming the nearest verbs the
    database has) unless ``skip_unknown``, which drops those motions. A text
    that asks for more than :mod:`text2anim.limits` allows (output over
    ``max_seconds``) raises :class:`limits.LimitError` before any frame is made.
    """
    limits.check_text(text)
    analysis = nlp.analyze(text)
    limits.check_analysis(analysis, max_seconds)
    unknown = unknown_motions(analysis, db)
    skipped: tuple[str, ...] = ()
    if unknown:
        if not skip_unknown:
            raise next(iter(unknown.values()))
        skipped = tuple(m.verb for m in analysis.motions if m.id in unknown)
        analysis = without(analysis, set(unknown))
        if not analysis.motions:
            raise ScheduleError("no motion of this text is in the motion database: " + "、".join(skipped))
    finder = _Finder(db)
    table = plan(analysis, finder, fps)
    # posture continuity: clips whose postures meet, bridging clips where none can (text2anim.postures)
    arranged = postures.arrange(analysis, table, finder.chosen, finder.search, db)
    if arranged.changed:
        analysis, finder = arranged.analysis, _Finder(db)
        table = plan(analysis, arranged.finder(finder), fps)
    limits.check_table(table, fps, max_seconds)
    return Planned(analysis, table, dict(finder.chosen), skipped)
