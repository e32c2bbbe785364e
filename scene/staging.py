"""The scene stage: a planned text's :class:`~scene.types.Staging`."""
from __future__ import annotations

from text2anim.scheduler import Schedule

from .layout import default_spots
from .types import Staging


def stage(planned: Schedule) -> Staging:
    """The staging of ``planned``: its actors, in the order of the time table, on :func:`default_spots`."""
    return Staging(default_spots(planned.table.actors()))
