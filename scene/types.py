"""The records the scene stage writes: the :class:`Staging` read by synthesis, and the :class:`Scene` that
places the synthesised actors and the things of the text.

Positions are ground positions ``(x, z)`` in metres or world points ``(x, y, z)`` (Y up); headings are
radians about +Y, 0 facing +Z (a heading of +pi/2 faces +X). Times are seconds on the animation's clock.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from text2anim.core.ground import Rigid
from text2anim.core.motion import Motion


@dataclass(frozen=True)
class Spot:
    """Where one actor stands when the animation starts: ``origin`` ``(x, z)`` m, ``heading`` rad."""

    actor: str | None
    origin: tuple[float, float] = (0.0, 0.0)
    heading: float = 0.0


@dataclass(frozen=True)
class Direction:
    """What one element of the time table is directed at: the row's ``target`` (a person by name, a thing or
    a place as written), its ``role`` and ``side`` (docs/language.md §8), and the ``object`` it handles."""

    element: int
    actor: str | None
    verb: str
    target: str | None = None
    role: str | None = None
    side: str | None = None
    object: str | None = None


@dataclass(frozen=True)
class Staging:
    """The staging of a text: one :class:`Spot` per actor, in the order the tracks are laid, and the
    :class:`Direction` of every element that has a target or an object."""

    spots: tuple[Spot, ...]
    directions: tuple[Direction, ...] = ()

    def spot(self, actor: str | None) -> Spot:
        """``actor``'s spot (``KeyError`` if the staging has none for it)."""
        for s in self.spots:
            if s.actor == actor:
                return s
        raise KeyError(actor)


@dataclass(frozen=True)
class Kick:
    """A kick of a thing lying on the floor: the kicker, the kicking foot (``left``/``right``), the frame its
    row starts and the frame the foot strikes (the thing lies under it until then), on the kicker's clock."""

    actor: str | None
    side: str
    start: int
    hit: int


@dataclass(frozen=True)
class Relation:
    """Where one actor should be relative to another at one time, from one element.

    ``kind``: ``face`` (``actor`` at ``distance`` m from ``other``, facing them, and they face back),
    ``behind`` (``actor`` that far behind ``other``, facing the same way), ``beside`` (``actor`` that far
    to ``other``'s left, facing the same way), ``away`` (``actor`` that far in front of ``other``, facing
    away from them: where a motion leaving them starts).
    """

    element: int
    actor: str | None
    other: str
    kind: str
    distance: float
    time: float
    verb: str
    role: str
    #: s: the times over which the actor's facing counts (the middle half of a gesture, whose body may turn
    #: as it throws or bows); ``None``: at ``time`` only
    span: tuple[float, float] | None = None
    #: rad, in the actor's own synthesised frame: where the actor faces at ``time`` when it is not where the
    #: hips face (a throw's or a kick's chest as it sends the thing off)
    facing: float | None = None
    #: s: when an approach sets off (its row's start), ``None`` for any other relation
    start: float | None = None
    #: the effectors (``right_hand``, ``both_hands``) of the actor and the other that meet at ``time`` (a
    #: handshake, a hand-over and its taking): the two are placed hand to hand
    hands: tuple[str, str] | None = None


@dataclass(frozen=True)
class Met:
    """How well a :class:`Relation` holds in the placed scene: the hips' distance (m) and the heading error
    of the actor towards the other (deg, 0 = facing them as the kind asks)."""

    relation: Relation
    distance: float
    heading_error_deg: float

    def to_dict(self) -> dict[str, Any]:
        r = self.relation
        return {"element": r.element, "actor": r.actor, "other": r.other, "kind": r.kind, "verb": r.verb,
                "role": r.role, "time": round(r.time, 3), "distance_m": round(self.distance, 3),
                "wanted_m": round(r.distance, 3), "heading_error_deg": round(self.heading_error_deg, 1)}


@dataclass(frozen=True, eq=False)
class Thing:
    """A thing of the scene (ボール, 椅子): its name as written, a simple shape and where it is at every frame.

    ``shape`` and ``size`` ``(w, h, d)`` m as :data:`output.viewer.types.PROP_SHAPES` draws them (centred on
    the bounding box); ``positions`` ``(T, 3)`` m, ``rotations`` ``(T, 4)`` quaternions (x, y, z, w);
    ``events`` what happened to it and when (``(time s, what)``), for the report; ``known`` is false when
    its shape is a stand-in (a noun the scene has no shape for: a box).
    """

    name: str
    shape: str
    size: tuple[float, float, float]
    color: str
    positions: np.ndarray
    rotations: np.ndarray
    events: tuple[tuple[float, str], ...] = ()
    known: bool = True

    def to_dict(self) -> dict[str, Any]:
        first, last = self.positions[0], self.positions[-1]
        return {"name": self.name, "shape": self.shape, "size": [round(v, 3) for v in self.size],
                "shape_known": self.known, "start": [round(float(v), 3) for v in first],
                "end": [round(float(v), 3) for v in last],
                "events": [{"time": round(t, 3), "what": w} for t, w in self.events]}


@dataclass(frozen=True, eq=False)
class Scene:
    """The placed scene: each actor's motion moved where the relations want it (``rigids``, applied in
    ``motions``), where each actor starts (``spots``), the things, how well each relation holds, and what the
    text names that the scene could not place (``unplaced``: one sentence each)."""

    motions: dict[str | None, Motion]
    rigids: dict[str | None, Rigid]
    spots: tuple[Spot, ...]
    things: tuple[Thing, ...] = ()
    met: tuple[Met, ...] = ()
    unplaced: tuple[str, ...] = ()
    fps: float = 30.0

    @property
    def empty(self) -> bool:
        """Nothing placed: no relation, no thing, nothing said (the report then has no scene)."""
        return not (self.met or self.things or self.unplaced)

    def to_dict(self) -> dict[str, Any]:
        return {"actors": [{"actor": s.actor, "origin": [round(v, 3) for v in s.origin],
                            "heading_deg": round(float(np.degrees(s.heading)), 1)} for s in self.spots],
                "relations": [m.to_dict() for m in self.met],
                "things": [t.to_dict() for t in self.things],
                "unplaced": list(self.unplaced)}
