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
