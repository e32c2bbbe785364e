"""Warnings speak the user's terms: a motion by its row in the printed time table and its verb, a join by
its two motions and seconds; never the synthesizer's element ids (3回跳ぶ's repetitions have ids the table
does not show) or the paper's names of its search ranges (S0, S1)."""
from __future__ import annotations

import json
import re

import pytest

from cli_run import text2anim

SENTENCES = ["太郎は3回跳んで、歩く。", "太郎は2回跳んで、蹴る。", "太郎は走って、ボールを蹴る。そして喜ぶ。"]
ROW = re.compile(r"^\s*(\d+) \S+ (\S+)\s", re.M)  # " 1 太郎 跳ぶ  jump  initial  0.00- 3.00 s"


def _jargon(warning: str, rows: dict[str, str]) -> list[str]:
    """What in ``warning`` the user cannot find in the printed table."""
    bad = re.findall(r"\d+→\d+|\belement \d+|\bS\d\b", warning)
    for row, verb in re.findall(r"\brow (\d+) (\S+)", warning):
        if rows.get(row) != verb:
            bad.append(f"row {row} {verb}")
    return bad


@pytest.mark.parametrize("blend", ["optimal", "constraint"])
def test_warnings_name_rows_verbs_and_seconds(tmp_path, library_db, blend):
    said = []
    for k, text in enumerate(SENTENCES):
        report = tmp_path / f"r{k}.json"
        proc = text2anim(text, "-o", tmp_path / f"a{k}.bvh", "--report", report, "--blend", blend, "--db", library_db)
        assert proc.returncode == 0, proc.stderr
        rows = dict(ROW.findall(proc.stdout))
        warnings = [ln.split("warning: ", 1)[1] for ln in proc.stderr.splitlines() if "warning: " in ln]
        doc = json.loads(report.read_text(encoding="utf-8"))
        assert doc["warnings"] == warnings
        warnings += [w for j in doc["joins"] for w in j.get("warnings", ())]
        said += warnings
        assert {w: _jargon(w, rows) for w in warnings if _jargon(w, rows)} == {}
    assert said  # the sentences do make the synthesizer warn
    assert any(re.search(r"\brow 1 跳ぶ \(2 of 3\)", w) for w in said), said
    assert all(re.search(r"\d+\.\d\d s\b", w) for w in said if " → " in w)


def test_every_form_of_the_synthesizers_messages_is_reworded(library_db):
    """The forms the synthesizer composes (optimal.plan's skip, timing's core, placed's bone lengths, the
    engines' fallback) on a real animation's ids: 3回跳ぶ's repetitions are ids 1, 3, 4; 歩く is id 2."""
    import text2anim

    terms = text2anim.animate("太郎は3回跳んで、歩く。", db=library_db).terms
    said = {
        "element 3 (jump) is not executed: its core (1.10 s) would begin before the core of element 1 ends (1.20 s)":
            "row 1 跳ぶ (2 of 3) is not executed: its core (1.10 s) would begin before the core of row 1 跳ぶ (1 of 3) "
            "ends (1.20 s)",
        "element 2: its core (1.00 s) does not fit in 0.80 s":
            "row 2 歩く: its core (1.00 s) does not fit in 0.80 s",
        "element 4 (jump_forward) was recorded on other bone lengths": "row 1 跳ぶ (3 of 3) was recorded on other bone lengths",
        "太郎: optimal blending left feet skating at join 1→3, 4→2; rendered with the constraint engine instead":
            "太郎: optimal blending left feet skating at join row 1 跳ぶ (1 of 3) → row 1 跳ぶ (2 of 3) at 1.00 s, "
            "row 1 跳ぶ (3 of 3) → row 2 歩く at 3.00 s; rendered with the constraint engine instead",
    }
    assert {m: terms.reword(m) for m in said} == said


def _run(tmp_path, library_db, text: str) -> tuple[list[str], list[dict]]:
    report = tmp_path / "r.json"
    proc = text2anim(text, "-o", tmp_path / "a.bvh", "--report", report, "--db", library_db)
    assert proc.returncode == 0, proc.stderr
    warnings = [ln.split("warning: ", 1)[1] for ln in proc.stderr.splitlines() if "warning: " in ln]
    return warnings, json.loads(report.read_text(encoding="utf-8"))["joins"]


def _into_cores(joins: list[dict]) -> list[float]:
    """Seconds each join's blend runs into the motions' cores (the report's ``into_core_s``)."""
    return [max(j.get("metrics", {}).get("into_core_s", {"": 0.0}).values()) for j in joins]


def test_blends_running_into_the_motions_are_said_once_and_only_when_they_show(tmp_path, library_db):
    """ジャンプしながら手を叩いた repeats the jump under the clap: each join between two jumps blends the upper
    body 2 frames into the next jump (less than the 0.1 s that counts as touching), which once printed
    "the cores leave no room for the upper-body blend; it overlaps a core" three times."""
    from text2anim.synthesis.optimal.planner import CORE_TOLERANCE

    warnings, joins = _run(tmp_path, library_db, "ジャンプしながら手を叩いた")
    into = _into_cores(joins)
    assert 0 < max(into) <= CORE_TOLERANCE
    assert warnings == []


def test_a_blend_that_shows_is_one_warning_in_the_users_words(tmp_path, library_db):
    from text2anim.synthesis.optimal.planner import CORE_TOLERANCE

    warnings, joins = _run(tmp_path, library_db, "太郎は3回跳んで、歩く。")
    rows = [w for w in warnings if "softer than recorded" in w]
    assert sum(s > CORE_TOLERANCE for s in _into_cores(joins)) == len(rows) == 1
    assert len(warnings) == len(set(warnings))
    assert re.search(r"^row 1 跳ぶ \(\d of 3\) follows row 1 跳ぶ \(\d of 3\) too closely for the upper body", rows[0])
    assert "more time" in rows[0] and not re.search(r"\bcores?\b|\bblend", rows[0])
