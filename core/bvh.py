"""BVH reader and writer.

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
The writer needs no recursion: any hierarchy the reader accepts is written back.

Root position: the root's world position is its OFFSET plus its position
channels (Blender's reading); the writer inverts that.

Units: lengths are converted to metres on reading. ``scale="auto"`` guesses
the unit from the rest pose's largest extent ``h`` (see :func:`guess_scale`);
a number multiplies every length by it; ``1`` keeps the file's units.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from . import quat
from .motion import Motion
from .skeleton import POSITION_CHANNELS, ROTATION_CHANNELS, Skeleton

#: CMU's ASF length unit in metres (1/0.45 inch), used by cgspeed's BVH release.
CMU_UNIT = 0.0254 / 0.45

#: At most this many joints (skeletons with fingers and face have a few hundred).
MAX_JOINTS = 10_000
#: At most this many joint-frames (frames x joints): the rotations alone take 32 bytes each, so a
#: few hundred bytes of channel-less joints cannot ask for gigabytes (22 min of 31 joints at 120 fps).
MAX_JOINT_FRAMES = 5_000_000
#: ``Frame Time`` in seconds: 1e-5 (100 kHz) to an hour.
FRAME_TIME_RANGE = (1e-5, 3600.0)
#: Largest offset or position value, in file units (a kilometre in millimetres).
MAX_LENGTH = 1e6
#: Largest rotation value, in degrees (a thousand turns).
MAX_DEGREES = 360_000.0

_VALID_CHANNELS = {c.upper(): c for c in POSITION_CHANNELS + ROTATION_CHANNELS}

# scipy.spatial.transform is imported by the functions that use it (it is slow to load).


class BVHError(ValueError):
    """A BVH file that cannot be read; the message names file and line."""

    user_facing = True


class _Tokens:
    """Hierarchy tokens with their line numbers."""

    def __init__(self, lines: list[str], source: str):
        self.items: list[tuple[str, int, int]] = []  # (token, line number, index in line)
        self.lines = lines
        self.source = source
        for lineno, line in enumerate(lines, start=1):
            for k, tok in enumerate(line.split()):
                self.items.append((tok, lineno, k))
        self.pos = 0

    def error(self, msg: str, lineno: int | None = None) -> BVHError:
        if lineno is None:
            lineno = self.items[self.pos][1] if self.pos < len(self.items) else len(self.lines)
        return BVHError(f"{self.source}:{lineno}: {msg}")

    def next(self, what: str) -> tuple[str, int, int]:
        if self.pos >= len(self.items):
            raise self.error(f"unexpected end of file, expected {what}")
        item = self.items[self.pos]
        self.pos += 1
        return item

    def expect(self, keyword: str) -> int:
        tok, lineno, _ = self.next(keyword)
        if tok.upper() != keyword.upper():
            raise self.error(f"expected {keyword!r}, found {tok!r}", lineno)
        return lineno

    def number(self, what: str) -> float:
        tok, lineno, _ = self.next(what)
        try:
            value = float(tok)
        except ValueError:
            raise self.error(f"expected a number for {what}, found {tok!r}", lineno) from None
        if not np.isfinite(value):
            raise self.error(f"{what} is not finite ({tok})", lineno)
        if abs(value) > MAX_LENGTH:
            raise self.error(f"{what} is {tok}, beyond ±{MAX_LENGTH:g} units", lineno)
        return value

    def rest_of_line(self, lineno: int) -> str:
        parts = []
        while self.pos < len(self.items) and self.items[self.pos][1] == lineno:
            parts.append(self.items[self.pos][0])
            self.pos += 1
        return " ".join(parts)

    def peek(self) -> str | None:
        return self.items[self.pos][0].upper() if self.pos < len(self.items) else None


def _parse_hierarchy(tok: _Tokens):
    names: list[str] = []
    parents: list[int] = []
    offsets: list[list[float]] = []
    channels: list[tuple[str, ...]] = []
    end_sites: list[tuple[int, list[float]]] = []

    tok.expect("HIERARCHY")
    kw, lineno, _ = tok.next("ROOT")
    if kw.upper() != "ROOT":
        raise tok.error(f"expected 'ROOT', found {kw!r}", lineno)
    # Explicit stack instead of recursion: deep or hostile files cannot overflow.
    stack: list[int] = []  # joint index per open brace, -2 for an End Site
    pending_parent = -1
    name = tok.rest_of_line(lineno)
    seen: set[str] = set()  # a set: a file with 100k joints is refused at once, not after minutes
    while True:
        if not name:
            raise tok.error("joint without a name", lineno)
        if name in seen:
            raise tok.error(f"duplicate joint name {name!r}", lineno)
        if len(names) >= MAX_JOINTS:
            raise tok.error(f"more than {MAX_JOINTS} joints", lineno)
        seen.add(name)
        j = len(names)
        names.append(name)
        parents.append(pending_parent)
        tok.expect("{")
        tok.expect("OFFSET")
        offsets.append([tok.number("OFFSET x"), tok.number("OFFSET y"), tok.number("OFFSET z")])
        chans: tuple[str, ...] = ()
        if tok.peek() == "CHANNELS":
            tok.next("CHANNELS")
            n = tok.number("channel count")
            if n != int(n) or not 0 <= n <= 6:
                raise tok.error(f"channel count must be 0..6, found {n:g}")
            ch = []
            for _ in range(int(n)):
                c, ln, _ = tok.next("a channel name")
                if c.upper() not in _VALID_CHANNELS:
                    raise tok.error(f"unknown channel {c!r}", ln)
                ch.append(_VALID_CHANNELS[c.upper()])
            if len(set(ch)) != len(ch):
                raise tok.error(f"repeated channel in {' '.join(ch)}")
            chans = tuple(ch)
        channels.append(chans)
        stack.append(j)
        # Children, end sites and closing braces until the next JOINT opens.
        while True:
            word, lineno, _ = tok.next("JOINT, End Site or '}'")
            w = word.upper()
            if w == "JOINT":
                pending_parent = stack[-1]
                name = tok.rest_of_line(lineno)
                break
            if w == "END":
                tok.expect("SITE")
                tok.expect("{")
                tok.expect("OFFSET")
                end_sites.append((stack[-1], [tok.number("OFFSET x"), tok.number("OFFSET y"), tok.number("OFFSET z")]))
                tok.expect("}")
                continue
            if w == "}":
                stack.pop()
                if not stack:
                    nxt = tok.peek()
                    if nxt == "ROOT":
                        raise tok.error("more than one ROOT: this reader reads one character per file")
                    if nxt is None:
                        raise tok.error("unexpected end of file, expected 'MOTION'")
                    if nxt != "MOTION":
                        raise tok.error(f"expected 'MOTION' after the hierarchy, found {nxt!r}")
                    return names, parents, offsets, channels, end_sites
                continue
            raise tok.error(f"expected JOINT, End Site or '}}', found {word!r}", lineno)


_FRAMES_RE = re.compile(r"^\s*frames\s*:?\s*(\S+)\s*$", re.IGNORECASE)
_FRAME_TIME_RE = re.compile(r"^\s*frame\s*time\s*:?\s*(\S+)\s*$", re.IGNORECASE)


def _parse_motion_header(lines: list[str], start: int, source: str) -> tuple[int, float, int]:
    """Frames and Frame Time lines after MOTION; returns (frames, frame_time, first data line index)."""
    i = start
    found: dict[str, tuple[str, int]] = {}
    for regex, key in ((_FRAMES_RE, "frames"), (_FRAME_TIME_RE, "frame time")):
        while i < len(lines) and not lines[i].strip():
            i += 1
        if i >= len(lines):
            raise BVHError(f"{source}:{len(lines)}: unexpected end of file, expected '{key.title()}:'")
        m = regex.match(lines[i])
        if not m:
            raise BVHError(f"{source}:{i + 1}: expected '{key.title()}:', found {lines[i].strip()[:40]!r}")
        found[key] = (m.group(1), i + 1)
        i += 1
    try:
        frames = int(found["frames"][0])
    except ValueError:
        raise BVHError(f"{source}:{found['frames'][1]}: frame count {found['frames'][0]!r} is not a whole number") from None
    try:
        frame_time = float(found["frame time"][0])
    except ValueError:
        raise BVHError(f"{source}:{found['frame time'][1]}: frame time {found['frame time'][0]!r} is not a number") from None
    if frames < 0:
        raise BVHError(f"{source}:{found['frames'][1]}: negative frame count {frames}")
    if not (np.isfinite(frame_time) and frame_time > 0):
        raise BVHError(f"{source}:{found['frame time'][1]}: frame time must be a positive number, found {frame_time}")
    lo, hi = FRAME_TIME_RANGE
    if not lo <= frame_time <= hi:
        raise BVHError(f"{source}:{found['frame time'][1]}: frame time {frame_time:g} s is outside "
                       f"{lo:g}-{hi:g} s ({1 / hi:g} to {1 / lo:g} frames per second)")
    return frames, frame_time, i


def _locate_bad_value(lines: list[str], first: int, n_channels: int, source: str) -> BVHError:
    """Slow path, only on error: find the first data line that is not n_channels finite numbers."""
    for k, line in enumerate(lines[first:], start=first + 1):
        toks = line.split()
        if not toks:
            continue
        if len(toks) != n_channels:
            return BVHError(f"{source}:{k}: {len(toks)} values on a frame line, the hierarchy declares {n_channels} channels")
        for t in toks:
            try:
                v = float(t)
            except ValueError:
                return BVHError(f"{source}:{k}: {t!r} is not a number")
            if not np.isfinite(v):
                return BVHError(f"{source}:{k}: {t!r} is not a finite number")
    return BVHError(f"{source}: malformed frame data")


def _parse_frames(lines: list[str], first: int, frames: int, channels, source: str) -> np.ndarray:
    n_channels = sum(len(c) for c in channels)
    data_lines = [ln for ln in lines[first:] if ln.strip()]
    if len(data_lines) != frames:
        where = f"{source}:{len(lines)}"
        raise BVHError(f"{where}: the file declares {frames} frames but has {len(data_lines)} frame lines"
                       + (" (truncated?)" if len(data_lines) < frames else ""))
    if frames == 0:
        return np.zeros((0, n_channels))
    try:  # numpy's C reader: whitespace-separated, one frame per line, no comment syntax
        values = np.loadtxt(data_lines, dtype=np.float64, comments=None, ndmin=2)
    except ValueError:
        raise _locate_bad_value(lines, first, n_channels, source) from None
    if values.shape != (frames, n_channels) or not np.all(np.isfinite(values)):
        raise _locate_bad_value(lines, first, n_channels, source)
    _check_ranges(values, channels, first, lines, source)
    return values


def _check_ranges(values: np.ndarray, channels, first: int, lines: list[str], source: str) -> None:
    """Refuse positions beyond :data:`MAX_LENGTH` units and rotations beyond :data:`MAX_DEGREES`, ``(T, C)``."""
    flat = [c for chans in channels for c in chans]
    limit = np.array([MAX_DEGREES if c in ROTATION_CHANNELS else MAX_LENGTH for c in flat])
    bad = np.abs(values) > limit
    if not bad.any():
        return
    f, k = np.argwhere(bad)[0]
    data_lines = [i for i in range(first, len(lines)) if lines[i].strip()]
    unit = "degrees" if flat[k] in ROTATION_CHANNELS else "units"
    raise BVHError(f"{source}:{data_lines[f] + 1}: {flat[k]} value {values[f, k]:g} is beyond "
                   f"±{limit[k]:g} {unit}")


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


_JOINT_RE = re.compile(r"^[ \t]*(?:joint|root)\b", re.IGNORECASE | re.MULTILINE)


def _check_joint_count(head: list[str], source: str) -> None:
    """Refuse more than :data:`MAX_JOINTS` joints at C speed, before the hierarchy is tokenised."""
    text = "\n".join(head)
    for k, m in enumerate(_JOINT_RE.finditer(text)):
        if k == MAX_JOINTS:
            raise BVHError(f"{source}:{text.count(chr(10), 0, m.start()) + 1}: more than {MAX_JOINTS} joints")


def _build_motion(skel: Skeleton, data: np.ndarray, fps: float) -> Motion:
    """Frame data ``(T, C)`` to a motion: one vectorised Euler conversion per distinct rotation order."""
    T, J = len(data), skel.n_joints
    rotations = np.zeros((T, J, 4))
    rotations[..., 3] = 1.0  # joints without rotation channels keep the identity
    for order, (joints, columns) in _rotation_columns(skel).items():
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
    trans = None if m.translations is None else c.apply(m.translations.reshape(-1, 3)).reshape(T, J, 3)
    root = c.apply(m.root_positions) if T else m.root_positions
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
    if text.startswith("\ufeff"):
        text = text[1:]
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    motion_idx = next((i for i, ln in enumerate(lines) if ln.strip().upper() == "MOTION"), None)
    head = lines[:motion_idx] if motion_idx is not None else lines
    _check_joint_count(head, source)
    tok = _Tokens(head, source)
    if motion_idx is not None:
        tok.items.append(("MOTION", motion_idx + 1, 0))
    names, parents, offsets, channels, end_sites = _parse_hierarchy(tok)
    if tok.pos != len(tok.items) - 1:
        raise tok.error("unexpected text after the hierarchy")
    skel = Skeleton(names, parents, offsets, end_sites, channels)
    frames, frame_time, first = _parse_motion_header(lines, motion_idx + 1, source)
    if frames * len(names) > MAX_JOINT_FRAMES:
        raise BVHError(f"{source}:{motion_idx + 2}: {frames} frames of {len(names)} joints is more than "
                       f"{MAX_JOINT_FRAMES:,} joint-frames; split the file")
    data = _parse_frames(lines, first, frames, channels, source)
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
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise BVHError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise BVHError(f"{path}: is a directory, not a BVH file") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    if "\x00" in text:
        raise BVHError(f"{path}:1: binary data, not a BVH text file")
    return parse_bvh(text, source=str(path), **options)


# ---------------------------------------------------------------------- writer
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
    from .atomic import atomic_write_text

    atomic_write_text(path, format_bvh(m))
