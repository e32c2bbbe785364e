"""Two ``text2anim batch`` runs on one ``--out`` (issue 28): one owns the folder, every line once.

Real processes: the owner is another process holding ``DIR/.lock`` (the test itself, or a
second ``text2anim batch``); the kernel's ``flock`` is what they contend for.
"""
from __future__ import annotations

import fcntl
import os
import subprocess
import sys
import time

from cli_run import REPO, assert_clean_error, text2anim
from text2anim.cli.batch import manifest

TEXTS = ["太郎は歩く。", "花子は座る。", "太郎は走る。", "これは本です。"]


def _corpus(tmp_path):
    path = tmp_path / "c.txt"
    path.write_text("\n".join(TEXTS) + "\n", encoding="utf-8")
    return path


def _start(*args):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(REPO), os.environ.get("PYTHONPATH")]))}
    return subprocess.Popen([sys.executable, "-m", "text2anim.cli.main", *map(str, args)], cwd=REPO, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _hold(out):
    out.mkdir(exist_ok=True)
    fd = os.open(out / ".lock", os.O_RDWR | os.O_CREAT)
    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    return fd


def test_a_second_run_on_an_owned_folder_says_so_and_does_nothing(tmp_path, library_db):
    out = tmp_path / "out"
    fd = _hold(out)
    try:
        proc = text2anim("batch", _corpus(tmp_path), "--out", out, "--db", library_db)
    finally:
        os.close(fd)
    assert_clean_error(proc, f"{out}: another batch run owns this folder", "--wait")
    assert not (out / "manifest.jsonl").exists()


def test_wait_runs_after_the_owner_lets_go(tmp_path, library_db):
    out = tmp_path / "out"
    fd = _hold(out)
    waiting = _start("batch", _corpus(tmp_path), "--out", out, "--db", library_db, "--wait")
    try:
        time.sleep(3)
        assert waiting.poll() is None, waiting.communicate()  # blocked on the lock, not refused
        assert not (out / "manifest.jsonl").exists()
    finally:
        os.close(fd)
    _, err = waiting.communicate(timeout=300)
    assert waiting.returncode == 0, err
    assert sorted(r["line"] for r in manifest.read(str(out))) == [1, 2, 3, 4]


def test_two_concurrent_runs_leave_one_record_per_line(tmp_path, library_db):
    corpus, out = _corpus(tmp_path), tmp_path / "out"
    runs = [_start("batch", corpus, "--out", out, "--db", library_db, "--wait") for _ in range(2)]
    results = [run.communicate(timeout=300) for run in runs]
    assert [run.returncode for run in runs] == [0, 0], results
    assert sorted(r["line"] for r in manifest.read(str(out))) == [1, 2, 3, 4]
    lines = (out / "manifest.jsonl").read_text(encoding="utf-8").splitlines()
    assert len(lines) == len(TEXTS)  # the README's "exactly once": no record written twice
