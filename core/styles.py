"""The styles a manner word gives a motion (docs/language.md §2.1) and what each does to a clip.

One vocabulary for every stage: the analyzer reads a manner word as one of :data:`STYLES` with an
intensity (0.25-1.5; 1 is the word's plain meaning), the scheduler plays the clip at the style's
``tempo``, and the synthesis stage (:mod:`synthesis.manner`) changes the clip's posture, amplitude,
stride and bounce by the other parameters; a clip stored with that style is played as it is
(docs/timetable.md §1, "Manner"). Every parameter is the change at intensity 1; at intensity ``k``
a factor ``f`` becomes ``f ** k`` and an angle ``a`` becomes ``k * a``.

The figures were set by eye on the built-in library's walk, run, wave and jump (contact sheets of
the styled against the neutral motion) and held to the motion-quality limits (README, *Quality
figures*): a tired walk is about 20 % slower with its torso bent 10° and its head 12° down, and so on.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Style:
    """What a style does to a clip, at intensity 1.

    Attributes:
        name: the style's name (``tired``).
        tempo: time scale of the clip (0.8: played at 80 % speed); a speed word of the text wins.
        amplitude: the arms' excursions about the clip's mean pose, as a factor (1: unchanged).
        stride: the legs' swing and the hips' travel of a locomotion, as a factor.
        spine_pitch: degrees the torso bends forward (negative: leans back, chest out).
        head_pitch: degrees the head and neck bend forward (down).
        shoulders: degrees the shoulders drop and round forward (negative: drawn back).
        bounce: the hips' vertical excursion about their mean height, as a factor.
    """

    name: str
    tempo: float = 1.0
    amplitude: float = 1.0
    stride: float = 1.0
    spine_pitch: float = 0.0
    head_pitch: float = 0.0
    shoulders: float = 0.0
    bounce: float = 1.0


#: Every style, by name (docs/timetable.md §1 "Manner" shows the same table).
STYLES: dict[str, Style] = {s.name: s for s in (
    Style("energetic", tempo=1.15, amplitude=1.3, stride=1.1, spine_pitch=-3, head_pitch=-5, bounce=1.6),
    Style("tired", tempo=0.8, amplitude=0.7, stride=0.8, spine_pitch=10, head_pitch=12, shoulders=8, bounce=0.6),
    Style("sad", tempo=0.85, amplitude=0.7, stride=0.85, spine_pitch=8, head_pitch=22, shoulders=10, bounce=0.7),
    Style("angry", tempo=1.1, amplitude=1.2, stride=1.1, spine_pitch=5, head_pitch=5, shoulders=-3, bounce=1.2),
    Style("proud", tempo=0.95, amplitude=1.1, stride=1.1, spine_pitch=-5, head_pitch=-8, shoulders=-8),
    Style("timid", tempo=0.9, amplitude=0.6, stride=0.8, spine_pitch=6, head_pitch=10, shoulders=8, bounce=0.8),
    Style("sneaky", tempo=0.75, amplitude=0.7, stride=0.85, spine_pitch=12, head_pitch=-4, shoulders=5, bounce=0.6),
    Style("light", amplitude=1.1, stride=1.05, spine_pitch=-2, bounce=1.4),
    Style("heavy", tempo=0.85, amplitude=0.9, stride=0.95, spine_pitch=4, head_pitch=4, shoulders=4, bounce=1.3),
    Style("big", amplitude=1.4, stride=1.2, bounce=1.2),
    Style("small", amplitude=0.55, stride=0.75, bounce=0.8),
    Style("hurried", tempo=1.3, amplitude=1.1, stride=1.1, spine_pitch=6, head_pitch=2),
    Style("relaxed", tempo=0.85, amplitude=0.9, spine_pitch=-1, head_pitch=-2, shoulders=-2, bounce=0.9),
)}

#: Intensities are kept within these bounds (a degree word scales the word's own: とても, 少し).
INTENSITY_RANGE = (0.25, 1.5)


def tempo(style: str | None, intensity: float = 1.0) -> float:
    """The time scale ``style`` plays a clip at (1.0 for none)."""
    if style is None:
        return 1.0
    return float(STYLES[style].tempo ** intensity)
