"""``text2anim metrics FILE.bvh [--json]``: the quality metrics of docs/timetable.md §3.

Foot skate, jerk and body speeds at the file's own rate; then the figures the
literature compares (GMD foot-skating ratio, root pop, joint jerk p99, floor
penetration, frozen frames) after resampling to 30 fps, with the thresholds
issue 11 holds motion made from the built-in library to
(:data:`text2anim.core.metrics.BUILTIN_LIMITS`).
"""
from __future__ import annotations

import json


from .bvh_options import add_read_options, read_options
from .terminal import safe_json, say

NAME = "metrics"
HELP = ("quality metrics of a BVH file: skating ratio, root pop, jerk, floor penetration, frozen frames, "
        "floating feet")


def add_arguments(p):
    p.add_argument("file", help="a BVH file")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    add_read_options(p)


def run(args) -> int:
    from text2anim.core import read_bvh
    from text2anim.core.metrics import BUILTIN_LIMITS, MAX_FROZEN, compute_metrics
    from text2anim.core.size import HUMAN_LEG, at_human_size

    m, k = at_human_size(read_bvh(args.file, **read_options(args)))  # a 0.2 m or 20 m body: as a person's
    met = compute_metrics(m)
    if args.json:
        print(safe_json(json.dumps({"file": args.file, "scaled_to_human": k, **met.to_dict()},
                                   ensure_ascii=False, indent=2)))
        return 0
    say(f"{args.file}: {met.frames} frames, {met.fps:.3f} fps, {met.duration:.3f} s")
    if k != 1.0:
        say(f"measured at human size: the body scaled by {k:.4g} to legs of {HUMAN_LEG} m "
            "(lengths and speeds below are the scaled body's)")
    print(f"{'foot':6} {'contact frames':>14} {'skate cm/s':>11} {'slide cm':>9}")
    for side, fs in met.foot_skate.items():
        print(f"{side:6} {fs.contact_frames:14d} {fs.mean_speed_cm_s:11.2f} {fs.slide_cm:9.2f}")
    print(f"foot-skating ratio (GMD's rule, floor y = 0) at {met.fps:g} fps: {met.skating_ratio:.4f}")
    print(f"jerk: max {met.jerk.max:.1f} m/s^3, RMS {met.jerk.rms:.1f} m/s^3")
    print(f"mean speed: upper body {met.mean_upper_speed:.3f} m/s, lower body {met.mean_lower_speed:.3f} m/s")
    q, lim = met.quality, BUILTIN_LIMITS
    print(f"at {q.fps:g} fps (resampled; the rate figures are compared at)    value   built-in limit")
    for label, value, limit in (
            ("foot-skating ratio, floor y = 0", f"{q.skating_ratio:8.4f}", f"{lim['skating_ratio']:g}"),
            ("foot-skating ratio, GMD's floor (lowest foot)", f"{q.skating_gmd:8.4f}",
             f"{lim['skating_gmd']:g} (capture)"),
            ("root pop, hips' horizontal accel. m/s^2", f"{q.root_pop:8.2f}", f"{lim['root_pop']:g}"),
            ("joint jerk p99 m/s^3", f"{q.jerk_p99:8.0f}", f"{lim['jerk_p99']:g}"),
            ("floor penetration cm (joints, toe/finger tips)", f"{q.floor_penetration_cm:8.2f}", f"{lim['floor_penetration_cm']:g}"),
            ("frozen frames (fraction)", f"{q.frozen_fraction:8.4f}", f"{MAX_FROZEN:g}"),
            ("floating foot cm (a still foot on air)", f"{q.floating_cm:8.2f}", f"{lim['floating_cm']:g}")):
        print(f"  {label:46} {value:>8}   {limit}")
    return 0
