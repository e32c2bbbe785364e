"""Issue 40: a manner changes the motion, through the real pipeline on the built-in library.

Each styled motion is measured against the neutral one by :mod:`core.style_figures` (the hips' speed, the
cadence and step length of a walk, the head's height above the hips, a hand's range, the hips' bounce)
and held to the quality limits of motion made from the built-in library; a manner no modifier does is
said on stderr, in the report and in the warnings the studio shows.
"""
from __future__ import annotations

import json

import pytest

import text2anim
from cli_run import text2anim as run
from text2anim.core.metrics import against_limits, quality
from text2anim.core.style_figures import style_figures

WALK = "太郎は{}4秒間歩いた。"


@pytest.fixture(scope="module")
def figures(library_db):
    """Text -> (its animation's figures over the steady part of the walk, its quality against the limits)."""
    cache: dict = {}

    def measure(text: str, hand: str = "right"):
        if text not in cache:
            (motion,) = text2anim.animate(text, db=library_db).motions.values()
            window = (0.5, motion.duration - 0.5) if motion.duration > 2 else None
            cache[text] = (style_figures(motion, window, hand), against_limits(quality(motion)))
        return cache[text]

    return measure


def test_a_tired_walk_is_slower_with_shorter_steps_and_the_head_lower(figures):
    neutral, _ = figures(WALK.format(""))
    tired, meets = figures(WALK.format("疲れて"))
    assert tired.hips_speed < 0.8 * neutral.hips_speed
    assert tired.cadence < 0.9 * neutral.cadence and tired.step_length < 0.9 * neutral.step_length
    assert tired.head_height < neutral.head_height - 0.01
    assert all(meets.values()), meets


def test_a_hurried_walk_is_faster_in_cadence_and_stride(figures):
    neutral, _ = figures(WALK.format(""))
    hurried, meets = figures(WALK.format("足早に"))
    assert hurried.hips_speed > 1.3 * neutral.hips_speed
    assert hurried.cadence > 1.05 * neutral.cadence and hurried.step_length > 1.1 * neutral.step_length
    assert all(meets.values()), meets


def test_a_sad_walk_hangs_its_head_and_an_energetic_one_bounces(figures):
    neutral, _ = figures(WALK.format(""))
    sad, sad_meets = figures(WALK.format("しょんぼり"))
    energetic, energetic_meets = figures(WALK.format("元気よく"))
    assert sad.head_height < neutral.head_height - 0.02
    assert energetic.bounce > 1.3 * neutral.bounce
    assert all(sad_meets.values()) and all(energetic_meets.values()), (sad_meets, energetic_meets)


def test_a_big_wave_reaches_further_than_a_small_one(figures):
    plain, _ = figures("太郎は右手を振った。")
    big, big_meets = figures("太郎は大きく右手を振った。")
    small, small_meets = figures("太郎は小さく右手を振った。")
    assert small.hand_range < 0.85 * plain.hand_range < 0.85 * big.hand_range
    assert all(big_meets.values()) and all(small_meets.values()), (big_meets, small_meets)


def test_the_plan_and_the_report_say_how_the_manner_is_done(library_db):
    planned = text2anim.plan("太郎はとても疲れて歩いた。", library_db)
    (row,) = planned.table.elements
    assert row.to_dict()["manner"] == {"word": "疲れて", "style": "tired", "intensity": 1.4, "by": "modifiers"}
    assert row.speed == pytest.approx(0.8 ** 1.4, abs=1e-3)  # the style's tempo
    anim = text2anim.animate("太郎はとても疲れて歩いた。", db=library_db)
    (done,) = anim.report["manners"]
    assert done["by"] == "modifiers" and done["changes"]["spine_pitch"] == pytest.approx(14.0)
    assert "manners" not in text2anim.animate("太郎は歩いた。", db=library_db).report


def test_a_speed_word_sets_the_speed_and_the_style_keeps_its_other_changes(library_db):
    (row,) = text2anim.plan("太郎は急いで歩いた。", library_db).table.elements
    assert row.speed == 1.5 and row.manner is not None and row.manner.by == "modifiers"


def test_a_manner_no_modifier_does_is_said_on_stderr_in_the_report_and_the_warnings(library_db, tmp_path):
    report = tmp_path / "r.json"
    proc = run("花子はにこにこ歩いた。", "--db", library_db, "-o", tmp_path / "a.bvh", "--report", report)
    assert proc.returncode == 0, proc.stderr
    assert "にこにこ is not shown" in proc.stderr
    data = json.loads(report.read_text(encoding="utf-8"))
    assert any("にこにこ is not shown" in w for w in data["warnings"])
    assert data["manners"][0]["by"] is None and data["time_table"][0]["manner"]["style"] is None


def test_a_repeating_mimetic_is_performed_not_reported(library_db):
    anim = text2anim.animate("観客はぱちぱちと拍手した。", db=library_db)
    assert not anim.warnings and "manners" not in anim.report
