"""Outputs (issue 9): only regular files are written, ``-o -``, one path per output, all-or-nothing
without deleting what existed, fsync, one-line errors for bad names; and the CLI's hygiene
(``--version``, a mistyped option named, broken pipes)."""
from __future__ import annotations

import os
import resource
import stat
import subprocess
import sys

import pytest

import text2anim
from cli_run import REPO, assert_clean_error, text2anim as run
from text2anim.core import parse_bvh
from text2anim.core.atomic import OutputError, atomic_write_bytes, write_all

WALK = "太郎は歩く。"
TWO = "太郎が歩くと同時に花子が走る。"


@pytest.fixture(scope="module")
def two_actors(library_db):
    return text2anim.animate(TWO, db=library_db)


# ------------------------------------------------------------------ only regular files
def test_a_fifo_or_a_link_to_one_is_never_replaced(tmp_path, library_db):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    (tmp_path / "out").symlink_to(fifo)  # what /dev/stdout is: a link to a device or pipe
    for target in ("pipe", "out"):
        proc = run(WALK, "-o", target, "--db", library_db, cwd=tmp_path)
        assert_clean_error(proc, "not a regular file")
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and (tmp_path / "out").is_symlink()
    with pytest.raises(OutputError, match="not a regular file"):
        atomic_write_bytes(fifo, b"x")
    with pytest.raises(OutputError, match="is a directory"):
        atomic_write_bytes(tmp_path, b"x")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "pipe"]


def test_dash_writes_the_bvh_to_standard_output(tmp_path, library_db):
    proc = run(WALK, "-o", "-", "--report", "r.json", "--db", library_db, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    m = parse_bvh(proc.stdout)  # standard output is the BVH and nothing else
    assert m.n_frames > 30 and m.fps == pytest.approx(30)
    assert "wrote standard output, r.json" in proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.json"]
    want = text2anim.animate(WALK, db=library_db)
    want.save_bvh(tmp_path / "a.bvh")
    assert (tmp_path / "a.bvh").read_text() == proc.stdout


@pytest.mark.parametrize("args", [("-o", "a.bvh", "--html", "a.bvh"), ("-o", "a.bvh", "--glb", "sub/../a.bvh")])
def test_two_outputs_on_one_path_are_refused_before_any_work(tmp_path, args):
    (tmp_path / "sub").mkdir()
    proc = run(WALK, *args, "--db", tmp_path / "never-opened.sqlite", cwd=tmp_path)
    assert_clean_error(proc, "two outputs on one file")
    assert [p.name for p in tmp_path.iterdir()] == ["sub"]  # not even the database was created


def test_the_api_refuses_two_outputs_on_one_path(tmp_path, two_actors):
    with pytest.raises(OutputError, match="two outputs on one file"):
        two_actors.save(bvh=tmp_path / "x.bvh", html=tmp_path / "x_花子.bvh")
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------------- all-or-nothing
def test_a_folder_in_the_way_of_the_second_actor_keeps_the_first_actors_file(tmp_path, library_db):
    (tmp_path / "x_太郎.bvh").write_text("mine\n")
    (tmp_path / "x_花子.bvh").mkdir()
    proc = run(TWO, "-o", "x.bvh", "--db", library_db, cwd=tmp_path)
    assert_clean_error(proc, "x_花子.bvh: is a directory")
    assert (tmp_path / "x_太郎.bvh").read_text() == "mine\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x_太郎.bvh", "x_花子.bvh"]


def _file_size_limit(limit: int):
    def apply():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return apply


