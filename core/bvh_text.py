"""The BVH text grammar for :mod:`text2anim.core.bvh`: the hierarchy's tokens and joints, the MOTION
header and the frame data, with the limits that keep any file's work bounded checked on the way
(:class:`BVHError` names file and line)."""
from __future__ import annotations

import io
import itertools
import re
import warnings

import numpy as np

from .inputs import QUOTE_WIDTH, quoted
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


#: Longest token of the hierarchy (a keyword, a number, a word of a name) and longest joint name, in characters.
MAX_TOKEN = 256
#: Characters of a header line (``Frames:``, ``Frame Time:``) and, per channel, of a frame line.
MAX_HEADER_LINE = 256
MAX_CHARS_PER_VALUE = 64

_TOKEN_RE = re.compile(r"\S+")


class Tokens:
    """The hierarchy's tokens with their line numbers, read one ahead from the text (never listed: a 60 MB
    file of newlines or one 63 MB token costs one pass at C speed, not a list of millions of lines)."""

    def __init__(self, head: str, source: str):
        self.head = head
        self.source = source
        self._found = _TOKEN_RE.finditer(head)
        self._line, self._at = 1, 0  # the line number at offset _at
        self._ahead = self._read()

    def _read(self) -> tuple[str, int] | None:
        m = next(self._found, None)
        if m is None:
            return None
        start, end = m.span()
        self._line += self.head.count("\n", self._at, start)
        self._at = start
        if end - start > MAX_TOKEN:
            raise self.error(f"a word of {end - start:,} characters, over {MAX_TOKEN} "
                             f"(it starts {quoted(self.head[start:start + QUOTE_WIDTH], length=end - start)})", self._line)
        return m.group(), self._line

    def error(self, msg: str, lineno: int | None = None) -> BVHError:
        if lineno is None:
            lineno = self._ahead[1] if self._ahead else self.head.count("\n") + 1
        return BVHError(f"{self.source}:{lineno}: {msg}")

    def next(self, what: str) -> tuple[str, int]:
        item = self._ahead
        if item is None:
            raise self.error(f"unexpected end of file, expected {what}")
        self._ahead = self._read()
        return item

    def expect(self, keyword: str) -> int:
        tok, lineno = self.next(keyword)
        if tok.upper() != keyword.upper():
            raise self.error(f"expected {keyword!r}, found {quoted(tok)}", lineno)
        return lineno

    def number(self, what: str) -> float:
        tok, lineno = self.next(what)
        try:
            value = float(tok)
        except ValueError:
            raise self.error(f"expected a number for {what}, found {quoted(tok)}", lineno) from None
        if not np.isfinite(value):
            raise self.error(f"{what} is not finite ({quoted(tok)})", lineno)
        if abs(value) > MAX_LENGTH:
            raise self.error(f"{what} is {quoted(tok)}, beyond ±{MAX_LENGTH:g} units", lineno)
        return value

    def rest_of_line(self, lineno: int) -> str:
        parts: list[str] = []
        size = 0
        while self._ahead is not None and self._ahead[1] == lineno:
            size += len(self._ahead[0]) + 1
            if size > MAX_TOKEN + 1:
                raise self.error(f"a joint name over {MAX_TOKEN} characters", lineno)
            parts.append(self.next("a name")[0])
        return " ".join(parts)

    def peek(self) -> str | None:
        return self._ahead[0].upper() if self._ahead else None


