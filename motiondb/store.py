"""The motion database: open or create it, store clips, search them, load frames.

>>> db = MotionDB.open()                    # TEXT2ANIM_DB or the XDG default, seeded on first use
>>> hits = db.search("蹴る", object="ボール")  # ranked ClipInfo, no frame data read
>>> motion = db.load(hits[0])               # synthesis.Motion, decoded from the clip's blob

Any SQLAlchemy URL works; SQLite and PostgreSQL are tested. Transactions are
short: every public method runs in its own, and every change (``add``,
``import_bvh``, ``remove``, first-use seeding) is all-or-nothing. Writers are
serialised (SQLite ``BEGIN IMMEDIATE``; PostgreSQL a transaction-scoped
advisory lock), so two processes creating and seeding the same new database
at once end with one copy of the library.

Units: seconds for times (``duration``, ``core``), frames for contact
intervals (``[start, stop)`` at the clip's ``fps``), metres for lengths.

Postures: every clip has a ``start_posture`` and an ``end_posture`` (one of
:data:`motiondb.types.POSTURES`), declared by the record or classified from
its first and last frames by :func:`classify_posture` when it is stored;
``search(..., prefer_start_posture=...)`` ranks clips starting in a posture
first (so a clip can follow one that ends seated, crouched or lying).
"""
from __future__ import annotations

import json
import hashlib
import math
import os
import warnings
from collections.abc import Callable, Iterable, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import numpy as np
from sqlalchemy import bindparam, case, create_engine, delete, event, exists, func, inspect, select, text
from sqlalchemy import exc as sa_exc
from sqlalchemy.engine import Engine, make_url
from sqlalchemy.orm import Session

from text2anim.core.bodyparts import GROUPS, BodyMapError, body_map
from text2anim.core.bvh import BVHError, read_bvh
from text2anim.core.contacts import detect_contacts
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton

from . import search as _search
from .blobs import ENCODING, decode_frames, encode_frames
from .errors import (
    ClipExistsError,
    SeedWarning,
    ClipValidationError,
    DBError,
    SchemaVersionError,
    UnknownCharacterError,
    UnknownClipError,
    UnknownVerbError,
)
from .location import resolve_url
from .readings import nearest, normalize, reading
from .schema import (
    OLDEST_MIGRATABLE,
    SCHEMA_VERSION,
    TABLE_NAMES,
    Base,
    Character,
    Clip,
    ClipFrames,
    ClipObject,
    ClipVerb,
    Contact,
    ObjectRow,
    SchemaVersion,
    SkeletonRow,
    Verb,
    utcnow,
)
from .types import DEFAULT_POSTURE, POSTURES, ClipRecord

#: ``source`` of the built-in library's clips (``builtin`` or ``builtin:<file>``).
BUILTIN_SOURCE = "builtin"
#: Key of the PostgreSQL advisory lock that serialises writers ("t2aM").
_PG_LOCK_KEY = 0x7432614D
#: Seconds an SQLite connection waits for another process's write lock.
SQLITE_BUSY_TIMEOUT = 60.0
#: Seconds a PostgreSQL connection attempt may take.
PG_CONNECT_TIMEOUT = 10
_CHUNK = 500
_MAX_NAME = 200
_MAX_WORD = 100


