"""A limited search ranks only the candidates of the ranking table (``search_ranks``): its answer must be the
first ``limit`` clips of the full ranking, for every combination of query options, after removals and
replacements, and after a schema-version-2 database is migrated."""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from sqlalchemy import create_engine, text

from text2anim.motiondb import MotionDB

VERBS = ["跳ぶ", "飛ぶ", "歩く", "走る"]  # 跳ぶ and 飛ぶ share the reading トブ: とぶ matches both by reading
OBJECTS = ["ボール", "箱", "棒"]
CHARACTERS = ["default", "taro", "hanako"]
PARTS = [None, None, "right_arm", "left_arm", "right_leg"]
POSTURES = ["standing", "seated", "crouched"]


def _clips(record, n: int, seed: int):
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        verbs = [VERBS[int(i)] for i in rng.choice(len(VERBS), size=int(rng.integers(1, 4)), replace=False)]
        objects = [OBJECTS[int(i)] for i in rng.choice(len(OBJECTS), size=int(rng.integers(0, 3)), replace=False)]
        out.append(record(f"c{seed}_{k:03d}{'ab'[k % 2]}", verbs, frames=6, objects=tuple(objects),
                          character=CHARACTERS[int(rng.integers(len(CHARACTERS)))],
                          body_part=PARTS[int(rng.integers(len(PARTS)))],
                          start_posture=POSTURES[int(rng.integers(len(POSTURES)))], end_posture="standing"))
    return out


QUERIES = list(itertools.product(["とぶ", "跳ぶ", "歩く"], [None, "ボール", "はこ"], [None, "taro"],
                                 [None, "right_arm", "left_leg"], [None, "seated"], [None, "hanako"]))


def _assert_limited_searches_are_the_full_ranking_cut(db: MotionDB) -> int:
    checked = 0
    for verb, obj, prefer, part, posture, character in QUERIES:
        kw = dict(object=obj, prefer_character=prefer, body_part=part, prefer_start_posture=posture,
                  character=character)
        full = [c.name for c in db.search(verb, **kw)]
        for limit in (1, 2, 3, 5):
            got = [c.name for c in db.search(verb, limit=limit, **kw)]
            assert got == full[:limit], (verb, kw, limit)
            checked += len(full) > limit
    return checked


def test_a_limited_search_is_the_full_rankings_first_clips(db_url, record):
    with MotionDB.open(db_url, seed=False) as db:
        db.add(_clips(record, 60, seed=1))
        assert _assert_limited_searches_are_the_full_ranking_cut(db) > 200  # the limit really cut most rankings
        # removed and replaced clips leave the ranking table with them
        names = [c.name for c in db.clips()]
        db.remove(names[::3])
        db.add([record(n, ["とぶ"], frames=6, objects=("箱",), character="taro") for n in names[1::5]], replace=True)
        _assert_limited_searches_are_the_full_ranking_cut(db)
        assert [c.name for c in db.search("とぶ", object="箱", prefer_character="taro", limit=3)] == \
            sorted(names[1::5])[:3]


def test_a_version_2_database_gets_its_ranking_table_and_keeps_every_clip(db_url, record):
    with MotionDB.open(db_url, seed=False) as db:
        db.add(_clips(record, 40, seed=2))
        before = {q: [c.name for c in db.search(q[0], object=q[1], limit=4)] for q in QUERIES[:9]}
        clips = {c.name: (c.verbs, c.objects, c.character, c.start_posture) for c in db.clips()}
    engine = create_engine(db_url)
    try:
        with engine.begin() as conn:  # what schema version 2 wrote: no ranking table
            conn.execute(text("DROP TABLE search_ranks"))
            conn.execute(text("ALTER TABLE clips DROP COLUMN style"))  # schema 5
            conn.execute(text("ALTER TABLE clips DROP COLUMN description"))
            conn.execute(text("UPDATE schema_version SET version = 2"))
    finally:
        engine.dispose()
    with MotionDB.open(db_url, seed=False) as db:  # migrated in place
        assert {c.name: (c.verbs, c.objects, c.character, c.start_posture) for c in db.clips()} == clips
        assert {q: [c.name for c in db.search(q[0], object=q[1], limit=4)] for q in QUERIES[:9]} == before
        _assert_limited_searches_are_the_full_ranking_cut(db)


@pytest.fixture
def record(record):
    return record
