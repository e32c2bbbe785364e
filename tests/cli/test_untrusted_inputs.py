"""Files and names a user hands us, as an attacker or a careless user would (issue 28).

Every reader goes through ``core.inputs.read_input``: a FIFO, ``/dev/zero``, a folder or a
symlink loop is one clear line and exit 2 at once (no hang, no traceback), and a file over its
kind's limit is refused before it is read. Names with control characters are refused at import;
whatever a database already holds is printed escaped.
"""
from __future__ import annotations

import json
import os
import sqlite3
from pathlib import Path

import pytest

from cli_run import assert_clean_error, text2anim
from text2anim.core.inputs import LIMITS
from text2anim.motiondb import MotionDB

TINY = Path(__file__).resolve().parents[1] / "data" / "walk_tiny.bvh"


@pytest.fixture
def specials(tmp_path):
    """A FIFO with no writer, ``/dev/zero`` (behind a link with the kind's suffix), a loop of two symlinks and a folder, each named like the kind asked."""
    def make(suffix: str) -> dict[str, Path]:
        fifo = tmp_path / f"fifo{suffix}"
        os.mkfifo(fifo)
        a, b = tmp_path / f"loop_a{suffix}", tmp_path / f"loop_b{suffix}"
        a.symlink_to(b)
        b.symlink_to(a)
        folder = tmp_path / f"folder{suffix}"
        folder.mkdir()
        zero = tmp_path / f"zero{suffix}"
        zero.symlink_to("/dev/zero")
        return {"fifo": fifo, "zero": zero, "loop": a, "folder": folder}
    return make


WHY = {"fifo": "not a regular file", "zero": "not a regular file", "loop": "a loop of symbolic links",
       "folder": "is a folder"}


@pytest.mark.parametrize("kind", sorted(WHY))
@pytest.mark.parametrize("command", ["info", "metrics", "convert", "db import", "db preview"])
def test_a_special_file_given_as_a_bvh_is_one_line(tmp_path, specials, command, kind):
    path = specials(".bvh")[kind]
    args = {"info": ["info", path], "metrics": ["metrics", path], "convert": ["convert", path, "-o", tmp_path / "o.bvh"],
            "db import": ["db", "--db", tmp_path / "m.sqlite", "import", path, "--verb", "歩く"],
            "db preview": ["db", "preview", path, "-o", tmp_path / "p.png"]}[command]
    proc = text2anim(*args)
    assert_clean_error(proc, f"{path}: {WHY[kind]}" if kind != "loop" else WHY[kind])
    assert not (tmp_path / "o.bvh").exists() and not (tmp_path / "p.png").exists()


@pytest.mark.parametrize("kind", ["fifo", "loop"])
def test_a_special_file_given_as_a_rig_joint_map_corpus_or_project_is_one_line(tmp_path, specials, kind):
    rig = specials(".glb")[kind]
    assert_clean_error(text2anim("太郎は歩く。", "--rig", rig, "-o", tmp_path / "x.bvh"), str(rig), WHY[kind])
    joint_map = specials(".json")[kind]
    assert_clean_error(text2anim("太郎は歩く。", "--rig", TINY, "--map", joint_map, "-o", tmp_path / "x.bvh"),
                       str(joint_map), WHY[kind])
    corpus = specials(".txt")[kind]
    assert_clean_error(text2anim("batch", corpus, "--check"), str(corpus), WHY[kind])
    project = specials(".t2a.json")[kind]  # a studio project (text2anim FILE.t2a.json): a FIFO hung the command
    assert_clean_error(text2anim(project, "-o", tmp_path / "x.bvh"), str(project), WHY[kind])
    assert not (tmp_path / "x.bvh").exists()


def test_a_bvh_over_the_limit_is_refused_before_it_is_read(tmp_path):
    big = tmp_path / "big.bvh"
    big.write_bytes(TINY.read_bytes())
    os.truncate(big, LIMITS["BVH"] + 1)  # sparse: the size is real, the disk barely used
    assert_clean_error(text2anim("info", big), f"{big}: {LIMITS['BVH'] + 1} bytes", "at most 64 MB")


def test_a_joint_map_over_the_limit_is_refused(tmp_path):
    joint_map = tmp_path / "map.json"
    joint_map.write_text('{"hips": "Hips"' + " " * LIMITS["joint map"] + "}")
    proc = text2anim("db", "--db", tmp_path / "m.sqlite", "import", TINY, "--verb", "歩く", "--map", joint_map)
    assert_clean_error(proc, str(joint_map), "at most 1 MB")


CONTROLS = {"ESC": "\x1b]0;pwned\x07", "NUL": "a\x00b", "DEL": "a\x7f", "C1": "a\x9b2J", "RLO": "a\u202eb"}


