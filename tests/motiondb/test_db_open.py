"""Where the database lives, first-use creation and seeding (also by two processes at once), bad URLs."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from sqlalchemy import create_engine, text

from text2anim.motiondb import ClipRecord, DBError, MotionDB
from text2anim.motiondb.errors import SeedWarning
from text2anim.motiondb.location import resolve_url
from conftest import make_motion

REPO = Path(__file__).resolve().parents[2]


def _records(n=3, verb="歩く"):
    return [ClipRecord(f"seed{k}", make_motion(seed=k), (verb,)) for k in range(n)]


def _builtin_clips():
    try:
        from text2anim.motiondb.library import builtin_clips
    except ImportError:
        pytest.skip("motiondb.library.builtin_clips is not there yet")
    return builtin_clips


# ------------------------------------------------------------------ location
def test_url_resolution_follows_argument_then_env_then_xdg(monkeypatch, tmp_path):
    monkeypatch.delenv("TEXT2ANIM_DB", raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "xdg"))
    assert resolve_url(None) == (f"sqlite:///{tmp_path}/xdg/text2anim/motions.sqlite", True)
    monkeypatch.setenv("XDG_DATA_HOME", "relative/ignored")  # the XDG spec: relative paths are invalid
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert resolve_url(None)[0] == f"sqlite:///{tmp_path}/home/.local/share/text2anim/motions.sqlite"
    monkeypatch.setenv("TEXT2ANIM_DB", str(tmp_path / "env.sqlite"))
    assert resolve_url(None) == (f"sqlite:///{tmp_path}/env.sqlite", False)
    monkeypatch.setenv("TEXT2ANIM_DB", "postgresql+psycopg2://u@h/db")
    assert resolve_url(None) == ("postgresql+psycopg2://u@h/db", False)
    assert resolve_url(tmp_path / "arg.sqlite") == (f"sqlite:///{tmp_path}/arg.sqlite", False)
    assert resolve_url("sqlite:///x.sqlite") == ("sqlite:///x.sqlite", False)


def test_the_default_database_is_created_in_the_xdg_data_folder(monkeypatch, tmp_path):
    monkeypatch.delenv("TEXT2ANIM_DB", raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    with MotionDB.open(seed=_records) as db:
        assert [c.name for c in db.clips()] == ["seed0", "seed1", "seed2"]
    assert (tmp_path / "data" / "text2anim" / "motions.sqlite").is_file()


# ------------------------------------------------------------------- seeding
def test_seeding_happens_once_when_the_database_is_created(db_url):
    calls = []

    def seed():
        calls.append(1)
        return _records()

    with MotionDB.open(db_url, seed=seed) as db:
        assert len(db.clips()) == 3
        db.remove("seed1")
    with MotionDB.open(db_url, seed=seed) as db:  # already seeded: a removed clip stays removed
        assert [c.name for c in db.clips()] == ["seed0", "seed2"]
    assert len(calls) == 1


def test_a_database_created_empty_stays_empty(db_url):
    MotionDB.open(db_url, seed=False).close()
    with MotionDB.open(db_url, seed=_records) as db:
        assert db.clips() == []


def test_late_seeding_keeps_the_users_clips(db_url):
    """A database created before the built-in library existed is seeded later; user clips win."""
    with MotionDB.open(db_url, seed=False) as db:
        mine = ClipRecord("seed1", make_motion(seed=99), ("走る",))
        db.add([mine])
    engine = create_engine(db_url)
    try:
        with engine.begin() as conn:  # as if the library had been missing at creation
            conn.execute(text("UPDATE schema_version SET builtin_library = NULL"))
    finally:
        engine.dispose()
    with pytest.warns(SeedWarning, match="1 built-in clip.*seed1"):
        db = MotionDB.open(db_url, seed=_records)
    with db:
        assert [c.name for c in db.clips()] == ["seed0", "seed1", "seed2"]
        assert db.info("seed1").verbs == ("走る",)


def test_a_failed_seeding_leaves_no_half_database(db_url):
    def broken():
        return _records() + [ClipRecord("bad", make_motion(), ("歩く",), core=(3.0, 1.0))]

    with pytest.raises(DBError):
        MotionDB.open(db_url, seed=broken)
    engine = create_engine(db_url)
    try:
        with engine.connect() as conn:
            from sqlalchemy import inspect

            assert not inspect(conn).has_table("clips")  # the creation was rolled back with the seeding
    finally:
        engine.dispose()


def test_the_library_tag_follows_every_change_of_its_files_with_the_cache_or_without(tmp_path, monkeypatch):
    """The built-in library's tag (what a database was seeded with) is kept in the cache folder by its files'
    sizes and times: a file edited, added or removed gives the new content's tag, and a cache that is
    garbage or cannot be written still gives the right one."""
    import os

    from text2anim.motiondb.seed import files_tag, library_tag

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    lib = tmp_path / "library"
    (lib / "sub").mkdir(parents=True)
    (lib / "clips.json").write_text('{"walk": 1}')
    (lib / "sub" / "keyframed.npz").write_bytes(b"\0" * 1000)
    first = library_tag(lib)
    assert first == files_tag(lib) and library_tag(lib) == first
    (lib / "clips.json").write_text('{"walk": 2}')  # same size: its time tells
    os.utime(lib / "clips.json", ns=(1, 1))
    assert library_tag(lib) == files_tag(lib) != first
    (lib / "run.json").write_text("{}")
    assert library_tag(lib) == files_tag(lib)
    (lib / "run.json").unlink()
    assert library_tag(lib) == files_tag(lib)
    for kept in (tmp_path / "cache" / "text2anim").iterdir():
        kept.write_text("garbage")
    assert library_tag(lib) == files_tag(lib)
    monkeypatch.setenv("XDG_CACHE_HOME", str(lib / "clips.json"))  # a file where the folder would be
    assert library_tag(lib) == files_tag(lib)


def test_first_open_seeds_the_builtin_library(tmp_path):
    builtin_clips = _builtin_clips()
    expected = sorted(r.name for r in builtin_clips())
    with MotionDB.open(tmp_path / "builtin.sqlite") as db:
        assert sorted(c.name for c in db.clips()) == expected
        for info in db.clips():
            assert [c.name for c in db.search(info.verb)].count(info.name) == 1


def test_a_changed_builtin_library_replaces_the_old_builtin_clips(db_url):
    builtin_clips = _builtin_clips()
    MotionDB.open(db_url).close()  # seeded with the current library
    engine = create_engine(db_url)
    try:
        with engine.begin() as conn:
            current = conn.execute(text("SELECT builtin_library FROM schema_version")).scalar()
            conn.execute(text("UPDATE schema_version SET builtin_library = 'an older library'"))
    finally:
        engine.dispose()
    with MotionDB.open(db_url, seed=False) as db:
        built = builtin_clips()
        old_motion = built[0].motion if built else make_motion(seed=1)  # on the default character's skeleton
        db.add([ClipRecord("retired", old_motion, ("消える",), source="builtin:retired.json"),
                ClipRecord("mine", make_motion(seed=2), ("歩く",), character="me", source="/home/me/walk.bvh")])
    with MotionDB.open(db_url) as db:  # the library differs from what was seeded: refreshed
        names = sorted(c.name for c in db.clips())
    assert names == sorted([r.name for r in builtin_clips()] + ["mine"])
    engine = create_engine(db_url)
    try:
        with engine.connect() as conn:
            assert conn.execute(text("SELECT builtin_library FROM schema_version")).scalar() == current
    finally:
        engine.dispose()


_RACE = r"""
import json, sys, time
sys.path[:0] = [sys.argv[4], sys.argv[5]]
from text2anim.motiondb import ClipRecord, MotionDB
from conftest import make_motion

