"""Clips of a style (issue 40): ``db import --style`` stores it, an older database migrates to it, and a
text asking for the style plays such a clip before changing a neutral one; a neutral text never does."""
from __future__ import annotations

import json

import pytest
from sqlalchemy import create_engine, text

import text2anim
from text2anim.cli.main import main
from text2anim.motiondb import ClipRecord, MotionDB
from text2anim.motiondb.errors import ClipValidationError
from text2anim.motiondb.schema import SCHEMA_VERSION


def _library_walk(library_db):
    with MotionDB.open(library_db) as lib:
        return lib.load("walk")


def test_import_style_is_stored_shown_and_listed(db_url, capsys, tmp_path, library_db):
    from text2anim.output.bvh_write import write_bvh

    MotionDB.open(db_url, seed=False).close()
    path = tmp_path / "sad_walk.bvh"
    write_bvh(_library_walk(library_db), path)
    assert main(["db", "import", str(path), "--verb", "歩く", "--cyclic", "--scale", "1", "--style", "sad",
                 "--db", db_url]) == 0
    assert "style sad" in capsys.readouterr().out
    assert main(["db", "show", "sad_walk", "--db", db_url]) == 0
    assert "style:      sad" in capsys.readouterr().out
    assert main(["db", "list", "--db", db_url]) == 0
    header = capsys.readouterr().out.splitlines()[0].split()
    assert header[5:7] == ["posture", "style"]
    assert main(["db", "list", "--json", "--db", db_url]) == 0
    assert json.loads(capsys.readouterr().out)[0]["style"] == "sad"
    with pytest.raises(SystemExit) as refused:
        main(["db", "import", str(path), "--verb", "歩く", "--style", "gloomy", "--db", db_url])
    assert refused.value.code == 2


def test_an_unknown_style_is_refused_by_the_api(db_url, library_db):
    with MotionDB.open(db_url, seed=False) as db, pytest.raises(ClipValidationError, match="unknown style"):
        db.add([ClipRecord("w", _library_walk(library_db), ("歩く",), style="gloomy")])


def test_a_version_4_database_gets_the_style_column_with_every_clip_neutral(db_url, library_db):
    with MotionDB.open(db_url, seed=False) as db:
        db.add([ClipRecord("a_walk", _library_walk(library_db), ("歩く",), cyclic=True)])
    engine = create_engine(db_url)
    try:
        with engine.begin() as conn:  # what schema version 4 wrote: no style
            conn.execute(text("ALTER TABLE clips DROP COLUMN style"))
            conn.execute(text("UPDATE schema_version SET version = 4"))
    finally:
        engine.dispose()
    with MotionDB.open(db_url, seed=False) as db:
        assert db.info("a_walk").style is None
        db.add([ClipRecord("b_walk", _library_walk(library_db), ("歩く",), cyclic=True, style="tired")])
        assert db.info("b_walk").style == "tired"
    engine = create_engine(db_url)
    try:
        with engine.connect() as conn:
            assert conn.execute(text("SELECT version FROM schema_version")).scalar() == SCHEMA_VERSION
    finally:
        engine.dispose()


@pytest.fixture(scope="module")
def styled_db(tmp_path_factory, library_db):
    """The built-in library with a walk captured sad (the library's walk, stored as a sad one)."""
    url = f"sqlite:///{tmp_path_factory.mktemp('styled') / 'motions.sqlite'}"
    with MotionDB.open(url) as db:
        db.add([ClipRecord("walk_sad", _library_walk(library_db), ("歩く",), cyclic=True, style="sad")])
    return url


def test_a_clip_of_the_asked_style_plays_as_it_is(styled_db):
    (row,) = text2anim.plan("太郎はしょんぼり歩いた。", styled_db).table.elements
    assert row.clip == "walk_sad" and row.manner is not None and row.manner.by == "clip"
    assert row.speed == 1.0  # no tempo: the clip is the style
    anim = text2anim.animate("太郎はしょんぼり歩いた。", db=styled_db)
    assert anim.report["manners"][0]["by"] == "clip" and "changes" not in anim.report["manners"][0]


def test_a_neutral_text_and_another_style_never_play_the_styled_clip(styled_db):
    (plain,) = text2anim.plan("太郎は歩いた。", styled_db).table.elements
    (tired,) = text2anim.plan("太郎は疲れて歩いた。", styled_db).table.elements
    assert plain.clip != "walk_sad" and plain.manner is None
    assert tired.clip != "walk_sad" and tired.manner is not None and tired.manner.by == "modifiers"