# ------------------------------------------------------------------ records out
@dataclass(frozen=True)
class ClipInfo:
    """A stored clip's metadata, without its frames (``MotionDB.load`` reads those).

    Attributes:
        name: unique clip name.
        character: the character it belongs to.
        verbs: its verbs, primary first, then synonyms.
        objects: object nouns it declares (may be empty).
        fps: frames per second.
        frames: frame count.
        duration: seconds (``frames / fps``).
        core: ``(begin, end)`` seconds, the interval that must be kept.
        body_part: group a partial action is declared for, ``None`` for whole body.
        cyclic: the clip loops.
        source: ``builtin`` or the imported file's path.
        created: when it was stored (UTC).
        joints: joint count of its skeleton.
        left_contacts, right_contacts: foot-contact intervals ``[start, stop)`` in frames.
        start_posture, end_posture: the posture of its first and of its last frame
            (:data:`motiondb.types.POSTURES`: ``standing``, ``seated``, ``crouched``,
            ``kneeling``, ``lying``).
    """

    name: str
    character: str
    verbs: tuple[str, ...]
    objects: tuple[str, ...]
    fps: float
    frames: int
    duration: float
    core: tuple[float, float]
    body_part: str | None
    cyclic: bool
    source: str
    created: datetime
    joints: int
    left_contacts: tuple[tuple[int, int], ...] = ()
    right_contacts: tuple[tuple[int, int], ...] = ()
    start_posture: str = DEFAULT_POSTURE
    end_posture: str = DEFAULT_POSTURE

    @property
    def verb(self) -> str:
        """The primary verb."""
        return self.verbs[0]

    def contacts(self, side: str) -> tuple[tuple[int, int], ...]:
        """Contact intervals of the ``left`` or ``right`` foot, ``[start, stop)`` frames."""
        if side not in ("left", "right"):
            raise ValueError(f"side must be 'left' or 'right', not {side!r}")
        return self.left_contacts if side == "left" else self.right_contacts

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (lists for tuples, ISO 8601 time)."""
        return {
            "name": self.name, "character": self.character, "verbs": list(self.verbs),
            "objects": list(self.objects), "fps": self.fps, "frames": self.frames,
            "duration": self.duration, "core": list(self.core), "body_part": self.body_part,
            "cyclic": self.cyclic, "source": self.source, "created": self.created.isoformat(),
            "joints": self.joints, "start_posture": self.start_posture, "end_posture": self.end_posture,
            "contacts": {"left": [list(c) for c in self.left_contacts],
                         "right": [list(c) for c in self.right_contacts]},
        }


@dataclass(frozen=True)
class VerbInfo:
    """A verb the database knows: ``clips`` clips use it, ``primary`` of them as their primary verb."""

    lemma: str
    reading: str
    clips: int
    primary: int


# ------------------------------------------------------------ skeleton as JSON
def skeleton_json(skel: Skeleton) -> str:
    """Canonical JSON of a skeleton (exact floats), the ``skeletons.definition`` column."""
    return json.dumps({
        "names": list(skel.names),
        "parents": [int(p) for p in skel.parents],
        "offsets": skel.offsets.tolist(),
        "end_sites": [[int(j), o.tolist()] for j, o in skel.end_sites],
        "channels": [list(c) for c in skel.channels],
    }, ensure_ascii=False, sort_keys=True, separators=(",", ":"))


def skeleton_from_json(definition: str) -> Skeleton:
    d = json.loads(definition)
    return Skeleton(tuple(d["names"]), np.array(d["parents"], dtype=np.int64),
                    np.array(d["offsets"], dtype=np.float64).reshape(-1, 3),
                    tuple((j, np.array(o, dtype=np.float64)) for j, o in d["end_sites"]),
                    tuple(tuple(c) for c in d["channels"]))


# ----------------------------------------- metadata queries (never frame data)
_IDS = bindparam("ids", expanding=True)
_INFO_CLIPS = (
    select(Clip.id, Clip.name, Character.name.label("character"), Clip.fps, Clip.frames, Clip.duration,
           Clip.core_begin, Clip.core_end, Clip.body_part, Clip.cyclic, Clip.source, Clip.created,
           Clip.start_posture, Clip.end_posture, SkeletonRow.n_joints)
    .join(Character, Character.id == Clip.character_id)
    .join(SkeletonRow, SkeletonRow.id == Clip.skeleton_id)
    .where(Clip.id.in_(_IDS))
)
_INFO_VERBS = (select(ClipVerb.clip_id, Verb.lemma).join(Verb, Verb.id == ClipVerb.verb_id)
               .where(ClipVerb.clip_id.in_(_IDS)).order_by(ClipVerb.clip_id, ClipVerb.position))
_INFO_OBJECTS = (select(ClipObject.clip_id, ObjectRow.name).join(ObjectRow, ObjectRow.id == ClipObject.object_id)
                 .where(ClipObject.clip_id.in_(_IDS)).order_by(ClipObject.clip_id, ClipObject.position))
_INFO_CONTACTS = (select(Contact.clip_id, Contact.side, Contact.start_frame, Contact.stop_frame)
                  .where(Contact.clip_id.in_(_IDS)).order_by(Contact.clip_id, Contact.start_frame))


# ------------------------------------------------------- validation, preparing
@dataclass
class _Prepared:
    """A validated record with everything computed that the insert needs."""

    name: str
    verbs: tuple[str, ...]
    objects: tuple[str, ...]
    character: str
    skeleton: Skeleton
    skeleton_def: str
    fingerprint: str
    fps: float
    frames: int
    duration: float
    core: tuple[float, float]
    body_part: str | None
    cyclic: bool
    source: str
    blob: bytes
    start_posture: str = DEFAULT_POSTURE
    end_posture: str = DEFAULT_POSTURE
    contacts: list[tuple[str, int, int]] = field(default_factory=list)


def _words(values, what: str, where: str, *, required: bool) -> tuple[str, ...]:
    if isinstance(values, str):
        values = (values,)
    out: list[str] = []
    for v in values or ():
        if not isinstance(v, str):
            raise ClipValidationError(f"{where}: {what} must be text, got {v!r}")
        w = normalize(v)
        if not w:
            raise ClipValidationError(f"{where}: empty {what}")
        if len(w) > _MAX_WORD:
            raise ClipValidationError(f"{where}: {what} {w[:20]!r}… is longer than {_MAX_WORD} characters")
        if w not in out:
            out.append(w)
    if required and not out:
        raise ClipValidationError(f"{where}: a clip needs at least one verb")
    return tuple(out)


def _check_name(name, what: str, where: str) -> str:
    if not isinstance(name, str) or not normalize(name):
        raise ClipValidationError(f"{where}: the {what} name is empty")
    n = normalize(name)
    if len(n) > _MAX_NAME or any(ord(c) < 32 for c in n):
        raise ClipValidationError(f"{where}: bad {what} name {n[:40]!r} (at most {_MAX_NAME} printable characters)")
    return n


# --------------------------------------------------------------- postures
#: Hip joints at least this fraction of the leg length above the floor: standing.
STAND_HIP = 0.75
#: Head below this fraction of the leg length above the floor: lying.
LIE_HEAD = 0.45
#: A knee this close to the floor (fraction of the leg length) rests on it ...
KNEE_DOWN = 0.15
#: ... and with the hips this much higher than it (fraction of the leg length): kneeling.
KNEEL_HIP = 0.15
#: Hips this low (fraction of the leg length) sit on the floor.
FLOOR_SIT_HIP = 0.25
#: Hips this far (fraction of the leg length, horizontally) from the middle of the ankles
#: are not over the feet: seated (on a seat), else crouched.
SEAT_OFFSET = 0.3


def _leg_joints(skel: Skeleton, side: str) -> tuple[int, int, int, int]:
    """``(hip, knee, ankle, toe)`` joint indices of one leg (the hip is the knee's parent)."""
    ankle, toe = body_map(skel).feet[side]
    knee = int(skel.parents[ankle])
    hip = int(skel.parents[knee])
    if knee < 0 or hip < 0:
        raise BodyMapError(f"the {side} leg has no knee and hip above its ankle")
    return hip, knee, ankle, toe


def classify_posture(motion: Motion, frame: int = 0) -> str:
    """The posture (one of :data:`motiondb.types.POSTURES`) of one frame of ``motion``.

    Heights are measured from the floor, taken as the lowest foot joint's 5th
    percentile over the clip (clamped to 0..0.10 m, as the contact detector
    does), in units of the leg length ``L`` (rest-pose height of the hip joints
    above the lowest foot joint: 0.86 m on the built-in 1.70 m skeleton). In
    this order:

    1. hip joints at least :data:`STAND_HIP` ``L`` up: ``standing`` (bending
       over or reaching does not change it);
    2. the head below :data:`LIE_HEAD` ``L``: ``lying`` (face down or up);
    3. a knee within :data:`KNEE_DOWN` ``L`` of the floor and the hips
       :data:`KNEEL_HIP` ``L`` above it: ``kneeling`` (also on all fours);
    4. hips below :data:`FLOOR_SIT_HIP` ``L``: ``seated`` (on the floor);
    5. hips more than :data:`SEAT_OFFSET` ``L`` horizontally from the middle of
       the ankles (the weight is not over the feet): ``seated``; else ``crouched``.

    Falls back to :data:`motiondb.types.DEFAULT_POSTURE` for a skeleton whose
    legs cannot be found.
    """
    skel = motion.skeleton
    try:
        legs = [_leg_joints(skel, side) for side in ("left", "right")]
    except BodyMapError:
        return DEFAULT_POSTURE
    rest = skel.rest_positions()
    foot_joints = [j for leg in legs for j in leg[2:]]
    length = float(np.mean([rest[leg[0], 1] for leg in legs]) - rest[foot_joints, 1].min())
    if not length > 1e-6:
        return DEFAULT_POSTURE
    pos = motion.positions
    floor = float(np.clip(np.percentile(pos[:, foot_joints, 1].min(axis=1), 5.0), 0.0, 0.10))
    p = pos[frame]
    hips = np.mean([p[leg[0]] for leg in legs], axis=0)
    hip_h = (hips[1] - floor) / length
    if hip_h >= STAND_HIP:
        return "standing"
    head_h = (p[body_map(skel).head, 1] - floor) / length
    if head_h < LIE_HEAD:
        return "lying"
    knees = [(p[leg[1], 1] - floor) / length for leg in legs]
    if min(knees) < KNEE_DOWN and hip_h - min(knees) > KNEEL_HIP:
        return "kneeling"
    if hip_h < FLOOR_SIT_HIP:
        return "seated"
    ankles = np.mean([p[leg[2]] for leg in legs], axis=0)
    offset = float(np.hypot(*(hips - ankles)[[0, 2]])) / length
    return "seated" if offset > SEAT_OFFSET else "crouched"


def clip_postures(motion: Motion) -> tuple[str, str]:
    """``(start, end)`` postures of a clip: :func:`classify_posture` of its first and last frames."""
    return classify_posture(motion, 0), classify_posture(motion, motion.n_frames - 1)


def prepare_record(rec: ClipRecord, where: str | None = None) -> _Prepared:
    """Validate a record and compute its blob, skeleton fingerprint and foot contacts.

    Raises :class:`ClipValidationError` naming ``where`` (a file) or the clip.
    """
    where = where or f"clip {getattr(rec, 'name', '?')!r}"
    name = _check_name(rec.name, "clip", where)
    character = _check_name(rec.character, "character", where)
    verbs = _words(rec.verbs, "verb", where, required=True)
    objects = _words(rec.objects, "object", where, required=False)
    m = rec.motion
    if not isinstance(m, Motion):
        raise ClipValidationError(f"{where}: motion must be a synthesis.Motion, got {type(m).__name__}")
    if m.n_frames < 1:
        raise ClipValidationError(f"{where}: the motion has no frames")
    if not math.isfinite(m.fps):
        raise ClipValidationError(f"{where}: fps must be finite, got {m.fps}")
    arrays = [m.root_positions, m.rotations] + ([] if m.translations is None else [m.translations])
    if not all(np.all(np.isfinite(a)) for a in arrays):
        raise ClipValidationError(f"{where}: the motion has non-finite values")
    norms = np.linalg.norm(m.rotations, axis=-1)
    if np.any(np.abs(norms - 1.0) > 1e-3):
        raise ClipValidationError(
            f"{where}: rotations are not unit quaternions (norm {norms.min():.3g}..{norms.max():.3g})")
    duration = m.n_frames / m.fps
    if rec.core is None:
        core = (0.0, duration)
    else:
        try:
            b, e = (float(x) for x in rec.core)
        except (TypeError, ValueError):
            raise ClipValidationError(f"{where}: core must be (begin, end) seconds, got {rec.core!r}") from None
        # up to one frame past the end is rounding (a core given in seconds on a frame grid): clamped
        slack = 1.0 / m.fps + 1e-9
        if not (math.isfinite(b) and math.isfinite(e) and 0 <= b < e <= duration + slack and b < duration):
            raise ClipValidationError(
                f"{where}: core {b:g}..{e:g} s must satisfy 0 <= begin < end <= duration ({duration:.3f} s)")
        core = (b, min(e, duration))
    if rec.body_part is not None and rec.body_part not in GROUPS:
        raise ClipValidationError(f"{where}: unknown body part {rec.body_part!r}; known: {', '.join(GROUPS)}")
    try:
        fc = detect_contacts(m)
    except BodyMapError as exc:
        raise ClipValidationError(f"{where}: cannot compute foot contacts: {exc}") from None
    contacts = [(side, a, b) for side in ("left", "right") for a, b in fc.intervals(side)]
    postures = []
    for what, declared, frame in (("start", rec.start_posture, 0), ("end", rec.end_posture, -1)):
        if declared is None:
            postures.append(classify_posture(m, frame))
        elif declared not in POSTURES:
            raise ClipValidationError(f"{where}: unknown {what} posture {declared!r}; known: {', '.join(POSTURES)}")
        else:
            postures.append(declared)
    definition = skeleton_json(m.skeleton)
    return _Prepared(
        name=name, verbs=verbs, objects=objects, character=character, skeleton=m.skeleton,
        skeleton_def=definition, fingerprint=hashlib.sha256(definition.encode("utf-8")).hexdigest(),
        fps=float(m.fps), frames=int(m.n_frames), duration=float(duration), core=core,
        body_part=rec.body_part, cyclic=bool(rec.cyclic), source=str(rec.source or ""),
        blob=encode_frames(m), start_posture=postures[0], end_posture=postures[1], contacts=contacts,
    )


# ---------------------------------------------------------------- engine setup
def _first_line(exc: BaseException) -> str:
    msg = str(getattr(exc, "orig", None) or exc).strip()
    return msg.splitlines()[0].strip() if msg else type(exc).__name__


def _make_engine(url_text: str) -> tuple[Engine, str]:
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
        hint = " (pip install 'text2anim[postgres]')" if backend == "postgresql" else ""
        raise DBError(f"the driver for {url.drivername} is not installed: {exc.name or exc}{hint}") from None
    except (sa_exc.ArgumentError, TypeError, ValueError) as exc:
        raise DBError(f"bad database URL {display}: {_first_line(exc)}") from None
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
        cur.close()

    @event.listens_for(engine, "begin")
    def _begin(conn):
        write = conn.get_execution_options().get("t2a_write", False)
        conn.exec_driver_sql("BEGIN IMMEDIATE" if write else "BEGIN")


def _describe(exc: BaseException, display: str, backend: str) -> str:
    line = _first_line(exc)
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


# ----------------------------------------------------------------- the database
class MotionDB:
    """A motion database behind an SQLAlchemy engine. Open it with :meth:`open`.

    Attributes:
        engine: the SQLAlchemy engine (for tools and tests; use the methods for data).
        url: the database URL, password hidden.
    """

    def __init__(self, engine: Engine, display_url: str):
        self.engine = engine
        self.url = display_url
        self.backend = engine.dialect.name
        self._writer = engine.execution_options(t2a_write=True)
        self._skeletons: dict[int, Skeleton] = {}

    # ------------------------------------------------------------- open/close
    @classmethod
    def open(cls, url: str | os.PathLike | None = None, *,
             seed: bool | Callable[[], Iterable[ClipRecord]] = True) -> "MotionDB":
        """Open (and on first use create) a motion database.

        Args:
            url: an SQLAlchemy URL or an SQLite file path; ``None`` means the
                ``TEXT2ANIM_DB`` environment variable, else
                ``$XDG_DATA_HOME/text2anim/motions.sqlite`` (its folder is created).
            seed: what a new database is filled with, in the transaction that
                creates it: ``True`` the built-in library
                (``motiondb.library.builtin_clips()``), ``False`` nothing, or a
                callable returning the records. A database created while the
                built-in library was unavailable is seeded by the next open that
                has it. When the installed built-in library differs from the one
                a database was seeded with (its ``LIBRARY_VERSION``, else a hash
                of its code and data files), its clips whose ``source`` is
                ``builtin``/``builtin:…`` are replaced by the new ones; other
                clips are kept, and win over built-in clips of the same name.

        A database of an older schema version is migrated in place first, in
        one transaction (see :mod:`motiondb.schema` for what each version adds).

        Raises:
            DBError: a bad URL, an unreachable server, a file that is not a
                database, a schema written by a newer text2anim.
        """
        url_text, is_default = resolve_url(url)
        if is_default:
            folder = Path(make_url(url_text).database).parent
            try:
                folder.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise DBError(f"cannot create the folder {folder} for the motion database: {exc.strerror}") from None
        engine, display = _make_engine(url_text)
        try:
            with engine.connect():
                pass
        except (sa_exc.DBAPIError, sa_exc.InterfaceError) as exc:
            engine.dispose()
            if engine.dialect.name == "sqlite":
                raise DBError(_describe(exc, display, "sqlite")) from None
            raise DBError(f"cannot connect to the database {display}: {_first_line(exc)}") from None
        db = cls(engine, display)
        try:
            db._prepare(seed)
        except BaseException:
            engine.dispose()
            raise
        return db

    def close(self) -> None:
        """Release the connections."""
        self.engine.dispose()

    def __enter__(self) -> "MotionDB":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"MotionDB({self.url!r})"

    # -------------------------------------------------------------- sessions
    @contextmanager
    def _errors(self):
        try:
            yield
        except DBError:
            raise
        except sa_exc.IntegrityError as exc:
            raise DBError(f"database {self.url} refused the change: {_first_line(exc)}") from None
        except (sa_exc.DBAPIError, sa_exc.InterfaceError) as exc:
            raise DBError(_describe(exc, self.url, self.backend)) from None

    @contextmanager
    def _session(self, write: bool = False):
        """A session in one transaction, committed on success; writers serialised."""
        with self._errors():
            with Session(self._writer if write else self.engine, expire_on_commit=False) as session:
                with session.begin():
                    if write and self.backend == "postgresql":
                        session.execute(text("SELECT pg_advisory_xact_lock(:k)"), {"k": _PG_LOCK_KEY})
                    yield session

    # ------------------------------------------------------- schema, seeding
    def _state(self, session: Session) -> tuple[int | None, str | None]:
        """``(schema version, builtin_library)``; ``(None, None)`` for a database without our schema.

        An older version this code can migrate (see :mod:`motiondb.schema`) is
        returned as it is; a newer one, or one too old, raises :class:`SchemaVersionError`.
        """
        insp = inspect(session.connection())
        if not insp.has_table("schema_version"):
            ours = [t for t in TABLE_NAMES if insp.has_table(t)]
            if ours:
                raise DBError(f"{self.url} already has tables named {', '.join(ours)} that text2anim did not "
                              "create; use another database (or PostgreSQL schema) for motions")
            return None, None
        row = session.get(SchemaVersion, 1)
        if row is None:
            return None, None
        if row.version > SCHEMA_VERSION:
            raise SchemaVersionError(f"{self.url} has motion-database schema version {row.version}, newer than "
                                     f"this text2anim reads ({SCHEMA_VERSION}); upgrade text2anim")
        if row.version < OLDEST_MIGRATABLE:
            raise SchemaVersionError(f"{self.url} has motion-database schema version {row.version}, "
                                     f"which this text2anim cannot upgrade to {SCHEMA_VERSION}")
        return row.version, row.builtin_library

    def _migrate(self, s: Session, version: int) -> None:
        """Bring a database of schema ``version`` to :data:`SCHEMA_VERSION` in session ``s`` (under
        the write lock; the caller's transaction makes it all or nothing)."""
        if version < 2:
            # 1 -> 2: clip postures. The columns come with the default; then every stored clip is
            # classified from its frames (one clip at a time, so memory stays one clip's).
            for column in ("start_posture", "end_posture"):
                s.execute(text(f"ALTER TABLE clips ADD COLUMN {column} VARCHAR(16) "
                               f"DEFAULT '{DEFAULT_POSTURE}' NOT NULL"))
            rows = s.execute(select(Clip.id, Clip.name, Clip.fps, Clip.frames, Clip.skeleton_id)
                             .order_by(Clip.id)).all()
            for row in rows:
                enc, data = s.execute(select(ClipFrames.encoding, ClipFrames.data)
                                      .where(ClipFrames.clip_id == row.id)).one()
                try:
                    motion = decode_frames(data, self._skeleton(s, row.skeleton_id), row.fps, encoding=enc,
                                           frames=row.frames, clip=row.name)
                    start, end = clip_postures(motion)
                except (DBError, BodyMapError, ValueError):
                    continue  # a clip that cannot be read keeps the default; loading it will say why
                s.execute(Clip.__table__.update().where(Clip.__table__.c.id == row.id)
                          .values(start_posture=start, end_posture=end))
        meta = s.get(SchemaVersion, 1)
        meta.version = SCHEMA_VERSION
        meta.updated = utcnow()
        s.flush()

    def _prepare(self, seed) -> None:
        """Create the schema if missing and seed (or refresh the built-in clips) when needed."""
        source = _seed_source(seed)
        with self._session() as s:
            version, library = self._state(s)
        if version == SCHEMA_VERSION and not _seeding_needed(library, source):
            return
        with self._session(write=True) as s:
            version, library = self._state(s)  # again, under the write lock: another process may have done it
            if version is None:
                Base.metadata.create_all(s.connection())
                library = "" if seed is False else None
                s.add(SchemaVersion(id=1, version=SCHEMA_VERSION, builtin_library=library))
                s.flush()
            elif version < SCHEMA_VERSION:
                self._migrate(s, version)
            if not _seeding_needed(library, source):
                return
            try:
                prepared = [prepare_record(r) for r in source.records()]
            except ClipValidationError as exc:
                what = "the built-in motion library" if source.builtin else "the seed records"
                raise DBError(f"cannot fill {self.url} with {what}: {exc}") from None
            if library is not None:  # a newer built-in library: replace the old built-in clips
                old = [n for n, src in s.execute(select(Clip.name, Clip.source))
                       if src == BUILTIN_SOURCE or src.startswith(BUILTIN_SOURCE + ":")]
                self._delete_clips(s, old)
            before = {p.name for p in prepared}
            stored = self._store(s, prepared, conflicts="skip")
            if len(stored) < len(before):
                kept = set(s.scalars(select(Clip.name).where(Clip.id.in_(stored)))) if stored else set()
                skipped = sorted(before - kept)
                warnings.warn(SeedWarning(
                    f"{len(skipped)} built-in clip(s) not stored because clips of those names or a character "
                    f"'default' of another skeleton are already in {self.url}: {', '.join(skipped[:8])}"
                    f"{'…' if len(skipped) > 8 else ''}"), stacklevel=3)
            row = s.get(SchemaVersion, 1)
            row.builtin_library = source.tag
            row.updated = utcnow()

    # ------------------------------------------------------------------ store
    def add(self, records: Sequence[ClipRecord], *, replace: bool = False) -> list[ClipInfo]:
        """Store clips, all or nothing; returns their :class:`ClipInfo` in the given order.

        Contacts are computed here (:func:`core.contacts.detect_contacts`).
        ``replace`` overwrites clips of the same names; otherwise an existing
        name raises :class:`ClipExistsError` and nothing is stored.
        """
        prepared = [prepare_record(r) for r in records]
        with self._session(write=True) as s:
            self._require_schema(s)
            ids = self._store(s, prepared, conflicts="replace" if replace else "error")
            return self._infos(s, ids)

    def import_bvh(self, paths: Sequence[str | os.PathLike], verbs: Sequence[str], objects: Sequence[str] = (),
                   character: str = "default", core: tuple[float, float] | None = None, part: str | None = None,
                   cyclic: bool = False, *, names: Sequence[str] | None = None, scale: float | str = "auto",
                   up: str = "y", drop_first: bool = False, replace: bool = False,
                   progress: Callable[[int, int, str], None] | None = None,
                   start_posture: str | None = None, end_posture: str | None = None) -> list[ClipInfo]:
        """Read BVH files and store them as clips, all or nothing.

        Every file becomes one clip named after the file (``02_01_walk``) unless
        ``names`` are given, with the same verbs, objects, character, core
        (seconds), body ``part`` and ``cyclic`` flag. ``scale``/``up``/``drop_first``
        are :func:`synthesis.read_bvh`'s options (``drop_first`` drops the T-pose
        frame 0 of CMU/cgspeed files). ``start_posture``/``end_posture`` declare
        every clip's postures (:data:`motiondb.types.POSTURES`); ``None``
        classifies each file's first/last frame (:func:`classify_posture`). A
        file that cannot be read or validated raises :class:`ClipValidationError`
        naming it, and nothing is stored.
        ``progress(done, total, path)`` is called before each file and once at the end.
        """
        paths = [Path(p) for p in paths]
        if not paths:
            raise ClipValidationError("no files to import")
        if names is not None and len(names) != len(paths):
            raise ClipValidationError(f"{len(names)} names for {len(paths)} files")
        clip_names = list(names) if names is not None else [p.stem for p in paths]
        prepared = []
        for k, (path, name) in enumerate(zip(paths, clip_names)):
            if progress:
                progress(k, len(paths), str(path))
            try:
                motion = read_bvh(path, scale=scale, up=up, drop_first=drop_first)
            except BVHError as exc:
                raise ClipValidationError(f"{exc} (nothing was imported)") from None
            except ValueError as exc:
                raise ClipValidationError(f"{path}: {exc} (nothing was imported)") from None
            rec = ClipRecord(name=name, motion=motion, verbs=tuple(verbs), objects=tuple(objects),
                             character=character, core=core, body_part=part, cyclic=cyclic,
                             source=str(path.resolve()), start_posture=start_posture, end_posture=end_posture)
            try:
                prepared.append(prepare_record(rec, where=str(path)))
            except ClipValidationError as exc:
                raise ClipValidationError(f"{exc} (nothing was imported)") from None
        if progress:
            progress(len(paths), len(paths), "")
        with self._session(write=True) as s:
            self._require_schema(s)
            ids = self._store(s, prepared, conflicts="replace" if replace else "error",
                              where={p.name: str(path) for p, path in zip(prepared, paths)})
            return self._infos(s, ids)

    def _require_schema(self, s: Session) -> None:
        version, _ = self._state(s)
        if version is None:
            raise DBError(f"{self.url} has no motion tables (it was emptied after opening)")
        if version != SCHEMA_VERSION:
            raise SchemaVersionError(f"{self.url} went back to motion-database schema version {version} after "
                                     "opening; open it again to migrate it")

    def _store(self, s: Session, prepared: list[_Prepared], *, conflicts: str,
               where: dict[str, str] | None = None) -> list[int]:
        """Insert prepared clips in session ``s``; ``conflicts``: ``error``, ``replace`` or ``skip``."""
        where = where or {}
        seen: set[str] = set()
        for p in prepared:
            if p.name in seen:
                raise ClipValidationError(f"two clips named {p.name!r} in one batch; nothing was stored")
            seen.add(p.name)
        existing = set()
        for chunk in _chunks([p.name for p in prepared]):
            existing.update(s.scalars(select(Clip.name).where(Clip.name.in_(chunk))))
        if existing:
            if conflicts == "error":
                shown = sorted(existing)
                listed = ", ".join(repr(n) for n in shown[:5]) + ("…" if len(shown) > 5 else "")
                many = len(shown) > 1
                raise ClipExistsError(
                    f"{'clips' if many else 'clip'} {listed} {'are' if many else 'is'} already in the database "
                    f"(remove {'them' if many else 'it'} first, or replace); nothing was stored")
            if conflicts == "replace":
                self._delete_clips(s, sorted(existing))
            else:
                prepared = [p for p in prepared if p.name not in existing]

        characters: dict[str, Character] = {}
        char_skel: dict[str, Skeleton] = {}
        skeletons: dict[str, SkeletonRow] = {}
        verbs: dict[str, Verb] = {}
        objects: dict[str, ObjectRow] = {}
        keep = []
        for p in prepared:
            # the character's joint hierarchy (its skeleton: the first clip's) must match
            ch = characters.get(p.character) or s.scalar(select(Character).where(Character.name == p.character))
            if ch is not None:
                if p.character not in char_skel:
                    char_skel[p.character] = self._skeleton(s, ch.skeleton_id)
                ref = char_skel[p.character]
                if not ref.same_hierarchy(p.skeleton):
                    if conflicts == "skip":
                        continue
                    label = where.get(p.name, f"clip {p.name!r}")
                    raise ClipValidationError(
                        f"{label}: its skeleton ({p.skeleton.n_joints} joints) has not the joint hierarchy of "
                        f"character {p.character!r} ({ref.n_joints} joints); import it under another character "
                        "(--character NAME); nothing was stored")
            # the skeleton, stored once per fingerprint
            srow = skeletons.get(p.fingerprint) or s.scalar(
                select(SkeletonRow).where(SkeletonRow.fingerprint == p.fingerprint))
            if srow is None:
                srow = SkeletonRow(fingerprint=p.fingerprint, n_joints=p.skeleton.n_joints, definition=p.skeleton_def)
                s.add(srow)
                s.flush()
            skeletons[p.fingerprint] = srow
            if ch is None:
                ch = Character(name=p.character, skeleton_id=srow.id)
                s.add(ch)
                s.flush()
                char_skel[p.character] = p.skeleton
            characters[p.character] = ch
            clip = Clip(name=p.name, character_id=ch.id, skeleton_id=srow.id, fps=p.fps, frames=p.frames,
                        duration=p.duration, core_begin=p.core[0], core_end=p.core[1], body_part=p.body_part,
                        cyclic=p.cyclic, source=p.source, created=utcnow(), start_posture=p.start_posture,
                        end_posture=p.end_posture)
            for k, lemma in enumerate(p.verbs):
                v = verbs.get(lemma) or s.scalar(select(Verb).where(Verb.lemma == lemma))
                if v is None:
                    v = Verb(lemma=lemma, reading=reading(lemma))
                    s.add(v)
                verbs[lemma] = v
                clip.verb_links.append(ClipVerb(verb=v, position=k, is_primary=(k == 0)))
            for k, name in enumerate(p.objects):
                o = objects.get(name) or s.scalar(select(ObjectRow).where(ObjectRow.name == name))
                if o is None:
                    o = ObjectRow(name=name, reading=reading(name))
                    s.add(o)
                objects[name] = o
                clip.object_links.append(ClipObject(object=o, position=k))
            clip.contacts = [Contact(side=side, start_frame=a, stop_frame=b) for side, a, b in p.contacts]
            clip.frame_data = ClipFrames(encoding=ENCODING, data=p.blob)
            s.add(clip)
            keep.append(clip)
        s.flush()
        return [c.id for c in keep]

    # ----------------------------------------------------------------- remove
    def remove(self, names: str | Sequence[str]) -> None:
        """Delete clips by name, all or nothing (an unknown name raises :class:`UnknownClipError`).

        Verbs, objects, characters and skeletons no remaining clip uses go with them.
        """
        names = [names] if isinstance(names, str) else list(names)
        with self._session(write=True) as s:
            for n in names:
                if s.scalar(select(Clip.id).where(Clip.name == normalize(n))) is None:
                    raise UnknownClipError(n, self._near_names(s, n))
            self._delete_clips(s, [normalize(n) for n in names])

    def _delete_clips(self, s: Session, names: list[str]) -> None:
        ids = list(s.scalars(select(Clip.id).where(Clip.name.in_(names))))
        for chunk in _chunks(ids):
            for table in (ClipFrames, Contact, ClipVerb, ClipObject):
                s.execute(delete(table).where(table.clip_id.in_(chunk)))
            s.execute(delete(Clip).where(Clip.id.in_(chunk)))
        s.execute(delete(Verb).where(~exists().where(ClipVerb.verb_id == Verb.id)))
        s.execute(delete(ObjectRow).where(~exists().where(ClipObject.object_id == ObjectRow.id)))
        s.execute(delete(Character).where(~exists().where(Clip.character_id == Character.id)))
        s.execute(delete(SkeletonRow).where(~exists().where(Clip.skeleton_id == SkeletonRow.id),
                                            ~exists().where(Character.skeleton_id == SkeletonRow.id)))
        s.expire_all()

    # ----------------------------------------------------------------- search
    def search(self, verb: str, object: str | None = None, character: str | None = None,
               body_part: str | None = None, prefer_character: str | None = None,
               limit: int | None = None, prefer_start_posture: str | None = None) -> list[ClipInfo]:
        """Clips retrieved by ``verb``, best first; frame data is not read.

        ``verb`` is a lemma, a synonym or another spelling with the same
        reading (``とぶ`` for ``跳ぶ``/``飛ぶ``). ``object`` ranks clips declaring
        it first; ``character`` keeps that character's clips only;
        ``body_part`` keeps clips for that part, its mirror side or the whole
        body; ``prefer_character`` (the previous clip's) ranks that character's
        clips first; ``prefer_start_posture`` (the posture the previous clip
        ends in, one of :data:`motiondb.types.POSTURES`) ranks clips starting
        in it next; ``limit`` keeps the best ``limit``. The full ranking is in
        :mod:`motiondb.search`.

        Returns an empty list when the verb is known but no clip passes the
        filters. Raises :class:`UnknownVerbError` (with the nearest verbs by
        reading) when no clip has the verb at all, :class:`UnknownCharacterError`
        for an unknown ``character``.
        """
        if not isinstance(verb, str) or not normalize(verb):
            raise DBError("search needs a verb")
        if body_part is not None and body_part not in GROUPS:
            raise DBError(f"unknown body part {body_part!r}; known: {', '.join(GROUPS)}")
        if limit is not None and limit < 0:
            raise ValueError("limit must not be negative")
        if prefer_start_posture is not None and prefer_start_posture not in POSTURES:
            raise DBError(f"unknown posture {prefer_start_posture!r}; known: {', '.join(POSTURES)}")
        with self._session() as s:
            match = _search.match_verbs(s, verb)
            if not match.all:
                raise self._unknown_verb(s, verb)
            char_id = None
            if character is not None:
                char_id = _search.character_id(s, normalize(character))
                if char_id is None:
                    raise UnknownCharacterError(character, self._character_names(s))
            pref_id = _search.character_id(s, normalize(prefer_character)) if prefer_character else None
            object_ids = _search.match_objects(s, object) if object is not None and normalize(object) else None
            ids = _search.ranked_clip_ids(s, match, object_ids=object_ids, character_id=char_id,
                                          body_part=body_part, prefer_character_id=pref_id,
                                          prefer_start_posture=prefer_start_posture, limit=limit)
            return self._infos(s, ids)

    def _unknown_verb(self, s: Session, verb: str) -> UnknownVerbError:
        rows = s.execute(select(Verb.lemma, Verb.reading)
                         .order_by(_search.binary_order(s, Verb.reading), _search.binary_order(s, Verb.lemma))).all()
        cands = {lemma: r for lemma, r in rows}
        near = nearest(verb, cands, n=5)
        return UnknownVerbError(verb, [(lemma, cands[lemma]) for lemma in near], n_verbs=len(cands))

    # ------------------------------------------------------------- listings
    def clips(self, character: str | None = None) -> list[ClipInfo]:
        """Every clip (of one character when given), by name."""
        with self._session() as s:
            stmt = select(Clip.id).order_by(_search.binary_order(s, Clip.name))
            if character is not None:
                cid = _search.character_id(s, normalize(character))
                if cid is None:
                    raise UnknownCharacterError(character, self._character_names(s))
                stmt = stmt.where(Clip.character_id == cid)
            return self._infos(s, list(s.scalars(stmt)))

    def info(self, name: str) -> ClipInfo:
        """The metadata of one clip; :class:`UnknownClipError` (with near names) if there is none."""
        with self._session() as s:
            return self._infos(s, [self._clip_id(s, name)])[0]

    def verbs(self) -> list[VerbInfo]:
        """Every verb with its reading and how many clips use it (by reading, then lemma)."""
        with self._session() as s:
            primary = func.sum(case((ClipVerb.is_primary, 1), else_=0))
            rows = s.execute(
                select(Verb.lemma, Verb.reading, func.count(ClipVerb.clip_id), primary)
                .join(ClipVerb, ClipVerb.verb_id == Verb.id)
                .group_by(Verb.id, Verb.lemma, Verb.reading)
                .order_by(_search.binary_order(s, Verb.reading), _search.binary_order(s, Verb.lemma))
            ).all()
            return [VerbInfo(lemma, r, int(n), int(p or 0)) for lemma, r, n, p in rows]

    def characters(self) -> list[str]:
        """Character names, sorted."""
        with self._session() as s:
            return self._character_names(s)

    # ------------------------------------------------------------------ load
    def load(self, clip: ClipInfo | str) -> Motion:
        """The frames of a clip (by :class:`ClipInfo` or name) as a :class:`synthesis.Motion`."""
        name = clip.name if isinstance(clip, ClipInfo) else clip
        with self._session() as s:
            cid = self._clip_id(s, name)
            row = s.execute(select(Clip.name, Clip.fps, Clip.frames, Clip.skeleton_id).where(Clip.id == cid)).one()
            enc, data = s.execute(select(ClipFrames.encoding, ClipFrames.data).where(ClipFrames.clip_id == cid)).one()
            skel = self._skeleton(s, row.skeleton_id)
        return decode_frames(data, skel, row.fps, encoding=enc, frames=row.frames, clip=row.name)

    def record(self, name: str) -> ClipRecord:
        """A stored clip as a :class:`ClipRecord` (frames and metadata), e.g. to export or mirror it."""
        info = self.info(name)
        return ClipRecord(name=info.name, motion=self.load(info.name), verbs=info.verbs, objects=info.objects,
                          character=info.character, core=info.core, body_part=info.body_part,
                          cyclic=info.cyclic, source=info.source, start_posture=info.start_posture,
                          end_posture=info.end_posture)

    # --------------------------------------------------------------- helpers
    def _clip_id(self, s: Session, name: str) -> int:
        cid = s.scalar(select(Clip.id).where(Clip.name == normalize(name))) if isinstance(name, str) else None
        if cid is None:
            raise UnknownClipError(str(name), self._near_names(s, str(name)))
        return cid

    def _near_names(self, s: Session, name: str) -> list[str]:
        import difflib

        names = list(s.scalars(select(Clip.name).order_by(_search.binary_order(s, Clip.name))))
        return difflib.get_close_matches(normalize(name), names, n=5, cutoff=0.5)

    def _character_names(self, s: Session) -> list[str]:
        return list(s.scalars(select(Character.name).order_by(_search.binary_order(s, Character.name))))

    def _skeleton(self, s: Session, skeleton_id: int) -> Skeleton:
        skel = self._skeletons.get(skeleton_id)
        if skel is None:
            definition = s.scalar(select(SkeletonRow.definition).where(SkeletonRow.id == skeleton_id))
            skel = skeleton_from_json(definition)
            self._skeletons[skeleton_id] = skel
        return skel

    def _infos(self, s: Session, ids: list[int]) -> list[ClipInfo]:
        """ClipInfo for clip ids, in that order (metadata, verbs, objects, contacts; never frame data).

        Plain column queries (four per 500 clips), not ORM objects: this is the
        hot path of every search.
        """
        if not ids:
            return []
        rows: dict[int, Any] = {}
        verbs: dict[int, list[str]] = {}
        objects: dict[int, list[str]] = {}
        contacts: dict[int, dict[str, list[tuple[int, int]]]] = {}
        for chunk in _chunks(ids):
            p = {"ids": chunk}
            for r in s.execute(_INFO_CLIPS, p):
                rows[r.id] = r
            for cid, lemma in s.execute(_INFO_VERBS, p):
                verbs.setdefault(cid, []).append(lemma)
            for cid, name in s.execute(_INFO_OBJECTS, p):
                objects.setdefault(cid, []).append(name)
            for cid, side, a, b in s.execute(_INFO_CONTACTS, p):
                contacts.setdefault(cid, {"left": [], "right": []})[side].append((a, b))
        out = []
        for i in ids:
            r = rows[i]
            created = r.created if r.created.tzinfo else r.created.replace(tzinfo=timezone.utc)
            sides = contacts.get(i, {"left": [], "right": []})
            out.append(ClipInfo(
                name=r.name, character=r.character, verbs=tuple(verbs.get(i, ())),
                objects=tuple(objects.get(i, ())), fps=r.fps, frames=r.frames, duration=r.duration,
                core=(r.core_begin, r.core_end), body_part=r.body_part, cyclic=bool(r.cyclic), source=r.source,
                created=created, joints=int(r.n_joints),
                left_contacts=tuple(sides["left"]), right_contacts=tuple(sides["right"]),
                start_posture=r.start_posture, end_posture=r.end_posture,
            ))
        return out


def _chunks(items: list, n: int = _CHUNK):
    for i in range(0, len(items), n):
        yield items[i:i + n]


@dataclass(frozen=True)
class _SeedSource:
    tag: str  # stored in schema_version.builtin_library
    records: Callable[[], Iterable[ClipRecord]]
    builtin: bool  # the built-in library (refreshed when its tag changes)


def _seeding_needed(library: str | None, source: _SeedSource | None) -> bool:
    """Whether a database whose ``builtin_library`` is ``library`` should be (re)seeded from ``source``.

    ``""`` means created without seeding (never seeded later); ``None`` means
    not seeded yet (the library was unavailable); another value is the tag of
    what was seeded: the built-in library is refreshed when its tag changes.
    """
    if source is None or library == "":
        return False
    if library is None:
        return True
    return source.builtin and library != source.tag


def _library_tag(library) -> str:
    """``LIBRARY_VERSION`` if the library has one, else a hash of its code and data files."""
    version = getattr(library, "LIBRARY_VERSION", None)
    if version:
        return str(version)[:64]
    root = Path(library.__file__).parent
    h = hashlib.sha256()
    for path in sorted(p for p in root.rglob("*") if p.suffix in (".py", ".json") and p.is_file()):
        h.update(path.relative_to(root).as_posix().encode("utf-8") + b"\0")
        h.update(path.read_bytes() + b"\0")
    return "sha256:" + h.hexdigest()[:32]


def _seed_source(seed) -> _SeedSource | None:
    """What to seed a new database with; ``None`` for nothing (or the built-in library is absent)."""
    if seed is False or seed is None:
        return None
    if callable(seed) and seed is not True:
        return _SeedSource(getattr(seed, "__name__", "custom")[:64], seed, builtin=False)
    import importlib

    try:
        library = importlib.import_module("text2anim.motiondb.library")
    except ModuleNotFoundError as exc:
        if exc.name == "text2anim.motiondb.library":
            return None  # the built-in library is not there (yet)
        raise
    fn = getattr(library, "builtin_clips", None)
    if fn is None:
        return None
    return _SeedSource(_library_tag(library), fn, builtin=True)
