"""The database schema (SQLAlchemy Core tables) and its version.

Tables (schema version :data:`SCHEMA_VERSION`)::

    schema_version  id=1, version, builtin_library, created, updated
    skeletons       id, fingerprint (sha256, unique), n_joints, definition (JSON)
    characters      id, name (unique), skeleton_id -> skeletons
    clips           id, name (unique), character_id -> characters, skeleton_id -> skeletons,
                    fps, frames, duration, core_begin, core_end, body_part, cyclic,
                    source, created, start_posture, end_posture, description, style
    clip_frames     clip_id (PK) -> clips, encoding, data (compressed .npy bytes)
    verbs           id, lemma (unique), reading (indexed)
    clip_verbs      clip_id -> clips, verb_id -> verbs, position, is_primary
    objects         id, name (unique), reading (indexed)
    clip_objects    clip_id -> clips, object_id -> objects, position
    contacts        id, clip_id -> clips, side ('left'|'right'), start_frame, stop_frame
    search_ranks    verb_id -> verbs, clip_id -> clips, object_id (0 or -> objects), secondary,
                    has_objects, character_id, start_posture, body_part, name

Meaning and units:

- ``skeletons.definition``: JSON ``{"names", "parents", "offsets" (metres),
  "end_sites" ([[joint, [x, y, z]], ...], metres), "channels"}``; identical
  skeletons are stored once (``fingerprint`` is the SHA-256 of that JSON).
- ``characters``: a named character and its skeleton (the first clip stored
  for it decides). Every clip of a character has the same joint hierarchy
  (names and parents); proportions (``offsets``) may differ per clip, so a
  clip keeps its own ``skeleton_id`` (CMU subjects differ in size).
- ``clips``: ``fps`` frames per second; ``frames`` frame count; ``duration``
  seconds (``frames / fps``); ``core_begin``/``core_end`` seconds from the
  clip's start, the コア区間 that must be kept (the whole clip when none was
  declared); ``body_part`` one of :data:`core.bodyparts.GROUPS` for a
  partial action, NULL for whole-body clips; ``cyclic`` the clip loops;
  ``source`` where it came from (``builtin``, a file path); ``created`` UTC;
  ``start_posture``/``end_posture`` the posture of the first and of the last
  frame, one of :data:`motiondb.types.POSTURES` (``standing``, ``seated``,
  ``crouched``, ``kneeling``, ``lying``; checked when stored, not by the
  database, so the vocabulary can grow without a migration); ``description`` JSON
  ``{"actions", "locomotion", "moving", "energy"}``, what the body does
  (:class:`motiondb.types.ClipDescription`); ``style`` the style it was performed in (one of
  :data:`core.styles.STYLES`: ``sad``, ``tired``, ...), NULL for a neutral clip (checked when stored).
- ``clip_frames``: the frame data in its own table, so listing and searching
  clips never reads it (see :mod:`motiondb.blobs` for the layout).
- ``verbs``: lemmas (NFKC) and their katakana readings (see
  :mod:`motiondb.readings`). ``clip_verbs.position`` keeps the clip's order;
  position 0 is the primary verb (``is_primary``), the others are synonyms.
- ``objects``: object nouns (ボール, 箱) with readings, linked to clips in order.
- ``contacts``: foot-contact intervals ``[start_frame, stop_frame)`` per foot,
  computed with :func:`core.contacts.detect_contacts` when the clip is stored.
- ``search_ranks``: what a search ranks by, copied from the tables above when a clip is
  stored (:mod:`motiondb.ranks`): one row per ``clip_verbs`` row (``object_id`` 0) and
  one more per object the clip declares (``object_id``), with ``secondary`` (0 for the
  primary verb), ``has_objects`` and the clip's character, start posture, body part and
  name. Its indexes list a verb's clips in ranking order, so a search with a ``limit``
  reads a few rows per ranking tier instead of every clip of the verb.

Versions and migrations (:func:`motiondb.store.MotionDB.open` migrates an
older database in place, in one transaction, under the writers' lock):

- 1: the first schema;
- 2: ``clips.start_posture`` and ``clips.end_posture`` (``VARCHAR(16) NOT NULL
  DEFAULT 'standing'``). Migrating from 1 adds them with ``ALTER TABLE ... ADD
  COLUMN`` and classifies every stored clip from its first and last frames;
- 3: ``search_ranks``. Migrating from 2 creates it and fills it from the stored clips.
- 4: ``clips.description`` (``TEXT NOT NULL DEFAULT '{}'``). Migrating from 3 adds it and
  measures every stored clip from its frames (:func:`motiondb.description.describe`; no
  actions: an imported clip's actions are read from its primary verb when a stand-in is sought).
- 5: ``clips.style`` (``VARCHAR(16)``, NULL). Migrating from 4 adds it: every stored clip is neutral.

Deleting a clip deletes its frames, verb/object links and contacts (ON DELETE
CASCADE); verbs, objects, characters and skeletons no clip uses any more are
removed with it.

The tables are SQLAlchemy Core :class:`~sqlalchemy.Table` objects (``clips.c.name``), not ORM
classes: every read and write is a plain statement, and a run never imports ``sqlalchemy.orm``
(a tenth of a second of a command's start). Databases made by the earlier ORM models have the same
tables, columns, constraints and index names.
"""
from __future__ import annotations

