"""``text2anim info FILE.bvh``: skeleton summary, frames, fps, duration, contact phases."""
from __future__ import annotations

from .bvh_options import add_read_options, read_options
from .terminal import say

NAME = "info"
HELP = "summarise a BVH file: skeleton, frames, fps, duration, foot contact phases"


def add_arguments(p):
    p.add_argument("file", help="a BVH file")
    add_read_options(p)


#: levels: deeper joints are drawn at this indent with their depth written out (a 9,999-joint chain
#: drawn in full indentation was 100 MB of spaces and took 32 s)
MAX_INDENT = 24


def _tree(skel) -> list[str]:
    depth = [0] * skel.n_joints
    lines = []
    for j, p in enumerate(skel.parents):
        depth[j] = 0 if p < 0 else depth[p] + 1
        order = skel.rotation_order(j) or "-"
        deep = f"(depth {depth[j]}) " if depth[j] > MAX_INDENT else ""
        lines.append(f"  {'  ' * min(depth[j], MAX_INDENT)}{deep}{skel.names[j]}  [{len(skel.channels[j])} ch, {order}]")
    return lines


def run(args) -> int:
    from text2anim.core import read_bvh
    from text2anim.core.bodyparts import BodyMapError, body_map
    from text2anim.core.contacts import detect_contacts
    m = read_bvh(args.file, **read_options(args))
    s = m.skeleton
    say(f"file:      {args.file}")
    say(f"frames:    {m.n_frames} at {m.fps:.3f} fps, {m.duration:.3f} s")
    say(f"skeleton:  {s.n_joints} joints, {len(s.end_sites)} end sites, rest height {s.height():.3f} m")
    say(f"root:      {s.names[0]}")
    say(*_tree(s), sep="\n")
    if m.n_frames == 0:
        return 0
    try:
        body_map(s)
    except BodyMapError as exc:
        say(f"contacts:  not available ({exc})")
        return 0
    c = detect_contacts(m)
    for side in ("left", "right"):
        iv = c.intervals(side)
        say(f"{side + ' foot:':10} {len(iv)} contacts: "
              + ", ".join(f"{a / m.fps:.2f}-{b / m.fps:.2f}s" for a, b in iv))
    say("phases:    " + " ".join(f"{st}({(b - a) / m.fps:.2f}s)" for a, b, st in c.phases()))
    return 0
