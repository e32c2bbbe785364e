"""What every engine returns: one motion per actor, a report per join and per element (:class:`Result`).

The engines' shared contract with the API: :class:`~synthesis.plan.JoinReport` per join (from
:mod:`synthesis.plan`), the figures per element, and the warnings.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .plan import JoinReport


@dataclass(frozen=True)
class Result:
    """What :func:`synthesize` returns.

    Attributes:
        motions: one motion per actor (key: the track's ``actor``), at ``fps``, starting at track time 0.
        joins: one :class:`~synthesis.plan.JoinReport` per join (connections, transitions,
            repetitions, compositions), in track and time order.
        elements: per element id: ``actor``, ``start``/``end`` as played (s), ``core`` (s on the
            track), ``core_fidelity_cm`` (and ``core_fidelity_untouched_cm`` when a
            composition changed part of it), ``placement`` (yaw, x, z).
        warnings: what could not be honoured.
    """

    motions: dict
    joins: list
    fps: float
    elements: dict = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    def report(self) -> dict:
        """The ``joins`` part of the synthesis report (``timetable.md`` §2) as plain JSON-ready data."""
        return {"joins": [join_to_dict(j) for j in self.joins]}


def join_to_dict(j: JoinReport) -> dict:
    d = {"first": j.first, "second": j.second, "method": j.method, "blend": j.blend,
         "intervals": [{"part": i.part, "kind": i.kind, "begin": round(i.begin, 3), "end": round(i.end, 3)}
                       for i in j.intervals]}
    if j.cost is not None:
        d["cost"] = j.cost
    d["metrics"] = j.metrics
    if j.warnings:
        d["warnings"] = list(j.warnings)
    return d

