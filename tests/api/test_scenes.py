"""Issue 29's own scene set (tests/corpus/scenes.txt: chains, compositions, repeats, several characters,
delays, falls, objects, the everyday captures): every animation meets all six built-in limits at 30 fps,
the floating foot included, and every join keeps the body balanced (core.balance). benchmarks/bench_quality.py
prints the same figures beside a baseline."""
from __future__ import annotations

from pathlib import Path

import pytest

import text2anim
from text2anim.core.balance import LIMIT_CM
from text2anim.core.metrics import against_limits, quality
from text2anim.motiondb import MotionDB

SCENES = [t for t in (line.strip() for line in (Path(__file__).resolve().parents[1] / "corpus" / "scenes.txt")
                      .read_text(encoding="utf-8").splitlines()) if t and not t.startswith("#")]


def test_the_set_has_forty_scenes():
    assert len(SCENES) == len(set(SCENES)) == 40


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


@pytest.mark.parametrize("text", SCENES)
def test_every_scene_is_clean(db, text):
    anim = text2anim.animate(text, db=db)
    for actor, motion in anim.motions.items():
        q = quality(motion)
        assert all(against_limits(q).values()), (actor, q)
    for join in anim.report["joins"]:  # the frames a join made keep the centre of mass over the feet, the hips
        # change speed as a body's do, and nothing hangs in the air (the calibrated limits)
        t = join["quality"]["transition"]
        assert t["balance_cm"] <= LIMIT_CM, (join["first"], join["second"], t)
        assert all(t["meets"].values()), (join["first"], join["second"], t)
