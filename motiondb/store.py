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

Why one module of about 380 lines: it is the :class:`MotionDB` facade, one short method per public
operation, each delegating the work to :mod:`.reads`, :mod:`.writes`, :mod:`.search`, :mod:`.seed` and
:mod:`.bvh_import`; splitting the class would split its public API across files for no gain.
"""
from __future__ import annotations

import itertools
import os
from collections import OrderedDict
from collections.abc import Callable, Iterable, Sequence
from contextlib import AbstractContextManager, contextmanager
from typing import TYPE_CHECKING

from sqlalchemy import Connection, case, func, select, text
from sqlalchemy import exc as sa_exc
from sqlalchemy.engine import Engine

from text2anim.core.bodyparts import GROUPS

from . import search as _search
from .connect import PG_LOCK_KEY, describe_error, first_line, open_engine
from .errors import DBError, UnknownCharacterError, UnknownClipError, UnknownVerbError
from .location import resolve_url
from .migrate import create_schema, migrate, require_schema, schema_state
from .reads import SkeletonCache, clip_infos
from .readings import normalize
from . import schema as tb
from .schema import SCHEMA_VERSION
from .seed import seed_source, seeding_needed
from .types import POSTURES, ClipInfo, ClipRecord, VerbInfo

if TYPE_CHECKING:  # BVH import brings scipy (retargeting): loaded by import_bvh only
    from .bvh_import import ImportOptions, Notify, Progress
    # frames and skeletons are numpy arrays: decoded by load(); searching and planning load no numpy
    from text2anim.core.motion import Motion
    from text2anim.core.skeleton import Skeleton

# Writing (records, contacts, writes, seeding) is imported by the methods that write: a command that
# only reads (text2anim plan) does not load it.


def __getattr__(name: str):
    if name == "classify_posture":  # re-exported: it was defined here
        from .postures import classify_posture

        return classify_posture
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


#: Decoded clips a :class:`MotionDB` keeps (least recently loaded dropped first).
LOADED_CLIPS = 32
#: Search answers kept between :meth:`MotionDB.memoised` blocks at most (then they start afresh): a plan asks ~3.
KEPT_ANSWERS = 4096
#: serial numbers of the connections :meth:`MotionDB._stamp` has seen (an ``id()`` may be reused)
_SERIALS = itertools.count(1)


# ----------------------------------------------------------------- the database
class MotionDB(AbstractContextManager):
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
        self._skeletons = SkeletonCache()
        self._memo: dict | None = None  # search answers inside memoised(), else None
        self._kept: tuple[tuple[int, int] | None, dict] = (None, {})  # (stamp, answers) between memoised() blocks
        self._loaded: OrderedDict[str, tuple[tuple, Motion]] = OrderedDict()  # name -> (row key, motion)

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
                a database was seeded with (a hash of its code and data files,
                taken without importing it), its clips whose ``source`` is
                ``builtin``/``builtin:…`` are replaced by the new ones; other
                clips are kept, and win over built-in clips of the same name.

        A database of an older schema version is migrated in place first, in
        one transaction (see :mod:`motiondb.schema` for what each version adds).

        Raises:
            DBError: a bad URL, an unreachable server, a file that is not a
                database, a schema written by a newer text2anim.
        """
        engine, display = open_engine(*resolve_url(url))
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
            raise DBError(f"database {self.url} refused the change: {first_line(exc)}") from None
        except (sa_exc.DBAPIError, sa_exc.InterfaceError) as exc:
            raise DBError(describe_error(exc, self.url, self.backend)) from None

    @contextmanager
    def memoised(self):
        """Within the block, a search asked again is answered from memory (a plan's searches repeat).

        Any change made through this object inside the block forgets the answers.
        Nested blocks share the outer one's memory. On SQLite the answers are kept for the next
        block while no connection has changed the file since (:meth:`_stamp`): a warm process
        planning sentence after sentence asks the database only for what it has not asked yet.
        """
        outer = self._memo is not None
        if not outer:
            stamp = self._stamp()
            if stamp is None or stamp != self._kept[0] or len(self._kept[1]) > KEPT_ANSWERS:
                self._kept = (stamp, {})
            self._memo = self._kept[1]
        try:
            yield self
        finally:
            if not outer:
                self._memo = None

    def _stamp(self) -> tuple[int, int] | None:
        """What the kept answers are valid for: the connection and its SQLite ``data_version``, which
        changes when another connection (of this or any process) commits to the file; ``None`` when
        it cannot be known (another database). This object's own writes forget the answers (a
        connection's own commits leave its ``data_version`` as it was)."""
        if self.backend != "sqlite":
            return None
        with self._errors(), self.engine.connect() as conn:
            fairy = conn.connection
            serial = fairy.info.setdefault("t2a_serial", next(_SERIALS))  # for the life of the DBAPI connection
            cursor = fairy.cursor()  # the driver's own: no statement event, nothing compiled
            try:
                cursor.execute("PRAGMA data_version")
                row = cursor.fetchone()
            finally:
                cursor.close()
            assert row is not None
            return serial, int(row[0])

    @contextmanager
    def _session(self, write: bool = False):
        """A connection in one transaction, committed on success; writers serialised."""
        if write:
            self._kept = (None, {})
            if self._memo:
                self._memo.clear()
        with self._errors():
            with (self._writer if write else self.engine).begin() as conn:
                if write and self.backend == "postgresql":
                    conn.execute(text("SELECT pg_advisory_xact_lock(:k)"), {"k": PG_LOCK_KEY})
                yield conn

    # ------------------------------------------------------- schema, seeding
    def _prepare(self, seed) -> None:
        """Create the schema if missing, migrate an older one, and seed (or refresh the built-in clips) when needed."""
        source = seed_source(seed)
        with self._session() as s:
            version, library = schema_state(s, self.url)
        if version == SCHEMA_VERSION and not seeding_needed(library, source):
            return
        from .seed import fill

        with self._session(write=True) as s:
            # again, under the write lock: another process may have done it
            version, library = schema_state(s, self.url)
            if version is None:
                create_schema(s, seeded=seed is not False)
                library = "" if seed is False else None
            elif version < SCHEMA_VERSION:
                migrate(s, version, self._skeletons)
            if source is not None and seeding_needed(library, source):
                fill(s, source, library, self.url, self._skeletons)

    # ------------------------------------------------------------------ store
    def add(self, records: Sequence[ClipRecord], *, replace: bool = False) -> list[ClipInfo]:
        """Store clips, all or nothing; returns their :class:`ClipInfo` in the given order.

        Contacts are computed here (:func:`core.contacts.detect_contacts`).
        ``replace`` overwrites clips of the same names; otherwise an existing
        name raises :class:`ClipExistsError` and nothing is stored.
        """
        from .records import prepare_record
        from .writes import store_clips

        prepared = [prepare_record(r) for r in records]
        with self._session(write=True) as s:
            require_schema(s, self.url)
            ids = store_clips(s, prepared, self._skeletons, conflicts="replace" if replace else "error")
            return clip_infos(s, ids)

    def import_bvh(self, paths: Sequence[str | os.PathLike], options: ImportOptions, *,
                   progress: Progress | None = None, notify: Notify | None = None) -> list[ClipInfo]:
        """Read BVH files and store them as clips (:mod:`motiondb.bvh_import`), all or nothing.

        Every file becomes one clip with the metadata of ``options``, on the
        floor and on its character's skeleton (retargeted when it was recorded
        on another). A file that cannot be read, mapped or validated raises
        :class:`ClipValidationError` naming it, and nothing is stored.
        ``progress(done, total, path)`` is called before each file and once at
        the end; ``notify(path, message)`` says what was done to a file.
        """
        from .bvh_import import read_clips
        from .writes import store_clips

        clips = read_clips(paths, options, progress, skeleton=self.character_skeleton(options.character),
                           notify=notify)
        with self._session(write=True) as s:
            require_schema(s, self.url)
            ids = store_clips(s, [p for p, _ in clips], self._skeletons,
                              conflicts="replace" if options.replace else "error",
                              where={p.name: str(path) for p, path in clips})
            return clip_infos(s, ids)

    def character_skeleton(self, character: str) -> Skeleton | None:
        """The skeleton every clip of ``character`` is stored on; ``None`` for a character with no clips."""
        with self._session() as s:
            characters = tb.characters.c
            sid = s.scalar(select(characters.skeleton_id).where(characters.name == normalize(character)))
            return None if sid is None else self._skeletons.get(s, sid)

    # ----------------------------------------------------------------- remove
    def remove(self, names: str | Sequence[str]) -> None:
        """Delete clips by name, all or nothing (an unknown name raises :class:`UnknownClipError`).

        Verbs, objects, characters and skeletons no remaining clip uses go with them.
        """
        from .writes import delete_clips

        names = [names] if isinstance(names, str) else list(names)
        with self._session(write=True) as s:
            for n in names:
                if s.scalar(select(tb.clips.c.id).where(tb.clips.c.name == normalize(n))) is None:
                    raise UnknownClipError(n, _search.near_clip_names(s, n))
            delete_clips(s, [normalize(n) for n in names])

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
        if self._memo is None:
            return self._find(verb, object, character, body_part, prefer_character, limit, prefer_start_posture)
        # memoised: one query per (verb, object, character, body part), ranked without the preferences;
        # the preferred character and start posture are ranked here, as the query ranks them
        key = (verb, object, character, body_part)
        if key not in self._memo:
            try:
                self._memo[key] = tuple(self._find(verb, object, character, body_part, None, None, None))
            except UnknownVerbError as exc:  # a verb the database lacks is asked again too (a plan's refusal)
                self._memo[key] = exc
        known = self._memo[key]
        if isinstance(known, UnknownVerbError):  # a new error each time; its suggestions are found once
            raise UnknownVerbError(known.verb, lambda: known.suggestions, known.n_verbs)
        hits = _search.prefer(known, body_part=body_part, character=prefer_character,
                              start_posture=prefer_start_posture)
        return hits if limit is None else hits[:limit]

    def _remembered(self, key: tuple, read: Callable[[], list]) -> list:
        """``read()``, answered from memory inside :meth:`memoised` (a refused plan lists every clip and verb)."""
        if self._memo is None:
            return read()
        if key not in self._memo:
            self._memo[key] = tuple(read())
        return list(self._memo[key])

    def _find(self, verb: str, object: str | None, character: str | None, body_part: str | None,
              prefer_character: str | None, limit: int | None, prefer_start_posture: str | None) -> list[ClipInfo]:
        """:meth:`search` in the database (arguments checked)."""
        with self._session() as s:
            found = _search.find(s, verb, object=object, character=character, body_part=body_part,
                                 prefer_character=prefer_character, prefer_start_posture=prefer_start_posture,
                                 limit=limit)
            if found:
                return found
            # nothing: say why when it is an unknown verb or character (these look-ups only run here)
            if not _search.match_verbs(s, verb).all:
                raise _search.unknown_verb_error(s, verb)
            if character is not None and _search.character_id(s, normalize(character)) is None:
                raise UnknownCharacterError(character, _search.character_names(s))
        return []

    # ------------------------------------------------------------- listings
    def clips(self, character: str | None = None) -> list[ClipInfo]:
        """Every clip (of one character when given), by name."""
        return self._remembered(("clips", character), lambda: self._clips(character))

    def _clips(self, character: str | None) -> list[ClipInfo]:
        with self._session() as s:
            stmt = select(tb.clips.c.id).order_by(_search.binary_order(s, tb.clips.c.name))
            if character is not None:
                cid = _search.character_id(s, normalize(character))
                if cid is None:
                    raise UnknownCharacterError(character, _search.character_names(s))
                stmt = stmt.where(tb.clips.c.character_id == cid)
            return clip_infos(s, list(s.scalars(stmt)))

    def info(self, name: str) -> ClipInfo:
        """The metadata of one clip; :class:`UnknownClipError` (with near names) if there is none."""
        with self._session() as s:
            return clip_infos(s, [self._clip_id(s, name)])[0]

    def verbs(self) -> list[VerbInfo]:
        """Every verb with its reading and how many clips use it (by reading, then lemma)."""
        return self._remembered(("verbs",), self._verbs)

    def _verbs(self) -> list[VerbInfo]:
        with self._session() as s:
            verbs, links = tb.verbs.c, tb.clip_verbs.c
            primary = func.sum(case((links.is_primary, 1), else_=0))
            rows = s.execute(
                select(verbs.lemma, verbs.reading, func.count(links.clip_id), primary)
                .join(tb.clip_verbs, links.verb_id == verbs.id)
                .group_by(verbs.id, verbs.lemma, verbs.reading)
                .order_by(_search.binary_order(s, verbs.reading), _search.binary_order(s, verbs.lemma))
            ).all()
            return [VerbInfo(lemma, r, int(n), int(p or 0)) for lemma, r, n, p in rows]

    def characters(self) -> list[str]:
        """Character names, sorted."""
        with self._session() as s:
            return _search.character_names(s)

    # ------------------------------------------------------------------ load
    def load(self, clip: ClipInfo | str) -> Motion:
        """The frames of a clip (by :class:`ClipInfo` or name) as a :class:`synthesis.Motion`.

        The last :data:`LOADED_CLIPS` clips loaded are kept decoded: a clip loaded again while its row is
        the same (id, creation time, size; one query checks it) is the same motion (immutable), its pose
        and derived data computed once for every use.
        """
        name = clip.name if isinstance(clip, ClipInfo) else clip
        clips, frames = tb.clips.c, tb.clip_frames.c
        with self._session() as s:
            row = (s.execute(select(clips.id, clips.name, clips.fps, clips.frames, clips.skeleton_id, clips.created)
                             .where(clips.name == normalize(name))).first() if isinstance(name, str) else None)
            if row is None:
                raise UnknownClipError(str(name), _search.near_clip_names(s, str(name)))
            key = tuple(row)  # id, creation time, frames, fps, skeleton: a replaced clip differs
            known = self._loaded.get(row.name)
            if known is not None and known[0] == key:
                self._loaded.move_to_end(row.name)
                return known[1]
            enc, data = s.execute(select(frames.encoding, frames.data).where(frames.clip_id == row.id)).one()
            skel = self._skeletons.get(s, row.skeleton_id)
        from .blobs import decode_frames

        motion = decode_frames(data, skel, row.fps, encoding=enc, frames=row.frames, clip=row.name)
        self._loaded[row.name] = (key, motion)
        while len(self._loaded) > LOADED_CLIPS:
            self._loaded.popitem(last=False)
        return motion

    def record(self, name: str) -> ClipRecord:
        """A stored clip as a :class:`ClipRecord` (frames and metadata), e.g. to export or mirror it."""
        info = self.info(name)
        return ClipRecord(name=info.name, motion=self.load(info.name), verbs=info.verbs, objects=info.objects,
                          character=info.character, core=info.core, body_part=info.body_part,
                          cyclic=info.cyclic, source=info.source, start_posture=info.start_posture,
                          end_posture=info.end_posture, style=info.style)

    # --------------------------------------------------------------- helpers
    def _clip_id(self, s: Connection, name: str) -> int:
        cid = (s.scalar(select(tb.clips.c.id).where(tb.clips.c.name == normalize(name)))
               if isinstance(name, str) else None)
        if cid is None:
            raise UnknownClipError(str(name), _search.near_clip_names(s, str(name)))
        return cid
