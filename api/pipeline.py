"""The pipeline: one ordered list of stages (:data:`STAGES`) over one piece of :class:`Work`.

Like spaCy's pipeline over one document, each stage takes the work so far and returns it with its own
part filled in; :func:`text2anim.animate` runs them all, :func:`text2anim.plan` the first, and
``text2anim compare`` runs them up to the tracks once, then the rest once per joining method:

============= =============================================================================
``plan``      analyse, settle the verbs the database lacks, schedule (:func:`plan_text`)
``staging``   where each actor starts, what each row is directed at (:func:`scene.stage`)
``tracks``    each row's clip loaded from the database (:func:`text2anim.tracks.build_tracks`)
``manner``    each row's manner made from its clip where no clip of it exists (:mod:`text2anim.manners`)
``synthesis`` the motions, by the asked joiner (:func:`synthesis.registry.synthesize_with`)
``scene``     the actors moved where the text wants them, the things placed (:func:`scene.place`)
============= =============================================================================

This module only calls the stages in order; :class:`Planned` and :func:`plan_text` (the first stage)
are :mod:`text2anim.planning`'s, named here too.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from text2anim.motiondb import MotionDB

from . import limits
from .planning import Planned, plan_text

if TYPE_CHECKING:
    from text2anim.scene import Scene, Staging
    from text2anim.synthesis.result import Result


@dataclass(frozen=True)
class Request:
    """What the user asked for: the text and every option of :func:`text2anim.animate` (checked there)."""

    text: str
    fps: float = 30.0
    skip_unknown: bool = False
    fallback: str = "strict"
    max_seconds: float = limits.MAX_SECONDS
    edits: tuple = ()
    blend: str = "optimal"
    smoothness: float = 0.5
    lock_feet: bool = True
    sway: bool = True


@dataclass(frozen=True)
class Work:
    """One text on its way through :data:`STAGES`: each stage fills its own field.

    ``db`` is needed by ``plan``, ``staging`` and ``tracks`` only (the caller may close it after them).
    """

    request: Request
    db: MotionDB | None = None
    timing: tuple = ()  # edits of the time table the staging asked for (two people's contact instants met)
    planned: Planned | None = None
    staging: Staging | None = None
    tracks: tuple = ()
    manners: tuple = ()  # manners.Styled per row with a manner: what the manner stage did
    result: Result | None = None
    scene: Scene | None = None


def _plan_stage(work: Work) -> Work:
    r = work.request
    assert work.db is not None
    return replace(work, planned=plan_text(r.text, work.db, fps=r.fps, skip_unknown=r.skip_unknown,
                                           fallback=r.fallback, max_seconds=r.max_seconds,
                                           edits=r.edits + work.timing))


def _staging_stage(work: Work) -> Work:
    """The staging; first, when two people's contact instants do not meet, the text planned again with the
    later one started later (:func:`scene.sync_shifts`, kept as edits of the time table)."""
    from text2anim.scene.staging import stage
    from text2anim.scene.timing import sync_shifts

    from .edits import Edit, apply_edits, occurrences
    from .tracks import contact_instants

    assert work.planned is not None and work.db is not None
    planned = work.planned
    shifts = sync_shifts(planned.table.elements, planned.analysis.constraints,
                         contact_instants(planned, work.db, work.request.fps))
    if shifts:
        from text2anim import nlp

        names = {i: key for key, i in occurrences(apply_edits(nlp.analyze(work.request.text),
                                                              work.request.edits)).items()}
        edits = tuple(Edit(names[i][0], names[i][1], shift=s) for i, s in sorted(shifts.items()) if i in names)
        work = _plan_stage(replace(work, timing=work.timing + edits))
        assert work.planned is not None
        planned = work.planned
    return replace(work, staging=stage(planned))


def _tracks_stage(work: Work) -> Work:
    from .tracks import build_tracks

    assert work.db is not None and work.planned is not None and work.staging is not None
    return replace(work, tracks=tuple(build_tracks(work.planned, work.db, work.request.fps, work.staging)))


def _manner_stage(work: Work) -> Work:
    from .manners import restyle_tracks

    assert work.planned is not None
    tracks, styled = restyle_tracks(work.planned.table, work.tracks)
    return replace(work, tracks=tracks, manners=styled)


def _synthesis_stage(work: Work) -> Work:
    from text2anim.synthesis.registry import synthesize_with

    r = work.request
    return replace(work, result=synthesize_with(r.blend, work.tracks, r.fps, smoothness=r.smoothness,
                                                lock_feet=r.lock_feet, sway=r.sway))


def _place_stage(work: Work) -> Work:
    from text2anim.scene.place import place

    from .placed import moved_result, played_rows

    assert work.planned is not None and work.result is not None and work.staging is not None
    scene = place(work.staging, played_rows(work.planned.table, work.result), work.result.motions, work.request.fps)
    return replace(work, scene=scene, result=moved_result(work.result, scene.motions, scene.rigids))


#: The stages in order: (name, stage). Each takes the :class:`Work` so far and returns it with its part.
STAGES: tuple[tuple[str, Callable[[Work], Work]], ...] = (
    ("plan", _plan_stage), ("staging", _staging_stage), ("tracks", _tracks_stage), ("manner", _manner_stage),
    ("synthesis", _synthesis_stage), ("scene", _place_stage),
)
NAMES = tuple(name for name, _ in STAGES)


def run(work: Work, *, after: str | None = None, until: str | None = None) -> Work:
    """``work`` through the stages after the stage ``after`` (from the first when ``None``) up to and
    including ``until`` (to the last when ``None``)."""
    first = NAMES.index(after) + 1 if after is not None else 0
    last = NAMES.index(until) + 1 if until is not None else len(NAMES)
    for _, step in STAGES[first:last]:
        work = step(work)
    return work


def animation(work: Work) -> Any:
    """The :class:`~text2anim.animation.Animation` of a work that went through every stage."""
    from .animation import Animation

    r = work.request
    assert work.planned is not None and work.result is not None
    return Animation(work.planned, work.result, r.fps, r.blend, r.smoothness, work.tracks, work.staging, work.scene,
                     work.manners)


__all__ = ["NAMES", "STAGES", "Planned", "Request", "Work", "animation", "plan_text", "run"]
