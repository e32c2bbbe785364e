"""Argument types for argparse: each turns the text of one option into its value or raises
:class:`argparse.ArgumentTypeError` with one clear message (argparse prints it and exits 2).

Limits come from :mod:`text2anim.limits`, imported when an option is parsed: building the parser
imports no stage.
"""
from __future__ import annotations

import argparse


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None


def positive_float(text: str) -> float:
    """A finite number > 0."""
    value = _number(text)
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r} must be a positive number")
    return value


def unit_float(text: str) -> float:
    """A number in [0, 1] (``--smoothness``)."""
    value = _number(text)
    if not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"{text} is not between 0 and 1")
    return value


def scale_type(text: str) -> str | float:
    """``auto`` or a positive number (metres per file unit, ``--scale``)."""
    if text == "auto":
        return text
    return positive_float(text)


def fps_type(text: str) -> float:
    """A frame rate within the documented limits (:mod:`text2anim.limits`), frames per second."""
    from text2anim.limits import FPS_MAX, FPS_MIN

    value = positive_float(text)
    if not FPS_MIN <= value <= FPS_MAX:
        raise argparse.ArgumentTypeError(f"{text} is outside {FPS_MIN:g}-{FPS_MAX:g} frames per second")
    return value


def seconds_type(text: str) -> float:
    """An output budget in seconds (``--max-seconds``), at most :data:`text2anim.limits.MAX_SECONDS_CEILING`."""
    from text2anim.limits import MAX_SECONDS_CEILING

    value = positive_float(text)
    if value > MAX_SECONDS_CEILING:
        raise argparse.ArgumentTypeError(f"{text} is over {MAX_SECONDS_CEILING:g} s")
    return value


def core_span(text: str) -> tuple[float, float]:
    """``BEGIN:END`` seconds, ``0 <= BEGIN < END`` (``db import --core``)."""
    try:
        b, e = (float(x) for x in text.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not BEGIN:END in seconds (e.g. 0.4:1.6)") from None
    if not (0 <= b < e < float("inf")):
        raise argparse.ArgumentTypeError(f"{text!r}: need 0 <= BEGIN < END")
    return b, e


def frame_count(text: str) -> int:
    """A whole number of frames to draw, 1 to 48 (``db preview --frames``)."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if not 1 <= n <= 48:
        raise argparse.ArgumentTypeError(f"{n} is outside 1-48 frames")
    return n


def method_list(text: str) -> list[str]:
    """Comma-separated joining methods of :data:`text2anim.synthesis.registry.METHODS`, in order, each once."""
    from text2anim.synthesis.registry import METHODS

    names = [m.strip() for m in text.split(",") if m.strip()]
    bad = [m for m in names if m not in METHODS]
    if bad or not names:
        raise argparse.ArgumentTypeError(f"unknown method(s) {', '.join(bad) or '(none)'}; "
                                         f"choose from {','.join(METHODS)}")
    return list(dict.fromkeys(names))