def test_a_failure_while_writing_leaves_every_file_as_it_was(tmp_path, library_db):
    """The GLB (~150 kB) cannot be written under a 100 kB file-size limit; the BVHs (~70 kB) could."""
    (tmp_path / "x_太郎.bvh").write_text("mine\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(REPO), os.environ.get("PYTHONPATH")]))}
    proc = subprocess.run([sys.executable, "-m", "text2anim.cli.main", TWO, "-o", "x.bvh", "--glb", "x.glb",
                           "--db", str(library_db)], capture_output=True, text=True, cwd=tmp_path, env=env,
                          preexec_fn=_file_size_limit(100_000), timeout=300)
    assert_clean_error(proc, "x.glb", "too large")
    assert (tmp_path / "x_太郎.bvh").read_text() == "mine\n"  # the old file, not deleted, not replaced
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x_太郎.bvh"]  # no temporaries, no half set


def test_html_into_a_missing_folder_writes_nothing(tmp_path, library_db):
    proc = run(WALK, "-o", "a.bvh", "--html", "nowhere/a.html", "--db", library_db, cwd=tmp_path)
    assert_clean_error(proc, "the folder nowhere does not exist")
    assert list(tmp_path.iterdir()) == []


def test_write_all_renames_only_after_every_temporary_is_written(tmp_path):
    (tmp_path / "a").write_bytes(b"old a")

    def fails(path):
        path.write_bytes(b"half")
        raise OSError(28, "No space left on device")

    with pytest.raises(OutputError, match="No space left"):
        write_all({tmp_path / "a": b"new a", tmp_path / "b": fails})
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a"]
    assert (tmp_path / "a").read_bytes() == b"old a"
    assert write_all({tmp_path / "a": b"new a", tmp_path / "b": b"b"}) == [tmp_path / "a", tmp_path / "b"]
    assert (tmp_path / "a").read_bytes() == b"new a"


def test_files_and_their_folder_are_fsynced(tmp_path, monkeypatch):
    synced = []
    real_fsync = os.fsync

    def recording_fsync(fd):
        synced.append(stat.S_IFMT(os.fstat(fd).st_mode))
        real_fsync(fd)

    monkeypatch.setattr(os, "fsync", recording_fsync)
    write_all({tmp_path / "a": b"1", tmp_path / "b": b"2"})
    assert synced.count(stat.S_IFREG) == 2 and synced.count(stat.S_IFDIR) == 1


# ------------------------------------------------------------------------- bad names
@pytest.mark.parametrize("name, fragment", [("", "empty output file name"),
                                            ("x" * 300 + ".bvh", "file name too long (304 bytes"),
                                            ("a/", "names a folder")])
def test_bad_names_are_one_line_errors(tmp_path, name, fragment):
    proc = run(WALK, "-o", name, "--db", tmp_path / "never-opened.sqlite", cwd=tmp_path)
    assert_clean_error(proc, fragment)
    assert len(proc.stderr.strip().splitlines()) == 1 and len(proc.stderr) < 200
    assert list(tmp_path.iterdir()) == []


# ------------------------------------------------------------------------ CLI hygiene
def test_version():
    proc = run("--version")
    assert proc.returncode == 0 and proc.stdout.strip() == f"text2anim {text2anim.__version__}"


@pytest.mark.parametrize("args, suggestion", [((WALK, "--fsp", "60"), "did you mean --fps?"),
                                              (("info", "x.bvh", "--drop-frist"), "did you mean --drop-first?")])
def test_a_mistyped_option_names_the_closest(args, suggestion):
    proc = run(*args)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert "unrecognized arguments" in proc.stderr and suggestion in proc.stderr, proc.stderr


def test_a_broken_pipe_ends_quietly(tmp_path):
    bvh = tmp_path / "big.bvh"
    from text2anim.output.bvh_write import format_bvh

    bvh.write_text(format_bvh(_long_motion()))
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    proc = subprocess.Popen([sys.executable, "-m", "text2anim.cli.main", "info", str(bvh)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, cwd=REPO, env=env)
    proc.stdout.close()  # the reader is gone before the first line (`| head -0`)
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 141
    assert err == ""


def _long_motion():
    from conftest import make_motion

    return make_motion(frames=60)


def test_convert_writes_to_standard_output_and_refuses_a_fifo(tmp_path):
    from conftest import make_motion
    from text2anim.output.bvh_write import format_bvh

    src = tmp_path / "in.bvh"
    src.write_text(format_bvh(make_motion(frames=10)))
    proc = run("convert", src, "-o", "-")
    assert proc.returncode == 0, proc.stderr
    assert parse_bvh(proc.stdout).n_frames == 10
    os.mkfifo(tmp_path / "p")
    assert_clean_error(run("convert", src, "-o", tmp_path / "p"), "not a regular file")
    assert stat.S_ISFIFO(os.lstat(tmp_path / "p").st_mode)
