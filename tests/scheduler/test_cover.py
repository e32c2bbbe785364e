"""ながら with a short whole-body action (issue 27): it repeats to cover the other motion.

Real analyzer, real built-in library, the scheduler's own entry point; one sentence synthesised.
"""
from __future__ import annotations

import numpy as np
import pytest

from text2anim import nlp
from text2anim.clip_search import DatabaseClips
from text2anim.motiondb import MotionDB
from text2anim.scheduler import schedule


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


def table(text: str, db: MotionDB):
    return {e.clip: e for e in schedule(nlp.analyze(text), DatabaseClips(db), 30.0).table.elements}


@pytest.mark.parametrize("text", ["ジャンプしながら手を叩く", "手を叩きながらジャンプする"])
def test_a_short_base_repeats_to_cover_the_composition(db, text):
    rows = table(text, db)
    jump, clap = rows["jump"], rows["clap"]
    n = round(db.info("clap").duration / db.info("jump").duration)
    assert n >= 2
    assert (jump.method, jump.repeat) == ("initial", n)
    assert jump.end == pytest.approx(n * db.info("jump").duration)
    assert (clap.method, clap.prev, clap.start) == ("composition", jump.id, 0.0)
    assert jump.end >= clap.end - db.info("jump").duration / 2  # covered to the nearest jump


def test_counts_and_comparable_lengths_are_left_as_the_text_says(db):
    rows = table("3回ジャンプしながら手を叩く", db)
    assert rows["jump"].repeat == 3  # the text's count wins
    rows = table("お辞儀しながら手を振る", db)  # bow and wave last about as long: one bow
    assert rows["bow"].repeat == 1
    rows = table("歩きながら手を振る", db)  # a loop covers by looping
    assert rows["walk"].repeat == 1


def test_the_jumps_are_played(db):
    """Synthesised: the hips leave their standing height once per jump while the hands clap."""
    from text2anim.pipeline import plan_text
    from text2anim.synthesis.constraint.engine import synthesize
    from text2anim.tracks import build_tracks

    planned = plan_text("ジャンプしながら手を叩く", db)
    (motion,) = synthesize(build_tracks(planned, db, 30.0), 30.0).motions.values()
    y = motion.root_positions[:, 1]
    high = y > np.median(y) + 0.15
    takeoffs = int(np.count_nonzero(high[1:] & ~high[:-1]) + high[0])
    assert takeoffs == round(db.info("clap").duration / db.info("jump").duration) == planned.table.element(1).repeat
