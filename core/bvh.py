"""BVH reader (the writer, its inverse, is :mod:`text2anim.output.bvh_write`).

What is read:
- any keyword case, tabs, CRLF, blank lines, a UTF-8 BOM;
- joint names with ``:``, ``.``, ``-`` (the rest of the ROOT/JOINT line);
- per-joint channel lists: root channels in any order, position channels on
  non-root joints, 0-3 rotation channels. Rotation channels are applied as an
  intrinsic Euler rotation in the order listed (``Zrotation Xrotation
  Yrotation`` means R = Rz·Rx·Ry);
- End Site offsets (kept, and written back);
- ``Frame Time`` in any float form (``.0083333``, ``8.3333e-3``).

What is refused with :class:`BVHError` (file and line number in the message):
a declared frame count that differs from the data lines present, a truncated
file, a non-numeric or non-finite value, duplicate joint names, and more than
one ROOT (this reader reads one character per file; split multi-character
files first). Absurd values are refused too, so that no file makes the work
unbounded or the numbers meaningless: more than :data:`MAX_JOINTS` joints or
:data:`MAX_JOINT_FRAMES` frames x joints, a
``Frame Time`` outside :data:`FRAME_TIME_RANGE` seconds, an offset or position
beyond :data:`MAX_LENGTH` file units, a rotation beyond :data:`MAX_DEGREES`.
Any hierarchy the reader accepts is written back by the writer.

Root position: the root's world position is its OFFSET plus its position
channels (Blender's reading); the writer inverts that.

Units: lengths are converted to metres on reading. ``scale="auto"`` guesses
the unit from the rest pose's largest extent ``h`` (see :func:`guess_scale`);
a number multiplies every length by it; ``1`` keeps the file's units.
"""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from . import quat
from .bvh_text import (FRAME_TIME_RANGE, MAX_DEGREES, MAX_JOINT_FRAMES, MAX_JOINTS, MAX_LENGTH, BVHError,
                       parse_channels)
from .inputs import read_input
from .motion import Motion
from .skeleton import POSITION_CHANNELS, ROTATION_CHANNELS, Skeleton

#: The reader's names, importable from here as before the split into :mod:`~text2anim.core.bvh_text` (the grammar).
__all__ = ["CMU_UNIT", "FRAME_TIME_RANGE", "MAX_DEGREES", "MAX_JOINTS", "MAX_JOINT_FRAMES", "MAX_LENGTH", "BVHError",
           "guess_scale", "parse_bvh", "parse_channels", "read_bvh"]

#: CMU's ASF length unit in metres (1/0.45 inch), used by cgspeed's BVH release.
CMU_UNIT = 0.0254 / 0.45

# scipy.spatial.transform is imported by the functions that use it (it is slow to load).


def guess_scale(skeleton: Skeleton) -> float:
    """Metres per file unit, guessed from the rest pose's largest extent ``h``.

    - ``h < 3``: already metres (1);
    - CMU/cgspeed joint names (``LHipJoint``, ``LowerBack``) and ``h`` in 15-60: CMU ASF units (0.05644);
    - ``20 <= h < 45`` otherwise: CMU units as well (a 1.7 m person is ~30 units);
    - ``45 <= h < 110``: inches; ``110 <= h < 300``: centimetres; ``800 <= h < 3000``: millimetres.
    Anything else raises :class:`BVHError` asking for an explicit ``scale``.
    """
    pos = skeleton.rest_positions()
    ends = [pos[j] + o for j, o in skeleton.end_sites]
    allp = np.vstack([pos, *ends]) if ends else pos
    h = float(np.max(np.ptp(allp, axis=0))) if len(allp) > 1 else 0.0
    cmu_names = {"LHipJoint", "LowerBack"} <= set(skeleton.names)
    if h < 3:
        return 1.0
    if cmu_names and 15 <= h < 60:
        return CMU_UNIT
    if 20 <= h < 45:
        return CMU_UNIT
    if 45 <= h < 110:
        return 0.0254
    if 110 <= h < 300:
        return 0.01
    if 800 <= h < 3000:
        return 0.001
    raise BVHError(f"cannot guess the length unit of a skeleton {h:.3g} units tall; pass an explicit scale")


def _rotation_columns(skel: Skeleton) -> dict[str, tuple[list[int], list[list[int]]]]:
    """Joints grouped by Euler order: ``order -> (joints, their rotation columns in the frame data)``."""
    groups: dict[str, tuple[list[int], list[list[int]]]] = {}
    col = 0
    for j, chans in enumerate(skel.channels):
        cols = [col + k for k, c in enumerate(chans) if c in ROTATION_CHANNELS]
        joints, columns = groups.setdefault(skel.rotation_order(j), ([], []))
        joints.append(j)
        columns.append(cols)
        col += len(chans)
    return groups


