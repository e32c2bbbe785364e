"""BVH writer: a motion as BVH text (metres, degrees, the skeleton's own channel layout), written atomically."""
from __future__ import annotations

import os

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
    cols = []
    local_t = m.local_translations()
    for j, chans in enumerate(skel.channels):
        if not chans:
            continue
        order = skel.rotation_order(j)
        euler = np.zeros((T, 3))
        if T and order:
            euler = Rotation.from_quat(m.rotations[:, j]).as_euler(_full_order(order), degrees=True)
        pos = local_t[:, j] - skel.offsets[j]
        block = np.empty((T, len(chans)))
        for k, c in enumerate(chans):
            if c in ROTATION_CHANNELS:
                block[:, k] = euler[:, order.index(c[0])]
            else:
                block[:, k] = pos[:, "XYZ".index(c[0])]
        cols.append(block)
    return np.concatenate(cols, axis=1) if cols else np.zeros((T, 0))


def _fmt(v) -> str:
    return f"{float(v):.8f}"


def format_bvh(m: Motion) -> str:
    """The motion as BVH text (metres, degrees, the skeleton's own channel layout)."""
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
    row = " ".join(["%.7f"] * values.shape[1])
    out += [row % tuple(r) for r in values.tolist()]  # Python floats: the same text, formatted faster
    return "\n".join(out) + "\n"


def write_bvh(m: Motion, path: str | os.PathLike) -> None:
    """Write ``m`` as BVH, atomically: the file appears whole or not at all."""
    from text2anim.core.atomic import atomic_write_text

    atomic_write_text(path, format_bvh(m))
