"""A manner made from a clip with no clip of it (docs/timetable.md §1, "Manner"): one module per change.

:func:`restyle` applies a style of :data:`core.styles.STYLES` to a clip's motion: its posture
(:mod:`.posture`), its limbs' amplitude (:mod:`.amplitude`), a gait's stride (:mod:`.stride`) and the hips'
bounce (:mod:`.bounce`); its tempo is the scheduler's (the row's speed). Intensity ``k`` raises each factor to
``k`` and scales each angle by ``k``. The clip keeps its length and frames; the feet are planted again by
the foot locking of the synthesis, which runs after.
"""
from __future__ import annotations

from dataclasses import dataclass

from text2anim.core.bodyparts import BodyMapError
from text2anim.core.motion import Motion
from text2anim.core.styles import STYLES

from .amplitude import amplify
from .body import Body
from .bounce import bounce
from .posture import pose
from .stride import is_gait, stride

__all__ = ["Restyled", "restyle"]


@dataclass(frozen=True)
class Restyled:
    """A clip's motion in a style, and what was changed: ``changes`` maps each parameter applied
    (``spine_pitch``, ``amplitude``, ...) to its value at the asked intensity; ``refused`` says why nothing
    could be done (a skeleton without the joints a modifier needs), else ``""``."""

    motion: Motion
    changes: dict[str, float]
    refused: str = ""


def restyle(motion: Motion, style: str, intensity: float, cyclic: bool) -> Restyled:
    """``motion`` (a clip, looping when ``cyclic``) in ``style`` at ``intensity`` (1: the style's table)."""
    s = STYLES[style]
    try:
        body = Body.of(motion)
    except BodyMapError as exc:
        return Restyled(motion, {}, f"its skeleton has no body the modifiers know: {exc}")
    k = intensity
    gait = is_gait(motion, cyclic)
    changes = {"spine_pitch": s.spine_pitch * k, "head_pitch": s.head_pitch * k, "shoulders": s.shoulders * k,
               "amplitude": s.amplitude ** k, "stride": s.stride ** k if gait else 1.0, "bounce": s.bounce ** k}
    out = pose(motion, body, changes["spine_pitch"], changes["head_pitch"], changes["shoulders"])
    out = amplify(out, body, changes["amplitude"], cyclic, gait)
    if gait:
        out = stride(out, body, changes["stride"])
    out = bounce(out, changes["bounce"], cyclic)
    done = {name: round(v, 3) for name, v in changes.items() if v != (1.0 if name in ("amplitude", "stride", "bounce") else 0.0)}
    return Restyled(out, done)
