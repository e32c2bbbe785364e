"""Storing, loading and removing clips; all-or-nothing changes; lazy frame data; schema version."""
from __future__ import annotations

import io
import zlib

import numpy as np
import pytest
from sqlalchemy import create_engine, event, text, update

from conftest import make_motion, make_skeleton
from text2anim.motiondb import (
    ClipExistsError,
    ClipRecord,
    ClipValidationError,
    DBError,
    MotionDB,
    SchemaVersionError,
    UnknownCharacterError,
    UnknownClipError,
)
from text2anim.motiondb.blobs import decode_frames, encode_frames
from text2anim.motiondb.schema import SCHEMA_VERSION, clips, schema_version
from text2anim.core.contacts import detect_contacts


def _same_skeleton(a, b):
    assert a.names == b.names
    assert np.array_equal(a.parents, b.parents)
    assert np.array_equal(a.offsets, b.offsets)
    assert a.channels == b.channels
    assert len(a.end_sites) == len(b.end_sites)
    for (ja, oa), (jb, ob) in zip(a.end_sites, b.end_sites):
        assert ja == jb and np.array_equal(oa, ob)


def test_add_then_load_gives_back_the_same_frames(empty_db, record):
    recs = [record("walk", ("歩く", "進む"), objects=("ボール",), character="alice", core=(0.2, 0.6),
                   cyclic=True, source="test"),
            record("wiggle", ("揺れる",), translations=True, body_part="torso")]
    infos = empty_db.add(recs)
    assert [i.name for i in infos] == ["walk", "wiggle"]
    for rec in recs:
        m = empty_db.load(rec.name)
        assert np.array_equal(m.root_positions, rec.motion.root_positions)
        assert np.array_equal(m.rotations, rec.motion.rotations)
        if rec.motion.translations is None:
            assert m.translations is None
        else:
            assert np.array_equal(m.translations, rec.motion.translations)
        assert m.fps == rec.motion.fps
        _same_skeleton(m.skeleton, rec.motion.skeleton)
    walk = empty_db.info("walk")
    assert walk.verbs == ("歩く", "進む") and walk.verb == "歩く"
    assert walk.objects == ("ボール",) and walk.character == "alice"
    assert walk.core == (0.2, 0.6) and walk.cyclic and walk.source == "test"
    assert walk.frames == 24 and walk.fps == 30.0 and walk.duration == pytest.approx(0.8)
    assert walk.joints == 23 and walk.created.tzinfo is not None
    contacts = detect_contacts(recs[0].motion)
    assert walk.contacts("left") == tuple(contacts.intervals("left"))
    assert walk.contacts("right") == tuple(contacts.intervals("right"))
    wiggle = empty_db.info("wiggle")
    assert wiggle.core == (0.0, wiggle.duration)  # no core declared: the whole clip
    assert wiggle.body_part == "torso" and not wiggle.cyclic
    assert [c.name for c in empty_db.clips()] == ["walk", "wiggle"]
    assert [c.name for c in empty_db.clips(character="alice")] == ["walk"]
    assert empty_db.characters() == ["alice", "default"]


def test_a_clip_loaded_again_is_decoded_once_and_follows_a_replacement(empty_db, record):
    empty_db.add([record("walk", ("歩く",), seed=1)])
    first = empty_db.load("walk")
    seen: list[str] = []
    event.listen(empty_db.engine, "before_cursor_execute", lambda conn, cur, statement, *a: seen.append(statement))
    again = empty_db.load("walk")
    assert not any("clip_frames" in s for s in seen)  # the frames were not read again
    assert again is first  # the same immutable motion: forward kinematics done once for both
    with pytest.raises(ValueError, match="read-only"):
        again.rotations[:] = 0.0  # no caller can edit a motion another caller is given
    assert again.pose is first.pose
    replacement = record("walk", ("歩く",), seed=2)
    empty_db.add([replacement], replace=True)
    assert np.array_equal(empty_db.load("walk").rotations, replacement.motion.rotations)
    with pytest.raises(UnknownClipError):
        empty_db.load("walkk")


def test_record_round_trips_into_another_database(empty_db, record, tmp_path):
    empty_db.add([record("kick", ("蹴る", "キックする"), objects=("ボール",), core=(0.1, 0.5), body_part="right_leg")])
    rec = empty_db.record("kick")
    assert isinstance(rec, ClipRecord)
    assert rec.verbs == ("蹴る", "キックする") and rec.objects == ("ボール",)
    assert rec.core == (0.1, 0.5) and rec.body_part == "right_leg" and rec.character == "default"
    with MotionDB.open(tmp_path / "other.sqlite", seed=False) as other:
        other.add([rec])
        again = other.load("kick")
    assert np.array_equal(again.rotations, rec.motion.rotations)


