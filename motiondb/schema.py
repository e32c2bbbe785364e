"""The database schema (SQLAlchemy 2.x ORM models) and its version.

Tables (schema version :data:`SCHEMA_VERSION`)::

    schema_version  id=1, version, builtin_library, created, updated
    skeletons       id, fingerprint (sha256, unique), n_joints, definition (JSON)
    characters      id, name (unique), skeleton_id -> skeletons
    clips           id, name (unique), character_id -> characters, skeleton_id -> skeletons,
                    fps, frames, duration, core_begin, core_end, body_part, cyclic,
                    source, created, start_posture, end_posture
    clip_frames     clip_id (PK) -> clips, encoding, data (compressed .npy bytes)
    verbs           id, lemma (unique), reading (indexed)
    clip_verbs      clip_id -> clips, verb_id -> verbs, position, is_primary
    objects         id, name (unique), reading (indexed)
    clip_objects    clip_id -> clips, object_id -> objects, position
    contacts        id, clip_id -> clips, side ('left'|'right'), start_frame, stop_frame

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
  database, so the vocabulary can grow without a migration).
- ``clip_frames``: the frame data in its own table, so listing and searching
  clips never reads it (see :mod:`motiondb.blobs` for the layout).
- ``verbs``: lemmas (NFKC) and their katakana readings (see
  :mod:`motiondb.readings`). ``clip_verbs.position`` keeps the clip's order;
  position 0 is the primary verb (``is_primary``), the others are synonyms.
- ``objects``: object nouns (ボール, 箱) with readings, linked to clips in order.
- ``contacts``: foot-contact intervals ``[start_frame, stop_frame)`` per foot,
  computed with :func:`core.contacts.detect_contacts` when the clip is stored.

Versions and migrations (:func:`motiondb.store.MotionDB.open` migrates an
older database in place, in one transaction, under the writers' lock):

- 1: the first schema;
- 2: ``clips.start_posture`` and ``clips.end_posture`` (``VARCHAR(16) NOT NULL
  DEFAULT 'standing'``). Migrating from 1 adds them with ``ALTER TABLE ... ADD
  COLUMN`` and classifies every stored clip from its first and last frames.

Deleting a clip deletes its frames, verb/object links and contacts (ON DELETE
CASCADE); verbs, objects, characters and skeletons no clip uses any more are
removed with it.
"""
from __future__ import annotations

from datetime import datetime, timezone

from sqlalchemy import (
    Boolean,
    CheckConstraint,
    DateTime,
    Float,
    ForeignKey,
    Index,
    Integer,
    LargeBinary,
    String,
    Text,
    UniqueConstraint,
)
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column, relationship

from .types import DEFAULT_POSTURE

#: Bumped whenever a table or column changes meaning; see :class:`SchemaVersion` and the
#: migrations in the module docstring.
SCHEMA_VERSION = 2
#: The oldest schema version :meth:`motiondb.store.MotionDB.open` can migrate from.
OLDEST_MIGRATABLE = 1

#: The tables of this schema, for detecting a database that holds someone else's tables.
TABLE_NAMES = ("schema_version", "skeletons", "characters", "clips", "clip_frames", "verbs",
               "clip_verbs", "objects", "clip_objects", "contacts")


def utcnow() -> datetime:
    return datetime.now(timezone.utc)


class Base(DeclarativeBase):
    pass


class SchemaVersion(Base):
    """One row (``id = 1``): the schema version and which built-in library was seeded.

    ``builtin_library`` is NULL until the built-in clips have been stored (the
    library's version string, or ``"1"`` when it has none).
    """

    __tablename__ = "schema_version"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    version: Mapped[int] = mapped_column(Integer, nullable=False)
    builtin_library: Mapped[str | None] = mapped_column(String(64), nullable=True)
    created: Mapped[datetime] = mapped_column(DateTime(timezone=True), nullable=False, default=utcnow)
    updated: Mapped[datetime] = mapped_column(DateTime(timezone=True), nullable=False, default=utcnow)


class SkeletonRow(Base):
    __tablename__ = "skeletons"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    fingerprint: Mapped[str] = mapped_column(String(64), nullable=False, unique=True)
    n_joints: Mapped[int] = mapped_column(Integer, nullable=False)
    definition: Mapped[str] = mapped_column(Text, nullable=False)


class Character(Base):
    __tablename__ = "characters"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200), nullable=False, unique=True)
    skeleton_id: Mapped[int] = mapped_column(ForeignKey("skeletons.id"), nullable=False)


