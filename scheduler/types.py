"""What the scheduler reads (clip timing) and writes (the motion time table)."""
from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from text2anim.core.bodyparts import BodyPart
from text2anim.core.methods import ELEMENT_METHODS, Method

__all__ = ["ELEMENT_METHODS", "ClipTiming", "Element", "Manner", "Method", "TimeTable"]



@dataclass(frozen=True)
class ClipTiming:
    """The metadata of a retrieved clip that timing depends on (seconds of clip time).

    Attributes:
        name: the clip's name in the database.
        duration: its length.
        core: ``(begin, end)`` of its core interval (コア区間).
        cyclic: the clip loops.
        body_part: the group a partial clip is declared for; ``None`` for whole-body.
        foot_moving: ``((begin, end), ...)`` intervals where one foot is off the ground, sorted.
        character: the character (skeleton) the clip belongs to.
        cycle_steps: steps in one cycle of a looping clip (a walk's cycle: 2); 0 for any other.
        style: the style the clip was performed in (``core.styles.STYLES``), ``None`` for a neutral one.
    """

    name: str
    duration: float
    core: tuple[float, float]
    cyclic: bool = False
    body_part: BodyPart | None = None
    foot_moving: tuple[tuple[float, float], ...] = ()
    character: str = "default"
    cycle_steps: int = 0
    style: str | None = None


@dataclass(frozen=True)
class Manner:
    """How a row is done (docs/language.md §2.1): the text's ``word``, its ``style`` (``None``: a word of no
    style, such as にこにこ) and ``intensity``, and ``by`` what it is played: ``"clip"`` (a clip of that
    style), ``"modifiers"`` (the synthesis changes a neutral clip) or ``None`` (not shown)."""

    word: str
    style: str | None
    intensity: float
    by: str | None

    def to_dict(self) -> dict:
        return {"word": self.word, "style": self.style, "intensity": self.intensity, "by": self.by}


@dataclass(frozen=True)
class Element:
    """One row of the motion time table (Table 1 of paper 003), times in seconds on the actor's track.

    ``body_part`` is set for a composition: the part taken from this element's clip.
    ``speed``, ``repeat``, ``hold`` and ``delay`` say how the clip is played. ``object`` is the thing the
    motion handles (ボール) and ``target``, ``target_role``, ``target_side`` whom or what it is directed at
    (docs/language.md §8), as the analysis found them; the scene stage places them.
    """

    id: int
    actor: str | None
    verb: str
    clip: str
    method: Method
    prev: int | None
    start: float
    end: float
    body_part: str | None = None
    speed: float = 1.0
    repeat: int = 1
    hold: bool = False
    delay: float | None = None
    object: str | None = None
    target: str | None = None
    target_role: str | None = None
    target_side: str | None = None
    manner: Manner | None = None

    def to_dict(self) -> dict:
        """The row's JSON; ``object``, the target fields and ``manner`` only where the text gives them."""
        d: dict[str, Any] = {
            "id": self.id, "actor": self.actor, "verb": self.verb, "clip": self.clip,
            "method": self.method, "prev": self.prev,
            "start": round(self.start, 3), "end": round(self.end, 3), "body_part": self.body_part,
            "speed": self.speed, "repeat": self.repeat, "hold": self.hold,
        }
        if self.object is not None:
            d["object"] = self.object
        if self.target is not None:
            d.update(target=self.target, target_role=self.target_role, target_side=self.target_side)
        if self.manner is not None:
            d["manner"] = self.manner.to_dict()
        return d


@dataclass(frozen=True)
class TimeTable:
    """The motion time table: every element, ordered by id."""

    text: str
    fps: float
    elements: tuple[Element, ...]

    def to_dict(self) -> dict:
        return {"text": self.text, "fps": self.fps, "elements": [e.to_dict() for e in self.elements]}

    def to_json(self, indent: int | None = 2) -> str:
        return json.dumps(self.to_dict(), ensure_ascii=False, indent=indent)

    def actors(self) -> list[str | None]:
        """Actors in order of first appearance."""
        seen: list[str | None] = []
        for e in self.elements:
            if e.actor not in seen:
                seen.append(e.actor)
        return seen

    def element(self, id: int) -> Element:
        return next(e for e in self.elements if e.id == id)