def parse_hierarchy(tok: Tokens):
    names: list[str] = []
    parents: list[int] = []
    offsets: list[list[float]] = []
    channels: list[tuple[str, ...]] = []
    end_sites: list[tuple[int, list[float]]] = []

    tok.expect("HIERARCHY")
    kw, lineno = tok.next("ROOT")
    if kw.upper() != "ROOT":
        raise tok.error(f"expected 'ROOT', found {quoted(kw)}", lineno)
    # Explicit stack instead of recursion: deep or hostile files cannot overflow.
    stack: list[int] = []  # joint index per open brace, -2 for an End Site
    pending_parent = -1
    name = tok.rest_of_line(lineno)
    seen: set[str] = set()  # a set: a file with 100k joints is refused at once, not after minutes
    while True:
        if not name:
            raise tok.error("joint without a name", lineno)
        if name in seen:
            raise tok.error(f"duplicate joint name {quoted(name)}", lineno)
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
                c, ln = tok.next("a channel name")
                if c.upper() not in _VALID_CHANNELS:
                    raise tok.error(f"unknown channel {quoted(c)}", ln)
                ch.append(_VALID_CHANNELS[c.upper()])
            if len(set(ch)) != len(ch):
                raise tok.error(f"repeated channel in {' '.join(ch)}")
            chans = tuple(ch)
        channels.append(chans)
        stack.append(j)
        # Children, end sites and closing braces until the next JOINT opens.
        while True:
            word, lineno = tok.next("JOINT, End Site or '}'")
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
                        raise tok.error(f"expected 'MOTION' after the hierarchy, found {quoted(nxt)}")
                    return names, parents, offsets, channels, end_sites
                continue
            raise tok.error(f"expected JOINT, End Site or '}}', found {quoted(word)}", lineno)


_FRAMES_RE = re.compile(r"^\s*frames\s*:?\s*(\S+)\s*$", re.IGNORECASE)
_FRAME_TIME_RE = re.compile(r"^\s*frame\s*time\s*:?\s*(\S+)\s*$", re.IGNORECASE)
_MOTION_RE = re.compile(r"^[^\S\n]*MOTION[^\S\n]*$", re.IGNORECASE | re.MULTILINE)
_BLANKS_RE = re.compile(r"\s*")
_EXTRA_LINES_COUNTED = 10_000  # frame lines past the declared count that a message counts
_DATA_LINE_RE = re.compile(r"\S[^\n]*")  # a frame line from its first value (no backtracking over blanks)


def _line_at(text: str, offset: int) -> int:
    """The 1-based line number of ``offset`` in ``text``."""
    return text.count("\n", 0, offset) + 1


def parse_motion_header(text: str, start: int, source: str) -> tuple[int, float, int]:
    """Frames and Frame Time lines from offset ``start`` (after MOTION); returns (frames, frame_time,
    offset of the frame data). Blank lines between them are skipped at C speed."""
    i = start
    found: dict[str, tuple[str, int]] = {}
    for regex, key in ((_FRAMES_RE, "frames"), (_FRAME_TIME_RE, "frame time")):
        blanks = _BLANKS_RE.match(text, i)  # always matches (perhaps nothing)
        i = blanks.end() if blanks else i
        lineno = _line_at(text, i)
        if i >= len(text):
            raise BVHError(f"{source}:{lineno}: unexpected end of file, expected '{key.title()}:'")
        end = text.find("\n", i)
        end = len(text) if end < 0 else end
        m = regex.match(text[i:end]) if end - i <= MAX_HEADER_LINE else None
        if not m:
            raise BVHError(f"{source}:{lineno}: expected '{key.title()}:', found {quoted(text[i:i + QUOTE_WIDTH], length=end - i)}")
        found[key] = (m.group(1), lineno)
        i = end
    (frames_text, frames_line), (time_text, time_line) = found["frames"], found["frame time"]
    try:
        frames = int(frames_text)
    except ValueError:
        raise BVHError(f"{source}:{frames_line}: frame count {quoted(frames_text)} is not a whole number") from None
    try:
        frame_time = float(time_text)
    except ValueError:
        raise BVHError(f"{source}:{time_line}: frame time {quoted(time_text)} is not a number") from None
    if frames < 0:
        raise BVHError(f"{source}:{frames_line}: negative frame count {quoted(frames_text)}")
    if frames > MAX_JOINT_FRAMES:
        raise BVHError(f"{source}:{frames_line}: {quoted(frames_text)} frames is more than {MAX_JOINT_FRAMES:,} "
                       "joint-frames; split the file")
    if not (np.isfinite(frame_time) and frame_time > 0):
        raise BVHError(f"{source}:{time_line}: frame time must be a positive number, found {quoted(time_text)}")
    lo, hi = FRAME_TIME_RANGE
    if not lo <= frame_time <= hi:
        raise BVHError(f"{source}:{time_line}: frame time {frame_time:g} s is outside "
                       f"{lo:g}-{hi:g} s ({1 / hi:g} to {1 / lo:g} frames per second)")
    return frames, frame_time, i


