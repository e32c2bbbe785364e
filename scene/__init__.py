"""The scene: where the people and the things of a text stand, whom they face, what they handle.

Two stages of the pipeline (:mod:`text2anim.pipeline`): before synthesis, :func:`stage` reads the planned
text and writes a :class:`Staging` (each actor's spot at time 0; per element what it is directed at),
which every synthesis engine reads through the tracks; after it, :func:`place` moves each actor's motion
where the relations between the actors want it and places the things (a :class:`Scene`). :func:`cast`
puts a person the text only speaks of into the analysis, waiting. Units: metres, radians about +Y (0
faces +Z).
"""
from __future__ import annotations

from text2anim.core.lazy import lazy_attribute

#: Each name from its module, imported on first use: a time table (``text2anim plan``) casts its persons
#: without loading numpy.
_LAZY = {
    "cast": "cast", "ACTOR_SPACING": "layout", "default_spots": "layout", "place": "place", "stage": "staging",
    "sync_shifts": "timing", "Direction": "types", "Met": "types", "Relation": "types", "Scene": "types",
    "Spot": "types", "Staging": "types", "Thing": "types",
}

__all__ = list(_LAZY)


def __getattr__(name: str):
    return lazy_attribute(__name__, _LAZY, name)
