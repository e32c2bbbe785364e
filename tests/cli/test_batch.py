"""text2anim batch in one process: the project corpus, checking, the manifest, resuming, the summary.

The Dask runs (local cluster, a killed worker) are in test_batch_cluster.py."""
from __future__ import annotations

import io
import json
from pathlib import Path

import pytest

from text2anim.cli.batch import Options, compare, load_corpus, manifest, run_corpus, shard_path
from text2anim.cli import cmd_batch
from text2anim.cli.main import main

CORPUS = Path(__file__).parents[1] / "corpus" / "nlp_corpus.jsonl"

#: Categories of docs/language.md §3 (and §1-§2) the corpus must cover.
REQUIRED_CATEGORIES = {
    "te", "renyou", "period", "nagara", "tsutsu", "tekara", "ato", "owattara", "mama",
    "douji", "mae", "aida", "uchini", "soshite", "sorekara", "sonogo", "tsugini", "doujini",
    "shibaraku", "delay_arabic", "delay_fullwidth", "delay_kanji", "sugu", "actors",
    "sahen", "ojigi", "aspect", "variants", "negation", "relative", "no_complement",
    "manner", "object", "body_part", "repeat", "speed", "duration",
    # issue 14: what users actually write (nlp/README.md)
    "te_aux", "manner_te", "delay_opening", "kana", "object_adverb", "object_null", "request", "casual",
}


