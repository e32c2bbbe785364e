"""Options shared by the commands that read BVH files, and argument types."""
from __future__ import annotations

import argparse


def scale_type(text: str):
    """``auto`` or a positive number (metres per file unit)."""
    if text == "auto":
        return text
    return positive_float(text)


def positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r} must be a positive number")
    return value


def fps_type(text: str) -> float:
    """A frame rate within the documented limits (:mod:`text2anim.limits`) for argparse."""
    from text2anim.limits import FPS_MAX, FPS_MIN

    value = positive_float(text)
    if not FPS_MIN <= value <= FPS_MAX:
        raise argparse.ArgumentTypeError(f"{text} is outside {FPS_MIN:g}-{FPS_MAX:g} frames per second")
    return value


def seconds_type(text: str) -> float:
    """An output budget in seconds (``--max-seconds``) for argparse."""
    from text2anim.limits import MAX_SECONDS_CEILING

    value = positive_float(text)
    if value > MAX_SECONDS_CEILING:
        raise argparse.ArgumentTypeError(f"{text} is over {MAX_SECONDS_CEILING:g} s")
    return value


def add_budget_option(p: argparse.ArgumentParser) -> None:
    """``--max-seconds``: the output budget of :mod:`text2anim.limits`."""
    from text2anim.limits import BUDGET_FPS, MAX_SECONDS

    p.add_argument("--max-seconds", type=seconds_type, default=MAX_SECONDS, metavar="S",
                   help=f"output budget: at most S seconds of animation summed over the actors and S x "
                        f"{BUDGET_FPS:g} frames (default {MAX_SECONDS:g}; raise it for long batch work)")


def add_read_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--scale", default="auto", type=scale_type,
                   help="metres per file unit, or 'auto' to guess from the skeleton's size (default)")
    p.add_argument("--z-up", action="store_true", help="the file is Z-up: convert it to Y-up")
    p.add_argument("--drop-first", action="store_true",
                   help="drop frame 0 (the T-pose that cgspeed/CMU files prepend)")


def read_options(args: argparse.Namespace) -> dict:
    return {"scale": args.scale, "up": "z" if args.z_up else "y", "drop_first": args.drop_first}
