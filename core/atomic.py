"""Atomic file writes: a file is either written whole or left as it was.

- Only a regular file or a missing path is written: a device (``/dev/full``,
  ``/dev/stdout``), a pipe, a socket or a folder at the path is refused, never
  replaced by a file.
- Several files (:func:`write_all`) are all-or-nothing without touching
  anything that existed before: every temporary is written and fsynced first,
  then all are renamed into place; on a failure before the renames only the
  temporaries are removed.
- The file and its folder are fsynced, so a crash after the call keeps the file.
- A temporary is named ``.NAME.PID.XXXXXXXX.part`` beside its file; one left by a writer that was
  killed (its process gone) is removed on the next write of that file (:func:`remove_stale_parts`).
- A replaced file keeps its permission bits (a 0600 file stays 0600); a symbolic link at
  the path is written through (the file it points to is replaced, the link stays).
"""
from __future__ import annotations

import os
import re
import stat
import tempfile
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

#: What a file's content may be: its bytes, or a function that writes it to the path it is given.
Content = bytes | Callable[[Path], None]


class OutputError(OSError, ValueError):
    """An output path that cannot be written (an ``OSError``, and a ``ValueError`` for a bad path)."""

    user_facing = True


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _shown(path: str) -> str:
    """A path short enough for a one-line message."""
    return path if len(path) <= 80 else path[:60] + "…" + path[-12:]


def check_output_path(path: str | os.PathLike) -> Path:
    """``path`` as a :class:`Path` if a file may be written there; else :class:`OutputError`.

    Checked before any work: a name (not empty, not too long), a folder that
    exists, and nothing but a regular file already at the path.
    """
    try:
        text = os.fspath(path)
    except TypeError:
        raise OutputError(f"an output path must be a str or path, not {type(path).__name__}") from None
    if isinstance(text, bytes):
        text = os.fsdecode(text)
    if not text:
        raise OutputError("empty output file name")
    if "\x00" in text:
        raise OutputError(f"{_shown(repr(text))}: a file name cannot contain a NUL character")
    p = Path(text)
    if text.endswith(("/", os.sep)) or p.name in ("", ".", ".."):
        raise OutputError(f"{_shown(text)}: names a folder, not a file")
    directory = p.parent
    try:
        name_max = os.pathconf(directory if directory.is_dir() else ".", "PC_NAME_MAX")
    except (OSError, ValueError):
        name_max = 255
    if len(os.fsencode(p.name)) > name_max:
        raise OutputError(f"{_shown(text)}: file name too long ({len(os.fsencode(p.name))} bytes; "
                          f"at most {name_max})")
    try:
        st = os.stat(p)
    except FileNotFoundError:
        st = None
    except NotADirectoryError:
        raise OutputError(f"{_shown(text)}: {directory} is not a folder") from None
    except OSError as exc:
        raise OutputError(f"{_shown(text)}: {exc.strerror or exc}") from None
    if st is not None and not stat.S_ISREG(st.st_mode):
        what = "a directory" if stat.S_ISDIR(st.st_mode) else "not a regular file (a device, pipe or socket)"
        raise OutputError(f"{_shown(text)}: is {what}; only regular files are written")
    if not directory.is_dir():
        raise OutputError(f"{_shown(text)}: the folder {_shown(str(directory))} does not exist")
    return p


def check_distinct(paths) -> None:
    """Refuse two outputs that name one file (``-o a.bvh --html a.bvh``, ``a.bvh`` and ``./a.bvh``)."""
    seen: dict[str, Path] = {}
    for p in paths:
        key = os.path.normcase(os.path.realpath(p))
        if key in seen:
            raise OutputError(f"{_shown(str(p))}: two outputs on one file ({_shown(str(seen[key]))} "
                              "is written already); give each output its own name")
        seen[key] = Path(p)


