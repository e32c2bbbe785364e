"""What every engine returns: one motion per actor, a report per join and per element (:class:`Result`).

The output half of the engines' contract (the input half is :mod:`synthesis.tracks`): a
:class:`JoinReport` per join (docs/timetable.md §2), an :class:`ElementReport` per element of the
time table, and the warnings. Times are seconds on the animation's clock.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from text2anim.core.motion import Motion


@dataclass(frozen=True)
class BlendInterval:
    """One blend of a join: body ``part`` (``lower``/``upper``/``whole`` or a group), the blend
    ``kind`` (``motion-motion``, ``pose-pose``, ``motion-pose``, ``pose-motion``) and its track times (s)."""

    part: str
    kind: str
    begin: float
    end: float


@dataclass(frozen=True)
class JoinReport:
    """What the synthesizer decided for one join (docs/timetable.md §2)."""

    first: int
    second: int
    method: str
    blend: str
    intervals: tuple[BlendInterval, ...]
    cost: dict[str, float] | None = None
    metrics: dict[str, Any] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()


@dataclass(frozen=True)
class Placement:
    """Where an element was put: turned by ``yaw`` (rad about +Y), then moved by ``(x, z)`` (m)."""

    yaw: float
    x: float
    z: float


@dataclass(frozen=True)
class ElementReport:
    """What became of one element of the time table.

    A whole-body element has ``start``/``end`` as played (s), its ``core`` (s on the track), its
    ``placement`` and ``core_fidelity_cm`` (largest joint error in its core against the clip; and
    ``core_fidelity_untouched_cm``, the legs only, when a composition changed part of it). A
    composition has ``start``/``end``, the ``part`` it switched and ``part_fidelity_cm``. An element
    not executed has only its ``reason``.
    """

    actor: str | None
    start: float | None = None
    end: float | None = None
    core: tuple[float, float] | None = None
    placement: Placement | None = None
    core_fidelity_cm: float | None = None
    core_fidelity_untouched_cm: float | None = None
    part: str | None = None
    part_fidelity_cm: float | None = None
    reason: str | None = None

    @property
    def executed(self) -> bool:
        return self.reason is None

    @property
    def fidelity_cm(self) -> float | None:
        """The core fidelity of a whole-body element, the part fidelity of a composition (cm)."""
        return self.core_fidelity_cm if self.core_fidelity_cm is not None else self.part_fidelity_cm

    def to_dict(self) -> dict[str, Any]:
        """The report's entry for the element (plain JSON values, keys in the report's order)."""
        if not self.executed:
            return {"actor": self.actor, "executed": False, "reason": self.reason}
        if self.part is not None:
            return {"actor": self.actor, "start": self.start, "end": self.end, "part": self.part,
                    "part_fidelity_cm": self.part_fidelity_cm}
        d: dict[str, Any] = {"actor": self.actor, "start": self.start}
        if self.core is not None:
            d["core"] = list(self.core)
        if self.placement is not None:
            d["placement"] = {"yaw": self.placement.yaw, "x": self.placement.x, "z": self.placement.z}
        d["end"] = self.end
        d["core_fidelity_cm"] = self.core_fidelity_cm
        if self.core_fidelity_untouched_cm is not None:
            d["core_fidelity_untouched_cm"] = self.core_fidelity_untouched_cm
        return d


@dataclass(frozen=True)
class Result:
    """What :func:`synthesize` returns.

    Attributes:
        motions: one motion per actor (key: the track's ``actor``), at ``fps``, starting at track time 0.
        joins: one :class:`JoinReport` per join (connections, transitions,
            repetitions, compositions), in track and time order.
        elements: per element id, its :class:`ElementReport`.
        warnings: what could not be honoured.
        placed_paths: per actor, ``(K, T, 2)`` m: the hips' horizontal path of each whole-body element
            as placed (the clip turned and moved, before any blend) on the motion's ``T`` frames, NaN
            where it is not played (:func:`synthesis.played.placed_paths`); empty when not known.
    """

    motions: dict[str | None, Motion]
    joins: list[JoinReport]
    fps: float
    elements: dict[int, ElementReport] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()
    placed_paths: dict[str | None, Any] = field(default_factory=dict, compare=False)

    def actor_of(self, element_id: int) -> str | None:
        """The actor an element belongs to (``None``: the default actor, or an unknown element)."""
        e = self.elements.get(element_id)
        return e.actor if e is not None else None

    def report(self) -> dict[str, Any]:
        """The ``joins`` part of the synthesis report (``docs/timetable.md`` §2) as plain JSON-ready data."""
        return {"joins": [join_to_dict(j) for j in self.joins]}


def join_to_dict(j: JoinReport) -> dict[str, Any]:
    """A join's entry in the report (plain JSON values)."""
    d: dict[str, Any]
    d = {"first": j.first, "second": j.second, "method": j.method, "blend": j.blend,
         "intervals": [{"part": i.part, "kind": i.kind, "begin": round(i.begin, 3), "end": round(i.end, 3)}
                       for i in j.intervals]}
    if j.cost is not None:
        d["cost"] = j.cost
    d["metrics"] = j.metrics
    if j.warnings:
        d["warnings"] = list(j.warnings)
    return d
