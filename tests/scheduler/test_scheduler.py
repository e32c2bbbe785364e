"""The motion time table from real analyses: methods, links and start times (docs/timetable.md §1).

Clip timing is given as data here so every expected time can be worked out by
hand; ``test_plan_cli.py`` runs the same stage on the real database.
"""
from __future__ import annotations

import pytest

from text2anim import nlp
from text2anim.scheduler import ClipTiming, ScheduleError, format_table, plan, without

RUN = ClipTiming("run", 2.0, (0.2, 1.8), True, None, ((0.1, 0.4), (0.5, 0.8), (1.1, 1.4), (1.5, 1.8)))
KICK = ClipTiming("kick_ball", 2.0, (0.5, 1.3), False, None, ((0.4, 1.2), (1.4, 1.6)))
CHEER = ClipTiming("cheer", 2.5, (0.3, 2.0))
WALK = ClipTiming("walk", 2.2, (0.0, 2.2), True, None, ((0.1, 0.6), (0.65, 1.15), (1.2, 1.7), (1.75, 2.2)))
WAVE = ClipTiming("wave", 2.0, (0.4, 1.6), False, "right_arm")
SIT = ClipTiming("sit", 2.0, (0.3, 1.5))
LAUGH = ClipTiming("laugh", 1.5, (0.2, 1.2))
CLIPS = {"走る": RUN, "蹴る": KICK, "喜ぶ": CHEER, "歩く": WALK, "振る": WAVE, "座る": SIT, "笑う": LAUGH}


def table(text):
    return plan(nlp.analyze(text), lambda m, prefer: CLIPS[m.verb])


def rows(text):
    return [(e.verb, e.method, e.prev, round(e.start, 3), round(e.end, 3), e.body_part) for e in table(text).elements]


def test_the_papers_example():
    t = table("太郎は走って、ボールを蹴る。そして喜ぶ。")
    assert [(e.actor, e.clip, e.method, e.prev) for e in t.elements] == [
        ("太郎", "run", "initial", None), ("太郎", "kick_ball", "transition", 1), ("太郎", "cheer", "connection", 2)]
    run, kick, cheer = t.elements
    # The run's last whole step (1.5-1.8 s) is where the kick overlaps it; the run ends with that step.
    assert (run.start, run.end) == (0.0, pytest.approx(1.8))
    assert kick.start == pytest.approx(1.5) and kick.end == pytest.approx(3.5)
    # Connection: the cheer starts when the kick has finished.
    assert cheer.start == pytest.approx(kick.end) and cheer.end == pytest.approx(kick.end + 2.5)


def test_transition_from_a_one_shot_overlaps_its_first_step_after_the_core():
    # The kick's core ends at 1.3 s; its next foot-moving interval is 1.4-1.6 s.
    assert rows("ボールを蹴って、走る。") == [
        ("蹴る", "initial", None, 0.0, 1.6, None), ("走る", "transition", 1, 1.4, 3.4, None)]


def test_composition_base_is_chosen_by_the_clips_not_word_order():
    a = rows("歩きながら右手を振る。")
    b = rows("右手を振りながら歩く。")
    walk_a = next(r for r in a if r[0] == "歩く")
    wave_a = next(r for r in a if r[0] == "振る")
    walk_b = next(r for r in b if r[0] == "歩く")
    wave_b = next(r for r in b if r[0] == "振る")
    assert walk_a[1] == walk_b[1] == "initial"
    assert wave_a[1:] [0] == wave_b[1:][0] == "composition"
    assert wave_a[3:] == wave_b[3:] == (0.0, 2.0, "right_arm")
    assert walk_a[3:] == walk_b[3:] == (0.0, 2.2, None)


def test_unsided_arm_takes_the_clips_side_and_left_stays_left():
    assert rows("歩きながら手を振る。")[1][5] == "right_arm"
    assert rows("歩きながら左手を振る。")[1][5] == "left_arm"


