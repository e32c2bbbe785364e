"""What optimal blending decides for one join: the blend intervals carried out (:class:`Interval`), the
whole decision (:class:`Plan`), or that the join is not carried out (:class:`Skip`). Frames on the track."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from text2anim.core.ground import Rigid
from text2anim.core.motion import Motion

from ..join.placed import Placed
from .blend_ranges import Range
from .blend_search import Found
from .method_select import Choice


@dataclass(frozen=True)
class Interval:
    """A blend interval as carried out: ``name``/``part``/``kind``, frames ``t0``..``t1`` (track), the
    weight of the second source per frame ``(t1 - t0 + 1,)``, sources, the §4.4 ``case``
    (``hermite``, or ``a``/``b``/``c`` of §4.4.2), the search's result and the range searched."""

    name: str
    part: str
    kind: str
    t0: int
    t1: int
    weights: np.ndarray
    src: tuple[str, str]
    case: str
    found: Found
    range: Range
    slopes: tuple[float, float]


@dataclass
class Plan:
    """What :func:`plan_join` decided for one join."""

    inc: Placed
    choice: Choice
    intervals: dict
    rigid: Rigid
    support: str | None
    placed: Motion
    adapted: Motion | None
    shift: int = 0
    phase: int = 0
    warnings: list = field(default_factory=list)
    info: dict = field(default_factory=dict)
    alternatives: list = field(default_factory=list)

    def cost(self) -> dict:
        """eq. (10)'s weighted terms summed over the searched intervals (the report's ``cost``)."""
        out = {"time": 0.0, "pose": 0.0, "velocity": 0.0}
        for iv in self.intervals.values():
            for k, v in iv.found.terms().items():
                out[k] += v
        out = {k: round(v, 4) for k, v in out.items()}
        out["total"] = round(sum(out.values()), 4)
        return out


@dataclass(frozen=True)
class Skip:
    """A join not carried out: the later element is not executed, and why."""

    reason: str
