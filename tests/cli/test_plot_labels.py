"""The ``--plot`` figure labels every motion of the time table by its row and verb (its clip where no font
draws the verb) and its curve by the actor, never "motion 1" for a text of three motions."""
from __future__ import annotations

import html
import importlib.util
import re

from cli_run import assert_clean_error, text2anim

TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。"
ROW = re.compile(r"^\s*(\d+) (\S+) (\S+)\s+(\S+)\s+(\S+)", re.M)  # id actor verb clip method


def test_the_speed_plot_labels_each_motion_by_its_row_and_verb(tmp_path, library_db):
    proc = text2anim(TEXT, "-o", tmp_path / "a.bvh", "--plot", tmp_path / "speeds.svg", "--db", library_db)
    if importlib.util.find_spec("matplotlib") is None:  # without the extra: refused, nothing written
        assert_clean_error(proc, "pip install 'text2anim[plot]'")
        assert list(tmp_path.iterdir()) == []
        return
    assert proc.returncode == 0, proc.stderr
    svg = (tmp_path / "speeds.svg").read_text(encoding="utf-8")
    texts = [html.unescape(t) for t in re.findall(r"<text[^>]*>([^<]*)</text>", svg)]  # svg.fonttype none
    rows = ROW.findall(proc.stdout)
    assert len(rows) == 3
    for row, actor, verb, clip, method in rows:
        assert f"{row} {verb} ({method})" in texts or f"{row} {clip} ({method})" in texts, (row, texts)
    assert not any(t.startswith("motion ") for t in texts), texts
    assert "太郎" in texts or "actor 1" in texts, texts