import os, pathlib
url, barrier, mode = sys.argv[1], pathlib.Path(sys.argv[2]), sys.argv[3]
calls = []

def seed():
    calls.append(1)
    time.sleep(0.5)  # a slow library: the other process must wait, not seed a second copy
    return [ClipRecord(f"clip{k}", make_motion(seed=k), ("歩く",)) for k in range(5)]

(barrier / f"ready{os.getpid()}").touch()  # start together: wait until both are ready
deadline = time.time() + 60
while len(list(barrier.iterdir())) < 2 and time.time() < deadline:
    time.sleep(0.001)
db = MotionDB.open(url, seed=seed if mode == "custom" else True)
print(json.dumps({"clips": [c.name for c in db.clips()], "seeded": len(calls)}))
"""


@pytest.mark.parametrize("mode", ["custom", "builtin"])
def test_two_processes_creating_the_database_at_once_seed_it_once(db_url, tmp_path, mode):
    expected = [f"clip{k}" for k in range(5)]
    if mode == "builtin":
        expected = sorted(r.name for r in _builtin_clips()())
    script = tmp_path / "race.py"
    script.write_text(_RACE)
    barrier = tmp_path / "barrier"
    barrier.mkdir()
    procs = [subprocess.Popen([sys.executable, str(script), db_url, str(barrier), mode, str(REPO),
                               str(REPO / "tests")], cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True) for _ in range(2)]
    results = []
    for p in procs:
        out, err = p.communicate(timeout=240)
        assert p.returncode == 0, err
        results.append(json.loads(out.strip().splitlines()[-1]))
    for r in results:
        assert sorted(r["clips"]) == expected
    if mode == "custom":
        assert sorted(r["seeded"] for r in results) == [0, 1]
    with MotionDB.open(db_url, seed=False) as db:  # look only: no built-in library over the custom one
        assert sorted(c.name for c in db.clips()) == expected


# --------------------------------------------------------------- broken URLs
@pytest.mark.parametrize("url, message", [
    ("sqlite:////no/such/folder/m.sqlite", "the folder /no/such/folder does not exist"),
    ("nosuchdb://user@host/x", "unknown kind of database 'nosuchdb'"),
    ("sqlite+nodriver:///x.sqlite", "unknown kind of database"),
])
def test_a_broken_url_is_one_clear_error(url, message):
    with pytest.raises(DBError, match=message) as err:
        MotionDB.open(url)
    assert err.value.user_facing and "\n" not in str(err.value)


def test_a_file_that_is_not_a_database(tmp_path):
    bogus = tmp_path / "notes.sqlite"
    bogus.write_text("these are not the motions you are looking for\n" * 100)
    with pytest.raises(DBError, match="is not an SQLite database"):
        MotionDB.open(bogus)
    with pytest.raises(DBError, match="it is a folder"):
        MotionDB.open(tmp_path)


def test_an_unreachable_server_is_one_clear_error():
    pytest.importorskip("psycopg2")
    with pytest.raises(DBError, match=r"cannot connect to the database postgresql\+psycopg2://u:\*\*\*@127.0.0.1:1/x"
                                      r": .*refused") as err:
        MotionDB.open("postgresql+psycopg2://u:secret@127.0.0.1:1/x")
    assert "secret" not in str(err.value)
    # a bare postgresql:// URL uses psycopg2 when psycopg (3), SQLAlchemy 2.1's default, is absent
    with pytest.raises(DBError, match=r"cannot connect to the database postgresql(\+psycopg2)?://u@127.0.0.1:1/x"):
        MotionDB.open("postgresql://u@127.0.0.1:1/x")
