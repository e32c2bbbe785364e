"""The records the scene stage writes: :class:`Staging` and its :class:`Spot` s.

Positions are ground positions ``(x, z)`` in metres, headings radians about +Y, 0 facing +Z (Y up,
right-handed: a heading of +pi/2 faces +X).
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Spot:
    """Where one actor stands when the animation starts: ``origin`` ``(x, z)`` m, ``heading`` rad."""

    actor: str | None
    origin: tuple[float, float] = (0.0, 0.0)
    heading: float = 0.0


@dataclass(frozen=True)
class Staging:
    """The staging of a text: one :class:`Spot` per actor, in the order the tracks are laid."""

    spots: tuple[Spot, ...]

    def spot(self, actor: str | None) -> Spot:
        """``actor``'s spot (``KeyError`` if the staging has none for it)."""
        for s in self.spots:
            if s.actor == actor:
                return s
        raise KeyError(actor)

    def to_dict(self) -> dict:
        return {"actors": [{"actor": s.actor, "origin": [round(v, 4) for v in s.origin],
                            "heading": round(s.heading, 4)} for s in self.spots]}
