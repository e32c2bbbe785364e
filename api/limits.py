"""The limits of the contract: what one text may ask for, checked before any work starts.

A ten-character text can ask for a million repetitions or a wait of a billion
seconds; these limits keep the work of one call bounded (a web front end or a
batch over user text cannot be taken down by one line). Every refusal is a
:class:`LimitError` (a ``ValueError``) with one clear line; the command line
prints it and exits with status 2.

==========================  ==========================================================
frame rate                  :data:`FPS_MIN` to :data:`FPS_MAX` frames per second
text                        at most :data:`MAX_TEXT_CHARS` characters, no control characters
motions per text            at most :data:`MAX_MOTIONS`
repeat count (3回)          at most :data:`MAX_REPEAT`
a duration or delay (秒)    at most the output budget ``max_seconds``
output (the budget)         the animation's length summed over the actors at most
                            ``max_seconds`` (default :data:`MAX_SECONDS`), and its frames
                            (length x fps x actors) at most ``max_seconds`` x :data:`BUDGET_FPS`
==========================  ==========================================================

``max_seconds`` is the one limit a caller may raise (``--max-seconds`` on the
command line) for batch work that knowingly wants long animations.
"""
from __future__ import annotations

import math
import numbers
import os
import unicodedata

from text2anim.core.inputs import BIDI_CONTROLS, is_control
from text2anim.core.notice import Notice
from text2anim.core.inputs import printable as printable  # the one escaping for a terminal, re-exported

FPS_MIN = 1.0
FPS_MAX = 240.0
MAX_TEXT_CHARS = 2000
MAX_MOTIONS = 32
MAX_REPEAT = 20
#: Default output budget: seconds of animation, summed over the actors.
MAX_SECONDS = 300.0
#: The frame budget is ``max_seconds * BUDGET_FPS`` frames (300 s at 60 fps by default).
BUDGET_FPS = 60.0
#: A raised budget is still a budget: at most a day of output.
MAX_SECONDS_CEILING = 86_400.0

#: Control characters that are kept in a text: line breaks and tabs (a text read from a file).
_ALLOWED_CONTROLS = frozenset("\n\r\t")


class InputError(ValueError):
    """An argument of the API with a value it cannot take (one clear line)."""

    user_facing = True


class InputTypeError(TypeError):
    """An argument of the API of the wrong type (``fps="30"``, ``skip_unknown="no"``)."""

    user_facing = True


class LimitError(InputError):
    """A text or option that asks for more work than the limits allow; ``notice`` says what, for a front end
    to word (:class:`core.notice.Notice`; kinds ``limit_fps``, ``limit_budget``, ``limit_text``,
    ``limit_motions``, ``limit_repeat``, ``limit_delay``, ``limit_duration``, ``limit_length``, ``limit_frames``,
    or ``limit`` for one given as a sentence only). ``str()`` is the English sentence."""

    def __init__(self, notice: Notice | str):
        self.notice = notice if isinstance(notice, Notice) else Notice("limit", notice)
        super().__init__(self.notice)


#: What ``fallback`` may be: ``strict`` refuses a verb the database lacks, ``nearest`` plays the
#: database verb nearest in meaning (:mod:`text2anim.fallback`).
FALLBACKS = ("strict", "nearest")


