"""The scene stage's staging: where each actor stands when the animation starts, read by every engine."""
from __future__ import annotations

import math

import pytest

import text2anim
from text2anim.motiondb import MotionDB
from text2anim.scene import ACTOR_SPACING, stage


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


def test_actors_the_text_does_not_place_stand_side_by_side(db):
    staging = stage(text2anim.plan("太郎は走る。花子が歩く。次郎はジャンプする。", db))
    assert [s.actor for s in staging.spots] == ["太郎", "花子", "次郎"]
    xs = [s.origin[0] for s in staging.spots]
    assert all(b - a == pytest.approx(ACTOR_SPACING) for a, b in zip(xs, xs[1:]))
    assert sum(xs) == pytest.approx(0.0) and all(s.origin[1] == 0.0 and s.heading == 0.0 for s in staging.spots)
    alone = stage(text2anim.plan("太郎は走る。", db))
    assert [(s.actor, s.origin, s.heading) for s in alone.spots] == [("太郎", (0.0, 0.0), 0.0)]


@pytest.mark.parametrize("blend", ["optimal", "constraint", "crossfade"])
def test_every_engine_starts_each_actor_on_its_spot(db, blend):
    anim = text2anim.animate("太郎は走る。3秒後に花子が歩く。", db=db, blend=blend)
    assert anim.staging is not None
    for spot in anim.staging.spots:
        hips = anim.motions[spot.actor].root_positions[0]
        assert math.dist((hips[0], hips[2]), spot.origin) < 0.1, (spot, hips)