def run_cli(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_corpus_is_large_and_covers_every_category():
    items = load_corpus(str(CORPUS))
    assert len(items) >= 150
    assert all(item.expect for item in items)
    assert REQUIRED_CATEGORIES <= {item.category for item in items}


def test_project_corpus_passes_check(capsys, tmp_path):
    code, out, err = run_cli(capsys, "batch", CORPUS, "--check", "--out", tmp_path, "--parse-only")
    assert code == 0, out
    assert "failed 0, errored 0" in out
    assert len(err.splitlines()) <= 12  # a short counter, not a line per sentence
    results = manifest.read(str(tmp_path))
    assert sorted(r["line"] for r in results) == [it.line for it in load_corpus(str(CORPUS))]
    assert all(r["check"] == "passed" for r in results)
    assert all("parse" in r for r in results if r["status"] == "parsed")
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["categories"]["nagara"]["passed"] >= 3


def write(tmp_path, name, lines):
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_failed_expectation_exits_1_with_check(capsys, tmp_path):
    corpus = write(tmp_path, "c.jsonl", [
        json.dumps({"text": "太郎は歩く。", "category": "x", "expect": {"motions": [{"verb": "走る"}]}},
                   ensure_ascii=False),
        json.dumps({"text": "花子は座る。", "category": "x", "expect": {"motions": [{"verb": "座る"}]}},
                   ensure_ascii=False),
    ])
    code, out, _ = run_cli(capsys, "batch", corpus, "--check")
    assert code == 1
    assert "passed 1, refused 0, failed 1, errored 0" in out
    assert "$.motions[0].verb: expected '走る', got '歩く'" in out
    code, _, _ = run_cli(capsys, "batch", corpus)  # without --check: a report, exit 0
    assert code == 0


def test_a_line_may_expect_the_clip_each_motion_plays(capsys, tmp_path):
    """The line is planned with the built-in library even with --parse-only: sit_down's captured
    variants count as sit_down, another clip or a text that cannot be planned misses it."""
    def line(text, motions):
        return json.dumps({"text": text, "category": "clips", "expect": {"motions": motions}}, ensure_ascii=False)

    corpus = write(tmp_path, "c.jsonl", [
        line("太郎と花子は座る。", [{"actor": "太郎", "clip": "sit_down"}, {"actor": "花子", "clip": "sit_down"}]),
        line("太郎は座る。", [{"clip": "stand_up"}]),
        line("太郎は泳ぐ。", [{"clip": "swim"}]),
        line("太郎は座る。", [{"clip": "sit"}]),
    ])
    code, out, _ = run_cli(capsys, "batch", corpus, "--check", "--out", tmp_path / "o", "--parse-only")
    assert code == 1
    records = sorted(manifest.read(str(tmp_path / "o")), key=lambda r: r["line"])
    assert [r["check"] for r in records] == ["passed", "failed", "failed", "failed"]
    assert "expected 'stand_up' (or a captured variant), got 'sit_down" in records[1]["mismatches"][0]
    assert "not planned (UnknownVerbsError" in records[2]["mismatches"][0]
    assert "expected 'sit'" in records[3]["mismatches"][0]  # a prefix of sit_down is another clip


def test_plain_text_lines_and_errors(capsys, tmp_path):
    corpus = write(tmp_path, "c.txt", ["# comment", "太郎は歩く。", "", "これは本です。"])
    code, out, _ = run_cli(capsys, "batch", corpus, "--check")
    assert code == 1
    assert "passed 1, refused 0, failed 0, errored 1 (of 2)" in out
    assert "no motion" in out


@pytest.mark.parametrize("out", [False, True])
def test_a_line_with_escape_codes_is_refused_and_printed_escaped(capsys, tmp_path, library_db, out):
    """A corpus line that retitles and clears the terminal (issue 41): refused the same with or without
    --out (it was parsed without), and the summary shows it escaped."""
    corpus = write(tmp_path, "c.txt", ["\x1b]0;pwned\x07太郎は歩く。\x1b[2J", "太郎は走る。"])
    extra = ["--out", tmp_path / "o", "--db", library_db] if out else []
    code, printed, _ = run_cli(capsys, "batch", corpus, *extra)
    assert code == 0
    assert "\x1b" not in printed and "\x07" not in printed
    assert "\\x1b]0;pwned\\x07太郎は歩く。\\x1b[2J" in printed
    assert "the text contains a control character" in printed and "refused                                1" in printed


def test_expected_error_passes(capsys, tmp_path):
    corpus = write(tmp_path, "c.jsonl", ['{"text": "Hello", "expect": {"error": "no motion"}}',
                                         '{"text": "歩く", "expect": {"error": "no motion"}}'])
    code, out, _ = run_cli(capsys, "batch", corpus, "--check")
    assert code == 1 and "passed 1, refused 0, failed 1" in out
    assert "expected an error" in out


@pytest.mark.parametrize("lines, words", [
    (["{not json"], "not valid JSON"),
    (['{"category": "x"}'], '"text"'),
    (["# only a comment"], "no lines"),
])
def test_bad_corpus_is_a_user_error(capsys, tmp_path, lines, words):
    code, _, err = run_cli(capsys, "batch", write(tmp_path, "c.jsonl", lines))
    assert code == 2 and words in err and "Traceback" not in err


def test_missing_corpus_is_a_user_error(capsys, tmp_path):
    code, _, err = run_cli(capsys, "batch", tmp_path / "nope.jsonl")
    assert code == 2 and "nope.jsonl" in err


@pytest.mark.parametrize("expected, actual, ok", [
    ({"a": 1}, {"a": 1, "b": 2}, True),
    ({"a": 1.0}, {"a": 1}, True),
    ({"a": [1, 2]}, {"a": [1, 2, 3]}, False),
    ({"a": None}, {"a": 0}, False),
    ({"a": True}, {"a": 1}, False),
    ({"a": {"b": "x"}}, {"a": {"b": "y"}}, False),
])
def test_compare_subset(expected, actual, ok):
    assert (list(compare(expected, actual, "$")) == []) is ok



# ------------------------------------------------------------------ animation, manifest, resuming
SMALL = ["太郎は歩く。", "太郎は走る。3秒後に花子が歩く。", "これは本です。", "太郎は泳ぐ。"]


def small_corpus(tmp_path, texts=SMALL, gap=0):
    """A corpus whose lines are numbered 1.. (after ``gap`` blank lines, to reach another shard)."""
    return write(tmp_path, "small.txt", [""] * gap + list(texts))


def test_lines_are_animated_into_sharded_folders_with_their_figures(capsys, tmp_path, library_db):
    corpus = small_corpus(tmp_path, gap=1000)
    out = tmp_path / "out"
    code, stdout, _ = run_cli(capsys, "batch", corpus, "--out", out, "--db", library_db)
    assert code == 0
    recs = {r["line"]: r for r in manifest.read(str(out))}
    assert sorted(recs) == [1001, 1002, 1003, 1004]
    walk, two, refused, unknown = (recs[n] for n in sorted(recs))
    assert walk["status"] == "animated" and walk["files"] == [shard_path(1001)] == ["0001/line_0001001.bvh"]
    assert (out / "0001" / "line_0001001.bvh").read_text().startswith("HIERARCHY")
    assert sorted(two["files"]) == ["0001/line_0001002_太郎.bvh", "0001/line_0001002_花子.bvh"]
    assert all((out / f).is_file() for f in two["files"])
    assert two["joins"] and {"skating_ratio", "root_pop", "jerk_p99", "core_fidelity_cm", "meets"} <= set(two["joins"][0])
    assert refused["status"] == "refused" and refused["reason"] == "no motion found in the text"
    assert refused["check"] == "errored" and not refused.get("files")
    assert unknown["status"] == "refused" and unknown["reason"] == "unknown verb 泳ぐ"
    assert unknown["check"] == "passed"  # a verb the database lacks is not a parse error
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == {"animated": 2, "parsed": 0, "refused": 2, "failed": 0}
    assert summary["reasons"]["refused"] == {"no motion found in the text": 1, "unknown verb 泳ぐ": 1}
    assert summary["quality"]["join_skating_ratio"]["n"] == summary["quality"]["joins"] >= 1
    assert "unknown verb 泳ぐ" in stdout and "join foot-skating ratio" in stdout
    assert "passed 2, refused 1, failed 0, errored 1 (of 4)" in stdout


def test_the_summary_counts_a_refused_line_as_refused_not_passed(capsys, tmp_path, library_db):
    """Issue 26: a line refused for a verb the database lacks passes ``--check`` (its parse is right) but
    did not go through: the last line and summary.json say "refused", not "passed"."""
    corpus = write(tmp_path, "c.jsonl", [
        "太郎は歩く。",
        json.dumps({"text": "花子は座る。", "category": "x", "expect": {"motions": [{"verb": "座る"}]}},
                   ensure_ascii=False),
        json.dumps({"text": "太郎はセーターを編む。", "category": "x", "expect": {"motions": [{"verb": "編む"}]}},
                   ensure_ascii=False),
        '{"text": "Hello", "category": "x", "expect": {"error": "no motion"}}',
    ])
    out = tmp_path / "out"
    code, stdout, _ = run_cli(capsys, "batch", corpus, "--check", "--out", out, "--db", library_db)
    assert code == 0  # nothing failed or errored: --check still passes
    statuses = {r["text"]: r["status"] for r in manifest.read(str(out))}
    assert statuses["太郎はセーターを編む。"] == "refused" and statuses["Hello"] == "refused"
    # the expected error met its expectation: passed; the missing verb: refused
    assert stdout.splitlines()[-1] == "passed 3, refused 1, failed 0, errored 0 (of 4)"
    assert "  x  passed   2  refused   1  failed   0  errored   0" in stdout
    summary = json.loads((out / "summary.json").read_text())
    assert (summary["total"], summary["passed"], summary["refused"], summary["failed"], summary["errored"]) \
        == (4, 3, 1, 0, 0)
    assert summary["categories"]["x"] == {"passed": 2, "refused": 1, "failed": 0, "errored": 0, "total": 3}


def test_rerun_skips_done_lines_and_resumes_after_a_crash(tmp_path, library_db):
    corpus = small_corpus(tmp_path)
    out = tmp_path / "out"
    opts = Options(out=str(out), db=library_db)
    first = run_corpus(str(corpus), opts)
    assert (first.ran, first.skipped) == (4, 0)
    before = {p.name: p.read_bytes() for p in out.rglob("*.bvh")}
    # A run killed while it wrote its third record: two whole records and half a line.
    text = (out / "manifest.jsonl").read_text(encoding="utf-8").splitlines(keepends=True)
    (out / "manifest.jsonl").write_text("".join(text[:2]) + text[2][:25], encoding="utf-8")
    done_before = {json.loads(x)["line"] for x in text[:2]}
    ran = []
    again = run_corpus(str(corpus), opts, on_record=lambda rec, n, total: ran.append(rec["line"]))
    assert (again.ran, again.skipped) == (2, 2)
    assert sorted(ran) == sorted({1, 2, 3, 4} - done_before)
    recs = manifest.read(str(out))
    assert sorted(r["line"] for r in recs) == [1, 2, 3, 4]
    assert {p.name: p.read_bytes() for p in out.rglob("*.bvh")} == before
    # Nothing left to do; then a changed line runs again, alone; then other options run everything.
    assert run_corpus(str(corpus), opts).ran == 0
    changed = small_corpus(tmp_path, ["太郎は座る。", *SMALL[1:]])
    assert run_corpus(str(changed), opts).ran == 1
    assert manifest.read(str(out))[-1]["text"] == "太郎は座る。"
    assert run_corpus(str(changed), Options(out=str(out), db=library_db, fps=24.0)).ran == 4
    assert len(manifest.read(str(out))) == 4


@pytest.mark.parametrize("flag", ["--jobs", "--chunk"])
def test_bad_settings_are_user_errors(capsys, tmp_path, flag):
    code, _, err = run_cli(capsys, "batch", small_corpus(tmp_path), flag, "0")
    assert code == 2 and flag in err and "Traceback" not in err


def test_progress_off_a_terminal_is_ten_lines_with_rate_and_eta():
    stream = io.StringIO()
    bar = cmd_batch.Progress(stream)
    bar.start(500, 7)
    for i in range(1, 501):
        bar.update({}, i, 500)
    bar.close()
    lines = stream.getvalue().splitlines()
    assert lines[0] == "batch: 7 lines already done, 500 to run"
    assert len(lines) == 11 and "500/500" in lines[-1] and "line/s" in lines[-1]
    assert "<" in lines[1]  # elapsed<remaining: the ETA