def _data_lines(text: str, first: int):
    """``(offset, end)`` of every frame line (one that is not blank) from offset ``first``."""
    return (m.span() for m in _DATA_LINE_RE.finditer(text, first))


def _locate_bad_value(text: str, first: int, n_channels: int, source: str) -> BVHError:
    """Slow path, only on error: find the first data line that is not n_channels finite numbers,
    reading no line longer than a frame line can be (its number counted only for the message)."""
    width = n_channels * MAX_CHARS_PER_VALUE
    for a, b in _data_lines(text, first):
        where = f"{source}:{{}}"
        if b - a > width:
            return BVHError(f"{where.format(_line_at(text, a))}: a frame line of {b - a:,} characters, over {width:,} "
                            f"for {n_channels} channels (it starts {quoted(text[a:a + QUOTE_WIDTH], length=b - a)})")
        toks = text[a:b].split()
        if len(toks) != n_channels:
            return BVHError(f"{where.format(_line_at(text, a))}: {len(toks)} values on a frame line, the hierarchy "
                            f"declares {n_channels} channels")
        for t in toks:
            try:
                if not t.isascii() or "_" in t:  # float() takes '1_000' and '１２'; numpy's reader takes neither
                    raise ValueError(t)
                v = float(t)
            except ValueError:
                return BVHError(f"{where.format(_line_at(text, a))}: {quoted(t)} is not a number")
            if not np.isfinite(v):
                return BVHError(f"{where.format(_line_at(text, a))}: {quoted(t)} is not a finite number")
    return BVHError(f"{source}: malformed frame data")  # numpy refused what float() reads: not seen


def _count_error(text: str, first: int, frames: int, source: str) -> BVHError | None:
    """The error of a file whose frame lines (counted to a bound) are not the ``frames`` it declares, else None."""
    rows = sum(1 for _ in itertools.islice(_data_lines(text, first), frames + _EXTRA_LINES_COUNTED + 1))
    if rows == frames:
        return None
    found = f"more than {frames + _EXTRA_LINES_COUNTED}" if rows > frames + _EXTRA_LINES_COUNTED else str(rows)
    return BVHError(f"{source}:{_line_at(text, len(text))}: the file declares {frames} frames but has {found} "
                    "frame lines" + (" (truncated?)" if rows < frames else ""))


def parse_frames(text: str, first: int, frames: int, channels, source: str) -> np.ndarray:
    """The frame data ``(frames, C)`` from offset ``first``: numpy's C reader takes at most ``frames + 1``
    lines, so a file of millions of short lines is refused after one more than it declares."""
    n_channels = sum(len(c) for c in channels)
    if frames == 0 or n_channels == 0:
        rows = sum(1 for _ in itertools.islice(_data_lines(text, first), frames + 1))
        values = np.zeros((rows, n_channels))
    else:
        try:  # whitespace-separated, one frame per line, blank lines skipped, no comment syntax
            with warnings.catch_warnings():  # numpy says blank lines do not count towards max_rows: wanted
                warnings.simplefilter("ignore", UserWarning)
                values = np.loadtxt(io.StringIO(text[first:]), dtype=np.float64, comments=None, ndmin=2,
                                    max_rows=frames + 1)
        except ValueError:  # a truncated file is told so first (its cut last line is not the news)
            raise _count_error(text, first, frames, source) or _locate_bad_value(text, first, n_channels, source) \
                from None
        rows = len(values)
    if rows != frames:  # counted on to a bound: millions of one-character lines are not each looked at
        raise _count_error(text, first, frames, source) or BVHError(f"{source}: malformed frame data")
    if values.shape != (frames, n_channels):
        raise _locate_bad_value(text, first, n_channels, source)
    _check_values(values, channels, first, text, source)
    return values