def test_whole_body_composition_lays_the_upper_body_on_the_locomotion():
    r = rows("笑いながら歩く。")
    assert ("歩く", "initial", None, 0.0, 2.2, None) in r
    assert ("笑う", "composition", 2, 0.0, 1.5, "upper") in r


def test_head_of_a_te_clause_is_not_the_nearest_predicate():
    t = table("太郎は走って、右手を振りながら歩く。")
    run, wave, walk = t.elements
    assert (walk.method, walk.prev) == ("transition", run.id)
    assert (wave.method, wave.prev, wave.start) == ("composition", walk.id, walk.start)


def test_mae_ni_reverses_the_order():
    sit, wave = table("座る前に手を振る。").elements
    assert (wave.method, wave.start) == ("initial", 0.0)
    assert (sit.method, sit.prev, sit.start) == ("connection", wave.id, pytest.approx(wave.end))


def test_tamama_holds_the_base_while_the_other_plays():
    sit, wave = table("座ったまま手を振る。").elements
    assert (wave.method, wave.prev) == ("composition", sit.id)
    assert wave.start == pytest.approx(2.0)  # after sitting down
    assert sit.end == pytest.approx(wave.end) and sit.hold


@pytest.mark.parametrize("text, delay", [("走る。3秒後に歩く。", 3.0), ("走る。３秒後に歩く。", 3.0),
                                         ("走る。三秒後に歩く。", 3.0), ("走る。しばらくして歩く。", 2.0)])
def test_delays(text, delay):
    run, walk = table(text).elements
    assert walk.method == "connection" and walk.start == pytest.approx(run.end + delay)


def test_repeat_speed_and_duration():
    assert rows("3回ボールを蹴る。")[0][3:5] == (0.0, 6.0)
    assert rows("5秒間歩く。")[0][3:5] == (0.0, 5.0)
    slow = table("ゆっくり歩く。").elements[0]
    assert slow.speed < 1 and slow.end == pytest.approx(2.2 / slow.speed)
    # A one-shot is never cut inside its core: 1 s of a kick whose core ends at 1.3 s plays 1.3 s.
    assert rows("1秒間ボールを蹴る。")[0][4] == 1.3


def test_cross_actor_links_fix_start_times_only():
    taro, hanako = table("太郎が走ると同時に花子が歩く。").elements
    assert (hanako.actor, hanako.method, hanako.prev, hanako.start) == ("花子", "initial", None, 0.0)
    taro, hanako = table("太郎が走って、花子が歩く。").elements
    assert hanako.start == pytest.approx(RUN.core[1])  # serial with overlap: when the run's core ends
    taro, hanako = table("太郎が走る。2秒後に花子が歩く。").elements
    assert hanako.start == pytest.approx(taro.end + 2)
    assert table("太郎が走る。2秒後に花子が歩く。").actors() == ["太郎", "花子"]


def test_dropping_an_unknown_motion_bridges_the_links():
    a = nlp.analyze("走って、踊る。そして喜ぶ。")
    dance = next(m.id for m in a.motions if m.verb == "踊る")
    t = plan(without(a, {dance}), lambda m, prefer: CLIPS[m.verb])
    assert [(e.verb, e.method) for e in t.elements] == [("走る", "initial"), ("喜ぶ", "connection")]


def test_json_and_paper_table():
    t = table("太郎は走って、ボールを蹴る。そして喜ぶ。")
    d = t.to_dict()
    assert list(d) == ["text", "fps", "elements"]
    assert list(d["elements"][0])[:9] == ["id", "actor", "verb", "clip", "method", "prev", "start", "end", "body_part"]
    text = format_table(t)
    assert "[要素 2]" in text and "接続形式  Transition" in text and "前要素    要素 1" in text


def test_cycle_is_refused():
    a = nlp.analyze("走って、歩く。")
    c = a.constraints[0]
    from dataclasses import replace
    looped = replace(a, constraints=(c, replace(c, first=c.second, second=c.first)))
    with pytest.raises(ScheduleError):
        plan(looped, lambda m, prefer: CLIPS[m.verb])