def test_a_bad_record_in_a_batch_changes_nothing(empty_db, record):
    with pytest.raises(ClipValidationError, match=r"clip 'late'.*core"):
        empty_db.add([record("fine", ("歩く",)), record("late", ("走る",), core=(0.5, 9.0))])
    assert empty_db.clips() == [] and empty_db.verbs() == [] and empty_db.characters() == []

    empty_db.add([record("fine", ("歩く",))])
    with pytest.raises(ClipExistsError, match="clip 'fine' is already in the database"):
        empty_db.add([record("new", ("跳ぶ",)), record("fine", ("歩く",), seed=5)])
    assert [c.name for c in empty_db.clips()] == ["fine"]
    assert [v.lemma for v in empty_db.verbs()] == ["歩く"]
    with pytest.raises(ClipValidationError, match="two clips named 'x'"):
        empty_db.add([record("x"), record("x")])

    replacement = record("fine", ("歩く", "進む"), seed=5)
    empty_db.add([replacement], replace=True)
    assert empty_db.info("fine").verbs == ("歩く", "進む")
    assert np.array_equal(empty_db.load("fine").rotations, replacement.motion.rotations)


@pytest.mark.parametrize("fields, message", [
    ({"verbs": ()}, "at least one verb"),
    ({"verbs": ("  ",)}, "empty verb"),
    ({"body_part": "tail"}, "unknown body part 'tail'"),
    ({"core": (0.5, 0.2)}, "core"),
    ({"name": ""}, "clip name is empty"),
    ({"character": ""}, "character name is empty"),
])
def test_invalid_records_are_refused_with_a_reason(tmp_path, record, fields, message):
    with MotionDB.open(tmp_path / "v.sqlite", seed=False) as db:
        rec = record(fields.pop("name", "c"), fields.pop("verbs", ("歩く",)), **fields)
        with pytest.raises(ClipValidationError, match=message) as err:
            db.add([rec])
        assert err.value.user_facing
        assert db.clips() == []


def test_bad_frames_are_refused(tmp_path, record):
    good = make_motion()
    with MotionDB.open(tmp_path / "f.sqlite", seed=False) as db:
        rot = good.rotations.copy()
        rot[3, 2] *= 3.0
        with pytest.raises(ClipValidationError, match="unit quaternions"):
            db.add([ClipRecord("bad", good.replace(rotations=rot), ("歩く",))])
        root = good.root_positions.copy()
        root[1, 0] = np.nan
        with pytest.raises(ClipValidationError, match="non-finite"):
            db.add([ClipRecord("bad", good.replace(root_positions=root), ("歩く",))])
        with pytest.raises(ClipValidationError, match="no frames"):
            db.add([ClipRecord("bad", good.frames(0, 0), ("歩く",))])


def test_remove_deletes_clips_and_what_only_they_used(empty_db, record):
    empty_db.add([record("walk", ("歩く", "進む"), objects=("ボール",), character="alice"),
                  record("run", ("走る", "進む"), character="bob")])
    with pytest.raises(UnknownClipError, match="'wlak'.*nearest: walk") as err:
        empty_db.remove(["run", "wlak"])
    assert err.value.user_facing
    assert len(empty_db.clips()) == 2  # all or nothing
    empty_db.remove("walk")
    assert [c.name for c in empty_db.clips()] == ["run"]
    assert sorted(v.lemma for v in empty_db.verbs()) == ["走る", "進む"]
    assert empty_db.characters() == ["bob"]
    with pytest.raises(UnknownClipError):
        empty_db.load("walk")
    empty_db.remove(["run"])
    assert empty_db.clips() == [] and empty_db.verbs() == [] and empty_db.characters() == []
    with empty_db.engine.connect() as conn:  # nothing left behind
        for table in ("clip_frames", "contacts", "clip_verbs", "clip_objects", "objects", "skeletons"):
            assert conn.execute(text(f"SELECT COUNT(*) FROM {table}")).scalar() == 0, table