class Clip(Base):
    __tablename__ = "clips"
    __table_args__ = (
        CheckConstraint("fps > 0", name="ck_clips_fps"),
        CheckConstraint("frames > 0", name="ck_clips_frames"),
        CheckConstraint("core_begin >= 0 AND core_begin < core_end", name="ck_clips_core"),
        Index("ix_clips_character", "character_id"),
    )

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200), nullable=False, unique=True)
    character_id: Mapped[int] = mapped_column(ForeignKey("characters.id"), nullable=False)
    skeleton_id: Mapped[int] = mapped_column(ForeignKey("skeletons.id"), nullable=False)
    fps: Mapped[float] = mapped_column(Float, nullable=False)
    frames: Mapped[int] = mapped_column(Integer, nullable=False)
    duration: Mapped[float] = mapped_column(Float, nullable=False)
    core_begin: Mapped[float] = mapped_column(Float, nullable=False)
    core_end: Mapped[float] = mapped_column(Float, nullable=False)
    body_part: Mapped[str | None] = mapped_column(String(32), nullable=True)
    cyclic: Mapped[bool] = mapped_column(Boolean, nullable=False, default=False)
    source: Mapped[str] = mapped_column(Text, nullable=False, default="")
    created: Mapped[datetime] = mapped_column(DateTime(timezone=True), nullable=False, default=utcnow)
    # schema version 2
    start_posture: Mapped[str] = mapped_column(String(16), nullable=False, default=DEFAULT_POSTURE,
                                               server_default=DEFAULT_POSTURE)
    end_posture: Mapped[str] = mapped_column(String(16), nullable=False, default=DEFAULT_POSTURE,
                                             server_default=DEFAULT_POSTURE)

    character: Mapped[Character] = relationship(lazy="joined", innerjoin=True)
    verb_links: Mapped[list["ClipVerb"]] = relationship(
        order_by=lambda: ClipVerb.position, lazy="selectin", cascade="all, delete-orphan", passive_deletes=True)
    object_links: Mapped[list["ClipObject"]] = relationship(
        order_by=lambda: ClipObject.position, lazy="selectin", cascade="all, delete-orphan", passive_deletes=True)
    contacts: Mapped[list["Contact"]] = relationship(
        order_by=lambda: [Contact.side, Contact.start_frame], lazy="selectin", cascade="all, delete-orphan",
        passive_deletes=True)
    # Frame data is never loaded through the clip: lazy="raise" turns an accidental read into an error.
    frame_data: Mapped["ClipFrames"] = relationship(
        lazy="raise", uselist=False, cascade="all, delete-orphan", passive_deletes=True)


class ClipFrames(Base):
    """The frame data of one clip (see :mod:`motiondb.blobs`)."""

    __tablename__ = "clip_frames"

    clip_id: Mapped[int] = mapped_column(ForeignKey("clips.id", ondelete="CASCADE"), primary_key=True)
    encoding: Mapped[str] = mapped_column(String(32), nullable=False)
    data: Mapped[bytes] = mapped_column(LargeBinary, nullable=False)


class Verb(Base):
    __tablename__ = "verbs"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    lemma: Mapped[str] = mapped_column(String(100), nullable=False, unique=True)
    reading: Mapped[str] = mapped_column(String(200), nullable=False, index=True)


class ClipVerb(Base):
    __tablename__ = "clip_verbs"
    __table_args__ = (
        UniqueConstraint("clip_id", "position", name="uq_clip_verbs_position"),
        Index("ix_clip_verbs_verb", "verb_id", "clip_id"),
    )

    clip_id: Mapped[int] = mapped_column(ForeignKey("clips.id", ondelete="CASCADE"), primary_key=True)
    verb_id: Mapped[int] = mapped_column(ForeignKey("verbs.id"), primary_key=True)
    position: Mapped[int] = mapped_column(Integer, nullable=False)
    is_primary: Mapped[bool] = mapped_column(Boolean, nullable=False)

    verb: Mapped[Verb] = relationship(lazy="joined", innerjoin=True)


class ObjectRow(Base):
    __tablename__ = "objects"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(100), nullable=False, unique=True)
    reading: Mapped[str] = mapped_column(String(200), nullable=False, index=True)


class ClipObject(Base):
    __tablename__ = "clip_objects"
    __table_args__ = (Index("ix_clip_objects_object", "object_id", "clip_id"),)

    clip_id: Mapped[int] = mapped_column(ForeignKey("clips.id", ondelete="CASCADE"), primary_key=True)
    object_id: Mapped[int] = mapped_column(ForeignKey("objects.id"), primary_key=True)
    position: Mapped[int] = mapped_column(Integer, nullable=False)

    object: Mapped[ObjectRow] = relationship(lazy="joined", innerjoin=True)


class Contact(Base):
    """A foot-contact interval: frames ``[start_frame, stop_frame)`` of one foot."""

    __tablename__ = "contacts"
    __table_args__ = (
        CheckConstraint("side IN ('left', 'right')", name="ck_contacts_side"),
        CheckConstraint("start_frame >= 0 AND start_frame < stop_frame", name="ck_contacts_range"),
        Index("ix_contacts_clip", "clip_id"),
    )

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    clip_id: Mapped[int] = mapped_column(ForeignKey("clips.id", ondelete="CASCADE"), nullable=False)
    side: Mapped[str] = mapped_column(String(8), nullable=False)
    start_frame: Mapped[int] = mapped_column(Integer, nullable=False)
    stop_frame: Mapped[int] = mapped_column(Integer, nullable=False)
