"""One batch run per output folder: ``DIR/.lock``, held with ``flock`` for the whole run.

Two runs on one ``--out`` would both run every line and write every manifest record twice
(README: each line is run exactly once). The lock is the kernel's, so it is released when
the holder exits, even by ``kill -9``: a stale lock file is no obstacle.
"""
from __future__ import annotations

import contextlib
import fcntl
import os
from typing import Iterator

from .errors import BatchError

NAME = ".lock"


@contextlib.contextmanager
def owning(out_dir: str, wait: bool = False) -> Iterator[None]:
    """Hold ``out_dir``'s lock inside the ``with``; another holder is a :class:`BatchError`, or waited for."""
    path = os.path.join(out_dir, NAME)
    fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            raise BatchError(f"{out_dir}: another batch run owns this folder (it holds {path}); "
                             "let it finish, or pass --wait to run after it") from None
        yield
    finally:
        os.close(fd)  # closing the descriptor releases the lock
