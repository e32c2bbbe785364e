"""text2anim: Japanese text to character animation.

The public Python API; the command line is a thin layer over it::

    import text2anim
    anim = text2anim.animate("太郎は走って、ボールを蹴る。そして喜ぶ。")
    anim.save_bvh("out.bvh"); anim.save_html("out.html")
    print(anim.table.to_json())

``text2anim.plan`` stops after the time table.
"""
from __future__ import annotations

import os
from dataclasses import replace
from typing import TYPE_CHECKING

from . import limits
from .limits import InputError, InputTypeError, LimitError

if TYPE_CHECKING:  # `import text2anim` stays light: the stages load on first use
    from text2anim.animation import Animation
    from text2anim.motiondb import MotionDB
    from text2anim.planning import Planned

__version__ = "0.1.0"


def plan(text: str, db: MotionDB | str | os.PathLike | None = None, *, fps: float = 30.0,
         skip_unknown: bool = False, fallback: str = "strict", max_seconds: float = limits.MAX_SECONDS) -> Planned:
    """Analyse ``text`` and build its motion time table with clips from ``db``.

    ``db`` is a :class:`motiondb.MotionDB`, a database URL or path, or ``None``
    for the default database (created with the built-in library on first use); a URL,
    path or the default is opened once and kept open for later calls (:mod:`text2anim.databases`).
    The arguments are checked as :func:`animate` checks them (:mod:`text2anim.limits`).
    """
    from .databases import database
    from .planning import plan_text

    fps, max_seconds, _ = limits.check_options(text, db, fps, max_seconds, skip_unknown=skip_unknown, fallback=fallback)
    with database(db) as opened:
        return plan_text(text, opened, fps=fps, skip_unknown=skip_unknown, fallback=fallback,
                         max_seconds=max_seconds)


def animate(text: str, *, db: MotionDB | str | os.PathLike | None = None, fps: float = 30.0,
            skip_unknown: bool = False, lock_feet: bool = True, sway: bool = True, blend: str = "optimal",
            smoothness: float = 0.5, fallback: str = "strict", max_seconds: float = limits.MAX_SECONDS,
            edits=()) -> Animation:
    """Analyse ``text``, schedule it, and synthesise one motion per actor.

    Args:
        db: a :class:`motiondb.MotionDB`, a database URL or SQLite path, or
            ``None`` for the default database (the built-in library on first use); a URL,
            path or the default is opened once and kept open for later calls (:mod:`text2anim.databases`).
        fps: output frame rate, 1 to 240 frames per second.
        skip_unknown: drop motions whose verb the database lacks instead of failing.
        fallback: ``nearest`` animates such a motion with the database verb nearest in
            meaning (said in ``planned.fallbacks`` and the report); ``strict`` (default) refuses.
        lock_feet, sway: the synthesis options of paper 003 (foot locking, sway transfer).
        blend: how consecutive motions are joined: ``optimal`` (paper 000, the default),
            ``constraint`` (paper 003), ``pose`` or ``crossfade`` (the common baselines);
            see :mod:`synthesis.registry`.
        smoothness: ``W`` of paper 000 §4.3 for ``optimal``: 0 joins as fast as it can, 1 as
            smoothly as it can.
        max_seconds: the output budget (seconds of animation summed over the actors; see
            :mod:`text2anim.limits`).
        edits: :class:`text2anim.edits.Edit` s of the time table (a motion moved, stretched or
            joined another way), kept as constraints on the text's analysis.

    Raises:
        limits.InputTypeError: an argument of the wrong type (a ``TypeError``).
        limits.InputError, limits.LimitError: a value out of range or a text that asks for
            more than the limits allow (``ValueError``), checked before any work starts; and
            the stages' own errors (``ValueError`` too) for a text they cannot serve.
    """
    from text2anim.synthesis.registry import check_method

    from .databases import database
    from .pipeline import Request, Work, animation, run

    fps, max_seconds, smoothness = limits.check_options(text, db, fps, max_seconds, smoothness, fallback,
                                                        skip_unknown=skip_unknown, lock_feet=lock_feet, sway=sway)
    if not isinstance(blend, str):
        raise limits.InputTypeError(f"blend must be a str, not {type(blend).__name__}")
    check_method(blend)
    request = Request(text, fps, skip_unknown, fallback, max_seconds, tuple(edits), blend, smoothness, lock_feet, sway)
    with database(db) as opened:  # kept open for the next call with the same URL (text2anim.databases)
        work = run(Work(request, opened), until="tracks")
    return animation(run(replace(work, db=None), after="tracks"))


__all__ = ["InputError", "InputTypeError", "LimitError", "__version__", "animate", "limits", "plan"]
