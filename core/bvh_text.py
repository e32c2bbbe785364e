"""The BVH text grammar for :mod:`text2anim.core.bvh`: the hierarchy's tokens and joints, the MOTION
header and the frame data, with the limits that keep any file's work bounded checked on the way
(:class:`BVHError` names file and line)."""
from __future__ import annotations

import re

import numpy as np

from .skeleton import POSITION_CHANNELS, ROTATION_CHANNELS, Skeleton

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


class BVHError(ValueError):
    """A BVH file that cannot be read; the message names file and line."""

    user_facing = True


class Tokens:
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


def parse_hierarchy(tok: Tokens):
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


def parse_motion_header(lines: list[str], start: int, source: str) -> tuple[int, float, int]:
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
                if not t.isascii() or "_" in t:  # float() takes '1_000' and '１２'; numpy's reader takes neither
                    raise ValueError(t)
                v = float(t)
            except ValueError:
                return BVHError(f"{source}:{k}: {t!r} is not a number")
            if not np.isfinite(v):
                return BVHError(f"{source}:{k}: {t!r} is not a finite number")
    return BVHError(f"{source}: malformed frame data")  # numpy refused what float() reads: not seen


def parse_frames(lines: list[str], first: int, frames: int, channels, source: str) -> np.ndarray:
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
    if values.shape != (frames, n_channels):
        raise _locate_bad_value(lines, first, n_channels, source)
    _check_values(values, channels, first, lines, source)
    return values


def _check_values(values: np.ndarray, channels, first: int, lines: list[str], source: str) -> None:
    """Refuse non-finite values, positions beyond :data:`MAX_LENGTH` units and rotations beyond
    :data:`MAX_DEGREES`, ``(T, C)``: one bound check covers all three (NaN and infinity fail it too)."""
    flat = [c for chans in channels for c in chans]
    limit = np.array([MAX_DEGREES if c in ROTATION_CHANNELS else MAX_LENGTH for c in flat])
    if (np.abs(values) <= limit).all():
        return
    if not np.all(np.isfinite(values)):
        raise _locate_bad_value(lines, first, len(flat), source)
    bad = np.abs(values) > limit
    f, k = np.argwhere(bad)[0]
    data_lines = [i for i in range(first, len(lines)) if lines[i].strip()]
    unit = "degrees" if flat[k] in ROTATION_CHANNELS else "units"
    raise BVHError(f"{source}:{data_lines[f] + 1}: {flat[k]} value {values[f, k]:g} is beyond "
                   f"±{limit[k]:g} {unit}")


_JOINT_RE = re.compile(r"^[ \t]*(?:joint|root)\b", re.IGNORECASE | re.MULTILINE)


def check_joint_count(head: list[str], source: str) -> None:
    """Refuse more than :data:`MAX_JOINTS` joints at C speed, before the hierarchy is tokenised."""
    text = "\n".join(head)
    for k, m in enumerate(_JOINT_RE.finditer(text)):
        if k == MAX_JOINTS:
            raise BVHError(f"{source}:{text.count(chr(10), 0, m.start()) + 1}: more than {MAX_JOINTS} joints")


def parse_channels(text: str, source: str = "<bvh>") -> tuple[Skeleton, float, np.ndarray]:
    """BVH text to its skeleton (file units, as written), ``Frame Time`` in seconds and the frame data
    ``(T, C)`` in the file's channel order, every limit above checked; :func:`~text2anim.core.bvh.parse_bvh`
    turns these into a motion."""
    if text.startswith("\ufeff"):
        text = text[1:]
    if "\r" in text:
        text = text.replace("\r\n", "\n").replace("\r", "\n")
    lines = text.split("\n")
    motion_idx = next((i for i, ln in enumerate(lines) if ln.strip().upper() == "MOTION"), None)
    head = lines[:motion_idx] if motion_idx is not None else lines
    check_joint_count(head, source)
    tok = Tokens(head, source)
    if motion_idx is not None:
        tok.items.append(("MOTION", motion_idx + 1, 0))
    names, parents, offsets, channels, end_sites = parse_hierarchy(tok)
    if tok.pos != len(tok.items) - 1:
        raise tok.error("unexpected text after the hierarchy")
    skel = Skeleton(names, parents, offsets, end_sites, channels)
    if motion_idx is None:  # the hierarchy ends in MOTION, so it was refused above; this keeps it explicit
        raise BVHError(f"{source}: no MOTION section")
    frames, frame_time, first = parse_motion_header(lines, motion_idx + 1, source)
    if frames * len(names) > MAX_JOINT_FRAMES:
        raise BVHError(f"{source}:{motion_idx + 2}: {frames} frames of {len(names)} joints is more than "
                       f"{MAX_JOINT_FRAMES:,} joint-frames; split the file")
    return skel, frame_time, parse_frames(lines, first, frames, channels, source)
