"""Cooperative cancellation: long work that a caller may abandon stops at its next checkpoint.

A caller that may lose interest (the studio, when the page sends a newer text) runs the work inside
:func:`cancellable` with a ``cancelled()`` callable; the work calls :func:`checkpoint` between its steps
(synthesis: between two joins, and between the join post-pass's regions), which raises :class:`Cancelled`
once ``cancelled()`` is true. Outside :func:`cancellable` a checkpoint costs a context-variable read and
never raises, so the command line and the API run as before. The callable is held in a
:class:`contextvars.ContextVar`, so threads and tasks each see their own.
"""
from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

__all__ = ["Cancelled", "cancellable", "checkpoint"]

_CANCELLED: ContextVar[Callable[[], bool] | None] = ContextVar("text2anim_cancelled", default=None)


class Cancelled(Exception):
    """The work was abandoned by its caller (:func:`cancellable`): nothing it made is kept."""


@contextmanager
def cancellable(cancelled: Callable[[], bool]) -> Iterator[None]:
    """Run the ``with`` block so that its :func:`checkpoint` calls raise :class:`Cancelled` once ``cancelled()``."""
    token = _CANCELLED.set(cancelled)
    try:
        yield
    finally:
        _CANCELLED.reset(token)


def checkpoint() -> None:
    """Raise :class:`Cancelled` if the work this runs in was abandoned (:func:`cancellable`); else nothing."""
    cancelled = _CANCELLED.get()
    if cancelled is not None and cancelled():
        raise Cancelled
