"""An abandoned animation stops inside synthesis, at the next join (core.cancel), not after it.

The studio runs a text inside ``cancellable(cancelled)`` and the page abandons it when a newer text is typed;
before, the stages checked ``cancelled()`` only between them, so a long synthesis ran to its end and the
newer text waited behind it.
"""
from __future__ import annotations

import pytest

from text2anim.core.cancel import Cancelled, cancellable, checkpoint
from text2anim.motiondb import MotionDB
from text2anim.pipeline import NAMES, Request, Work, run

TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。そして歩く。"


def _stages_until_synthesis(url: str):
    with MotionDB.open(url) as db:
        work, done = Work(Request(TEXT), db), None
        for name in NAMES[:NAMES.index("synthesis")]:
            work, done = run(work, after=done, until=name), name
    return work, done


def test_a_synthesis_abandoned_between_joins_stops_at_the_next_one(library_db):
    work, done = _stages_until_synthesis(library_db)
    asked = []

    def cancelled() -> bool:  # the page goes away once the synthesis has passed two checkpoints
        asked.append(True)
        return len(asked) > 2

    with pytest.raises(Cancelled), cancellable(cancelled):
        run(work, after=done, until="synthesis")
    assert len(asked) == 3  # it stopped at the first checkpoint after the page went away

    # the same work, never abandoned, runs to the end and passes more checkpoints than that
    seen = []
    with cancellable(lambda: seen.append(True) or False):
        finished = run(work, after=done, until="synthesis")
    assert len(seen) > 3 and finished.result is not None


def test_outside_a_cancellable_block_a_checkpoint_never_stops(library_db):
    checkpoint()
    work, done = _stages_until_synthesis(library_db)
    assert run(work, after=done, until="synthesis").result is not None
