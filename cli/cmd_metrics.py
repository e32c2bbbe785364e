"""``text2anim metrics FILE.bvh [--json]``: the quality metrics of timetable.md §3."""
from __future__ import annotations

import json


from .bvh_options import add_read_options, read_options

NAME = "metrics"
HELP = "quality metrics of a BVH file: foot skate, skating ratio, body speeds, jerk"


def add_arguments(p):
    p.add_argument("file", help="a BVH file")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    add_read_options(p)


def run(args) -> int:
    from text2anim.core import read_bvh
    from text2anim.core.metrics import compute_metrics
    m = read_bvh(args.file, **read_options(args))
    met = compute_metrics(m)
    if args.json:
        print(json.dumps({"file": args.file, **met.to_dict()}, ensure_ascii=False, indent=2))
        return 0
    print(f"{args.file}: {met.frames} frames, {met.fps:.3f} fps, {met.duration:.3f} s")
    print(f"{'foot':6} {'contact frames':>14} {'skate cm/s':>11} {'slide cm':>9}")
    for side, fs in met.foot_skate.items():
        print(f"{side:6} {fs.contact_frames:14d} {fs.mean_speed_cm_s:11.2f} {fs.slide_cm:9.2f}")
    print(f"foot-skating ratio (GMD): {met.skating_ratio:.4f}")
    print(f"jerk: max {met.jerk.max:.1f} m/s^3, RMS {met.jerk.rms:.1f} m/s^3")
    print(f"mean speed: upper body {met.mean_upper_speed:.3f} m/s, lower body {met.mean_lower_speed:.3f} m/s")
    return 0
