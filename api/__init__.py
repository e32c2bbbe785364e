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

if TYPE_CHECKING:  # `import text2anim` stays light: the stages load on first use
    from text2anim.animation import Animation
    from text2anim.motiondb import MotionDB
    from text2anim.pipeline import Planned

__version__ = "0.1.0"


def plan(text: str, db: MotionDB | str | os.PathLike | None = None, *, fps: float = 30.0,
         skip_unknown: bool = False, fallback: str = "strict") -> Planned:
    """Analyse ``text`` and build its motion time table with clips from ``db``.

    ``db`` is a :class:`motiondb.MotionDB`, a database URL or path, or ``None``
    for the default database (created with the built-in library on first use).
    """
    from text2anim.motiondb import MotionDB

    from .pipeline import plan_text

    if isinstance(db, MotionDB):
        return plan_text(text, db, fps=fps, skip_unknown=skip_unknown, fallback=fallback)
    with MotionDB.open(db) as opened:
        return plan_text(text, opened, fps=fps, skip_unknown=skip_unknown, fallback=fallback)


def animate(text: str, db: MotionDB | str | os.PathLike | None = None, *, fps: float = 30.0,
            skip_unknown: bool = False, lock_feet: bool = True, sway: bool = True, blend: str = "optimal",
            smoothness: float = 0.5, fallback: str = "strict") -> Animation:
    """Text to animation: :func:`text2anim.animation.animate`, which documents the options."""
    from .animation import animate as _animate

    return _animate(text, db, fps=fps, skip_unknown=skip_unknown, lock_feet=lock_feet, sway=sway, blend=blend,
                    smoothness=smoothness, fallback=fallback)
