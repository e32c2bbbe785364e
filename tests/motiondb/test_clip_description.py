"""What the body does (clips.description): measured on the built-in library, on real captures a user
imports, and on the clips of an older database when it is migrated."""
from __future__ import annotations

from sqlalchemy import create_engine, text

from shared_data import cmu, requires_cmu
from text2anim.motiondb import ClipRecord, ImportOptions, MotionDB
from text2anim.motiondb.description import describe
from text2anim.motiondb.schema import SCHEMA_VERSION


def test_the_built_in_clips_are_described_by_what_the_body_does(library_db):
    with MotionDB.open(library_db) as db:
        d = {c.name: c.description for c in db.clips()}
        walk = db.load("walk")
        info = db.info("walk")
    assert d["walk"].locomotion and d["run"].locomotion and "legs" in d["run"].moving
    assert not d["wave_hand"].locomotion and "arms" in d["wave_hand"].moving and "legs" not in d["wave_hand"].moving
    assert d["nod"].moving == ("head",) and not d["nod"].locomotion
    assert "legs" in d["kick"].moving and d["kick"].energy > 3 * d["nod"].energy
    assert d["walk"].actions[0] == "01908923"  # walk.v.01 first, from actions.json
    assert "02057865" in d["walk"].actions  # approach.v.01: who approaches walks (issue 39)
    # what the database was seeded with (shipped) is what storing the clip measures
    fresh = describe(walk, info.core, info.description.actions)
    assert fresh.locomotion == info.description.locomotion and fresh.moving == info.description.moving
    assert abs(fresh.energy - info.description.energy) < 1e-3


@requires_cmu
def test_an_imported_capture_is_measured_as_it_is_stored(empty_db):
    run, wave = empty_db.import_bvh([cmu("02_03_run"), cmu("14_24_wave")],
                                    ImportOptions(("走る",), character="cmu", drop_first=True))
    assert run.description.locomotion and {"arms", "legs"} <= set(run.description.moving)
    assert not wave.description.locomotion and "arms" in wave.description.moving
    assert run.description.actions == ()  # none declared: a stand-in reads them from the verb


def test_an_older_database_gets_its_clips_described_when_migrated(tmp_path, library_db):
    with MotionDB.open(library_db) as lib:
        walk, nod = lib.load("walk"), lib.load("nod")
    url = f"sqlite:///{tmp_path / 'v3.sqlite'}"
    with MotionDB.open(url, seed=False) as db:
        db.add([ClipRecord("a_walk", walk, ("歩く",), cyclic=True), ClipRecord("a_nod", nod, ("頷く",))])
    engine = create_engine(url)
    try:
        with engine.begin() as conn:  # what schema version 3 wrote: no descriptions
            conn.execute(text("ALTER TABLE clips DROP COLUMN style"))  # schema 5
            conn.execute(text("ALTER TABLE clips DROP COLUMN description"))
            conn.execute(text("UPDATE schema_version SET version = 3"))
    finally:
        engine.dispose()
    with MotionDB.open(url, seed=False) as db:  # migrated in place: measured from the stored frames
        assert db.info("a_walk").description.locomotion and db.info("a_nod").description.moving == ("head",)
    engine = create_engine(url)
    try:
        with engine.connect() as conn:
            assert conn.execute(text("SELECT version FROM schema_version")).scalar() == SCHEMA_VERSION
    finally:
        engine.dispose()