def test_a_character_keeps_one_joint_hierarchy(empty_db, record):
    empty_db.add([record("walk", character="alice")])
    other = record("stomp", ("踏む",), character="alice", skeleton=make_skeleton(without_toes=True))
    with pytest.raises(ClipValidationError, match="joint hierarchy of character 'alice'.*--character"):
        empty_db.add([other])
    # same hierarchy, other proportions (another performer): fine, and kept exactly
    tall = record("tall_walk", character="alice", skeleton=make_skeleton(scale=1.1))
    empty_db.add([tall])
    assert np.array_equal(empty_db.load("tall_walk").skeleton.offsets, tall.motion.skeleton.offsets)
    empty_db.add([record("stomp", ("踏む",), character="bobby", skeleton=make_skeleton(without_toes=True))])
    assert empty_db.characters() == ["alice", "bobby"]
    with pytest.raises(UnknownCharacterError, match="'bob'.*alice, bobby"):
        empty_db.clips(character="bob")


def test_listing_and_searching_never_read_frame_data(empty_db, record):
    empty_db.add([record("walk", ("歩く", "進む"), objects=("ボール",)), record("run", ("走る",))])
    statements: list[str] = []

    def log(conn, cursor, statement, params, context, executemany):
        statements.append(statement.lower())

    event.listen(empty_db.engine, "before_cursor_execute", log)
    try:
        hits = empty_db.search("歩く", object="ボール")
        empty_db.search("すすむ")
        empty_db.clips()
        empty_db.info("run")
        empty_db.verbs()
        assert hits[0].left_contacts or hits[0].right_contacts  # contacts come with the metadata
        assert statements and not any("clip_frames" in s for s in statements)
        empty_db.load(hits[0])
        assert any("clip_frames" in s for s in statements)
    finally:
        event.remove(empty_db.engine, "before_cursor_execute", log)
    # The clips table has no frame column.
    assert "data" not in clips.c


def test_frame_blobs_are_deterministic_npy_without_pickle():
    m = make_motion(seed=3, translations=True)
    blob = encode_frames(m)
    assert blob == encode_frames(make_motion(seed=3, translations=True))
    raw = zlib.decompress(blob)
    assert raw.startswith(b"\x93NUMPY")
    arr = np.load(io.BytesIO(raw), allow_pickle=False)
    assert arr.shape == (m.n_frames, 3 + 7 * m.skeleton.n_joints) and arr.dtype == np.float64
    back = decode_frames(blob, m.skeleton, m.fps, frames=m.n_frames)
    assert np.array_equal(back.translations, m.translations)
    # An object array (a pickle inside) is refused, never unpickled.
    buf = io.BytesIO()
    np.save(buf, np.array([{"a": 1}], dtype=object), allow_pickle=True)
    with pytest.raises(DBError, match="damaged"):
        decode_frames(zlib.compress(buf.getvalue()), m.skeleton, m.fps)
    with pytest.raises(DBError, match="does not fit"):
        decode_frames(blob, make_skeleton(without_toes=True), m.fps)


def test_schema_version_is_recorded_and_checked(db_url):
    MotionDB.open(db_url, seed=False).close()
    engine = create_engine(db_url)
    try:
        with engine.begin() as conn:
            assert conn.execute(text("SELECT version FROM schema_version WHERE id = 1")).scalar() == SCHEMA_VERSION
            conn.execute(update(schema_version).values(version=SCHEMA_VERSION + 1))
    finally:
        engine.dispose()
    with pytest.raises(SchemaVersionError, match="newer than this text2anim reads") as err:
        MotionDB.open(db_url)
    assert err.value.user_facing


def test_tables_of_someone_else_are_not_touched(db_url):
    engine = create_engine(db_url)
    try:
        with engine.begin() as conn:
            conn.execute(text("CREATE TABLE clips (id INTEGER PRIMARY KEY, title TEXT)"))
    finally:
        engine.dispose()
    with pytest.raises(DBError, match="already has tables named clips"):
        MotionDB.open(db_url, seed=False)


# ------------------------------------------------------------------ postures
def _library(name: str):
    from text2anim.motiondb.library import build_all

    return next(b.record for b in build_all(30.0) if b.record.name == name)


def test_postures_are_classified_unless_declared(empty_db):
    sit, up = _library("sit_down"), _library("stand_up")
    infos = empty_db.add([
        ClipRecord("plain_sit", sit.motion, ("座る",)),  # nothing declared: from the first/last frames
        ClipRecord("plain_up", up.motion, ("立ち上がる",)),
        ClipRecord("told", sit.motion, ("座り込む",), start_posture="kneeling", end_posture="lying"),
    ])
    assert [(i.start_posture, i.end_posture) for i in infos] == [
        ("standing", "seated"), ("seated", "standing"), ("kneeling", "lying")]
    info = empty_db.info("plain_sit")
    assert (info.start_posture, info.end_posture) == ("standing", "seated")
    assert info.to_dict()["start_posture"] == "standing" and info.to_dict()["end_posture"] == "seated"
    rec = empty_db.record("told")
    assert (rec.start_posture, rec.end_posture) == ("kneeling", "lying")
    assert [c.name for c in empty_db.search("座る", prefer_start_posture="kneeling")] == ["plain_sit"]