def _build_motion(skel: Skeleton, data: np.ndarray, fps: float) -> Motion:
    """Frame data ``(T, C)`` to a motion: one vectorised Euler conversion per distinct rotation order."""
    T, J = len(data), skel.n_joints
    groups = _rotation_columns(skel)
    if len(groups) == 1 and "" not in groups:  # every joint in one order (CMU, most exporters): no scatter
        ((order, (_, columns)),) = groups.items()
        angles = data.take(np.ravel(columns), axis=1).reshape(T, J, len(order))  # C order, unlike data[:, cols]
        rotations = quat.from_euler(order, angles, degrees=True)
    else:
        rotations = np.zeros((T, J, 4))
        rotations[..., 3] = 1.0  # joints without rotation channels keep the identity
        for order, (joints, columns) in groups.items():
            if not order:
                continue
            angles = data[:, np.array(columns, dtype=np.intp).reshape(len(joints), len(order))]  # (T, Jg, n)
            rotations[:, joints] = quat.from_euler(order, angles, degrees=True)
    root = np.tile(skel.offsets[0], (T, 1))
    trans = None
    col = 0
    for j, chans in enumerate(skel.channels):
        if not chans:
            continue
        block = data[:, col:col + len(chans)]
        col += len(chans)
        pos_idx = {c[0]: k for k, c in enumerate(chans) if c in POSITION_CHANNELS}
        if not pos_idx:
            continue
        target = np.tile(skel.offsets[j], (T, 1))
        for axis, k in pos_idx.items():
            target[:, "XYZ".index(axis)] += block[:, k]
        if j == 0:
            root = target
        else:
            if trans is None:
                trans = np.broadcast_to(skel.offsets, (T, J, 3)).copy()
            trans[:, j] = target
    return Motion(skel, fps, root, rotations, trans)


def _z_up_to_y_up(m: Motion) -> Motion:
    from scipy.spatial.transform import Rotation

    c = Rotation.from_euler("x", -90, degrees=True)  # -90 degrees about X maps (x, y, z) to (x, z, -y)
    skel = m.skeleton
    new_skel = Skeleton(skel.names, skel.parents, c.apply(np.array(skel.offsets)),
                        tuple((j, c.apply(np.array(o))) for j, o in skel.end_sites), skel.channels)
    T, J = m.rotations.shape[:2]
    r = Rotation.from_quat(m.rotations.reshape(-1, 4))
    cc = Rotation.concatenate([c] * len(r)) if len(r) else c
    rots = (cc * r * cc.inv()).as_quat().reshape(T, J, 4) if len(r) else m.rotations
    # (scipy takes no read-only arrays: a motion's are)
    trans = None if m.translations is None else c.apply(np.array(m.translations).reshape(-1, 3)).reshape(T, J, 3)
    root = c.apply(np.array(m.root_positions)) if T else m.root_positions
    return Motion(new_skel, m.fps, root, rots, trans)


def _scaled(m: Motion, s: float) -> Motion:
    if s == 1.0:
        return m
    return Motion(m.skeleton.scaled(s), m.fps, m.root_positions * s, m.rotations,
                  None if m.translations is None else m.translations * s)


def parse_bvh(text: str, *, source: str = "<bvh>", scale: float | str = "auto",
              up: str = "y", drop_first: bool = False) -> Motion:
    """Parse BVH text into a :class:`Motion` in metres, Y up.

    Args:
        scale: ``"auto"`` (see :func:`guess_scale`) or metres per file unit.
        up: ``"y"`` (as is) or ``"z"`` (the file is Z-up; converted to Y-up).
        drop_first: drop frame 0 (the T-pose that some exporters, cgspeed among them, prepend).
    """
    skel, frame_time, data = parse_channels(text, source)
    motion = _build_motion(skel, data, 1.0 / frame_time)
    if up.lower() == "z":
        motion = _z_up_to_y_up(motion)
    elif up.lower() != "y":
        raise ValueError(f"up must be 'y' or 'z', not {up!r}")
    s = guess_scale(motion.skeleton) if scale == "auto" else float(scale)
    if not (np.isfinite(s) and s > 0):
        raise BVHError(f"{source}: scale must be a positive number, got {scale!r}")
    motion = _scaled(motion, s)
    if drop_first and motion.n_frames:
        motion = motion.frames(1)
    return motion


def read_bvh(path: str | os.PathLike, **options) -> Motion:
    """Read a BVH file; options as :func:`parse_bvh`."""
    path = Path(path)
    raw = read_input(path, "BVH", BVHError)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    del raw  # up to 64 MB no longer needed while the text is parsed
    if "\x00" in text:
        raise BVHError(f"{path}:1: binary data, not a BVH text file")
    return parse_bvh(text, source=str(path), **options)
