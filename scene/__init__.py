"""The scene: where the people and the things of a text stand, whom they face, what they handle.

A stage of its own between the time table (:mod:`scheduler`) and synthesis: :func:`stage` reads the
planned text and writes a :class:`Staging` (each actor's spot at time 0; per element what it is directed
at), which every synthesis engine reads through the tracks. Units: metres, radians about +Y (0 faces +Z).
"""
from __future__ import annotations

from .layout import ACTOR_SPACING, default_spots
from .staging import stage
from .types import Spot, Staging

__all__ = ["ACTOR_SPACING", "Spot", "Staging", "default_spots", "stage"]