def _fsync_dir(directory: Path) -> None:
    try:
        fd = os.open(directory, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:  # some file systems cannot fsync a folder; the file itself is synced
        pass
    finally:
        os.close(fd)


def _mode(path: Path) -> int:
    """The permission bits of the file at ``path`` if there is one, else a new file's (0666 less the umask)."""
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except OSError:
        return 0o666 & ~_umask()


def _through_links(path: Path) -> Path:
    """The file a symbolic link at ``path`` points to (checked like any output), else ``path`` itself."""
    if not path.is_symlink():
        return path
    return check_output_path(os.path.realpath(path))


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True  # another user's process, or not a pid: not ours to judge
    return True


def remove_stale_parts(path: Path) -> list[Path]:
    """Remove the temporaries of ``path`` (``.NAME.PID.XXXXXXXX.part``) whose writer process is gone
    (killed during a write); returns them. Other files, and a live writer's temporaries, are left alone."""
    pattern = re.compile(rf"\.{re.escape(path.name[:40])}\.(\d+)\.[A-Za-z0-9_]{{8}}\.part")
    removed: list[Path] = []
    try:
        entries = list(os.scandir(path.parent))
    except OSError:
        return removed
    for entry in entries:
        m = pattern.fullmatch(entry.name)
        if m and int(m.group(1)) != os.getpid() and not _alive(int(m.group(1))) and entry.is_file(follow_symlinks=False):
            try:
                os.unlink(entry.path)
                removed.append(Path(entry.path))
            except OSError:
                pass
    return removed


def _write_temp(path: Path, content: Content) -> Path:
    """A fsynced temporary file beside ``path`` holding ``content``, with the mode of the file it replaces."""
    directory = path.parent
    remove_stale_parts(path)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name[:40]}.{os.getpid()}.", suffix=".part", dir=directory)
    except PermissionError:
        raise OutputError(f"{_shown(str(path))}: cannot write in {directory} (permission denied)") from None
    except OSError as exc:
        raise OutputError(f"{_shown(str(path))}: cannot write in {directory} ({exc.strerror or exc})") from None
    tmp_path = Path(tmp)
    try:
        if callable(content):
            os.close(fd)
            fd = -1
            content(tmp_path)
            fd = os.open(tmp_path, os.O_RDONLY)
        else:
            view = memoryview(content)
            while view:
                view = view[os.write(fd, view):]
        os.fsync(fd)
        os.close(fd)
        fd = -1
        os.chmod(tmp_path, _mode(path))  # mkstemp makes 0600; a new file gets the usual mode
    except BaseException as exc:
        if fd >= 0:
            os.close(fd)
        tmp_path.unlink(missing_ok=True)
        if isinstance(exc, OSError) and not isinstance(exc, OutputError):
            raise OutputError(f"{_shown(str(path))}: {exc.strerror or exc}") from None
        raise
    return tmp_path


def write_all(files: Mapping[Any, Content]) -> list[Path]:  # keys: str or os.PathLike (Mapping keys are invariant)
    """Write several files all-or-nothing; returns their paths.

    Every path is checked first (:func:`check_output_path`, :func:`check_distinct`);
    then every temporary is written and fsynced; then all are renamed into place
    and their folders fsynced. A failure before the renames removes only the
    temporaries: files that existed before are left as they were.
    """
    paths = [check_output_path(p) for p in files]
    check_distinct(paths)
    targets = [_through_links(p) for p in paths]
    temps: list[Path] = []
    renamed = 0
    try:
        for path, content in zip(targets, files.values()):
            temps.append(_write_temp(path, content))
        for path in targets:  # again, just before the renames: nothing may have appeared meanwhile
            check_output_path(path)
        for tmp, path in zip(temps, targets):
            try:
                os.replace(tmp, path)
            except OSError as exc:
                raise OutputError(f"{_shown(str(path))}: {exc.strerror or exc}") from None
            renamed += 1
    finally:
        for tmp in temps[renamed:]:
            tmp.unlink(missing_ok=True)
    for directory in dict.fromkeys(p.parent for p in targets):
        _fsync_dir(directory)
    return paths


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to a temporary file beside ``path``, fsync it and rename it into place."""
    write_all({path: data})


def atomic_write_text(path: str | os.PathLike, text: str) -> None:
    atomic_write_bytes(path, text.encode("utf-8"))
