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


def add_read_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--scale", default="auto", type=scale_type,
                   help="metres per file unit, or 'auto' to guess from the skeleton's size (default)")
    p.add_argument("--z-up", action="store_true", help="the file is Z-up: convert it to Y-up")
    p.add_argument("--drop-first", action="store_true",
                   help="drop frame 0 (the T-pose that cgspeed/CMU files prepend)")


def read_options(args: argparse.Namespace) -> dict:
    return {"scale": args.scale, "up": "z" if args.z_up else "y", "drop_first": args.drop_first}
