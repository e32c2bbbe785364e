"""text2anim parse: JSON, listing, --explain, stdin, errors."""
from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

import pytest

from text2anim.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。"


def run_cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_parse_json_is_the_contract(capsys):
    code, out, _ = run_cli(capsys, "parse", TEXT, "--json")
    data = json.loads(out)
    assert code == 0
    assert [m["span"] for m in data["motions"]] == [[3, 5], [11, 13], [17, 19]]
    assert [c["method"] for c in data["constraints"]] == ["transition", "connection"]
    assert set(data["motions"][0]) == {"id", "actor", "verb", "object", "body_part", "repeat",
                                       "speed", "duration", "span"}


def test_parse_listing(capsys):
    code, out, _ = run_cli(capsys, "parse", TEXT)
    assert code == 0
    assert "蹴る" in out and "object=ボール" in out
    assert "1 -> 2" in out and "transition" in out and "connection" in out


def test_parse_explain_prints_heads(capsys):
    code, out, _ = run_cli(capsys, "parse", "太郎は走って、右手を振りながら歩く。", "--explain")
    assert code == 0
    line = next(ln for ln in out.splitlines() if "走って" in ln and "->" in ln and "motion" in ln)
    assert "-> 4 歩く" in line and "skipping 振りながら" in line


def test_parse_reads_stdin(capsys, monkeypatch):
    monkeypatch.setattr(sys, "stdin", io.StringIO("花子は歩く。\n"))
    code, out, _ = run_cli(capsys, "parse", "-", "--json")
    data = json.loads(out)
    assert code == 0 and data["text"] == "花子は歩く。"
    assert data["motions"][0]["actor"] == "花子"


@pytest.mark.parametrize("text, words", [("  ", "empty"), ("Hello", "no motion")])
def test_parse_user_errors_are_one_line(capsys, text, words):
    code, out, err = run_cli(capsys, "parse", text)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and words in err and "Traceback" not in err


def test_parse_as_a_process():
    proc = subprocess.run([sys.executable, "-m", "text2anim.cli.main", "parse", TEXT, "--json"],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["motions"][2]["verb"] == "喜ぶ"


@pytest.mark.parametrize("text", [
    "Taro walks to the door.", "😀🎉", "\x00\x07\x1b[31m", "走る\u200b😀abcﾀﾞ\u3099", "ｱｲｳ１２３",
    "太郎は走る" * 500, "歩く。" * 700, "Ünïcödé 走って、歩く",
])
def test_parse_never_prints_a_traceback(capsys, text):
    code, out, err = run_cli(capsys, "parse", text, "--json", "--explain")
    assert code in (0, 2) and "Traceback" not in err
    if code == 0:
        assert json.loads(out.split("\nbunsetsu")[0])["motions"]
