"""``text2anim convert IN.bvh -o OUT.bvh``: rewrite a file through our reader and writer."""
from __future__ import annotations

from .bvh_options import add_read_options, positive_float, read_options

NAME = "convert"
HELP = "rewrite a BVH file in metres (optionally rescaled, resampled, Z-up→Y-up, T-pose dropped)"


def add_arguments(p):
    p.add_argument("input", help="the BVH file to read")
    p.add_argument("-o", "--output", required=True, help="the BVH file to write (written atomically)")
    p.add_argument("--fps", type=positive_float, help="resample to this frame rate (slerp)")
    add_read_options(p)


def run(args) -> int:
    from text2anim.core import read_bvh, write_bvh
    m = read_bvh(args.input, **read_options(args))
    if args.fps:
        m = m.resample(args.fps)
    write_bvh(m, args.output)
    print(f"wrote {args.output}: {m.n_frames} frames at {m.fps:g} fps, {m.duration:.3f} s")
    return 0
