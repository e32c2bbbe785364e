"""``text2anim db …`` as a user runs it: import, list, show, export, remove, verbs, preview, errors."""
from __future__ import annotations

import json

import numpy as np
import pytest

from text2anim.cli.main import main
from cli_run import assert_clean_error, text2anim
from text2anim.motiondb import MotionDB
from shared_data import cmu, requires_cmu
from text2anim.core import read_bvh
from text2anim.core.floor import place_on_floor


def run(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def cli_db(db_url):
    """A database URL, created empty (so the commands do not seed the built-in library into it)."""
    MotionDB.open(db_url, seed=False).close()
    return db_url


@requires_cmu
def test_import_list_show_export_remove(cli_db, capsys, tmp_path):
    code, out, err = run(capsys, "db", "import", cmu("02_03_run"), cmu("16_35_run"), "--verb", "走る",
                         "--verb", "ダッシュする", "--character", "cmu", "--cyclic", "--drop-first",
                         "--core", "0.1:1.2", "--db", cli_db)
    assert code == 0, err
    assert "imported 2 clips" in out and "02_03_run: 173 frames at 120 fps" in out
    assert "[1/2]" in err and "[2/2]" in err and "02_03_run.bvh" in err  # progress on stderr

    code, out, _ = run(capsys, "db", "--db", cli_db, "list")  # --db before the action works too
    assert code == 0 and out.splitlines()[0].split()[:3] == ["clip", "character", "verbs"]
    assert "02_03_run" in out and "16_35_run" in out and "走る/ダッシュする" in out

    code, out, _ = run(capsys, "db", "list", "--verb", "だっしゅする", "--json", "--db", cli_db)
    listed = json.loads(out)
    assert code == 0 and [c["name"] for c in listed] == ["02_03_run", "16_35_run"]
    assert listed[0]["core"] == [0.1, 1.2] and listed[0]["cyclic"] is True and listed[0]["contacts"]["left"]

    code, out, _ = run(capsys, "db", "show", "02_03_run", "--db", cli_db)
    assert code == 0
    assert "走る (synonyms: ダッシュする)" in out and "0.100 .. 1.200 s" in out and "31 joints" in out
    assert "contacts:   left 59-79, 151-171" in out

    code, out, _ = run(capsys, "db", "verbs", "--db", cli_db)
    assert code == 0 and "ハシル" in out and "ダッシュスル" in out

    target = tmp_path / "out.bvh"
    code, out, _ = run(capsys, "db", "export", "02_03_run", "-o", target, "--db", cli_db)
    assert code == 0 and target.is_file()
    exported = read_bvh(target, scale=1)
    original, _ = place_on_floor(read_bvh(cmu("02_03_run"), drop_first=True))  # import puts clips on the floor
    assert exported.n_frames == original.n_frames
    assert np.allclose(exported.positions, original.positions, atol=1e-4)

    code, out, _ = run(capsys, "db", "remove", "02_03_run", "--db", cli_db)
    assert code == 0 and "removed 02_03_run" in out
    code, out, _ = run(capsys, "db", "list", "--json", "--db", cli_db)
    assert [c["name"] for c in json.loads(out)] == ["16_35_run"]


@requires_cmu
def test_import_of_a_bad_batch_fails_cleanly_and_changes_nothing(cli_db, capsys, tmp_path):
    bad = tmp_path / "broken.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n")
    code, out, err = run(capsys, "db", "import", cmu("02_03_run"), bad, "--verb", "走る", "--db", cli_db)
    assert code == 2 and "Traceback" not in err
    last = err.splitlines()[-1]  # after the progress lines
    assert last.startswith("text2anim: error: ") and str(bad) in last and "nothing was imported" in last
    code, out, _ = run(capsys, "db", "list", "--json", "--db", cli_db)
    assert json.loads(out) == []


def test_user_errors_are_one_line_with_exit_2(cli_db, capsys, record):
    with MotionDB.open(cli_db) as db:
        db.add([record("fall", ("転ぶ",)), record("walk", ("歩く",))])
    code, _, err = run(capsys, "db", "list", "--verb", "ころがる", "--db", cli_db)
    assert code == 2 and err.count("\n") == 1 and "nearest verbs: 転ぶ (コロブ)" in err
    code, _, err = run(capsys, "db", "show", "wakl", "--db", cli_db)
    assert code == 2 and "no clip named 'wakl'" in err and "nearest: walk" in err
    code, _, err = run(capsys, "db", "remove", "nope", "--db", cli_db)
    assert code == 2 and "no clip named 'nope'" in err
    code, _, err = run(capsys, "db", "import", "a.bvh", "b.bvh", "--verb", "歩く", "--name", "x", "--db", cli_db)
    assert code == 2 and "--name needs exactly one file" in err


