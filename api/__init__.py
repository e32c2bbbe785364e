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
from typing import TYPE_CHECKING

from . import limits
from .limits import InputError, InputTypeError, LimitError

if TYPE_CHECKING:  # `import text2anim` stays light: the stages load on first use
    from text2anim.animation import Animation
    from text2anim.motiondb import MotionDB
    from text2anim.pipeline import Planned

__version__ = "0.1.0"


def plan(text: str, db: MotionDB | str | os.PathLike | None = None, *, fps: float = 30.0,
         skip_unknown: bool = False, fallback: str = "strict", max_seconds: float = limits.MAX_SECONDS) -> Planned:
    """Analyse ``text`` and build its motion time table with clips from ``db``.

    ``db`` is a :class:`motiondb.MotionDB`, a database URL or path, or ``None``
    for the default database (created with the built-in library on first use).
    The arguments are checked as :func:`animate` checks them (:mod:`text2anim.limits`).
    """
    from text2anim.motiondb import MotionDB

    from .animation import check_options
    from .pipeline import plan_text

    fps, max_seconds, _ = check_options(text, db, fps, max_seconds, skip_unknown=skip_unknown, fallback=fallback)
    if isinstance(db, MotionDB):
        return plan_text(text, db, fps=fps, skip_unknown=skip_unknown, fallback=fallback, max_seconds=max_seconds)
    with MotionDB.open(db) as opened:
        return plan_text(text, opened, fps=fps, skip_unknown=skip_unknown, fallback=fallback,
                         max_seconds=max_seconds)


def animate(text: str, *, db: MotionDB | str | os.PathLike | None = None, fps: float = 30.0,
            skip_unknown: bool = False, lock_feet: bool = True, sway: bool = True, blend: str = "optimal",
            smoothness: float = 0.5, fallback: str = "strict", max_seconds: float = limits.MAX_SECONDS) -> Animation:
    """Text to animation; see :func:`text2anim.animation.animate` for the arguments and errors."""
    from .animation import animate as _animate

    return _animate(text, db=db, fps=fps, skip_unknown=skip_unknown, lock_feet=lock_feet, sway=sway,
                    blend=blend, smoothness=smoothness, fallback=fallback, max_seconds=max_seconds)


__all__ = ["InputError", "InputTypeError", "LimitError", "__version__", "animate", "limits", "plan"]
