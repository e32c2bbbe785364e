"""Files a user hands us, read safely, and names shown safely.

Every reader of a user's file (BVH, glTF/VRM rig, joint map, batch corpus) reads it
through :func:`read_input`: a regular file only, never more than its kind's limit.
A FIFO, a device (``/dev/zero``), a folder or a symlink loop is refused at once with
one line naming the file, instead of hanging or filling the memory.

==========  ============  =====================================
kind        limit         read by
==========  ============  =====================================
BVH         64 MB         ``core.bvh.read_bvh``
rig         64 MB         ``core.gltf_rig.read_glb``
joint map   1 MB          ``core.rigs.load_joint_map``
corpus      16 MB         ``cli.batch.corpus.load_corpus``
project     1 MB          ``cli.project.read_project``
==========  ============  =====================================

Names that come from a file or the database (verbs, objects, clip, character and
joint names) may hold control characters; :func:`printable` escapes them before they
reach a terminal, and :func:`control_in` finds them so an import can refuse them.
"""
from __future__ import annotations

import errno
import os
import stat
import unicodedata

MB = 1 << 20
#: The most bytes read of each kind of file.
LIMITS = {"BVH": 64 * MB, "rig": 64 * MB, "joint map": 1 * MB, "corpus": 16 * MB, "project": 1 * MB}

#: Characters of a user's data (a token, a line, a name) a message quotes.
QUOTE_WIDTH = 40

#: Bidirectional-override characters, which make a terminal show text other than what it is.
BIDI_CONTROLS = frozenset("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


class InputFileError(ValueError):
    """A user's file that is not a readable regular file within its limit (one line)."""

    user_facing = True


def _mb(n: int) -> str:
    return f"{n // MB} MB" if n % MB == 0 else f"{n} bytes"


def read_input(path: str | os.PathLike, kind: str, error: type[Exception] = InputFileError) -> bytes:
    """The bytes of the ``kind`` file at ``path`` (a key of :data:`LIMITS`).

    Opened without blocking (a FIFO with no writer does not hang), checked to be a
    regular file, and read to at most the limit + 1 bytes; anything else raises
    ``error`` (a ``user_facing`` exception class taking one message).
    """
    limit = LIMITS[kind]
    name = os.fspath(path)
    try:
        fd = os.open(name, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise error(f"{name}: {_why(exc, kind)}") from None
    data = b""
    try:
        st = os.fstat(fd)
        refused = _refusal(st, kind, limit)
        data = b"" if refused else _read(fd, limit)
    except OSError as exc:
        refused = _why(exc, kind)
    finally:
        os.close(fd)
    if refused:
        raise error(f"{name}: {refused}")
    if len(data) > limit:  # grew while being read
        raise error(f"{name}: over {_mb(limit)}; a {kind} file may have at most {_mb(limit)}")
    return data


def _refusal(st: os.stat_result, kind: str, limit: int) -> str | None:
    if stat.S_ISDIR(st.st_mode):
        return f"is a folder, not a {kind} file"
    if not stat.S_ISREG(st.st_mode):
        return f"not a regular file (a pipe, device or socket); give the {kind} file itself"
    if st.st_size > limit:
        return f"{st.st_size} bytes; a {kind} file may have at most {_mb(limit)}"
    return None


def _read(fd: int, limit: int) -> bytes:
    with os.fdopen(fd, "rb", closefd=False) as fh:
        return fh.read(limit + 1)


def _why(exc: OSError, kind: str) -> str:
    if exc.errno == errno.ENOENT:
        return "no such file"
    if exc.errno == errno.ELOOP:
        return f"cannot read the {kind} file (a loop of symbolic links)"
    return f"cannot read the {kind} file ({exc.strerror or exc})"


def is_control(ch: str) -> bool:
    """True for a C0/C1 control or DEL (category Cc) and for a text-direction override."""
    return unicodedata.category(ch) == "Cc" or ch in BIDI_CONTROLS


def control_in(text: str) -> str | None:
    """The first control or text-direction character of ``text``, or ``None``."""
    return next((ch for ch in text if is_control(ch)), None)


def printable(text: str, keep: str = "") -> str:
    """``text`` with control and bidi characters shown as ``\\x1b``/``\\u202e`` escapes (safe on a terminal).

    ``keep``: characters left as they are (``"\\n"`` for text of several lines).
    """
    return "".join(ch.encode("unicode_escape").decode("ascii") if is_control(ch) and ch not in keep else ch
                   for ch in text)


def quoted(text: str, width: int = QUOTE_WIDTH, *, length: int | None = None) -> str:
    """``text`` quoted for a message, cut to ``width`` characters *before* it is quoted and escaped (a 63 MB
    token of ESC bytes quoted whole was 250 MB of ``\\x1b``), saying how long it was when it was cut;
    ``length``: the length of the whole when ``text`` is its first characters only."""
    length = len(text) if length is None else length
    if length <= width:
        return repr(text)
    return f"{text[:width]!r}… ({length:,} characters)"
