"""BVH writer: a motion as BVH text (metres, degrees, the skeleton's own channel layout), written atomically."""
from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from text2anim.core.motion import Motion
from text2anim.core.skeleton import ROTATION_CHANNELS


def _full_order(order: str) -> str:
    """Extend a partial Euler order with the missing axes so any rotation can be decomposed."""
    return order + "".join(a for a in "XYZ" if a not in order)


def _channel_values(m: Motion) -> np.ndarray:
    """The motion as a ``(T, C)`` block of BVH channel values (degrees, file units = metres)."""
    from scipy.spatial.transform import Rotation

    skel = m.skeleton
    T = m.n_frames
    out = np.empty((T, sum(len(c) for c in skel.channels)))  # filled in place: no per-joint blocks to join
    local_t = m.local_translations()
    col = 0
    for j, chans in enumerate(skel.channels):
        if not chans:
            continue
        order = skel.rotation_order(j)
        euler = np.zeros((T, 3))
        if T and order:
            euler = Rotation.from_quat(m.rotations[:, j]).as_euler(_full_order(order), degrees=True)
        pos = local_t[:, j] - skel.offsets[j]
        for k, c in enumerate(chans):
            if c in ROTATION_CHANNELS:
                out[:, col + k] = euler[:, order.index(c[0])]
            else:
                out[:, col + k] = pos[:, "XYZ".index(c[0])]
        col += len(chans)
    return out


def _fmt(v) -> str:
    return f"{float(v):.8f}"


#: Frames formatted at a time: a 5,000,000 joint-frame motion as one list of Python floats took 2 GB.
CHUNK_FRAMES = 2048


def format_bvh(m: Motion) -> str:
    """The motion as BVH text (metres, degrees, the skeleton's own channel layout)."""
    return "".join(bvh_chunks(m))


def bvh_chunks(m: Motion) -> Iterator[str]:
    """:func:`format_bvh`'s text in pieces: the hierarchy, then up to :data:`CHUNK_FRAMES` frame lines at a
    time, so a long motion is written in memory bounded by a chunk, not by its text."""
    skel = m.skeleton
    ends: dict[int, list[np.ndarray]] = {}
    for j, o in skel.end_sites:
        ends.setdefault(j, []).append(o)
    children: dict[int, list[int]] = {}
    for j, p in enumerate(skel.parents[1:], start=1):
        children.setdefault(int(p), []).append(j)
    out = ["HIERARCHY"]
    # An explicit stack, not recursion: a 1,000-deep chain the reader accepted is written back.
    # ("open", j, depth) writes a joint's header and schedules its children; ("close", j, depth)
    # writes its end sites and closing brace.
    stack: list[tuple[str, int, int]] = [("open", 0, 0)]
    while stack:
        what, j, depth = stack.pop()
        ind = "\t" * depth
        if what == "close":
            for o in ends.get(j, []):
                out.extend([f"{ind}\tEnd Site", f"{ind}\t{{", f"{ind}\t\tOFFSET {' '.join(_fmt(v) for v in o)}",
                            f"{ind}\t}}"])
            out.append(f"{ind}}}")
            continue
        out.append(f"{ind}{'ROOT' if j == 0 else 'JOINT'} {skel.names[j]}")
        out.append(f"{ind}{{")
        out.append(f"{ind}\tOFFSET {' '.join(_fmt(v) for v in skel.offsets[j])}")
        out.append(f"{ind}\tCHANNELS {len(skel.channels[j])}{''.join(' ' + c for c in skel.channels[j])}")
        stack.append(("close", j, depth))
        stack.extend(("open", c, depth + 1) for c in reversed(children.get(j, [])))
    values = _channel_values(m)
    out += ["MOTION", f"Frames: {m.n_frames}", f"Frame Time: {1.0 / m.fps:.8g}"]
    yield "\n".join(out) + "\n"
    row = " ".join(["%.7f"] * values.shape[1])
    for start in range(0, len(values), CHUNK_FRAMES):  # Python floats: the same text, formatted faster
        yield "".join([row % tuple(r) + "\n" for r in values[start:start + CHUNK_FRAMES].tolist()])


def write_bvh(m: Motion, path: str | os.PathLike) -> None:
    """Write ``m`` as BVH, atomically: the file appears whole or not at all."""
    from text2anim.core.atomic import write_all

    def write(tmp: Path) -> None:
        with open(tmp, "w", encoding="utf-8") as f:
            for piece in bvh_chunks(m):
                f.write(piece)

    write_all({path: write})