from datetime import datetime, timezone

from sqlalchemy import (
    Boolean,
    CheckConstraint,
    Column,
    DateTime,
    Float,
    ForeignKey,
    Index,
    Integer,
    LargeBinary,
    MetaData,
    String,
    Table,
    Text,
    UniqueConstraint,
)

from .types import DEFAULT_POSTURE

#: Bumped whenever a table or column changes meaning; see :data:`schema_version` and the
#: migrations in the module docstring.
SCHEMA_VERSION = 5
#: The oldest schema version :meth:`motiondb.store.MotionDB.open` can migrate from.
OLDEST_MIGRATABLE = 1

#: The tables of this schema, for detecting a database that holds someone else's tables.
TABLE_NAMES = ("schema_version", "skeletons", "characters", "clips", "clip_frames", "verbs",
               "clip_verbs", "objects", "clip_objects", "contacts", "search_ranks")


def utcnow() -> datetime:
    return datetime.now(timezone.utc)


metadata = MetaData()

#: One row (``id = 1``): the schema version and which built-in library was seeded.
#: ``builtin_library`` is NULL until the built-in clips have been stored (the library's
#: version string, or ``"1"`` when it has none).
schema_version = Table(
    "schema_version", metadata,
    Column("id", Integer, primary_key=True),
    Column("version", Integer, nullable=False),
    Column("builtin_library", String(64), nullable=True),
    Column("created", DateTime(timezone=True), nullable=False, default=utcnow),
    Column("updated", DateTime(timezone=True), nullable=False, default=utcnow),
)

skeletons = Table(
    "skeletons", metadata,
    Column("id", Integer, primary_key=True),
    Column("fingerprint", String(64), nullable=False, unique=True),
    Column("n_joints", Integer, nullable=False),
    Column("definition", Text, nullable=False),
)

characters = Table(
    "characters", metadata,
    Column("id", Integer, primary_key=True),
    Column("name", String(200), nullable=False, unique=True),
    Column("skeleton_id", Integer, ForeignKey("skeletons.id"), nullable=False),
)

clips = Table(
    "clips", metadata,
    Column("id", Integer, primary_key=True),
    Column("name", String(200), nullable=False, unique=True),
    Column("character_id", Integer, ForeignKey("characters.id"), nullable=False),
    Column("skeleton_id", Integer, ForeignKey("skeletons.id"), nullable=False),
    Column("fps", Float, nullable=False),
    Column("frames", Integer, nullable=False),
    Column("duration", Float, nullable=False),
    Column("core_begin", Float, nullable=False),
    Column("core_end", Float, nullable=False),
    Column("body_part", String(32), nullable=True),
    Column("cyclic", Boolean, nullable=False, default=False),
    Column("source", Text, nullable=False, default=""),
    Column("created", DateTime(timezone=True), nullable=False, default=utcnow),
    # schema version 2
    Column("start_posture", String(16), nullable=False, default=DEFAULT_POSTURE, server_default=DEFAULT_POSTURE),
    Column("end_posture", String(16), nullable=False, default=DEFAULT_POSTURE, server_default=DEFAULT_POSTURE),
    # schema version 4
    Column("description", Text, nullable=False, default="{}", server_default="{}"),
    # schema version 5
    Column("style", String(16), nullable=True),
    CheckConstraint("fps > 0", name="ck_clips_fps"),
    CheckConstraint("frames > 0", name="ck_clips_frames"),
    CheckConstraint("core_begin >= 0 AND core_begin < core_end", name="ck_clips_core"),
    Index("ix_clips_character", "character_id"),
)