def test_preview_draws_a_contact_sheet(cli_db, capsys, record, tmp_path):
    with MotionDB.open(cli_db) as db:
        db.add([record("walk", ("歩く",))])
    sheet = tmp_path / "sheet.png"
    code, out, err = run(capsys, "db", "preview", "walk", "-o", sheet, "--db", cli_db)
    assert code == 0, err
    assert sheet.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_preview_draws_an_animation_file_without_a_database(capsys, tmp_path, monkeypatch):
    monkeypatch.setenv("TEXT2ANIM_DB", str(tmp_path / "never.sqlite"))
    from text2anim.motiondb.library import builtin_clips
    from text2anim.output.bvh_write import write_bvh

    walk = next(c for c in builtin_clips() if c.name == "walk")
    path = tmp_path / "walk out.bvh"
    write_bvh(walk.motion, path)
    sheet = tmp_path / "sheet.png"
    code, out, err = run(capsys, "db", "preview", path, "-o", sheet, "--frames", "12")
    assert code == 0, err
    assert sheet.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and "wrote" in out
    assert not (tmp_path / "never.sqlite").exists()  # a file is drawn without opening (or seeding) a database
    code, _, err = run(capsys, "db", "preview", tmp_path / "missing.bvh", "-o", sheet)
    assert code == 2 and err.count("\n") == 1 and "missing.bvh" in err


@pytest.mark.parametrize("url, fragment", [
    ("sqlite:////no/such/folder/motions.sqlite", "the folder /no/such/folder does not exist"),
    ("nosuchdb://localhost/x", "unknown kind of database 'nosuchdb'"),
    ("postgresql+psycopg2://someone:pw@127.0.0.1:1/motions", "cannot connect to the database"),
])
def test_a_broken_database_url_through_the_real_command(url, fragment):
    if url.startswith("postgresql"):
        pytest.importorskip("psycopg2")
    proc = text2anim("db", "list", "--db", url)
    assert_clean_error(proc, fragment)
    assert proc.stderr.count("\n") == 1 and "pw" not in proc.stderr


def test_the_environment_variable_selects_the_database(tmp_path, record):
    path = tmp_path / "env.sqlite"
    with MotionDB.open(path, seed=False) as db:
        db.add([record("walk", ("歩く",))])
    import os

    env = dict(os.environ, TEXT2ANIM_DB=str(path))
    proc = text2anim("db", "list", "--json", env=env)
    assert proc.returncode == 0, proc.stderr
    assert [c["name"] for c in json.loads(proc.stdout)] == ["walk"]


def test_import_classifies_postures_and_takes_overrides(cli_db, capsys, tmp_path):
    from text2anim.motiondb.library import build_all
    from text2anim.output.bvh_write import write_bvh

    sit = next(b.record.motion for b in build_all(30.0) if b.record.name == "sit_down")
    path = tmp_path / "my_sit.bvh"
    write_bvh(sit, path)
    code, out, err = run(capsys, "db", "import", path, "--verb", "座る", "--scale", "1", "--db", cli_db)
    assert code == 0, err
    assert "posture standing→seated" in out
    code, out, err = run(capsys, "db", "import", path, "--verb", "座る", "--name", "told", "--scale", "1",
                         "--start-posture", "crouched", "--end-posture", "lying", "--db", cli_db)
    assert code == 0, err
    assert "told: " in out and "posture crouched→lying" in out
    code, out, _ = run(capsys, "db", "show", "my_sit", "--db", cli_db)
    assert "postures:   starts standing, ends seated" in out
    code, out, _ = run(capsys, "db", "list", "--db", cli_db)
    assert out.splitlines()[0].split()[:6] == ["clip", "character", "verbs", "objects", "part", "posture"]
    assert "crouched→lying" in out and "standing→seated" in out
    code, out, _ = run(capsys, "db", "list", "--verb", "座る", "--start-posture", "crouched", "--json", "--db", cli_db)
    listed = json.loads(out)
    assert [c["name"] for c in listed] == ["told", "my_sit"]
    assert listed[0]["start_posture"] == "crouched" and listed[1]["end_posture"] == "seated"
    from text2anim.cli.cmd_db import _POSTURES
    from text2anim.motiondb.types import POSTURES

    assert _POSTURES == POSTURES  # the parser's copy of the vocabulary
    with pytest.raises(SystemExit) as exc:
        main(["db", "import", str(path), "--verb", "座る", "--start-posture", "sitting", "--db", cli_db])
    assert exc.value.code == 2
    assert "invalid choice: 'sitting'" in capsys.readouterr().err
