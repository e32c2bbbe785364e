"""Drivers: an SQLAlchemy engine for a database URL, with its timeouts, transactions and error messages.

Where the database is (which URL) is :mod:`motiondb.location`'s business; this
module turns that URL into an engine: the PostgreSQL driver the ``postgres``
extra installs, connection and lock timeouts, SQLite transactions that take the
write lock up front, and one-line messages for driver errors.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

from sqlalchemy import create_engine, event
from sqlalchemy import exc as sa_exc
from sqlalchemy.engine import Engine, make_url

from text2anim.core import extras
from .errors import DBError

#: Key of the PostgreSQL advisory lock that serialises writers ("t2aM").
PG_LOCK_KEY = 0x7432614D
#: Seconds an SQLite connection waits for another process's write lock.
SQLITE_BUSY_TIMEOUT = 60.0
#: SQLite page cache per connection, KiB (the default is 2 MiB): a search at 100k clips touches the
#: rows of ~300 matching clips spread over the file; with them cached it takes a third less CPU.
SQLITE_CACHE_KIB = 32768
#: Bytes of an SQLite file read through a memory map instead of read() calls (reads only; SQLite writes as
#: before): a search touching pages no query has touched yet (a 100k-clip file is ~230 MB) costs a page
#: fault instead of a system call and a copy, a third less CPU on a cold search; a warm one is unchanged.
SQLITE_MMAP_BYTES = 1 << 30
#: Seconds a PostgreSQL connection attempt may take.
PG_CONNECT_TIMEOUT = 10


def first_line(exc: BaseException) -> str:
    """The first line of a (DBAPI) exception's message, for one-line user messages."""
    msg = str(getattr(exc, "orig", None) or exc).strip()
    return msg.splitlines()[0].strip() if msg else type(exc).__name__


def make_engine(url_text: str) -> tuple[Engine, str]:
    """An engine for ``url_text`` and the URL to show in messages (password hidden)."""
    try:
        url = make_url(url_text)
    except (sa_exc.ArgumentError, ValueError):
        raise DBError(f"not a database URL: {url_text!r} (expected e.g. sqlite:///path/motions.sqlite "
                      "or postgresql+psycopg2://user@host/dbname)") from None
    if url.drivername == "postgresql":
        # SQLAlchemy 2.1 reads a bare postgresql:// as psycopg (3); the postgres extra installs psycopg2
        import importlib.util

        if importlib.util.find_spec("psycopg") is None and importlib.util.find_spec("psycopg2") is not None:
            url = url.set(drivername="postgresql+psycopg2")
    display = url.render_as_string(hide_password=True)
    try:
        backend = url.get_backend_name()
    except Exception:  # noqa: BLE001
        backend = url.drivername
    connect_args: dict[str, Any] = {}
    if backend == "sqlite":
        db = url.database or ""
        if db and db != ":memory:" and not db.startswith("file:"):
            folder = Path(db).expanduser().resolve().parent
            if not folder.is_dir():
                raise DBError(f"cannot open the SQLite database {db}: the folder {folder} does not exist")
            if Path(db).is_dir():
                raise DBError(f"cannot open the SQLite database {db}: it is a folder")
        connect_args["timeout"] = SQLITE_BUSY_TIMEOUT
    elif backend == "postgresql" and url.get_driver_name() in ("psycopg2", "psycopg"):
        connect_args["connect_timeout"] = PG_CONNECT_TIMEOUT
    try:
        engine = create_engine(url, connect_args=connect_args)
    except sa_exc.NoSuchModuleError:
        raise DBError(f"unknown kind of database {url.drivername!r} in {display} "
                      "(use sqlite:///FILE or postgresql+psycopg2://...)") from None
    except ImportError as exc:
        missing = extras.from_import_error(exc, f"the {backend} database {display}")
        raise missing or DBError(f"the driver for {url.drivername} is not installed: {exc.name or exc}") from None
    except (sa_exc.ArgumentError, TypeError, ValueError) as exc:
        raise DBError(f"bad database URL {display}: {first_line(exc)}") from None
    if backend == "sqlite":
        _sqlite_transactions(engine)
    return engine, display


def _sqlite_transactions(engine: Engine) -> None:
    """Let SQLAlchemy, not pysqlite, start transactions; writers take the lock up front.

    pysqlite's own handling would not start a transaction before DDL and would
    start reads as deferred transactions that cannot safely upgrade to writes;
    here every transaction is explicit and writes use ``BEGIN IMMEDIATE``.
    """

    @event.listens_for(engine, "connect")
    def _connect(dbapi_conn, _record):
        dbapi_conn.isolation_level = None
        cur = dbapi_conn.cursor()
        cur.execute("PRAGMA foreign_keys = ON")
        cur.execute(f"PRAGMA cache_size = -{SQLITE_CACHE_KIB}")
        cur.execute(f"PRAGMA mmap_size = {SQLITE_MMAP_BYTES}")
        cur.close()

    @event.listens_for(engine, "begin")
    def _begin(conn):
        write = conn.get_execution_options().get("t2a_write", False)
        conn.exec_driver_sql("BEGIN IMMEDIATE" if write else "BEGIN")


def describe_error(exc: BaseException, display: str, backend: str) -> str:
    """A one-line user message for a driver error on database ``display`` (``backend``: ``sqlite``, ...)."""
    line = first_line(exc)
    low = line.lower()
    if backend == "sqlite":
        if "unable to open database file" in low:
            return f"cannot open the SQLite database {display} (missing folder or no permission)"
        if "file is not a database" in low:
            return f"{display} is not an SQLite database"
        if "database is locked" in low:
            return f"the SQLite database {display} stayed locked by another process for {SQLITE_BUSY_TIMEOUT:g} s"
        if "readonly" in low or "read-only" in low:
            return f"the SQLite database {display} is read-only"
    if isinstance(exc, sa_exc.OperationalError) and ("connect" in low or "could not translate" in low
                                                     or "timeout" in low):
        return f"lost the connection to the database {display}: {line}"
    return f"database {display}: {line}"


def open_engine(url_text: str, is_default: bool = False) -> tuple[Engine, str]:
    """:func:`make_engine` of ``url_text`` once a connection is made (``is_default``: the default SQLite file,
    whose folder is created); :class:`DBError` saying why when none can be."""
    if is_default:
        database = make_url(url_text).database
        assert database, url_text  # the default location is an SQLite file
        folder = Path(database).parent
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise DBError(f"cannot create the folder {folder} for the motion database: {exc.strerror}") from None
    engine, display = make_engine(url_text)
    try:
        with engine.connect():
            pass
    except (sa_exc.DBAPIError, sa_exc.InterfaceError) as exc:
        engine.dispose()
        if engine.dialect.name == "sqlite":
            raise DBError(describe_error(exc, display, "sqlite")) from None
        raise DBError(f"cannot connect to the database {display}: {first_line(exc)}") from None
    return engine, display