#: The frame data of one clip (see :mod:`motiondb.blobs`); never read by listing or searching.
clip_frames = Table(
    "clip_frames", metadata,
    Column("clip_id", Integer, ForeignKey("clips.id", ondelete="CASCADE"), primary_key=True),
    Column("encoding", String(32), nullable=False),
    Column("data", LargeBinary, nullable=False),
)

def _words(table: str, word: str) -> Table:
    """A table of words (verbs, objects): the word, unique, and its katakana reading, indexed."""
    return Table(table, metadata, Column("id", Integer, primary_key=True),
                 Column(word, String(100), nullable=False, unique=True),
                 Column("reading", String(200), nullable=False, index=True))


def _clip_words(table: str, words: str, word_id: str, *more) -> Table:
    """The words of each clip, in order (``position``), indexed by word; ``more`` columns and constraints."""
    return Table(table, metadata,
                 Column("clip_id", Integer, ForeignKey("clips.id", ondelete="CASCADE"), primary_key=True),
                 Column(word_id, Integer, ForeignKey(f"{words}.id"), primary_key=True),
                 Column("position", Integer, nullable=False),
                 *more, Index(f"ix_{table}_{word_id.removesuffix('_id')}", word_id, "clip_id"))


verbs = _words("verbs", "lemma")
clip_verbs = _clip_words("clip_verbs", "verbs", "verb_id", Column("is_primary", Boolean, nullable=False),
                         UniqueConstraint("clip_id", "position", name="uq_clip_verbs_position"))
objects = _words("objects", "name")
clip_objects = _clip_words("clip_objects", "objects", "object_id")

#: A foot-contact interval: frames ``[start_frame, stop_frame)`` of one foot.
contacts = Table(
    "contacts", metadata,
    Column("id", Integer, primary_key=True),
    Column("clip_id", Integer, ForeignKey("clips.id", ondelete="CASCADE"), nullable=False),
    Column("side", String(8), nullable=False),
    Column("start_frame", Integer, nullable=False),
    Column("stop_frame", Integer, nullable=False),
    CheckConstraint("side IN ('left', 'right')", name="ck_contacts_side"),
    CheckConstraint("start_frame >= 0 AND start_frame < stop_frame", name="ck_contacts_range"),
    Index("ix_contacts_clip", "clip_id"),
)


#: The name column of :data:`search_ranks`: ordered by code point on every backend (PostgreSQL's
#: ``C`` collation), as searches order clip names, so its indexes serve that order.
_RANK_NAME = String(200).with_variant(String(200, collation="C"), "postgresql")
_RANK_ORDER = ("has_objects", "secondary", "name")

#: A verb's clips in ranking order (see :mod:`motiondb.ranks`); schema version 3.
search_ranks = Table(
    "search_ranks", metadata,
    Column("verb_id", Integer, ForeignKey("verbs.id"), primary_key=True),
    Column("clip_id", Integer, ForeignKey("clips.id", ondelete="CASCADE"), primary_key=True),
    Column("object_id", Integer, primary_key=True),  # 0: the clip's own row, else one it declares
    Column("secondary", Integer, nullable=False),  # 0: the clip's primary verb, 1: a synonym
    Column("has_objects", Integer, nullable=False),
    Column("character_id", Integer, nullable=False),
    Column("start_posture", String(16), nullable=False),
    Column("body_part", String(32), nullable=True),
    Column("name", _RANK_NAME, nullable=False),
    Index("ix_search_ranks_order", "verb_id", "object_id", *_RANK_ORDER),
    Index("ix_search_ranks_character", "verb_id", "object_id", "character_id", *_RANK_ORDER),
    Index("ix_search_ranks_posture", "verb_id", "object_id", "start_posture", *_RANK_ORDER),
    Index("ix_search_ranks_part", "verb_id", "object_id", "body_part", *_RANK_ORDER),
    Index("ix_search_ranks_clip", "clip_id"),
)
