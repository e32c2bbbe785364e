"""The scene: where the people and the things of a text stand, whom they face, what they handle.

Two stages of the pipeline (:mod:`text2anim.pipeline`): before synthesis, :func:`stage` reads the planned
text and writes a :class:`Staging` (each actor's spot at time 0; per element what it is directed at),
which every synthesis engine reads through the tracks; after it, :func:`place` moves each actor's motion
where the relations between the actors want it and places the things (a :class:`Scene`). :func:`cast`
puts a person the text only speaks of into the analysis, waiting. Units: metres, radians about +Y (0
faces +Z).
"""
from __future__ import annotations

from .cast import cast
from .layout import ACTOR_SPACING, default_spots
from .place import place
from .staging import stage
from .timing import sync_shifts
from .types import Direction, Met, Relation, Scene, Spot, Staging, Thing

__all__ = ["ACTOR_SPACING", "Direction", "Met", "Relation", "Scene", "Spot", "Staging", "Thing", "cast",
           "default_spots", "place", "stage", "sync_shifts"]
