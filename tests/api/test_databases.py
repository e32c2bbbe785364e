"""The API keeps a database it opened by URL open for the next call, and notices when its file is replaced."""
from __future__ import annotations

import threading

import pytest

import text2anim
from text2anim.databases import database
from text2anim.motiondb import MotionDB, UnknownVerbError


def test_a_url_is_opened_once_and_kept(library_db):
    with database(library_db) as first:
        pass
    text2anim.plan("太郎は歩く。", library_db)
    with database(library_db) as again:
        assert again is first
    with database(first) as given:  # a database the caller opened is used as it is
        assert given is first


def test_a_replaced_file_is_opened_again(tmp_path):
    path = tmp_path / "motions.sqlite"
    MotionDB.open(path).close()
    assert text2anim.plan("太郎は歩く。", str(path)).table.elements
    path.unlink()
    MotionDB.open(path, seed=False).close()  # the same path, now a database without clips
    with pytest.raises(UnknownVerbError):
        text2anim.plan("太郎は歩く。", str(path))


def test_threads_share_one_database_and_agree(library_db):
    text = "太郎は走って、ボールを蹴る。"
    expected = text2anim.plan(text, library_db).table.to_json()
    got, errors = [], []

    def plan():
        try:
            got.append(text2anim.plan(text, library_db).table.to_json())
        except Exception as exc:  # noqa: BLE001 - reported below
            errors.append(exc)
    threads = [threading.Thread(target=plan) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors and got == [expected] * 4
