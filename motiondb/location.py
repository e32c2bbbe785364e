"""Where the motion database lives.

Resolution order for :func:`resolve_url`:

1. an explicit URL or path (``--db`` on the command line, ``MotionDB.open(url)``);
2. the ``TEXT2ANIM_DB`` environment variable;
3. ``$XDG_DATA_HOME/text2anim/motions.sqlite`` (``~/.local/share/...`` when
   ``XDG_DATA_HOME`` is unset, empty or relative, as the XDG Base Directory
   specification says).

Anything containing ``://`` is an SQLAlchemy URL (``sqlite:///x.sqlite``,
``postgresql+psycopg2://user@host/db``); anything else is the path of an
SQLite file. Only the default location's folder is created; a path or URL the
user gave must point into an existing folder.
"""
from __future__ import annotations

import os
from pathlib import Path

ENV_VAR = "TEXT2ANIM_DB"
DB_FILENAME = "motions.sqlite"


def data_home() -> Path:
    """``$XDG_DATA_HOME`` if absolute, else ``~/.local/share``."""
    xdg = os.environ.get("XDG_DATA_HOME", "")
    if xdg and os.path.isabs(xdg):
        return Path(xdg)
    return Path.home() / ".local" / "share"


def cache_home() -> Path:
    """``$XDG_CACHE_HOME`` if absolute, else ``~/.cache`` (what may be thrown away and found again)."""
    xdg = os.environ.get("XDG_CACHE_HOME", "")
    if xdg and os.path.isabs(xdg):
        return Path(xdg)
    return Path.home() / ".cache"


def default_path() -> Path:
    """The default SQLite file: ``<data home>/text2anim/motions.sqlite``."""
    return data_home() / "text2anim" / DB_FILENAME


def sqlite_url(path: str | os.PathLike) -> str:
    """The SQLAlchemy URL of an SQLite file (absolute path)."""
    return "sqlite:///" + str(Path(path).expanduser().resolve())


def resolve_url(url: str | os.PathLike | None = None) -> tuple[str, bool]:
    """``(sqlalchemy_url, is_default)`` for an explicit URL/path, ``TEXT2ANIM_DB`` or the default.

    ``is_default`` is true for the XDG default location (its folder may be created).
    """
    if url is None or (isinstance(url, str) and not url.strip()):
        url = os.environ.get(ENV_VAR, "").strip() or None
    if url is None:
        return sqlite_url(default_path()), True
    url = os.fspath(url)
    if "://" in url:
        return url, False
    return sqlite_url(url), False
