"""The waits of a time table are filled in the table itself: ``text2anim plan`` shows the stops and idles
that will play, and the report's time table lists every element the animation played.

Real built-in library (``library_db``), the real analyser, scheduler and synthesis engine.
"""
from __future__ import annotations

import json

import pytest

import text2anim
from cli_run import text2anim as run_cli
from text2anim.motiondb import MotionDB
from text2anim.scheduler.clips import played_duration
from text2anim.scheduler.fillers import IDLE_GAP, IDLE_VERB, STOP_VERB


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


def by_start(elements):
    return sorted(elements, key=lambda e: (e["start"], e["id"]))


def test_plan_shows_the_stop_and_the_idle_before_a_delayed_motion(library_db):
    proc = run_cli("plan", "--json", "--db", library_db, "太郎は走る。3秒後に歩く。")
    assert proc.returncode == 0, proc.stderr
    run, stop, idle, walk = by_start(json.loads(proc.stdout)["elements"])
    assert (run["verb"], stop["verb"], idle["verb"], walk["verb"]) == ("走る", STOP_VERB, IDLE_VERB, "歩く")
    # a chain: each joined to the one before, each starting where the one before ends
    assert (stop["method"], stop["prev"]) == ("transition", run["id"])
    assert (idle["method"], idle["prev"]) == ("connection", stop["id"])
    assert (walk["method"], walk["prev"]) == ("connection", idle["id"])
    assert stop["start"] == run["end"] and idle["start"] == stop["end"] and walk["start"] == idle["end"]
    assert walk["start"] - run["end"] > IDLE_GAP
    assert stop["id"] > walk["id"] and idle["id"] > walk["id"]  # added after the text's own motions


def test_a_walk_goes_on_until_the_stop_the_text_says(db):
    # 兄が止まると、彼も止まった: 次郎 walks until his brother stops, then stops once (no stop, idle, stop)
    planned = text2anim.plan("次郎は兄の後ろを歩いた。兄が止まると、彼も止まった。", db)
    mine = sorted((e for e in planned.table.elements if e.actor == "次郎"), key=lambda e: e.start)
    assert [e.verb for e in mine] == ["歩く", STOP_VERB]
    walk, stop = mine
    assert walk.end == stop.start
    assert walk.end - walk.start > played_duration(planned.clips[walk.id], planned.table.fps) + IDLE_GAP
    # a wait before another motion still stops and idles
    planned = text2anim.plan("太郎は走る。3秒後に歩く。", db)
    assert [e.verb for e in sorted(planned.table.elements, key=lambda e: e.start)][1:3] == [STOP_VERB, IDLE_VERB]


def test_the_stop_lasts_its_clip_as_played(db):
    planned = text2anim.plan("太郎は走る。3秒後に歩く。", db, fps=24.0)
    stop = next(e for e in planned.table.elements if e.verb == STOP_VERB)
    motion = db.load(planned.clips[stop.id]).resample(24.0)
    assert stop.end - stop.start == pytest.approx(motion.duration)
    assert played_duration(planned.clips[stop.id], 24.0) == motion.duration


@pytest.mark.parametrize("text", ["太郎は走る。3秒後に歩く。", "太郎は歩く。5秒後に花子が座る。",
                                  "花子が座るのと同時に太郎は転ぶ。そして起き上がる。"])
def test_the_report_time_table_lists_every_element_that_played(db, text):
    anim = text2anim.animate(text, db=db)
    report = anim.report
    table_ids = {e["id"] for e in report["time_table"]}
    assert {int(k) for k in report["elements"]} == table_ids
    assert set(anim.planned.fillers) <= table_ids
    assert {e.id for e in anim.table.elements} == set(anim.planned.clips)


def test_a_late_actor_idles_from_the_start_and_an_early_one_to_the_end(db):
    planned = text2anim.plan("太郎は歩く。5秒後に花子が座る。", db)
    end = max(e.end for e in planned.table.elements)
    hanako = by_start(e.to_dict() for e in planned.table.elements if e.actor == "花子")
    taro = by_start(e.to_dict() for e in planned.table.elements if e.actor == "太郎")
    assert (hanako[0]["verb"], hanako[0]["method"], hanako[0]["start"]) == (IDLE_VERB, "initial", 0.0)
    assert (hanako[1]["verb"], hanako[1]["method"], hanako[1]["prev"]) == ("座る", "connection", hanako[0]["id"])
    assert [e["verb"] for e in taro][-1] == IDLE_VERB and taro[-1]["end"] == pytest.approx(end, abs=1e-3)


def test_an_actor_who_ends_seated_idles_seated_to_the_end(db):
    """Since issue 12 the library has a captured seated idle: 花子 sits and then idles seated (was: held the pose)."""
    planned = text2anim.plan("花子が座るのと同時に太郎は転ぶ。そして起き上がる。", db)
    end = max(e.end for e in planned.table.elements)
    sit, idle = sorted((e for e in planned.table.elements if e.actor == "花子"), key=lambda e: e.start)
    assert sit.clip == "sit_down" and idle.id in planned.fillers and idle.prev == sit.id
    assert idle.start == sit.end and idle.end == end
    assert planned.clips[idle.id].start_posture == planned.clips[idle.id].end_posture == "seated"
