"""A manner made from a clip with no clip of it (docs/timetable.md §1, "Manner"): one module per change.

:func:`restyle` applies a style of :data:`core.styles.STYLES` to a clip's motion: its posture
(:mod:`.posture`), its limbs' amplitude (:mod:`.amplitude`), a gait's stride (:mod:`.stride`) and the hips'
bounce (:mod:`.bounce`), then holds its feet where the captured clip stands (:mod:`.plant`); its tempo is the
scheduler's (the row's speed). Intensity ``k`` raises each factor to ``k`` and scales each angle by ``k``.
The clip keeps its length and frames; the foot locking of the synthesis plants the feet at the joins. A style
that would take the clip past the quality limits it meets as captured (:mod:`.limits`) is applied at half
its intensity, then a quarter, else not at all, and the record says so.
"""
from __future__ import annotations

from dataclasses import dataclass

from text2anim.core.bodyparts import BodyMapError
from text2anim.core.motion import Motion
from text2anim.core.styles import STYLES, Style

from .amplitude import amplify
from .body import Body
from .bounce import bounce
from .limits import broken
from .plant import plant
from .posture import pose
from .stride import is_gait, stride

__all__ = ["Restyled", "restyle"]


@dataclass(frozen=True)
class Restyled:
    """A clip's motion in a style, and what was changed: ``changes`` maps each parameter applied
    (``spine_pitch``, ``amplitude``, ...) to its value at the asked intensity; ``refused`` says why nothing
    could be done (a skeleton without the joints a modifier needs, a style no intensity of which keeps the
    quality limits), else ``""``; ``intensity`` the intensity applied (lowered to keep the limits)."""

    motion: Motion
    changes: dict[str, float]
    refused: str = ""
    intensity: float = 1.0


def restyle(motion: Motion, style: str, intensity: float, cyclic: bool, speed: float = 1.0) -> Restyled:
    """``motion`` (a clip, looping when ``cyclic``, played at ``speed``) in
    ``style`` at ``intensity`` (1: the style's table), lowered where the quality limits ask (module docstring)."""
    try:
        body = Body.of(motion)
    except BodyMapError as exc:
        return Restyled(motion, {}, f"its skeleton has no body the modifiers know: {exc}")
    missed: list[str] = []
    for k in (intensity, intensity / 2, intensity / 4):
        out, changes = _styled(motion, body, STYLES[style], k, cyclic)
        missed = broken(out, motion, cyclic, speed)
        if not missed:
            return Restyled(out, changes, intensity=round(k, 3))
    return Restyled(motion, {}, f"in {style} it would miss the quality limits ({', '.join(missed)}) at any "
                                f"intensity down to {intensity / 4:g}")


def _styled(motion: Motion, body: Body, s: Style, k: float, cyclic: bool) -> tuple[Motion, dict[str, float]]:
    """The clip in style ``s`` at intensity ``k`` and the parameters applied (those that change anything)."""
    gait = is_gait(motion, cyclic)
    changes = {"spine_pitch": s.spine_pitch * k, "head_pitch": s.head_pitch * k, "shoulders": s.shoulders * k,
               "amplitude": s.amplitude ** k, "stride": s.stride ** k if gait else 1.0, "bounce": s.bounce ** k}
    out = pose(motion, body, changes["spine_pitch"], changes["head_pitch"], changes["shoulders"])
    out = amplify(out, body, changes["amplitude"], cyclic, gait)
    if gait:
        out = stride(out, body, changes["stride"])
    out = plant(bounce(out, changes["bounce"], cyclic), motion, body.map, cyclic)
    neutral = {"amplitude": 1.0, "stride": 1.0, "bounce": 1.0}
    return out, {name: round(v, 3) for name, v in changes.items() if v != neutral.get(name, 0.0)}