def _check_values(values: np.ndarray, channels, first: int, text: str, source: str) -> None:
    """Refuse non-finite values, positions beyond :data:`MAX_LENGTH` units and rotations beyond
    :data:`MAX_DEGREES`, ``(T, C)``: one bound check covers all three (NaN and infinity fail it too)."""
    flat = [c for chans in channels for c in chans]
    limit = np.array([MAX_DEGREES if c in ROTATION_CHANNELS else MAX_LENGTH for c in flat])
    if len(values) and (values.max(axis=0) <= limit).all() and (-values.min(axis=0) <= limit).all():
        return  # per column: no temporary the size of the data (NaN propagates through max and min)
    if not len(values):
        return
    if not np.all(np.isfinite(values)):
        raise _locate_bad_value(text, first, len(flat), source)
    bad = np.abs(values) > limit
    f, k = np.argwhere(bad)[0]
    offset = next(itertools.islice(_data_lines(text, first), int(f), None))[0]
    unit = "degrees" if flat[k] in ROTATION_CHANNELS else "units"
    raise BVHError(f"{source}:{_line_at(text, offset)}: {flat[k]} value {values[f, k]:g} is beyond "
                   f"±{limit[k]:g} {unit}")


_JOINT_RE = re.compile(r"^[ \t]*(?:joint|root)\b", re.IGNORECASE | re.MULTILINE)


def check_joint_count(head: str, source: str) -> None:
    """Refuse more than :data:`MAX_JOINTS` joints at C speed, before the hierarchy is tokenised."""
    lowered = head.lower()
    if lowered.count("joint") + lowered.count("root") <= MAX_JOINTS:  # the line-anchored scan is slower
        return
    for k, m in enumerate(_JOINT_RE.finditer(head)):
        if k == MAX_JOINTS:
            raise BVHError(f"{source}:{_line_at(head, m.start())}: more than {MAX_JOINTS} joints")


def parse_channels(text: str, source: str = "<bvh>") -> tuple[Skeleton, float, np.ndarray]:
    """BVH text to its skeleton (file units, as written), ``Frame Time`` in seconds and the frame data
    ``(T, C)`` in the file's channel order, every limit above checked; :func:`~text2anim.core.bvh.parse_bvh`
    turns these into a motion. The text is never split into a list of lines: every step is a scan at C
    speed or a loop over what the file declares (joints, frames), so no token, line or run of blank
    lines within the 64 MB a file may have makes the work unbounded."""
    if text.startswith("\ufeff"):
        text = text[1:]
    if "\r" in text:
        text = text.replace("\r\n", "\n").replace("\r", "\n")
    motion = _MOTION_RE.search(text)
    head = text[:motion.end()] if motion else text  # the hierarchy and its closing MOTION keyword
    check_joint_count(head, source)
    tok = Tokens(head, source)
    names, parents, offsets, channels, end_sites = parse_hierarchy(tok)
    tok.next("MOTION")
    if tok.peek() is not None:
        raise tok.error("unexpected text after the hierarchy")
    skel = Skeleton(names, parents, offsets, end_sites, channels)
    if motion is None:  # the hierarchy ends in MOTION, so it was refused above; this keeps it explicit
        raise BVHError(f"{source}: no MOTION section")
    frames, frame_time, first = parse_motion_header(text, motion.end(), source)
    if frames * len(names) > MAX_JOINT_FRAMES:
        raise BVHError(f"{source}:{_line_at(text, motion.end()) + 1}: {frames} frames of {len(names)} joints is more "
                       f"than {MAX_JOINT_FRAMES:,} joint-frames; split the file")
    return skel, frame_time, parse_frames(text, first, frames, channels, source)
