"""The limits of the contract (text2anim.limits): refused up front, one line, exit 2; the API's argument checks.

Every case here asked for unbounded work or crashed with a traceback before the limits
existed (issue 9): ``--fps 1000000`` grew to 12 GB, ``1000000回`` ran for minutes,
``999999999秒後`` and 400-digit numbers ended in MemoryError/ValueError tracebacks.
Refusals come before any frame is made, so these tests are fast.
"""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import text2anim
from cli_run import REPO, assert_clean_error, text2anim as run
from text2anim.limits import (FPS_MAX, MAX_MOTIONS, MAX_REPEAT, MAX_SECONDS, MAX_TEXT_CHARS, InputError,
                              InputTypeError, LimitError)

HUGE = "9" * 400


# ------------------------------------------------------------------------------ the CLI
UNBOUNDED = [
    ("太郎は1000000回跳ぶ。", f"at most {MAX_REPEAT} repetitions"),
    (f"太郎は{HUGE}回跳ぶ。", f"at most {MAX_REPEAT} repetitions"),
    ("太郎は歩く。999999999秒後に花子は走る。", "a delay of 1e+09 s"),
    (f"太郎は歩く。{HUGE}秒後に花子は走る。", "more than a day"),
    (f"太郎は{HUGE}秒歩く。", "more than a day"),
    (f"太郎は{'九' * 309}秒走る。", "asked to last more than 10³⁰⁸ s, more than a day"),  # OverflowError (issue 41)
    (f"{'九' * 309}秒後に走る。", "a delay of more than 10³⁰⁸ s is asked before 走る"),
    ("太郎は走ってから一〇〇〇〇〇〇秒後に歩く。", "a delay of 1e+06 s is asked, more than a day"),
    ("太郎は9999秒歩く。", "asked to last 9999 s"),
    ("太郎は299秒歩く。花子は走る。", "for 2 actors"),  # each alone fits; the two together do not
    ("歩く。" * (MAX_MOTIONS + 1), f"at most {MAX_MOTIONS} per text"),
    ("歩" * (MAX_TEXT_CHARS + 1), f"at most {MAX_TEXT_CHARS} are accepted"),
]


@pytest.mark.parametrize("text, fragment", UNBOUNDED)
def test_unbounded_texts_are_refused_before_any_work(library_db, text, fragment):
    with pytest.raises(LimitError, match=fragment.replace("+", r"\+")):
        text2anim.plan(text, library_db)


@pytest.mark.parametrize("text, fragment", UNBOUNDED[9:10] + UNBOUNDED[5:6])
def test_unbounded_texts_are_one_line_and_exit_2(tmp_path, library_db, text, fragment):
    proc = run(text, "-o", tmp_path / "a.bvh", "--db", library_db)
    assert_clean_error(proc, fragment)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command, fps", [((), "1000000"), (("plan",), "0.5"), (("compare",), "241")])
def test_frame_rate_outside_the_range_is_refused(tmp_path, command, fps):
    proc = run(*command, "太郎は歩く。", "--fps", fps, cwd=tmp_path)
    assert proc.returncode == 2 and "1-240 frames per second" in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr
    assert list(tmp_path.iterdir()) == []


def test_the_budget_counts_frames_too_and_can_be_raised(library_db):
    # 100 s at 240 fps is 24,000 frames: over the 18,000-frame budget of 300 s x 60 fps
    with pytest.raises(LimitError, match="24000 frames .* over the budget of 18000 frames"):
        text2anim.plan("太郎は100秒歩く。", library_db, fps=240)
    planned = text2anim.plan("太郎は400秒歩く。", library_db, max_seconds=500)  # a batch user's raised budget
    assert planned.table.elements[0].end == pytest.approx(400)
    with pytest.raises(LimitError, match="at most 300 s of output"):
        text2anim.plan("太郎は400秒歩く。", library_db)


@pytest.mark.parametrize("command, text, shown", [
    ((), "太郎は\x1b[31m歩く。", "U+001B at character 4"),
    (("parse",), "太郎は\x07歩く。", "U+0007 at character 4"),
    (("plan",), "太郎は\u202e歩く。", "text-direction control character (U+202E"),
])
def test_control_characters_are_refused_and_never_echoed(tmp_path, command, text, shown):
    proc = run(*command, text, cwd=tmp_path)
    assert_clean_error(proc, shown, "remove it")
    assert "no motion found" not in proc.stderr
    assert "\x1b" not in proc.stderr and "\x07" not in proc.stderr and "\u202e" not in proc.stderr


def test_control_characters_are_refused_by_the_api():
    with pytest.raises(InputError, match=r"U\+0000"):
        text2anim.animate("太郎は\x00歩く。")