# ----------------------------------------------------------------------------- arguments
def real(name: str, value) -> float:
    """``value`` as a float if it is a real number (not a bool, not a string); else :class:`InputTypeError`."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputTypeError(f"{name} must be a number, not {type(value).__name__} {value!r}")
    try:
        out = float(value)
    except OverflowError:  # an int with hundreds of digits
        out = math.inf
    if not math.isfinite(out):
        raise InputError(f"{name} must be a finite number, not {value!r}")
    return out


def flag(name: str, value) -> bool:
    """``value`` if it is a bool (``numpy.bool_`` too); a string such as ``"no"`` is refused."""
    if isinstance(value, bool) or (type(value).__module__ == "numpy" and type(value).__name__ in ("bool", "bool_")):
        return bool(value)
    raise InputTypeError(f"{name} must be True or False, not {type(value).__name__} {value!r}")


def check_fps(fps) -> float:
    """The frame rate as a float in [:data:`FPS_MIN`, :data:`FPS_MAX`] frames per second."""
    value = real("fps", fps)
    if not FPS_MIN <= value <= FPS_MAX:
        raise LimitError(Notice.of("limit_fps", f"fps must be between {FPS_MIN:g} and {FPS_MAX:g} frames per second, "
                                                f"not {fps!r}", fps=value, min=FPS_MIN, max=FPS_MAX))
    return value


def check_budget(max_seconds) -> float:
    """The output budget in seconds: positive, at most :data:`MAX_SECONDS_CEILING`."""
    value = real("max_seconds", max_seconds)
    if not 0 < value <= MAX_SECONDS_CEILING:
        raise LimitError(Notice.of("limit_budget", f"max_seconds must be above 0 and at most {MAX_SECONDS_CEILING:g} s, "
                                                   f"not {max_seconds!r}", s=value, max=MAX_SECONDS_CEILING))
    return value


def check_text(text) -> str:
    """``text`` if it is a string the analyser may read: bounded length, no control characters."""
    if not isinstance(text, str):
        raise InputTypeError(f"text must be a str, not {type(text).__name__}")
    if len(text) > MAX_TEXT_CHARS:
        raise LimitError(Notice.of("limit_text", f"the text has {len(text)} characters; at most {MAX_TEXT_CHARS} are "
                                                 "accepted (split it into several texts)", n=len(text), max=MAX_TEXT_CHARS))
    for i, ch in enumerate(text):
        if ch in _ALLOWED_CONTROLS:
            continue
        if unicodedata.category(ch) == "Cs":  # undecodable bytes of a command line (surrogateescape)
            raise InputError(f"the text is not valid UTF-8 (character {i + 1}); pass it as UTF-8")
        if is_control(ch):
            kind = "a text-direction control" if ch in BIDI_CONTROLS else "a control"
            raise InputError(f"the text contains {kind} character (U+{ord(ch):04X} at character {i + 1}); "
                             "remove it")
    return text


# ------------------------------------------------------------------------ the work asked
def check_analysis(analysis, max_seconds: float = MAX_SECONDS) -> None:
    """Refuse an analysed text that asks for too much, before any clip is looked up.

    ``analysis`` is an :class:`nlp.types.Analysis`: its motions' repeat counts
    and durations and its constraints' delays (seconds) are checked.
    """
    if len(analysis.motions) > MAX_MOTIONS:
        raise LimitError(Notice.of("limit_motions", f"the text asks for {len(analysis.motions)} motions; at most "
                                   f"{MAX_MOTIONS} per text are accepted (split it into several texts)",
                                   n=len(analysis.motions), max=MAX_MOTIONS))
    for m in analysis.motions:
        if not (isinstance(m.repeat, int) and 1 <= m.repeat <= MAX_REPEAT):
            raise LimitError(Notice.of("limit_repeat", f"{m.verb} is asked {_number(m.repeat)} times; at most "
                                       f"{MAX_REPEAT} repetitions are accepted", verb=m.verb, n=_number(m.repeat),
                                       max=MAX_REPEAT))
        if m.delay is not None and not (math.isfinite(m.delay) and abs(m.delay) <= MAX_SECONDS_CEILING):
            raise LimitError(Notice.of("limit_delay", f"a delay of {_number(m.delay)} s is asked before {m.verb}, more "
                                       f"than a day ({MAX_SECONDS_CEILING:,.0f} s): no budget allows it",
                                       s=_number(m.delay), max=MAX_SECONDS_CEILING))
        if m.duration is not None and not (math.isfinite(m.duration) and m.duration <= MAX_SECONDS_CEILING):
            raise LimitError(Notice.of("limit_duration", f"{m.verb} is asked to last {_number(m.duration)} s, more "
                                       f"than a day ({MAX_SECONDS_CEILING:,.0f} s): no budget allows it",
                                       verb=m.verb, s=_number(m.duration), max=MAX_SECONDS_CEILING))
        if m.duration is not None and not 0 <= m.duration <= max_seconds:
            raise LimitError(Notice.of("limit_duration", f"{m.verb} is asked to last {_number(m.duration)} s; at most "
                                       f"{max_seconds:g} s of output are accepted (the budget; --max-seconds raises it)",
                                       verb=m.verb, s=_number(m.duration), max=max_seconds))
    for c in analysis.constraints:
        if c.delay is not None and not (math.isfinite(c.delay) and abs(c.delay) <= MAX_SECONDS_CEILING):
            raise LimitError(Notice.of("limit_delay", f"a delay of {_number(c.delay)} s is asked, more than a day "
                                       f"({MAX_SECONDS_CEILING:,.0f} s): no budget allows it",
                                       s=_number(c.delay), max=MAX_SECONDS_CEILING))
        if c.delay is not None and not abs(c.delay) <= max_seconds:
            raise LimitError(Notice.of("limit_delay", f"a delay of {_number(c.delay)} s is asked; at most "
                                       f"{max_seconds:g} s of output are accepted (the budget; --max-seconds raises it)",
                                       s=_number(c.delay), max=max_seconds))


def check_table(table, fps: float, max_seconds: float = MAX_SECONDS) -> None:
    """Refuse a time table whose output exceeds the budget, before any frame is made.

    Every actor's motion lasts until the table's last element ends, so the
    output is ``length * actors`` seconds and ``length * fps * actors`` frames.
    """
    if not table.elements:
        return
    length = max(e.end for e in table.elements)
    actors = len(table.actors())
    seconds = length * actors
    budget_frames = math.floor(max_seconds * BUDGET_FPS)
    who = f" for {actors} actors" if actors > 1 else ""
    if not math.isfinite(seconds) or seconds > max_seconds:
        raise LimitError(Notice.of("limit_length", f"the animation would last {_number(length)} s{who}: "
                                   f"{_number(seconds)} s of output, over the budget of {max_seconds:g} s "
                                   "(--max-seconds raises it)", s=_number(length), actors=actors, max=max_seconds))
    frames = math.ceil(seconds * fps)  # finite now
    if frames > budget_frames:
        raise LimitError(Notice.of("limit_frames", f"the animation would have {frames} frames ({seconds:.1f} s at "
                                   f"{fps:g} fps{who}), over the budget of {budget_frames} frames ({max_seconds:g} s "
                                   f"at {BUDGET_FPS:g} fps; lower --fps or raise --max-seconds)",
                                   n=frames, max=budget_frames, fps=fps))


def check_options(text, db, fps, max_seconds, smoothness: float = 0.5, fallback: str = "strict",
                  **flags) -> tuple[float, float, float]:
    """Type and range checks of the API's arguments; returns ``(fps, max_seconds, smoothness)`` as floats."""
    from text2anim.motiondb import MotionDB

    check_text(text)
    if fallback not in FALLBACKS:
        raise InputError(f"fallback must be one of {', '.join(FALLBACKS)}, not {fallback!r}")
    if not (db is None or isinstance(db, (MotionDB, str, os.PathLike))):
        raise InputTypeError(f"db must be a MotionDB, a database URL or path, or None, not {type(db).__name__}")
    for name, value in flags.items():
        flag(name, value)
    smooth = real("smoothness", smoothness)
    if not 0.0 <= smooth <= 1.0:
        raise InputError(f"smoothness must be between 0 (time first) and 1 (smoothness first), not {smoothness!r}")
    return check_fps(fps), check_budget(max_seconds), smooth


def _number(x) -> str:
    """A number for a message, short even when it has 400 digits."""
    if isinstance(x, float) and math.isinf(x):
        return "more than 10³⁰⁸"  # a numeral beyond a float (309 digits of 九)
    try:
        text = f"{x:g}" if isinstance(x, float) else str(x)
    except (ValueError, OverflowError):
        text = "a huge number"
    return text if len(text) <= 20 else text[:8] + "…"
