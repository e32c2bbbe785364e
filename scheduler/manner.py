"""How a row plays the manner its text gives (docs/timetable.md §1, "Manner").

A clip stored with the asked style plays as it is (``by = "clip"``); else the synthesis stage makes the
style from the clip (``"modifiers"``, :mod:`synthesis.manner`), and the row plays at the style's tempo
(:func:`core.styles.tempo`) unless a speed word of the text already sets its speed (急いで, ゆっくり). A
manner word of no style (にこにこ) is kept on the row, ``by = None``: the animation says it is not shown;
a mimetic the motion already performs is no such word (ぱちぱち repeats the clap, きょろきょろする is its verb).
"""
from __future__ import annotations

from dataclasses import replace

from text2anim.core.styles import tempo
from text2anim.nlp.mimetics import repeats
from text2anim.nlp.types import MotionSpec

from .types import ClipTiming, Manner


def manner_of(spec: MotionSpec, clip: ClipTiming) -> Manner | None:
    """The row's manner: the text's word and style, and what plays it; None when the text gives none."""
    if spec.manner is None and spec.style is None:
        return None
    if spec.style is None and (repeats(spec.manner or "") or spec.written.startswith(spec.manner or "")):
        return None  # performed by the repeats or the verb itself
    by = None if spec.style is None else "clip" if clip.style == spec.style else "modifiers"
    return Manner(spec.manner or spec.style or "", spec.style, spec.intensity, by)


def played_spec(spec: MotionSpec, clip: ClipTiming) -> MotionSpec:
    """``spec`` at the speed ``clip`` plays it: the style's tempo when the modifiers make the style and the text
    gives no speed of its own."""
    manner = manner_of(spec, clip)
    if manner is None or manner.by != "modifiers" or spec.speed != 1.0:
        return spec
    return replace(spec, speed=round(tempo(spec.style, spec.intensity), 3))
