"""The scene stage: a planned text's :class:`~scene.types.Staging`."""
from __future__ import annotations

from text2anim.scheduler import Schedule

from .layout import default_spots
from .types import Direction, Staging


def stage(planned: Schedule) -> Staging:
    """The staging of ``planned``: its actors, in the order of the time table, on :func:`default_spots`;
    the :class:`Direction` of each row that has a target or an object."""
    rows = planned.table.elements
    directions = tuple(Direction(e.id, e.actor, e.verb, e.target, e.target_role, e.target_side, e.object)
                       for e in rows if e.target is not None or e.object is not None)
    return Staging(default_spots(planned.table.actors()), directions)