def test_control_characters_from_standard_input_too(tmp_path):
    proc = run("parse", "-", input="太郎は\x1b]0;pwned\x07歩く。\n", cwd=tmp_path)
    assert_clean_error(proc, "U+001B")
    assert "\x1b" not in proc.stderr


def test_line_breaks_and_tabs_are_text_not_control(library_db):
    analysis = text2anim.plan("太郎は歩く。\r\n\t花子は走る。", library_db).analysis
    assert [m.verb for m in analysis.motions] == ["歩く", "走る"]


# ------------------------------------------------------------------------------ the API
@pytest.mark.parametrize("options, error, fragment", [
    ({"fps": True}, InputTypeError, "fps must be a number, not bool"),
    ({"fps": "30"}, InputTypeError, "fps must be a number, not str"),
    ({"fps": float("nan")}, InputError, "finite"),
    ({"fps": 1e6}, LimitError, f"between 1 and {FPS_MAX:g}"),
    ({"fps": 10**400}, InputError, "fps must be a finite number"),
    ({"skip_unknown": "no"}, InputTypeError, "skip_unknown must be True or False"),
    ({"lock_feet": 1}, InputTypeError, "lock_feet must be True or False"),
    ({"sway": None}, InputTypeError, "sway must be True or False"),
    ({"smoothness": 2}, InputError, "between 0"),
    ({"smoothness": "0.5"}, InputTypeError, "smoothness must be a number"),
    ({"blend": 3}, InputTypeError, "blend must be a str"),
    ({"blend": "best"}, ValueError, "unknown blending method"),
    ({"db": 3.5}, InputTypeError, "db must be a MotionDB"),
    ({"max_seconds": -1}, LimitError, "max_seconds"),
])
def test_api_arguments_are_checked_with_the_projects_errors(options, error, fragment):
    with pytest.raises(error, match=fragment) as info:
        text2anim.animate("太郎は歩く。", **options)
    assert isinstance(info.value, (ValueError, TypeError)) and type(info.value).user_facing


def test_api_text_must_be_a_string():
    with pytest.raises(TypeError, match="text must be a str"):
        text2anim.animate(b"\xe6\xad\xa9\xe3\x81\x8f")
    with pytest.raises(TypeError):
        text2anim.animate("歩く。", "sqlite:///x.sqlite")  # db is keyword-only: no silent misreading


def test_api_accepts_numpy_numbers_and_bools(library_db):
    anim = text2anim.animate("太郎は歩く。", db=library_db, fps=np.float32(24), skip_unknown=np.bool_(False))
    (m,) = anim.motions.values()
    assert m.fps == 24.0 and type(anim.fps) is float


def test_every_stage_error_is_a_value_error(library_db):
    from text2anim.core.atomic import OutputError
    from text2anim.core.bvh import BVHError
    from text2anim.motiondb import DBError, UnknownVerbError
    from text2anim.nlp.errors import NLPError
    from text2anim.scheduler import ScheduleError

    for cls in (OutputError, BVHError, DBError, NLPError, ScheduleError, LimitError, InputError):
        assert issubclass(cls, ValueError), cls
    assert issubclass(OutputError, OSError)
    with pytest.raises(ValueError) as info:  # what a Python user writes
        text2anim.animate("宇宙遊泳する。", db=library_db)
    assert isinstance(info.value, UnknownVerbError)


def test_default_budget_is_documented():
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    for figure in (f"{MAX_SECONDS:g} s", f"{MAX_REPEAT}", f"{MAX_MOTIONS}", f"{MAX_TEXT_CHARS:,}", "1 to 240"):
        assert figure in readme, figure


def test_undecodable_text_is_one_line():
    """Bytes that are not UTF-8, on the command line or standard input: one line, not a UnicodeError."""
    env = {"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin", "LC_ALL": "C.UTF-8"}
    for args, stdin in (([b"parse", b"\xff\xfe\xe6\xad\xa9\xe3\x81\x8f"], b""), ([b"parse", b"-"], b"\xff\xfe")):
        proc = subprocess.run([sys.executable.encode(), b"-m", b"text2anim.cli.main", *args], input=stdin, cwd=REPO, env=env,
                              capture_output=True, timeout=120)
        err = proc.stderr.decode()
        assert proc.returncode == 2 and "Traceback" not in err and "UTF-8" in err, err


def test_a_duration_over_a_day_is_refused_whatever_the_budget(library_db):
    """--max-seconds raises the budget up to a day; a duration beyond it is refused for that reason."""
    with pytest.raises(LimitError, match="more than a day"):
        text2anim.plan("太郎は100000秒歩く。", library_db, max_seconds=86_400)
    assert text2anim.plan("太郎は400秒歩く。", library_db, max_seconds=86_400)
