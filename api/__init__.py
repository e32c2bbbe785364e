"""text2anim: Japanese text to character animation.

The public Python API; the command line is a thin layer over it::

    import text2anim
    anim = text2anim.animate("太郎は走って、ボールを蹴る。そして喜ぶ。")
    anim.save_bvh("out.bvh"); anim.save_html("out.html")
    print(anim.table.to_json())

``text2anim.plan`` stops after the time table.
"""
from __future__ import annotations

__version__ = "0.1.0"


def plan(text: str, db=None, *, fps: float = 30.0, skip_unknown: bool = False):
    """Analyse ``text`` and build its motion time table with clips from ``db``.

    ``db`` is a :class:`motiondb.MotionDB`, a database URL or path, or ``None``
    for the default database (created with the built-in library on first use).
    """
    from text2anim.motiondb import MotionDB

    from .pipeline import plan_text

    if isinstance(db, MotionDB):
        return plan_text(text, db, fps=fps, skip_unknown=skip_unknown)
    with MotionDB.open(db) as opened:
        return plan_text(text, opened, fps=fps, skip_unknown=skip_unknown)


def animate(text: str, db=None, **options):
    """Text to animation; see :func:`text2anim.animation.animate` for the options."""
    from .animation import animate as _animate

    return _animate(text, db, **options)
