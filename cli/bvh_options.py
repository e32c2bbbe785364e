"""Options shared by the commands that read BVH files, and the output budget."""
from __future__ import annotations

import argparse

from .arg_types import scale_type, seconds_type


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
