"""text2anim batch on Dask (the test extra installs it): a local cluster, a killed worker, a full corpus.

The bar of issue 16: a LocalCluster of two worker processes runs a corpus on
each database backend, one worker is killed mid-run, and still every line is in
the manifest exactly once and every output file equals, byte for byte, the one
the single-process path writes.
"""
from __future__ import annotations

import json
import logging
import os
import signal
from pathlib import Path

import pytest

from text2anim.cli.batch import Options, load_corpus, manifest, run_corpus
from text2anim.cli.main import main

CORPUS = Path(__file__).parents[1] / "corpus" / "nlp_corpus.jsonl"
VARIES = ("time", "cpu", "options")  # wall and CPU time; the options key names the database


@pytest.fixture(scope="module")
def cluster():
    """A client of a LocalCluster of two single-threaded worker processes (restarted by their nannies)."""
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                      silence_logs=logging.ERROR) as lc, Client(lc) as client:
        yield client


@pytest.fixture(scope="module")
def reference(tmp_path_factory, library_db):
    """A 12-line corpus (ten sentences of the project corpus, a refusal, an unknown verb) and its
    outputs from the single-process path."""
    folder = tmp_path_factory.mktemp("batch-reference")
    items = [it for it in load_corpus(str(CORPUS)) if "error" not in (it.expect or {})][:10]
    texts = [it.text for it in items] + ["これは本です。", "太郎は泳ぐ。"]
    corpus = folder / "corpus.txt"
    corpus.write_text("\n".join(texts) + "\n", encoding="utf-8")
    out = folder / "out"
    run_corpus(str(corpus), Options(out=str(out), db=library_db))
    return corpus, out


def outputs(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*.bvh"))}


def records(folder: Path) -> dict[int, dict]:
    return {r["line"]: {k: v for k, v in r.items() if k not in VARIES} for r in manifest.read(str(folder))}


def test_a_killed_worker_loses_no_line_and_the_outputs_equal_one_process(cluster, reference, db_url, tmp_path):
    corpus, ref = reference
    out = tmp_path / "out"
    killed: list[int] = []

    def kill_a_busy_worker(_rec, done, total):
        if done == 3:
            assert total == 12
            busy = [w for w, keys in cluster.processing().items() if keys] or list(cluster.nthreads())
            pid = cluster.run(os.getpid, workers=busy[:1])[busy[0]]
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    outcome = run_corpus(str(corpus), Options(out=str(out), db=db_url), scheduler=cluster.scheduler.address,
                         chunk=3, on_record=kill_a_busy_worker)
    assert killed and killed[0] not in cluster.run(os.getpid).values()
    lines = [r["line"] for r in manifest.read(str(out))]
    assert sorted(lines) == list(range(1, 13))  # every line, exactly once
    assert outcome.ran == 12
    assert records(out) == records(ref)
    got, want = outputs(out), outputs(ref)
    assert len(want) >= 10 and got.keys() == want.keys()
    assert all(got[k] == want[k] for k in want)


def test_every_corpus_sentence_animates_without_skating(capsys, tmp_path, library_db):
    """Issue 5's bar, on a local cluster of two workers (--jobs 2, the SQLite database shipped to each):
    every corpus sentence whose verbs the built-in library has renders, within issue 11's bounds for
    the built-in library: GMD foot-skating ratio (either foot, 30 fps) <= 0.02 (was 0.24 with the floor
    2 cm under the planted toes), the joins' root pop <= 15 m/s² (largest 13.4). The joins' own skating
    figure is the engine's, before its last step keeps swinging feet clear (synthesis.finish): its
    measured largest, 0.074 (dance → laugh), is the ceiling, so a regression still fails."""
    code = main(["batch", str(CORPUS), "--out", str(tmp_path), "--jobs", "2", "--db", library_db])
    out, _ = capsys.readouterr()
    assert code == 0, out
    summary = json.loads((tmp_path / "summary.json").read_text())
    items = load_corpus(str(CORPUS))
    refused = sum(1 for item in items if "error" in (item.expect or {}))
    assert summary["total"] == len(items) and summary["errored"] == 0 and summary["failed"] == 0
    st, reasons = summary["status"], summary["reasons"]["refused"]
    unknown = sum(n for r, n in reasons.items() if r.startswith("unknown verb"))
    assert st["failed"] == 0 and st["animated"] + st["refused"] == len(items)
    # unknown: 腰を回す, and 足を上げる / 左足を上げる, which played the raised hand before issue 39 (no clip lifts a leg)
    assert st["refused"] - unknown == refused and unknown <= 3
    q = summary["quality"]
    assert q["skating_ratio"]["max"] <= 0.02
    assert q["join_skating_ratio"]["max"] <= 0.075 and q["join_root_pop"]["max"] <= 15.0
    assert len(list(tmp_path.rglob("line_*.bvh"))) >= st["animated"]
