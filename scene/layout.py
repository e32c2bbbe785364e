"""Where actors stand when the text says nothing about it: side by side in a row.

:func:`default_spots` puts ``n`` actors on a row along X, :data:`ACTOR_SPACING` apart and centred on the
origin, every one facing +Z (heading 0): characters never start inside each other.
"""
from __future__ import annotations

from collections.abc import Sequence

from .types import Spot

ACTOR_SPACING = 1.5  # m between actors placed by default


def default_spots(actors: Sequence[str | None], spacing: float = ACTOR_SPACING) -> tuple[Spot, ...]:
    """One spot per actor, in the order given: ``((i - (n - 1) / 2) * spacing, 0)``, heading 0."""
    n = len(actors)
    return tuple(Spot(a, ((i - (n - 1) / 2.0) * spacing, 0.0), 0.0) for i, a in enumerate(actors))