def test_an_unknown_posture_is_refused(empty_db, record):
    with pytest.raises(ClipValidationError, match="unknown end posture 'sitting'.*standing, seated"):
        empty_db.add([record("x", end_posture="sitting")])
    assert empty_db.clips() == []


def _make_version_2(url: str) -> None:
    """Turn a database of this version into what schema version 2 wrote (no ranking table, no descriptions)."""
    engine = create_engine(url)
    try:
        with engine.begin() as conn:
            conn.execute(text("DROP TABLE search_ranks"))
            conn.execute(text("ALTER TABLE clips DROP COLUMN style"))  # schema 5
            conn.execute(text("ALTER TABLE clips DROP COLUMN description"))
            conn.execute(text("UPDATE schema_version SET version = 2"))
    finally:
        engine.dispose()


def _make_version_1(url: str) -> None:
    """Turn a database of this version into what schema version 1 wrote (no posture columns)."""
    _make_version_2(url)
    engine = create_engine(url)
    try:
        with engine.begin() as conn:
            conn.execute(text("ALTER TABLE clips DROP COLUMN start_posture"))
            conn.execute(text("ALTER TABLE clips DROP COLUMN end_posture"))
            conn.execute(text("UPDATE schema_version SET version = 1"))
    finally:
        engine.dispose()


def test_a_version_1_database_is_migrated_in_place(db_url, record):
    sit, fall = _library("sit_down"), _library("fall")

    def seed():
        return [ClipRecord("sitting", sit.motion, ("座る",)), ClipRecord("falling", fall.motion, ("転ぶ",)),
                record("walking", ("歩く",), character="other")]

    MotionDB.open(db_url, seed=seed).close()
    _make_version_1(db_url)
    engine = create_engine(db_url)
    try:
        with engine.connect() as conn:
            from sqlalchemy import inspect

            assert "start_posture" not in {c["name"] for c in inspect(conn).get_columns("clips")}
    finally:
        engine.dispose()
    with MotionDB.open(db_url, seed=seed) as db:  # migrates: adds the columns, classifies every clip
        got = {c.name: (c.start_posture, c.end_posture) for c in db.clips()}
        assert got == {"sitting": ("standing", "seated"), "falling": ("standing", "lying"),
                       "walking": ("standing", "standing")}
        db.add([record("after", ("跳ぶ",), character="other", start_posture="crouched")])
        assert db.info("after").start_posture == "crouched"
    engine = create_engine(db_url)
    try:
        with engine.connect() as conn:
            assert conn.execute(text("SELECT version FROM schema_version")).scalar() == SCHEMA_VERSION == 5
            # the columns were added with their default, for rows written by other tools
            conn.execute(text("SELECT start_posture, end_posture FROM clips")).all()
    finally:
        engine.dispose()
    with MotionDB.open(db_url, seed=seed) as db:  # opening again changes nothing
        assert db.info("sitting").end_posture == "seated" and len(db.clips()) == 4


def test_a_version_1_library_database_gets_the_new_library(tmp_path):
    """An old database seeded with the built-in library: migrated, then the new library replaces the old one."""
    path = tmp_path / "old.sqlite"
    MotionDB.open(path).close()
    _make_version_1(f"sqlite:///{path}")
    engine = create_engine(f"sqlite:///{path}")
    try:
        with engine.begin() as conn:  # as if seeded by the library of that version
            conn.execute(text("UPDATE schema_version SET builtin_library = 'sha256:old'"))
    finally:
        engine.dispose()
    with MotionDB.open(path) as db:
        assert db.info("get_up").start_posture == "lying"
        assert db.info("sit_down").end_posture == "seated"
        assert [c.name for c in db.search("立ち上がる", prefer_start_posture="crouched")][0] == "stand_from_crouch"


def test_a_schema_older_than_any_migration_is_refused(db_url):
    MotionDB.open(db_url, seed=False).close()
    engine = create_engine(db_url)
    try:
        with engine.begin() as conn:
            conn.execute(update(schema_version).values(version=0))
    finally:
        engine.dispose()
    with pytest.raises(SchemaVersionError, match=f"version 0, which this text2anim cannot upgrade to {SCHEMA_VERSION}"):
        MotionDB.open(db_url)
