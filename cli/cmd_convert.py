"""``text2anim convert IN.bvh -o OUT.bvh``: rewrite a file through our reader and writer (and onto a rig)."""
from __future__ import annotations

import sys

from .arg_types import fps_type
from .bvh_options import add_read_options, read_options
from .export_options import add_export_arguments, export_options
from .terminal import say

NAME = "convert"
HELP = ("rewrite a BVH file in metres (optionally rescaled, resampled, Z-up→Y-up, T-pose dropped, put on the floor, "
        "retargeted onto your rig)")


def add_arguments(p):
    p.add_argument("input", help="the BVH file to read")
    p.add_argument("-o", "--output", required=True,
                   help="the BVH file to write (written atomically), or - for standard output")
    p.add_argument("--fps", type=fps_type, help="resample to this frame rate, 1 to 240 (slerp)")
    p.add_argument("--floor", action="store_true",
                   help="move the clip so its floor, found from its foot contacts, is at y = 0 (always done with --rig)")
    add_read_options(p)
    add_export_arguments(p)


def run(args) -> int:
    from text2anim.core import read_bvh
    from text2anim.core.atomic import check_output_path
    from text2anim.core.floor import place_on_floor
    from text2anim.export import export_motion
    from text2anim.output.bvh_write import bvh_chunks, write_bvh

    if args.output != "-":
        check_output_path(args.output)
    export = export_options(args)
    m = read_bvh(args.input, **read_options(args))
    if args.fps:
        m = m.resample(args.fps)
    notes = sys.stderr if args.output == "-" else sys.stdout  # standard output carries the BVH alone
    if args.floor or args.rig:
        m, floor = place_on_floor(m)
        print(f"floor: moved {'down' if floor.height >= 0 else 'up'} {100 * abs(floor.height):.1f} cm "
              f"(from its {'foot contacts' if floor.method == 'contacts' else 'lowest foot reach'})", file=notes)
    m = export_motion(m, export)
    if args.output == "-":
        for piece in bvh_chunks(m):
            sys.stdout.write(piece)
        sys.stdout.flush()
        say(f"wrote standard output: {m.n_frames} frames at {m.fps:g} fps, {m.duration:.3f} s", file=sys.stderr)
        return 0
    write_bvh(m, args.output)
    say(f"wrote {args.output}: {m.n_frames} frames at {m.fps:g} fps, {m.duration:.3f} s")
    return 0
