"""The schema's life: its version, creating it, and migrating an older database in place.

What each version adds is in :mod:`motiondb.schema`. Everything here runs in
the caller's transaction (migrations under the writers' lock), so a migration
is all or nothing.
"""
from __future__ import annotations

from sqlalchemy import Connection, Row, inspect, select, text

from .errors import DBError, SchemaVersionError
from .reads import SkeletonCache
from . import schema as tb
from .schema import OLDEST_MIGRATABLE, SCHEMA_VERSION, TABLE_NAMES, utcnow
from .types import DEFAULT_POSTURE


def schema_state(conn: Connection, url: str) -> tuple[int | None, str | None]:
    """``(schema version, builtin_library)`` of database ``url``; ``(None, None)`` without our schema.

    An older version this code can migrate (see :mod:`motiondb.schema`) is
    returned as it is; a newer one, or one too old, raises :class:`SchemaVersionError`.
    """
    insp = inspect(conn)
    if not insp.has_table("schema_version"):
        ours = [t for t in TABLE_NAMES if insp.has_table(t)]
        if ours:
            raise DBError(f"{url} already has tables named {', '.join(ours)} that text2anim did not "
                          "create; use another database (or PostgreSQL schema) for motions")
        return None, None
    row = _version(conn)
    if row is None:
        return None, None
    if row.version > SCHEMA_VERSION:
        raise SchemaVersionError(f"{url} has motion-database schema version {row.version}, newer than "
                                 f"this text2anim reads ({SCHEMA_VERSION}); upgrade text2anim")
    if row.version < OLDEST_MIGRATABLE:
        raise SchemaVersionError(f"{url} has motion-database schema version {row.version}, "
                                 f"which this text2anim cannot upgrade to {SCHEMA_VERSION}")
    return row.version, row.builtin_library


def _version(conn: Connection) -> Row | None:
    sv = tb.schema_version.c
    return conn.execute(select(sv.version, sv.builtin_library).where(sv.id == 1)).first()


def set_version(conn: Connection, **values) -> None:
    """Update the ``schema_version`` row (``version``, ``builtin_library``) of a database that has our schema."""
    sv = tb.schema_version
    if conn.execute(sv.update().where(sv.c.id == 1).values(updated=utcnow(), **values)).rowcount != 1:
        raise DBError("the motion database lost its schema_version row")


def create_schema(conn: Connection, *, seeded: bool) -> None:
    """Create every table at :data:`SCHEMA_VERSION`; ``seeded=False`` marks it never to be seeded."""
    tb.metadata.create_all(conn)
    conn.execute(tb.schema_version.insert().values(id=1, version=SCHEMA_VERSION,
                                                    builtin_library=None if seeded else ""))


def migrate(s: Connection, version: int, skeletons: SkeletonCache) -> None:
    """Bring a database of schema ``version`` to :data:`SCHEMA_VERSION` in session ``s`` (under
    the write lock; the caller's transaction makes it all or nothing)."""
    if version < 2:
        from text2anim.core.bodyparts import BodyMapError

        from .blobs import decode_frames
        from .postures import clip_postures

        # 1 -> 2: clip postures. The columns come with the default; then every stored clip is
        # classified from its frames (one clip at a time, so memory stays one clip's).
        for column in ("start_posture", "end_posture"):
            s.execute(text(f"ALTER TABLE clips ADD COLUMN {column} VARCHAR(16) "
                           f"DEFAULT '{DEFAULT_POSTURE}' NOT NULL"))
        clips, frames = tb.clips, tb.clip_frames.c
        rows = s.execute(select(clips.c.id, clips.c.name, clips.c.fps, clips.c.frames, clips.c.skeleton_id)
                         .order_by(clips.c.id)).all()
        for row in rows:
            enc, data = s.execute(select(frames.encoding, frames.data).where(frames.clip_id == row.id)).one()
            try:
                motion = decode_frames(data, skeletons.get(s, row.skeleton_id), row.fps, encoding=enc,
                                       frames=row.frames, clip=row.name)
                start, end = clip_postures(motion)
            except (DBError, BodyMapError, ValueError):
                continue  # a clip that cannot be read keeps the default; loading it will say why
            s.execute(clips.update().where(clips.c.id == row.id).values(start_posture=start, end_posture=end))
    if version < 3:
        from .ranks import fill

        # 2 -> 3: the ranking table, filled from the stored clips (after their postures, above)
        tb.search_ranks.create(s)
        fill(s)
    if version < 4:
        _add_descriptions(s, skeletons)
    if version < 5:  # 4 -> 5: clips.style; every stored clip is neutral (NULL)
        s.execute(text("ALTER TABLE clips ADD COLUMN style VARCHAR(16)"))
    set_version(s, version=SCHEMA_VERSION)


def _add_descriptions(s: Connection, skeletons: SkeletonCache) -> None:
    """3 -> 4: ``clips.description``, measured from every stored clip's frames (one clip at a time)."""
    import json

    from text2anim.core.bodyparts import BodyMapError

    from .blobs import decode_frames
    from .description import describe

    s.execute(text("ALTER TABLE clips ADD COLUMN description TEXT DEFAULT '{}' NOT NULL"))
    clips, frames = tb.clips, tb.clip_frames.c
    rows = s.execute(select(clips.c.id, clips.c.name, clips.c.fps, clips.c.frames, clips.c.skeleton_id,
                            clips.c.core_begin, clips.c.core_end).order_by(clips.c.id)).all()
    for row in rows:
        enc, data = s.execute(select(frames.encoding, frames.data).where(frames.clip_id == row.id)).one()
        try:
            motion = decode_frames(data, skeletons.get(s, row.skeleton_id), row.fps, encoding=enc,
                                   frames=row.frames, clip=row.name)
            d = describe(motion, (row.core_begin, row.core_end))
        except (DBError, BodyMapError, ValueError):
            continue  # a clip that cannot be read keeps '{}'; loading it will say why
        s.execute(clips.update().where(clips.c.id == row.id)
                  .values(description=json.dumps(d.to_dict(), sort_keys=True)))


def require_schema(s: Connection, url: str) -> None:
    """Raise unless database ``url`` (opened earlier) still has this schema version."""
    version, _ = schema_state(s, url)
    if version is None:
        raise DBError(f"{url} has no motion tables (it was emptied after opening)")
    if version != SCHEMA_VERSION:
        raise SchemaVersionError(f"{url} went back to motion-database schema version {version} after "
                                 "opening; open it again to migrate it")
