"""The motion databases the API keeps open: one per URL for the life of the process, closed at exit.

Opening a database (an engine, a connection, the schema and library checks) cost more than planning a
sentence, and every clip decoded by one open database was decoded again by the next: `text2anim.animate`
and `text2anim.plan` given a URL, a path or nothing (the default database) opened and closed one per
call. Now the first call with a URL opens it and later calls with the same URL use it, so a warm call costs
the work only. A caller that opens its own :class:`~text2anim.motiondb.MotionDB` keeps using it as before.

Calls from several threads take turns on one database (its search memory and clip cache are not shared
across threads) for the stages that read it; synthesis runs outside that turn. An SQLite file that was
removed or replaced since it was opened (another inode) is opened again; a URL other than SQLite is
trusted to stay the same server. At most :data:`KEPT` databases stay open, the least recently used
closed first.
"""
from __future__ import annotations

import atexit
import os
import threading
from collections import OrderedDict
from collections.abc import Iterator
from contextlib import AbstractContextManager, contextmanager
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from text2anim.motiondb import MotionDB

#: databases kept open at once (by URL); the least recently used is closed first
KEPT = 4


@dataclass
class _Kept:
    db: MotionDB
    turn: AbstractContextManager[Any]  # an RLock: one thread at a time uses the database
    file: tuple[int, int] | None  # (device, inode) of an SQLite file when it was opened


_KEPT: OrderedDict[str, _Kept] = OrderedDict()
_LOCK = threading.Lock()


@lru_cache(maxsize=64)
def _url(db: str | None, env: str | None, data: str | None, home: str | None, cwd: str) -> str:
    """:func:`motiondb.location.resolve_url` of ``db``, once per argument, environment and working folder (a path
    resolved on every call was a tenth of a warm plan)."""
    from text2anim.motiondb.location import resolve_url

    return resolve_url(db)[0]


@lru_cache(maxsize=64)
def _file_of(url: str) -> str | None:
    """The path of the SQLite file ``url`` names (SQLAlchemy's reading of it, as ``motiondb.connect`` opens it),
    None for another database, an in-memory one or a URL that is none."""
    from sqlalchemy.engine import make_url
    from sqlalchemy.exc import ArgumentError

    try:
        parsed = make_url(url)
    except (ArgumentError, ValueError):
        return None
    path = parsed.database or ""
    if parsed.get_backend_name() != "sqlite" or not path or path == ":memory:" or path.startswith("file:"):
        return None
    return path


def _identity(path: str | None) -> tuple[int, int] | None:
    if path is None:
        return None
    try:
        st = os.stat(path)
    except OSError:
        return None
    return st.st_dev, st.st_ino


def _fresh(kept: _Kept, path: str | None) -> bool:
    """Whether ``kept`` still reads the file its URL names (always, for a database that is not a file)."""
    return path is None or (kept.file is not None and _identity(path) == kept.file)


@contextmanager
def database(db: MotionDB | str | os.PathLike | None) -> Iterator[MotionDB]:
    """The database ``db`` names, open, for the block: ``db`` itself when it is a :class:`MotionDB`, else the one
    kept open for its URL (opened on first use; the default database for ``None``), this thread's turn held.

    Raises:
        motiondb.DBError: the database cannot be opened (nothing is kept then).
    """
    from text2anim.motiondb import MotionDB

    if isinstance(db, MotionDB):
        yield db
        return
    url = _url(None if db is None else os.fspath(db), os.environ.get("TEXT2ANIM_DB"), os.environ.get("XDG_DATA_HOME"),
               os.environ.get("HOME"), os.getcwd())
    path = _file_of(url)
    with _LOCK:
        kept = _KEPT.get(url)
        if kept is not None and not _fresh(kept, path):
            _close(_KEPT.pop(url))
            kept = None
        if kept is None:
            opened = MotionDB.open(db)
            kept = _KEPT[url] = _Kept(opened, threading.RLock(), _identity(path))
            while len(_KEPT) > KEPT:
                _close(_KEPT.popitem(last=False)[1])
        _KEPT.move_to_end(url)
    with kept.turn:
        yield kept.db


def _close(kept: _Kept) -> None:
    with kept.turn:  # a thread still using it finishes first
        kept.db.close()


def close_all() -> None:
    """Close every database kept open (run at exit; the next call opens them again)."""
    with _LOCK:
        while _KEPT:
            _close(_KEPT.popitem()[1])


atexit.register(close_all)