@pytest.mark.parametrize("what", sorted(CONTROLS))
@pytest.mark.parametrize("option", ["--verb", "--object", "--name", "--character"])
def test_a_name_with_a_control_character_is_refused_at_import(tmp_path, option, what):
    db = tmp_path / "m.sqlite"
    MotionDB.open(db, seed=False).close()
    bad = CONTROLS[what]
    args = ["db", "--db", db, "import", TINY, *(["--verb", "歩く"] if option != "--verb" else []), option, bad]
    if what == "NUL":  # a command line cannot carry NUL: the API is the way in
        from text2anim.motiondb import ImportOptions
        from text2anim.motiondb.errors import ClipValidationError
        field = {"--verb": "verbs", "--object": "objects", "--name": "names", "--character": "character"}[option]
        kwargs = {"verbs": ("歩く",), field: bad if field == "character" else (bad,)}
        with MotionDB.open(db, seed=False) as opened, pytest.raises(ClipValidationError, match="control character"):
            opened.import_bvh([TINY], ImportOptions(**kwargs))
        return
    proc = text2anim(*args)
    assert_clean_error(proc, "control character", f"U+{ord(next(c for c in bad if c != 'a')):04X}")
    assert not _raw_controls(proc.stderr)
    with MotionDB.open(db, seed=False) as opened:
        assert opened.clips() == []


def _raw_controls(text: str) -> list[str]:
    return [c for c in text if (ord(c) < 32 and c not in "\n\t") or 0x7f <= ord(c) <= 0x9f or c == "\u202e"]


def test_names_already_in_a_database_are_printed_escaped(tmp_path):
    """A database filled before names were checked (or by another program) cannot drive the terminal."""
    db = tmp_path / "m.sqlite"
    MotionDB.open(db, seed=False).close()
    assert text2anim("db", "--db", db, "import", TINY, "--verb", "歩く", "--object", "箱").returncode == 0
    with sqlite3.connect(db) as con:
        con.execute("UPDATE verbs SET lemma = ?", ("\x1b]0;pwned\x07\x1b[2J",))
        con.execute("UPDATE clips SET name = ?", ("walk\x9b2J\u202e",))
    for args in (["verbs"], ["list"], ["verbs", "--json"], ["list", "--json"], ["show", "walk\x9b2J\u202e"]):
        proc = text2anim("db", "--db", db, *args)
        assert proc.returncode == 0, proc.stderr
        assert not _raw_controls(proc.stdout), (args, proc.stdout)
        assert "\\x1b]0;pwned\\x07" in proc.stdout or "\\u001b]0;pwned\\u0007" in proc.stdout
        if "--json" in args:
            json.loads(proc.stdout)  # escaped the JSON way, still JSON
    proc = text2anim("db", "--db", db, "show", "nothing\x1b[2J")
    assert_clean_error(proc, "nothing\\x1b[2J")
    assert not _raw_controls(proc.stderr)

    with sqlite3.connect(db) as con:  # the verb findable again: the poisoned clip name reaches plan and animate
        con.execute("UPDATE verbs SET lemma = ?", ("歩く",))
    for args in (["plan", "歩く。"], ["plan", "歩く。", "--json"], ["歩く。", "-o", tmp_path / "a.bvh"]):
        proc = text2anim(*args, "--db", db)
        assert proc.returncode == 0, (args, proc.stderr)
        assert not _raw_controls(proc.stdout + proc.stderr), (args, proc.stdout, proc.stderr)
        assert "walk\\x9b2J\\u202e" in proc.stdout or "walk\\u009b2J\\u202e" in proc.stdout, (args, proc.stdout)


def test_info_prints_a_joint_name_with_escape_codes_escaped(tmp_path):
    crafted = tmp_path / "crafted.bvh"
    crafted.write_text(TINY.read_text().replace("JOINT LHipJoint", "JOINT LHip\x1b]0;pwned\x07\x9b2J\u202e", 1))
    proc = text2anim("info", crafted)
    assert proc.returncode == 0, proc.stderr
    assert not _raw_controls(proc.stdout)
    assert "LHip\\x1b]0;pwned\\x07\\x9b2J\\u202e" in proc.stdout


def test_a_replaced_output_keeps_its_mode_and_a_link_is_written_through(tmp_path):
    private = tmp_path / "private.bvh"
    private.write_text("old")
    private.chmod(0o600)
    assert text2anim("convert", TINY, "-o", private).returncode == 0
    assert private.read_text().startswith("HIERARCHY") and (private.stat().st_mode & 0o777) == 0o600

    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "walk.bvh"
    target.write_text("old")
    link = tmp_path / "link.bvh"
    link.symlink_to(target)
    proc = text2anim("convert", TINY, "-o", link)
    assert proc.returncode == 0, proc.stderr
    assert link.is_symlink() and target.read_text().startswith("HIERARCHY")
    assert not [p for p in tmp_path.rglob(".*.part")]


def test_standard_input_over_the_limit_is_refused_not_cut(tmp_path):
    from text2anim.limits import MAX_TEXT_CHARS

    long_text = "太郎は歩く。" * (MAX_TEXT_CHARS * 4 // 6) + "花子は走る。"
    proc = text2anim("parse", "-", input=long_text)
    assert_clean_error(proc, "standard input holds more than", f"at most {MAX_TEXT_CHARS}")
