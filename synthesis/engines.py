"""One entry point for every joiner of consecutive motions: ``synthesize_with(method, tracks, fps, ...)``.

=============== =================================================================
method          what joins consecutive whole-body motions
=============== =================================================================
``optimal``     paper 000, optimal blending (:mod:`synthesis.optimal`), default
``constraint``  paper 003 / [6], constraint-based (:mod:`synthesis.engine`)
``pose``        closest poses, fixed-length linear blend (:mod:`synthesis.baselines`)
``crossfade``   fixed-length linear crossfade at the start (:mod:`synthesis.baselines`)
=============== =================================================================

Compositions (a body part laid onto a motion) are the same for all of them.
All return a :class:`synthesis.engine.Result`.
"""
from __future__ import annotations

from collections.abc import Sequence

from .plan import Track

METHODS = ("optimal", "constraint", "pose", "crossfade")
DEFAULT = "optimal"


class UnknownMethodError(ValueError):
    """A joining method that does not exist."""

    user_facing = True


def check_method(method: str) -> str:
    if method not in METHODS:
        raise UnknownMethodError(f"unknown blending method {method!r}; choose one of {', '.join(METHODS)}")
    return method


def synthesize_with(method: str, tracks: Sequence[Track], fps: float = 30.0, smoothness: float = 0.5,
                    lock_feet: bool = True, sway: bool = True):
    """Tracks → :class:`~synthesis.engine.Result` with the joiner ``method`` (see the table above).

    ``smoothness`` (0 time first … 1 smoothness first) is used by ``optimal`` only; ``lock_feet`` by
    ``optimal`` and ``constraint`` (the baselines never lock feet: that is what they stand for).
    """
    check_method(method)
    if not 0.0 <= float(smoothness) <= 1.0:
        raise UnknownMethodError(f"smoothness must be between 0 and 1, got {smoothness}")
    if method == "optimal":
        from .optimal import synthesize_optimal

        return synthesize_optimal(tracks, fps, smoothness, lock_feet=lock_feet, sway=sway)
    if method == "constraint":
        from .engine import synthesize

        return synthesize(tracks, fps, lock_feet=lock_feet, sway=sway)
    from .baselines import synthesize_baseline

    return synthesize_baseline(tracks, fps, method, sway=sway)
