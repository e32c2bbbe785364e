"""The schema's life: its version, creating it, and migrating an older database in place.

What each version adds is in :mod:`motiondb.schema`. Everything here runs in
the caller's transaction (migrations under the writers' lock), so a migration
is all or nothing.
"""
from __future__ import annotations

from sqlalchemy import inspect, select, text
from sqlalchemy.orm import Session

from text2anim.core.bodyparts import BodyMapError

from .blobs import decode_frames
from .errors import DBError, SchemaVersionError
from .postures import clip_postures
from .reads import SkeletonCache
from .schema import OLDEST_MIGRATABLE, SCHEMA_VERSION, TABLE_NAMES, Base, Clip, ClipFrames, SchemaVersion, utcnow
from .types import DEFAULT_POSTURE


def schema_state(session: Session, url: str) -> tuple[int | None, str | None]:
    """``(schema version, builtin_library)`` of database ``url``; ``(None, None)`` without our schema.

    An older version this code can migrate (see :mod:`motiondb.schema`) is
    returned as it is; a newer one, or one too old, raises :class:`SchemaVersionError`.
    """
    insp = inspect(session.connection())
    if not insp.has_table("schema_version"):
        ours = [t for t in TABLE_NAMES if insp.has_table(t)]
        if ours:
            raise DBError(f"{url} already has tables named {', '.join(ours)} that text2anim did not "
                          "create; use another database (or PostgreSQL schema) for motions")
        return None, None
    row = session.get(SchemaVersion, 1)
    if row is None:
        return None, None
    if row.version > SCHEMA_VERSION:
        raise SchemaVersionError(f"{url} has motion-database schema version {row.version}, newer than "
                                 f"this text2anim reads ({SCHEMA_VERSION}); upgrade text2anim")
    if row.version < OLDEST_MIGRATABLE:
        raise SchemaVersionError(f"{url} has motion-database schema version {row.version}, "
                                 f"which this text2anim cannot upgrade to {SCHEMA_VERSION}")
    return row.version, row.builtin_library


def version_row(s: Session) -> SchemaVersion:
    """The ``schema_version`` row of a database that has our schema."""
    row = s.get(SchemaVersion, 1)
    if row is None:
        raise DBError("the motion database lost its schema_version row")
    return row


def create_schema(s: Session, *, seeded: bool) -> None:
    """Create every table at :data:`SCHEMA_VERSION`; ``seeded=False`` marks it never to be seeded."""
    Base.metadata.create_all(s.connection())
    s.add(SchemaVersion(id=1, version=SCHEMA_VERSION, builtin_library=None if seeded else ""))
    s.flush()


def migrate(s: Session, version: int, skeletons: SkeletonCache) -> None:
    """Bring a database of schema ``version`` to :data:`SCHEMA_VERSION` in session ``s`` (under
    the write lock; the caller's transaction makes it all or nothing)."""
    if version < 2:
        # 1 -> 2: clip postures. The columns come with the default; then every stored clip is
        # classified from its frames (one clip at a time, so memory stays one clip's).
        for column in ("start_posture", "end_posture"):
            s.execute(text(f"ALTER TABLE clips ADD COLUMN {column} VARCHAR(16) "
                           f"DEFAULT '{DEFAULT_POSTURE}' NOT NULL"))
        clips = Base.metadata.tables["clips"]
        rows = s.execute(select(Clip.id, Clip.name, Clip.fps, Clip.frames, Clip.skeleton_id)
                         .order_by(Clip.id)).all()
        for row in rows:
            enc, data = s.execute(select(ClipFrames.encoding, ClipFrames.data)
                                  .where(ClipFrames.clip_id == row.id)).one()
            try:
                motion = decode_frames(data, skeletons.get(s, row.skeleton_id), row.fps, encoding=enc,
                                       frames=row.frames, clip=row.name)
                start, end = clip_postures(motion)
            except (DBError, BodyMapError, ValueError):
                continue  # a clip that cannot be read keeps the default; loading it will say why
            s.execute(clips.update().where(clips.c.id == row.id).values(start_posture=start, end_posture=end))
    meta = version_row(s)
    meta.version = SCHEMA_VERSION
    meta.updated = utcnow()
    s.flush()


def require_schema(s: Session, url: str) -> None:
    """Raise unless database ``url`` (opened earlier) still has this schema version."""
    version, _ = schema_state(s, url)
    if version is None:
        raise DBError(f"{url} has no motion tables (it was emptied after opening)")
    if version != SCHEMA_VERSION:
        raise SchemaVersionError(f"{url} went back to motion-database schema version {version} after "
                                 "opening; open it again to migrate it")
