"""Text → :class:`Planned`: analyse, settle the verbs the database lacks, schedule (the pipeline's first stage).

This module only calls the stages in order. The rules that write the time table
are the scheduler's (:func:`scheduler.schedule`); the clips it is offered come
from the database through :class:`clip_search.DatabaseClips`.
"""
from __future__ import annotations

from dataclasses import dataclass

from text2anim import nlp
from text2anim.motiondb import ClipInfo, MotionDB
from text2anim.scheduler import Schedule, ScheduleError, schedule, without

from . import limits
from .clip_search import DatabaseClips, unknown_motions


@dataclass(frozen=True)
class Planned(Schedule[ClipInfo]):
    """A text's analysis and time table, with the clip chosen for each element id.

    ``fillers`` are the ids of the elements added to fill the waits (stops, idles:
    :mod:`scheduler.fillers`); ``skipped`` the verbs dropped as unknown; ``mirrored`` the
    element ids whose clip plays mirrored and ``repeats``, for a repeated element, the clip
    of each repetition (co-actors and repeats are not clones: :mod:`scheduler.variants`).
    """

    skipped: tuple[str, ...] = ()
    fallbacks: tuple = ()  # fallback.Substitution per motion animated with a verb nearest in meaning


def plan_text(text: str, db: MotionDB, *, fps: float = 30.0, skip_unknown: bool = False,
              fallback: str = "strict", max_seconds: float = limits.MAX_SECONDS, edits=()) -> Planned:
    """Analyse ``text`` and schedule its motions with clips from ``db``, the waits filled.

    The table holds everything that will play: the text's motions, the clips
    bridging postures (:mod:`scheduler.arrangement`) and the stops and idles in
    the waits (:mod:`scheduler.fillers`). Unknown verbs raise :class:`UnknownVerbError`
    (naming every missing verb as written and the database verbs nearest in meaning)
    unless ``skip_unknown``, which drops those motions, or ``fallback="nearest"``, which
    animates each with the database verb nearest in meaning (:mod:`text2anim.fallback`).
    A text that asks for more than :mod:`text2anim.limits` allows (output over
    ``max_seconds``) raises :class:`limits.LimitError` before any frame is made. ``edits``
    (:class:`text2anim.edits.Edit`) change the analysis before it is scheduled (the studio's timeline).
    """
    limits.check_text(text)
    with db.memoised():  # the same motions are searched again by each step below
        return _plan(text, db, fps, skip_unknown, fallback, max_seconds, tuple(edits))


def _plan(text: str, db: MotionDB, fps: float, skip_unknown: bool, fallback: str, max_seconds: float,
          edits: tuple = ()) -> Planned:
    analysis = nlp.analyze(text)
    if edits:  # the studio's timeline; a command plans the text as written, without loading the edits
        from .edits import apply_edits

        analysis = apply_edits(analysis, edits)
    limits.check_analysis(analysis, max_seconds)
    analysis = _cast(analysis, db)
    unknown = unknown_motions(analysis, db)
    skipped: tuple[str, ...] = ()
    subs: tuple = ()
    if unknown and fallback == "nearest":
        from .fallback import substitute

        analysis, subs = substitute(analysis, unknown, db)
        unknown = {}
    if unknown:
        if not skip_unknown:
            from .fallback import unknown_error

            raise unknown_error(analysis, unknown, db)
        skipped = tuple(m.verb for m in analysis.motions if m.id in unknown)
        analysis = without(analysis, set(unknown))
        if not analysis.motions:
            raise ScheduleError("no motion of this text is in the motion database: " + "、".join(skipped))
    done = schedule(analysis, DatabaseClips(db), fps, check=lambda table: limits.check_table(table, fps, max_seconds))
    return Planned(done.analysis, done.table, done.clips, done.fillers, done.mirrored, done.repeats,
                   skipped=skipped, fallbacks=subs)


def _cast(analysis, db: MotionDB):
    """:func:`scene.cast`: a person who is only a target waits in the scene; not when ``db`` has no idle
    (a database of the user's own without 待つ clips: they are left out, as before)."""
    from text2anim.scene.cast import cast

    casted = cast(analysis)
    if casted is analysis:
        return analysis
    added = {m.id for m in casted.motions} - {m.id for m in analysis.motions}
    return analysis if set(unknown_motions(casted, db)) & added else casted
