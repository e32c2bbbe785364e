"""``text2anim convert IN.bvh -o OUT.bvh``: rewrite a file through our reader and writer."""
from __future__ import annotations

import sys

from .bvh_options import add_read_options, fps_type, read_options

NAME = "convert"
HELP = "rewrite a BVH file in metres (optionally rescaled, resampled, Z-up→Y-up, T-pose dropped)"


def add_arguments(p):
    p.add_argument("input", help="the BVH file to read")
    p.add_argument("-o", "--output", required=True, help="the BVH file to write (written atomically), or - for standard output")
    p.add_argument("--fps", type=fps_type, help="resample to this frame rate, 1 to 240 (slerp)")
    add_read_options(p)


def run(args) -> int:
    from text2anim.core import read_bvh, write_bvh
    from text2anim.core.atomic import check_output_path
    from text2anim.core.bvh import format_bvh

    if args.output != "-":
        check_output_path(args.output)
    m = read_bvh(args.input, **read_options(args))
    if args.fps:
        m = m.resample(args.fps)
    if args.output == "-":
        sys.stdout.write(format_bvh(m))
        sys.stdout.flush()
        print(f"wrote standard output: {m.n_frames} frames at {m.fps:g} fps, {m.duration:.3f} s", file=sys.stderr)
        return 0
    write_bvh(m, args.output)
    print(f"wrote {args.output}: {m.n_frames} frames at {m.fps:g} fps, {m.duration:.3f} s")
    return 0
